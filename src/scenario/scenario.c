/* rockdem — the scenario parser: a 3DEC-flavoured command language into rd_scenario.
 *
 * One command per line, `noun verb keyword value ...`, keywords in any order after the verb
 * (case-insensitive); `;` starts a comment; a `&` as the last token of a line continues the
 * command on the next line; strings in single or double quotes. Angles in the file are degrees,
 * accelerations may carry a `g` suffix (times standard gravity); everything stored is SI.
 * Every error is one line "file:line:col: message" pointing at the offending token.
 * This file: the command table, defaults, parse, load and free; the commands live in
 * parse_model.c, parse_block.c and parse_motion.c, the lexer in lexer.c.
 *
 * Folder scenario/ owns the scenario language (parse, --set overrides, validation); it may call
 * base/, records/ and geometry/, never engine/, io/ or cli/.
 */
#include "scenario/parse.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- commands ---- */

typedef int (*command_fn)(parser *P);

static const struct command {
    const char *noun, *verb;
    command_fn fn;
} commands[] = {
    { "model", "title", model_title },
    { "model", "gravity", model_gravity },
    { "model", "density", model_density },
    { "model", "damping", model_damping },
    { "model", "timestep", model_timestep },
    { "model", "settle", model_settle },
    { "model", "solve", model_solve },
    { "model", "overturn", model_overturn },
    { "model", "reference", model_reference },
    { "model", "domain", model_domain },
    { "model", "fence", model_fence },
    { "model", "save", model_save },
    { "model", "restore", model_restore },
    { "block", "create", block_create },
    { "block", "import", block_import },
    { "block", "initial", block_initial },
    { "contact", "property", contact_property },
    { "contact", "interface-perturbation", contact_perturbation },
    { "contact", "preset", contact_preset },
    { "contact", "model", contact_model },
    { "ground-motion", "pulse", motion_pulse },
    { "ground-motion", "import", motion_import },
    { "ground-motion", "stochastic", motion_stochastic },
    { "history", "interval", history_interval },
    { "history", "body", history_body },
    { "history", "joint", history_joint },
    { "history", "energy", history_energy },
    { "output", "hdf5", output_hdf5 },
};

#define NCOMMANDS (sizeof commands / sizeof commands[0])

/* The nouns (noun == NULL) or the verbs of one noun, comma-separated. */
static void command_list(char *buf, size_t size, const token *noun)
{
    buf[0] = '\0';
    for (size_t i = 0; i < NCOMMANDS; i++) {
        if (!noun && (i == 0 || strcmp(commands[i].noun, commands[i - 1].noun) != 0))
            append(buf, size, commands[i].noun);
        if (noun && tok_is(noun, commands[i].noun)) append(buf, size, commands[i].verb);
    }
}

static int run_command(parser *P)
{
    const token *noun = &P->tok[0], *verb = P->n > 1 ? &P->tok[1] : NULL;
    char list[256];
    int known = 0;
    for (size_t i = 0; i < NCOMMANDS; i++) {
        if (!tok_is(noun, commands[i].noun)) continue;
        known = 1;
        if (verb && tok_is(verb, commands[i].verb)) {
            snprintf(P->ctx, sizeof P->ctx, "%s %s", commands[i].noun, commands[i].verb);
            P->cur = 2;
            return commands[i].fn(P);
        }
    }
    command_list(list, sizeof list, known ? noun : NULL);
    if (!known)
        return perr(P, noun, "unknown command '%.*s' (expected %s)", noun->len, noun->s, list);
    if (!verb)
        return perr(P, noun, "missing verb after '%.*s' (expected %s)", noun->len, noun->s, list);
    return perr(P, verb, "unknown verb '%.*s' for '%.*s' (expected %s)", verb->len, verb->s,
                noun->len, noun->s, list);
}

/* ---- public: defaults, parse, load, free ---- */

int rd_contact_preset(rd_contact_def *c, rd_damping_def *d, const char *name)
{
    rd_contact_def keep = *c;
    *c = (rd_contact_def){ .perturb = keep.perturb, .model = keep.model };
    if (!strcmp(name, "rigid")) {
        /* rigid rocking theory (Housner, Kounadis): corner subcontacts, perfectly plastic point
           impacts, and a shear spring stiff enough (KS = 10 KN) to give the impacting edge
           its full tangential impulse within the normal impact, so the impact keeps the
           angular momentum about the new pivot; friction high enough not to slide. KN 1e11:
           the amplitude after a free-rocking impact is 2.3 % above Housner's at 1e10 and
           0.7 % at 1e11 (0.5 x 1.0 m block), converging as the contact stiffens */
        c->kn = 1e11;
        c->ks = 1e12;
        c->friction = 80.0 * RD_DEG;
        c->spacing = 0;
        c->restitution = 0;
    } else if (!strcmp(name, "3dec")) {
        /* the 3DEC practice of seed 002: KN 10 GPa/m, KS 1 GPa/m, 40 deg, fewest-triangle
           (corner) subcontacts, elastic joint, no damping */
        c->kn = 1e10;
        c->ks = 1e9;
        c->friction = 40.0 * RD_DEG;
        c->spacing = 0;
        c->restitution = 1;
    } else if (!strcmp(name, "default")) {
        /* docs/GUIDE.md, `contact preset`: seed 002's KN and friction on corner subcontacts with
           plastic point impacts and KS = 10 KN (the rigid preset's layout and ratio), so the
           impact loses what free-rocking tests on stone and concrete bases lose: r = 0.698 =
           1.00 Housner's r on the 0.5 x 1.0 m block, no hop, 0.02 mm slide (docs/CONTACT.md
           sections 3-5, tables written by `make docs`; adopted range 0.95-1.00 r_H,
           docs/REFERENCES.md). A point bed (spacing auto) rolls the pivot and loses too little
           (r = 0.86 = 1.22 r_H) */
        c->kn = 1e10;
        c->ks = 1e11;
        c->friction = 40.0 * RD_DEG;
        c->spacing = 0;
        c->restitution = 0;
    } else {
        *c = keep;
        return -1;
    }
    *d = (rd_damping_def){ RD_DAMPING_NONE, 0.0 };
    return 0;
}

void rd_scenario_defaults(rd_scenario *sc)
{
    memset(sc, 0, sizeof *sc);
    sc->gravity = RD_GRAVITY_DEFAULT;
    sc->density = 2700.0;
    rd_contact_preset(&sc->contact, &sc->damping, "default");
    sc->motion.horizontal.cycles = 1.0;
    sc->motion.vertical.cycles = 1.0;
    sc->motion.baseline = 4;
    sc->motion.factor = 1.0;
    sc->timestep = (rd_timestep_def){ RD_TIMESTEP_AUTO, 0.2, 0.0 };
    sc->settle = (rd_settle_def){ 1, 1e-6, 5.0 };
    sc->overturn = (rd_overturn_def){ RD_OVERTURN_TILT_RATIO, 1.5, 1 };
    sc->ref_restitution = -1.0;
    snprintf(sc->output.path, sizeof sc->output.path, "%s", "rockdem.h5");
    sc->output.interval = 0.005;
    sc->history_interval = 0.001;
}

/* Baseline-corrects and scales the records once all of them are read; errors "name: ...". */
static int prepare_records(rd_scenario *sc, const char *name, rd_error *err)
{
    rd_error e;
    if (!rd_motion_has_records(&sc->motion) || rd_motion_prepare(&sc->motion, &e) == 0) return 0;
    return rd_error_set(err, "%s: %s", name, e.msg);
}

int rd_scenario_parse(rd_scenario *sc, const char *name, const char *text, rd_error *err)
{
    size_t len = strlen(text);
    int rc;
    rd_scenario_defaults(sc);
    snprintf(sc->file, sizeof sc->file, "%s", name);
    sc->text = malloc(len + 1);
    if (!sc->text) return rd_error_set(err, "%s: out of memory", name);
    memcpy(sc->text, text, len + 1);
    parser P = { .sc = sc, .err = err, .name = name, .p = sc->text, .bol = sc->text, .line = 1 };
    while ((rc = lex_command(&P)) > 0)
        if (run_command(&P)) {
            rc = -1;
            break;
        }
    free(P.settings);
    rd_name_index_free(&P.names);
    if (rc >= 0 && prepare_records(sc, name, err)) rc = -1;
    if (rc < 0) {
        rd_scenario_free(sc);
        return -1;
    }
    return 0;
}

/* The most a scenario text may hold, bytes: a written scenario is a few kB (meshes and records
 * are files of their own), and a device read as one (`rockdem check /dev/zero`) never ends: its
 * buffer grew until memory ran out. A pipe stays a valid source. */
#define RD_SCENARIO_MAX_BYTES ((size_t)64 << 20)

/* Reads all of f into a NUL-terminated malloc'ed buffer; NULL when out of memory, or (with
 * *len = RD_SCENARIO_MAX_BYTES) when f holds more than that. */
static char *slurp(FILE *f, size_t *len)
{
    size_t cap = 4096, n = 0;
    char *buf = malloc(cap);
    while (buf && !feof(f) && !ferror(f)) {
        if (n >= RD_SCENARIO_MAX_BYTES) {
            free(buf);
            *len = RD_SCENARIO_MAX_BYTES;
            return NULL;
        }
        if (n + 1 == cap) {
            char *grown = realloc(buf, cap * 2);
            if (!grown) free(buf);
            buf = grown;
            cap *= 2;
            continue;
        }
        n += fread(buf + n, 1, cap - n - 1, f);
    }
    if (buf) buf[n] = '\0';
    *len = n;
    return buf;
}

static int read_file(const char *path, char **out, size_t *len, rd_error *err)
{
    FILE *f = fopen(path, "rb");
    if (!f) return rd_error_set(err, "%s: cannot open: %s", path, strerror(errno));
    errno = 0;
    *len = 0;
    *out = slurp(f, len);
    int bad = ferror(f), e = errno;
    fclose(f);
    if (*out && bad) {
        free(*out);
        *out = NULL;
        return rd_error_set(err, "%s: cannot read: %s", path, strerror(e));
    }
    if (!*out && *len == RD_SCENARIO_MAX_BYTES)
        return rd_error_set(err, "%s: more than %zu MiB: not a scenario text", path,
                            RD_SCENARIO_MAX_BYTES >> 20);
    if (!*out) return rd_error_set(err, "%s: out of memory", path);
    return 0;
}

int rd_scenario_parse_n(rd_scenario *sc, const char *name, const char *text, size_t len,
                        rd_error *err)
{
    const char *nul = memchr(text, '\0', len);
    if (nul) {
        rd_scenario_defaults(sc);
        return rd_error_set(err, "%s: contains a NUL byte at offset %zu of %zu (not a text?)", name,
                            (size_t)(nul - text), len);
    }
    char *copy = malloc(len + 1);
    if (!copy) return rd_error_set(err, "%s: out of memory", name);
    memcpy(copy, text, len);
    copy[len] = '\0';
    int rc = rd_scenario_parse(sc, name, copy, err);
    free(copy);
    return rc;
}

int rd_scenario_load(rd_scenario *sc, const char *path, rd_error *err)
{
    char *text = NULL;
    size_t len = 0;
    rd_scenario_defaults(sc);
    if (read_file(path, &text, &len, err)) return -1;
    if (strlen(text) != len) {
        free(text);
        return rd_error_set(err, "%s: contains a NUL byte (not a text file?)", path);
    }
    int rc = rd_scenario_parse(sc, path, text, err);
    free(text);
    return rc;
}

void rd_scenario_free(rd_scenario *sc)
{
    rd_motion_release(&sc->motion);
    for (int i = 0; i < sc->nbodies; i++) free(sc->bodies[i].verts);
    free(sc->bodies);
    sc->bodies = NULL;
    sc->nbodies = sc->cap_bodies = 0;
    free(sc->text);
    sc->text = NULL;
}

int rd_scenario_grow(rd_scenario *sc)
{
    if (sc->nbodies < sc->cap_bodies) return 0;
    int cap = sc->cap_bodies ? 2 * sc->cap_bodies : 16;
    rd_body_def *b = realloc(sc->bodies, (size_t)cap * sizeof *b);
    if (!b) return -1;
    sc->bodies = b;
    sc->cap_bodies = cap;
    return 0;
}

int rd_scenario_add_body(rd_scenario *sc, const rd_body_def *b, rd_error *err)
{
    double *v = NULL;
    if (b->verts && b->nverts > 0) {
        v = malloc((size_t)b->nverts * 3 * sizeof *v);
        if (v) memcpy(v, b->verts, (size_t)b->nverts * 3 * sizeof *v);
    }
    if ((b->verts && b->nverts > 0 && !v) || rd_scenario_grow(sc)) {
        free(v);
        return rd_error_set(err, "out of memory adding block '%s'", b->name);
    }
    sc->bodies[sc->nbodies] = *b;
    sc->bodies[sc->nbodies++].verts = v;
    return 0;
}

int rd_scenario_copy(rd_scenario *dst, const rd_scenario *src, rd_error *err)
{
    *dst = *src;
    dst->text = NULL;
    dst->bodies = NULL;
    dst->nbodies = dst->cap_bodies = 0;
    if (rd_motion_copy(&dst->motion, &src->motion, err)) {
        rd_scenario_free(dst);
        return -1;
    }
    if (src->text && !(dst->text = strdup(src->text))) {
        rd_scenario_free(dst);
        return rd_error_set(err, "out of memory copying the scenario text");
    }
    for (int i = 0; i < src->nbodies; i++)
        if (rd_scenario_add_body(dst, &src->bodies[i], err)) {
            rd_scenario_free(dst);
            return -1;
        }
    return 0;
}
