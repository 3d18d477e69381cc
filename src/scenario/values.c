/* rockdem — scenario values: numbers with units and ranges, names, paths, pulse durations;
 * shared by the parser, the `--set` overrides and the validation.
 * Folder scenario/ owns the scenario language (parse, --set overrides, validation); it may call
 * base/, records/ and geometry/, never engine/, io/ or cli/.
 */
#include "scenario/parse.h"
#include "base/constants.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

int parse_number(const char *s, size_t len, int accel, double *v)
{
    char buf[64], *end;
    if (len == 0 || len >= sizeof buf || isspace((unsigned char)s[0])) return -1;
    memcpy(buf, s, len);
    buf[len] = '\0';
    if (strpbrk(buf, RD_NOT_DECIMAL)) return -1; /* strtod also reads hexadecimal: 0x10 is not 10 */
    double x = strtod(buf, &end);
    if (end == buf) return -1;
    if (accel && end[0] == 'g' && end[1] == '\0') {
        x *= RD_G_STANDARD;
        end++;
    }
    if (*end != '\0' || !isfinite(x)) return -1;
    *v = x;
    return 0;
}

/* Valid range of every number, by keyword (docs/LIMITS.md lists the same table). Values are as
 * written: degrees for angles, m/s^2 for accelerations (a `g` suffix already applied). A
 * keyword's range category (range_error) applies as well; these bounds keep each number within
 * what the physics and the step budget can use. A keyword not listed takes |v| <= 1e9. */
typedef struct keyword_limit {
    const char *name;
    double lo, hi;
    const char *unit;
} keyword_limit;

static const keyword_limit keyword_limits[] = {
    { "stiffness-normal", 1e4, 1e15,
      "Pa/m" }, /* below: cm-scale sinking of a 1 m block; above: dt < 1e-9 s */
    { "stiffness-shear", 1e4, 1e15, "Pa/m" },
    { "friction-coefficient", 0, 100, "" }, /* mu = tan(phi): 100 is phi = 89.4 deg */
    { "cohesion", 0, 1e10, "Pa" },          /* stronger than any rock (granite: ~1e7 Pa) */
    { "tension", 0, 1e10, "Pa" },
    { "density", 1, 1e5, "kg/m^3" }, /* osmium: 22600 */
    { "mass", 1e-6, 1e12, "kg" },
    { "gravity", 0, 1e3, "m/s^2" },
    { "time", 1e-6, 1e5, "s" }, /* model solve: a day of shaking at most */
    { "tail", 1e-6, 1e5, "s" },
    { "time-limit", 1e-6, 1e5, "s" },
    { "duration", 1e-6, 1e5, "s" },
    { "start", 0, 1e4, "s" },
    { "interval", 1e-7, 1e3, "s" },
    { "fixed", 1e-12, 1, "s" }, /* model timestep fixed DT */
    { "dt", 1e-6, 1, "s" },     /* record sample steps */
    { "frequency", 1e-4, 1e3, "Hz" },
    { "cycles", 1e-3, 1e4, "" },
    { "amplitude", -1e6, 1e6, "m/s^2" }, /* earthquakes stay below 10 g; shocks (and the health
                                                check's test, 2e5 m/s^2) need more */
    { "pga", 0, 1e3, "m/s^2" },
    { "scale-pga", 0, 1e3, "m/s^2" },
    { "scale-pgv", 0, 1e2, "m/s" },
    { "scale", 0, 1e6, "" },
    { "size", 1e-6, 1e4, "m" },
    { "diameter", 1e-6, 1e4, "m" },
    { "radius", 1e-6, 1e4, "m" },
    { "radius-top", 1e-6, 1e4, "m" },
    { "height", 0, 1e4, "m" },
    { "plinth", 1e-6, 1e4, "m" },
    { "abacus", 1e-6, 1e4, "m" },
    { "cap", 1e-6, 1e4, "m" },
    { "lower", 1e-6, 1e4, "m" },
    { "upper", 1e-6, 1e4, "m" },
    { "position", -1e7, 1e7, "m" }, /* map coordinates */
    { "at", -1e7, 1e7, "m" },
    { "spacing", 1e-6, 1e4, "m" }, /* 0 is refused (spacing_error), not taken as vertices */
    { "raise", 0, 1e3, "m" },
    { "scatter", 0, 1e3, "m" },
    { "velocity", -1e3, 1e3, "m/s" },
    { "angular-velocity", -1e4, 1e4, "rad/s" },
    { "direction", -3600, 3600, "deg" },
    { "rotation", -3600, 3600, "deg" },
    { "sides", 3, 1e4, "" },
    { "drums", 1, 1e3, "" },
    { "seed", 0, 4294967295.0, "" }, /* generators take 32-bit seeds */
};

#define KEYWORD_DEFAULT_MAX 1e9 /* |v| of a keyword without its own row */

/* The row of keyword kw (len characters), NULL when it has none. */
static const keyword_limit *find_limit(const char *kw, size_t len)
{
    for (size_t i = 0; i < sizeof keyword_limits / sizeof keyword_limits[0]; i++) {
        const keyword_limit *l = &keyword_limits[i];
        if (strlen(l->name) == len && !strncmp(l->name, kw, len)) return l;
    }
    return NULL;
}

const char *limit_error(const char *kw, size_t len, double v, char *buf, size_t size)
{
    const keyword_limit *l = find_limit(kw, len);
    if (l) {
        if (v >= l->lo && v <= l->hi) return NULL;
        snprintf(buf, size, "is outside its valid range [%g, %g]%s%s (docs/LIMITS.md)", l->lo,
                 l->hi, l->unit[0] ? " " : "", l->unit);
        return buf;
    }
    if (fabs(v) <= KEYWORD_DEFAULT_MAX) return NULL;
    snprintf(buf, size, "is outside the range of any scenario number, |v| <= %g (docs/LIMITS.md)",
             KEYWORD_DEFAULT_MAX);
    return buf;
}

int rd_scenario_limit(const char *keyword, double *lo, double *hi)
{
    const keyword_limit *l = find_limit(keyword, strlen(keyword));
    *lo = l ? l->lo : -KEYWORD_DEFAULT_MAX;
    *hi = l ? l->hi : KEYWORD_DEFAULT_MAX;
    return l ? 0 : -1;
}

/* NULL when a subcontact spacing v (m) is valid, else why not (in buf). 0 is refused rather
 * than read as the faces' corners: a spacing is an edge length, and 0 reads as "as fine as can
 * be", the opposite of the corners, which are written 'vertices'. */
const char *spacing_error(double v, char *buf, size_t size)
{
    if (v == 0) {
        snprintf(buf, size,
                 "is no edge length: give one in m, or 'vertices' for the faces' corners");
        return buf;
    }
    return limit_error("spacing", strlen("spacing"), v, buf, size);
}

/* NULL when v (as written: degrees for angles) lies in r, else what it must be. */
const char *range_error(double v, range r)
{
    switch (r) {
    case R_ANY: return NULL;
    case R_POS: return v > 0 ? NULL : "must be > 0";
    case R_NONNEG: return v >= 0 ? NULL : "must be >= 0";
    case R_FRAC: return v > 0 && v <= 1 ? NULL : "must be in (0, 1]";
    case R_DAMP: return v > 0 && v <= 10 ? NULL : "must be in (0, 10]";
    case R_OPEN01: return v > 0 && v < 1 ? NULL : "must be in (0, 1)";
    case R_UNIT: return v >= 0 && v <= 1 ? NULL : "must be in [0, 1]";
    case R_ANGLE: return v >= 0 && v < 90 ? NULL : "must be in [0, 90) degrees";
    case R_TURN: return v > 0 && v <= 180 ? NULL : "must be in (0, 180] degrees";
    }
    return NULL;
}

double unit_si(double v, unit u)
{
    if (u == U_MU) return atan(v);
    return u == U_DEG ? v * RD_DEG : v;
}

int is_periodic(rd_pulse_kind k)
{
    return k == RD_PULSE_ONE_SINE || k == RD_PULSE_ONE_COSINE || k == RD_PULSE_HARMONIC;
}

/* Duration of a pulse, s: one period (cycles periods for harmonic) for the periodic shapes;
 * 1/frequency or the given duration for rectangular and triangle. */
double pulse_duration(const rd_pulse_def *p)
{
    if (p->kind == RD_PULSE_HARMONIC) return p->cycles / p->frequency;
    if (is_periodic(p->kind) || p->frequency > 0) return 1.0 / p->frequency;
    return p->duration;
}

/* Block names double as override keys (block.<name>.density): letters, digits, '_' and '-'. */
int valid_name(const char *s, size_t len)
{
    if (len == 0 || len >= RD_NAME_MAX) return 0;
    for (size_t i = 0; i < len; i++)
        if (!isalnum((unsigned char)s[i]) && s[i] != '_' && s[i] != '-') return 0;
    return 1;
}

int find_body(const rd_scenario *sc, const char *name, size_t len)
{
    for (int i = 0; i < sc->nbodies; i++)
        if (strlen(sc->bodies[i].name) == len && memcmp(sc->bodies[i].name, name, len) == 0)
            return i;
    return -1;
}

int parse_find_body(parser *P, const char *name, size_t len)
{
    int i = rd_name_index_find(&P->names, P->sc, name, len);
    return i == -2 ? find_body(P->sc, name, len) : i;
}

/* Appends ", word" (or "word" to an empty buf), truncating quietly. */
void append(char *buf, size_t size, const char *word)
{
    size_t n = strlen(buf);
    if (n + 1 < size) snprintf(buf + n, size - n, "%s%s", n ? ", " : "", word);
}

/* Resolves a file name relative to the directory of the scenario file `base` into dst. */
int resolve_path(const char *base, const char *file, char *dst, size_t size)
{
    const char *slash = strrchr(base, '/');
    int dir = file[0] != '/' && slash ? (int)(slash - base) + 1 : 0;
    int n = snprintf(dst, size, "%.*s%s", dir, base, file);
    return n >= 0 && (size_t)n < size ? 0 : -1;
}

/* Format from the file's extension: .at2, .h5/.hdf5 (FEMA P695 set), else text. */
rd_record_source source_of(const char *file)
{
    const char *dot = strrchr(file, '.');
    if (dot && strcasecmp(dot, ".at2") == 0) return RD_SOURCE_AT2;
    if (dot && (strcasecmp(dot, ".h5") == 0 || strcasecmp(dot, ".hdf5") == 0))
        return RD_SOURCE_FEMA;
    return RD_SOURCE_TEXT;
}
