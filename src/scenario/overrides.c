/* rockdem — command-line overrides (`--set section.key=value`): rd_scenario_set.
 * Folder scenario/ owns the scenario language (parse, --set overrides, validation); it may call
 * base/, records/ and geometry/, never engine/, io/ or cli/.
 */
#include "scenario/parse.h"

#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

/* ---- public: command-line overrides ---- */

typedef enum set_kind {
    S_NUMBER, /* a double at set_key.off */
    S_PULSE,  /* a double in the pulse, duration re-derived */
    S_SPACING,
    S_DAMPING,
    S_TIMESTEP,
    S_SETTLE,
    S_MODEL,
    S_FILE,
    S_RECORD, /* a record setting: the records are re-read and/or re-processed */
    S_THREADS /* rd_scenario.threads: a whole number, 1 to RD_THREADS_MAX */
} set_kind;

typedef struct set_key {
    const char *key;
    set_kind kind;
    size_t off; /* S_NUMBER: offset of the double in rd_scenario (rd_body_def for block keys);
                   S_PULSE: in rd_pulse_def */
    range range;
    unit unit;
} set_key;

static const set_key set_keys[] = {
    { "contact.stiffness-normal", S_NUMBER, offsetof(rd_scenario, contact.kn), R_POS, U_PLAIN },
    { "contact.stiffness-shear", S_NUMBER, offsetof(rd_scenario, contact.ks), R_POS, U_PLAIN },
    { "contact.friction", S_NUMBER, offsetof(rd_scenario, contact.friction), R_ANGLE, U_DEG },
    { "contact.friction-coefficient", S_NUMBER, offsetof(rd_scenario, contact.friction), R_NONNEG,
      U_MU },
    { "contact.cohesion", S_NUMBER, offsetof(rd_scenario, contact.cohesion), R_NONNEG, U_PLAIN },
    { "contact.tension", S_NUMBER, offsetof(rd_scenario, contact.tension), R_NONNEG, U_PLAIN },
    { "contact.spacing", S_SPACING, 0, R_NONNEG, U_PLAIN },
    { "contact.restitution", S_NUMBER, offsetof(rd_scenario, contact.restitution), R_UNIT,
      U_PLAIN },
    { "contact.interface-seed", S_NUMBER, offsetof(rd_scenario, contact.perturb.seed), R_NONNEG,
      U_PLAIN },
    { "contact.interface-remove", S_NUMBER, offsetof(rd_scenario, contact.perturb.remove), R_NONNEG,
      U_PLAIN },
    { "contact.interface-raise", S_NUMBER, offsetof(rd_scenario, contact.perturb.raise), R_NONNEG,
      U_PLAIN },
    { "contact.interface-scatter", S_NUMBER, offsetof(rd_scenario, contact.perturb.scatter),
      R_NONNEG, U_PLAIN },
    { "contact.model", S_MODEL, 0, R_ANY, U_PLAIN },
    { "model.gravity", S_NUMBER, offsetof(rd_scenario, gravity), R_NONNEG, U_ACCEL },
    { "model.density", S_NUMBER, offsetof(rd_scenario, density), R_POS, U_PLAIN },
    { "model.duration", S_NUMBER, offsetof(rd_scenario, duration), R_POS, U_PLAIN },
    { "model.damping", S_DAMPING, 0, R_ANY, U_PLAIN },
    { "model.timestep", S_TIMESTEP, 0, R_POS, U_PLAIN },
    { "model.safety", S_NUMBER, offsetof(rd_scenario, timestep.safety), R_FRAC, U_PLAIN },
    { "model.settle", S_SETTLE, 0, R_ANY, U_PLAIN },
    { "model.threads", S_THREADS, 0, R_POS, U_PLAIN },
    { "motion.amplitude", S_PULSE, offsetof(rd_pulse_def, amplitude), R_ANY, U_ACCEL },
    { "motion.frequency", S_PULSE, offsetof(rd_pulse_def, frequency), R_POS, U_PLAIN },
    { "motion.duration", S_PULSE, offsetof(rd_pulse_def, duration), R_POS, U_PLAIN },
    { "motion.direction", S_RECORD, offsetof(rd_pulse_def, direction), R_ANY, U_DEG },
    { "motion.cycles", S_PULSE, offsetof(rd_pulse_def, cycles), R_POS, U_PLAIN },
    { "motion.start", S_PULSE, offsetof(rd_pulse_def, start), R_NONNEG, U_PLAIN },
    { "motion.vertical-amplitude", S_PULSE, offsetof(rd_pulse_def, amplitude), R_ANY, U_ACCEL },
    { "motion.scale", S_RECORD, 0, R_POS, U_PLAIN },
    { "motion.scale-pga", S_RECORD, 0, R_POS, U_ACCEL },
    { "motion.scale-pgv", S_RECORD, 0, R_POS, U_PLAIN },
    { "motion.baseline", S_RECORD, 0, R_ANY, U_PLAIN },
    { "motion.file", S_RECORD, 0, R_ANY, U_PLAIN },
    { "motion.record", S_RECORD, 0, R_ANY, U_PLAIN },
    { "motion.seed", S_RECORD, 0, R_NONNEG, U_PLAIN },
    { "model.tail", S_NUMBER, offsetof(rd_scenario, tail), R_NONNEG, U_PLAIN },
    { "output.file", S_FILE, 0, R_ANY, U_PLAIN },
    { "output.interval", S_NUMBER, offsetof(rd_scenario, output.interval), R_POS, U_PLAIN },
    { "reference.restitution", S_NUMBER, offsetof(rd_scenario, ref_restitution), R_FRAC, U_PLAIN },
};

static const set_key body_keys[] = {
    { "density", S_NUMBER, offsetof(rd_body_def, density), R_POS, U_PLAIN },
    { "mass", S_NUMBER, offsetof(rd_body_def, mass), R_POS, U_PLAIN },
    { "tilt", S_NUMBER, offsetof(rd_body_def, tilt), R_ANGLE, U_DEG },
    { "direction", S_NUMBER, offsetof(rd_body_def, tilt_direction), R_ANY, U_DEG },
};

#define NSET_KEYS  (sizeof set_keys / sizeof set_keys[0])
#define NBODY_KEYS (sizeof body_keys / sizeof body_keys[0])

typedef struct setter {
    rd_scenario *sc;
    rd_error *err;
    const char *a;     /* the whole assignment, for messages */
    const char *value; /* after the '=' */
} setter;

static int serr(const setter *S, const char *fmt, ...) RD_PRINTF(2, 3);

static int serr(const setter *S, const char *fmt, ...)
{
    char msg[RD_ERROR_MAX];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return rd_error_set(S->err, "--set %s: %s", S->a, msg);
}

static int same_key(const char *key, const char *s, size_t len)
{
    return strlen(key) == len && strncasecmp(key, s, len) == 0;
}

/* Parses text as a number in range r (as written) and converts it to SI. */
static int set_parse(const setter *S, const char *text, range r, unit u, double *v)
{
    if (parse_number(text, strlen(text), u == U_ACCEL, v))
        return serr(S, "expected a number, got '%s'", text);
    const char *bad = range_error(*v, r);
    if (bad) return serr(S, "value %s", bad);
    size_t n =
        strcspn(S->a, "="); /* the key's last part names the keyword: contact.stiffness-normal */
    const char *kw = S->a;
    for (size_t i = 0; i < n; i++)
        if (S->a[i] == '.') kw = S->a + i + 1;
    char why[128];
    if ((bad = limit_error(kw, (size_t)(S->a + n - kw), *v, why, sizeof why)))
        return serr(S, "%s %s", text, bad);
    *v = unit_si(*v, u);
    return 0;
}

static double *field(void *base, size_t off) { return (double *)((char *)base + off); }

static int set_pulse(const setter *S, const set_key *k)
{
    int vertical = strcmp(k->key, "motion.vertical-amplitude") == 0;
    rd_pulse_def *p = vertical ? &S->sc->motion.vertical : &S->sc->motion.horizontal;
    double v;
    if (p->kind == RD_PULSE_NONE)
        return serr(S, "the scenario has no %s ground-motion pulse",
                    vertical ? "vertical" : "horizontal");
    if (k->off == offsetof(rd_pulse_def, duration) && is_periodic(p->kind))
        return serr(S, "motion.duration applies only to rectangular and triangle pulses "
                       "(set motion.frequency)");
    if (k->off == offsetof(rd_pulse_def, cycles) && p->kind != RD_PULSE_HARMONIC)
        return serr(S, "motion.cycles applies only to harmonic pulses");
    if (set_parse(S, S->value, k->range, k->unit, &v)) return -1;
    *field(p, k->off) = v;
    if (k->off == offsetof(rd_pulse_def, amplitude)) /* as written, for check's echo and advice */
        p->amplitude_in_g = S->value[0] && S->value[strlen(S->value) - 1] == 'g';
    if (k->off == offsetof(rd_pulse_def, duration)) p->frequency = 0.0;
    p->duration = pulse_duration(p);
    return 0;
}

static int set_spacing(const setter *S)
{
    double v;
    if (strcasecmp(S->value, "auto") == 0 || strcasecmp(S->value, "vertices") == 0) {
        S->sc->contact.spacing = strcasecmp(S->value, "auto") == 0 ? -1.0 : 0.0;
        return 0;
    }
    if (parse_number(S->value, strlen(S->value), 0, &v))
        return serr(S, "expected a number, auto or vertices, got '%s'", S->value);
    char why[128];
    const char *bad = spacing_error(v, why, sizeof why);
    if (bad) return serr(S, "%s %s", S->value, bad);
    S->sc->contact.spacing = v;
    return 0;
}

/* "none", "viscous <ratio>" or "local <alpha>". */
static int set_damping(const setter *S)
{
    const char *v = S->value;
    size_t wl = strcspn(v, " \t");
    const char *arg = v + wl + strspn(v + wl, " \t");
    rd_damping_def *d = &S->sc->damping;
    double x = 0.0;
    if (same_key("none", v, wl) && *arg == '\0')
        d->kind = RD_DAMPING_NONE;
    else if (same_key("viscous", v, wl) && *arg)
        d->kind = RD_DAMPING_VISCOUS;
    else if (same_key("local", v, wl) && *arg)
        d->kind = RD_DAMPING_LOCAL;
    else
        return serr(S, "expected none, viscous <ratio> or local <alpha>, got '%s'", v);
    if (d->kind != RD_DAMPING_NONE &&
        set_parse(S, arg, d->kind == RD_DAMPING_VISCOUS ? R_DAMP : R_OPEN01, U_PLAIN, &x))
        return -1;
    d->value = x;
    return 0;
}

static int set_timestep(const setter *S)
{
    rd_timestep_def *ts = &S->sc->timestep;
    double dt;
    if (strcasecmp(S->value, "auto") == 0) {
        ts->kind = RD_TIMESTEP_AUTO;
        return 0;
    }
    if (parse_number(S->value, strlen(S->value), 0, &dt))
        return serr(S, "expected auto or a time step in s, got '%s'", S->value);
    if (!(dt > 0)) return serr(S, "value must be > 0");
    ts->kind = RD_TIMESTEP_FIXED;
    ts->dt = dt;
    return 0;
}

static int set_settle(const setter *S)
{
    if (strcasecmp(S->value, "on") != 0 && strcasecmp(S->value, "off") != 0)
        return serr(S, "expected on or off, got '%s'", S->value);
    S->sc->settle.enabled = strcasecmp(S->value, "on") == 0;
    return 0;
}

/* contact.model: vertex (subcontacts) or surface (patches from the touching faces), as the
 * scenario's 'contact model' (docs/CONTACT.md section 8). */
static int set_model(const setter *S)
{
    if (strcasecmp(S->value, "vertex") != 0 && strcasecmp(S->value, "surface") != 0)
        return serr(S, "expected vertex or surface, got '%s'", S->value);
    S->sc->contact.model =
        strcasecmp(S->value, "surface") == 0 ? RD_CONTACT_SURFACE : RD_CONTACT_VERTEX;
    S->sc->contact.model_line = 0;
    return 0;
}

static int set_file(const setter *S)
{
    size_t len = strlen(S->value);
    if (len == 0) return serr(S, "empty file name");
    if (len >= RD_PATH_MAX) return serr(S, "file name longer than %d characters", RD_PATH_MAX - 1);
    memcpy(S->sc->output.path, S->value, len + 1);
    return 0;
}

/* The text of a --set value into dst (size), refusing empty or too long ones. */
static int set_text(const setter *S, char *dst, size_t size)
{
    size_t len = strlen(S->value);
    if (len == 0 || len >= size) return serr(S, "expected 1 to %zu characters", size - 1);
    memcpy(dst, S->value, len + 1);
    return 0;
}

/* motion.file (h1's file, relative to the scenario's directory), motion.seed (h1's generator),
 * motion.record (every FEMA component): change the source and re-read it. */
static int set_record_source(const setter *S, const char *key)
{
    rd_motion_def *m = &S->sc->motion;
    rd_component_def *h1 = &m->record[RD_H1];
    rd_error e;
    double seed;
    int n = 0;
    if (strcmp(key, "motion.record") == 0) {
        for (int c = 0; c < RD_NCOMPONENTS; c++) {
            if (m->record[c].source != RD_SOURCE_FEMA) continue;
            if (set_text(S, m->record[c].record, sizeof m->record[c].record)) return -1;
            if (rd_motion_load(m, c, &e)) return serr(S, "%s", e.msg);
            n++;
        }
        return n ? 0 : serr(S, "no ground-motion record comes from a FEMA P695 set");
    }
    if (strcmp(key, "motion.seed") == 0) {
        if (h1->source != RD_SOURCE_STOCHASTIC)
            return serr(S, "the h1 ground motion is not 'ground-motion stochastic'");
        if (set_parse(S, S->value, R_NONNEG, U_PLAIN, &seed)) return -1;
        if (seed != floor(seed) || seed > 4294967295.0)
            return serr(S, "expected a whole number in [0, 2^32)");
        h1->stochastic.seed = (unsigned long)seed;
    } else if (h1->source == RD_SOURCE_NONE || h1->source == RD_SOURCE_STOCHASTIC) {
        return serr(S, "the h1 ground motion is not 'ground-motion import'");
    } else if (!S->value[0] || resolve_path(S->sc->file, S->value, h1->path, sizeof h1->path)) {
        return serr(S, "expected a file name of at most %d characters", RD_PATH_MAX - 1);
    } else if ((h1->source == RD_SOURCE_FEMA) != (source_of(S->value) == RD_SOURCE_FEMA)) {
        return serr(S, "motion.file keeps the kind of file: a FEMA P695 set (.h5) or a record");
    } else {
        h1->source = source_of(S->value); /* the extension picks AT2 or text */
    }
    return rd_motion_load(m, RD_H1, &e) ? serr(S, "%s", e.msg) : 0;
}

/* motion.baseline: a degree 2..8 or off. */
static int set_baseline(const setter *S, int *degree)
{
    double v;
    if (strcasecmp(S->value, "off") == 0) {
        *degree = 0;
        return 0;
    }
    if (parse_number(S->value, strlen(S->value), 0, &v) || v != floor(v) || v < 2 || v > 8)
        return serr(S, "expected a degree (2 to 8) or off, got '%s'", S->value);
    *degree = (int)v;
    return 0;
}

/* Record settings: re-read (file, record, seed) and re-process (every key) the records. */
static int set_record(const setter *S, const set_key *k)
{
    static const char *const scales[] = { "motion.scale", "motion.scale-pga", "motion.scale-pgv",
                                          NULL };
    static const rd_scale_kind kinds[] = { RD_SCALE_FACTOR, RD_SCALE_PGA, RD_SCALE_PGV };
    rd_motion_def *m = &S->sc->motion;
    rd_error e;
    int rc = 0;
    if (!rd_motion_has_records(m)) {
        if (strcmp(k->key, "motion.direction") == 0) return set_pulse(S, k);
        return serr(
            S, "the scenario has no ground-motion record (ground-motion import or stochastic)");
    }
    if (strcmp(k->key, "motion.direction") == 0) {
        double v;
        if (set_parse(S, S->value, k->range, k->unit, &v)) return -1;
        m->direction = v;
        return 0;
    }
    for (int i = 0; scales[i]; i++) {
        double v;
        if (strcmp(k->key, scales[i]) != 0) continue;
        if (set_parse(S, S->value, k->range, k->unit, &v)) return -1;
        m->scale = kinds[i];
        m->scale_value = v;
    }
    if (strcmp(k->key, "motion.baseline") == 0)
        rc = set_baseline(S, &m->baseline);
    else if (strncmp(k->key, "motion.scale", 12) != 0)
        rc = set_record_source(S, k->key);
    if (rc) return -1;
    return rd_motion_prepare(m, &e) ? serr(S, "%s", e.msg) : 0;
}

static int set_apply(const setter *S, const set_key *k)
{
    double v;
    switch (k->kind) {
    case S_NUMBER:
        if (set_parse(S, S->value, k->range, k->unit, &v)) return -1;
        *field(S->sc, k->off) = v;
        return 0;
    case S_PULSE: return set_pulse(S, k);
    case S_SPACING: return set_spacing(S);
    case S_DAMPING: return set_damping(S);
    case S_TIMESTEP: return set_timestep(S);
    case S_SETTLE: return set_settle(S);
    case S_MODEL: return set_model(S);
    case S_FILE: return set_file(S);
    case S_RECORD: return set_record(S, k);
    case S_THREADS:
        if (set_parse(S, S->value, k->range, k->unit, &v)) return -1;
        if (v != floor(v) || v > RD_THREADS_MAX)
            return serr(S, "threads must be a whole number from 1 to %d", RD_THREADS_MAX);
        S->sc->threads = (int)v;
        return 0;
    }
    return 0;
}

/* Unknown key: lists the keys of its section, or the sections. */
static int unknown_key(const setter *S, const char *key, size_t len)
{
    char list[RD_ERROR_MAX - 96] = "";    /* room for the key and the words around the list */
    size_t sect = strcspn(key, ".=") + 1; /* section length with its dot */
    for (size_t i = 0; i < NSET_KEYS; i++)
        if (sect <= len && strncasecmp(set_keys[i].key, key, sect) == 0)
            append(list, sizeof list, set_keys[i].key);
    if (list[0] == '\0')
        snprintf(list, sizeof list, "a key in contact, model, motion, output or block.<name>");
    return serr(S, "unknown key '%.*s' (expected %s)", (int)len, key, list);
}

/* key = "<name>.<field>" after "block." */
static int set_body(const setter *S, const char *key, size_t len)
{
    size_t nlen = len;
    while (nlen > 0 && key[nlen - 1] != '.') nlen--;
    if (nlen < 2) return serr(S, "expected block.<name>.<field>");
    int i = find_body(S->sc, key, nlen - 1);
    if (i < 0) return serr(S, "unknown block '%.*s'", (int)(nlen - 1), key);
    rd_body_def *b = &S->sc->bodies[i];
    const char *f = key + nlen;
    size_t flen = len - nlen;
    for (size_t j = 0; j < NBODY_KEYS; j++) {
        const set_key *k = &body_keys[j];
        double v;
        if (!same_key(k->key, f, flen)) continue;
        if (b->fixed && k->unit == U_DEG)
            return serr(S, "block '%s' is fixed; %s applies only to free blocks", b->name, k->key);
        if (set_parse(S, S->value, k->range, k->unit, &v)) return -1;
        *field(b, k->off) = v;
        if (k->off == offsetof(rd_body_def, density)) b->mass = 0.0;
        if (k->off == offsetof(rd_body_def, mass)) b->density = 0.0;
        return 0;
    }
    return serr(S, "unknown key '%.*s' (expected block.%s.density, mass, tilt or direction)",
                (int)flen, f, b->name);
}

/* Records the override in sc->text as a comment line "; --set <assignment>". */
static int append_override(rd_scenario *sc, const char *a, rd_error *err)
{
    size_t old = sc->text ? strlen(sc->text) : 0;
    int nl = old > 0 && sc->text[old - 1] != '\n';
    char *t = realloc(sc->text, old + (size_t)nl + strlen(a) + sizeof "; --set \n");
    if (!t) return rd_error_set(err, "--set %s: out of memory", a);
    sprintf(t + old, "%s; --set %s\n", nl ? "\n" : "", a);
    sc->text = t;
    return 0;
}

/* Length of a "block." or "body." prefix of key, else 0. */
static size_t body_prefix(const char *key, size_t len)
{
    if (len > 6 && strncasecmp(key, "block.", 6) == 0) return 6;
    if (len > 5 && strncasecmp(key, "body.", 5) == 0) return 5;
    return 0;
}

static int set_key_value(const setter *S, const char *key, size_t len)
{
    size_t pre = body_prefix(key, len);
    if (pre) return set_body(S, key + pre, len - pre);
    for (size_t i = 0; i < NSET_KEYS; i++)
        if (same_key(set_keys[i].key, key, len)) return set_apply(S, &set_keys[i]);
    return unknown_key(S, key, len);
}

int rd_scenario_set(rd_scenario *sc, const char *assignment, rd_error *err)
{
    setter S = { sc, err, assignment, NULL };
    const char *eq = strchr(assignment, '=');
    if (strchr(assignment, '\n')) return serr(&S, "contains a line break");
    if (!eq || eq == assignment) return serr(&S, "expected section.key=value");
    S.value = eq + 1;
    if (set_key_value(&S, assignment, (size_t)(eq - assignment))) return -1;
    return append_override(sc, assignment, err);
}
