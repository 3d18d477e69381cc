/* rockdem — scenario commands `model ...`, `contact ...` and `output hdf5`: scene-wide
 * settings into rd_scenario.
 * Folder scenario/ owns the scenario language (parse, --set overrides, validation); it may call
 * base/, records/ and geometry/, never engine/, io/ or cli/.
 */
#include "scenario/parse.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* ---- model ---- */

int model_title(parser *P)
{
    if (command_once(P) || read_text(P, "a title", P->sc->title, sizeof P->sc->title)) return -1;
    return expect_end(P);
}

int model_gravity(parser *P)
{
    if (command_once(P) || read_value(P, verb_token(P), R_NONNEG, U_ACCEL, &P->sc->gravity))
        return -1;
    return expect_end(P);
}

int model_density(parser *P)
{
    if (command_once(P) || read_value(P, verb_token(P), R_POS, U_PLAIN, &P->sc->density)) return -1;
    return expect_end(P);
}

int model_damping(parser *P)
{
    static const char *const names[] = { "none", "viscous", "local", NULL };
    static const range ranges[] = { R_ANY, R_DAMP, R_OPEN01 };
    rd_damping_def *d = &P->sc->damping;
    const token *kw, *prev = NULL;
    unsigned seen = 0;
    int k;
    if (command_once(P)) return -1;
    while ((k = next_keyword(P, names, &seen, &kw)) >= 0) {
        if (exclusive(P, &prev, kw)) return -1;
        d->kind = (rd_damping_kind)k;
        d->value = 0;
        if (k > 0 && read_value(P, kw, ranges[k], U_PLAIN, &d->value)) return -1;
    }
    return keywords_end(P, k, prev != NULL, names);
}

int model_timestep(parser *P)
{
    static const char *const names[] = { "auto", "fixed", "safety", NULL };
    rd_timestep_def *ts = &P->sc->timestep;
    const token *kw, *prev = NULL, *safety = NULL;
    unsigned seen = 0;
    int k;
    if (command_once(P)) return -1;
    while ((k = next_keyword(P, names, &seen, &kw)) >= 0) {
        if (k == 2) {
            safety = kw;
            if (read_value(P, kw, R_FRAC, U_PLAIN, &ts->safety)) return -1;
            continue;
        }
        if (exclusive(P, &prev, kw)) return -1;
        ts->kind = k == 0 ? RD_TIMESTEP_AUTO : RD_TIMESTEP_FIXED;
        if (k == 1 && read_value(P, kw, R_POS, U_PLAIN, &ts->dt)) return -1;
    }
    if (k == KW_ERR) return -1;
    if (!prev) return perr(P, verb_token(P), "expected auto or fixed after 'model timestep'");
    if (safety && ts->kind == RD_TIMESTEP_FIXED)
        return perr(P, safety, "'safety' applies only to 'model timestep auto'");
    return 0;
}

int model_settle(parser *P)
{
    static const char *const names[] = { "on", "off", "ratio", "time-limit", NULL };
    rd_settle_def *st = &P->sc->settle;
    const token *kw, *prev = NULL;
    unsigned seen = 0;
    int k;
    while ((k = next_keyword(P, names, &seen, &kw)) >= 0) {
        int rc = 0;
        if (k < 2) {
            rc = exclusive(P, &prev, kw) || keyword_once(P, kw, "on|off");
            st->enabled = k == 0;
        } else {
            rc = keyword_once(P, kw, names[k]) ||
                 read_value(P, kw, R_POS, U_PLAIN, k == 2 ? &st->ratio : &st->max_time);
        }
        if (rc) return -1;
    }
    return keywords_end(P, k, seen != 0, names);
}

/* `until rest`: the word after `until` must be `rest`. */
static int read_until(parser *P, const token *kw, int *on)
{
    const token *t = take(P);
    if (!t || !tok_is(t, "rest"))
        return perr(P, t ? t : kw,
                    "expected 'rest' after 'until' (model solve until rest "
                    "time-limit T)");
    *on = 1;
    return 0;
}

int model_solve(parser *P)
{
    static const char *const names[] = { "time", "tail", "force", "until", "time-limit", NULL };
    const token *kw, *span = NULL;
    unsigned seen = 0;
    int k;
    rd_scenario *sc = P->sc;
    sc->solve_line = verb_token(P)->line;
    while ((k = next_keyword(P, names, &seen, &kw)) >= 0) {
        int rc = keyword_once(P, kw, names[k]);
        if (!rc && k == 2) rc = read_switch(P, kw, &sc->force);
        if (!rc && k == 3) rc = read_until(P, kw, &sc->runout.until_rest);
        if (!rc && (k == 0 || k == 4)) rc = exclusive(P, &span, kw);
        if (!rc && k != 2 && k != 3)
            rc = read_value(P, kw, R_POS, U_PLAIN, k == 1 ? &sc->tail : &sc->duration);
        if (rc) return -1;
    }
    if (k == KW_ERR) return -1;
    int until = seen >> 3 & 1u, limit = seen >> 4 & 1u;
    if (until && !limit)
        return perr(P, verb_token(P), "'until rest' needs 'time-limit T' (the longest run, s)");
    if (limit && !until)
        return perr(P, verb_token(P), "'time-limit' applies only with 'until rest'");
    if (until && (seen >> 1 & 1u))
        return perr(P, verb_token(P),
                    "'tail' does not apply with 'until rest' (which runs on "
                    "until rest by itself)");
    return keywords_end(P, k, seen != 0, names);
}

int model_overturn(parser *P)
{
    static const char *const names[] = { "tilt-ratio",   "angle", "height",
                                         "off-pedestal", "stop",  NULL };
    static const range ranges[] = { R_POS, R_TURN, R_OPEN01, R_NONNEG };
    static const unit units[] = { U_PLAIN, U_DEG, U_PLAIN, U_PLAIN };
    rd_overturn_def *ov = &P->sc->overturn;
    const token *kw, *prev = NULL;
    unsigned seen = 0;
    int k;
    while ((k = next_keyword(P, names, &seen, &kw)) >= 0) {
        if (k == 4) {
            if (keyword_once(P, kw, names[k]) || read_switch(P, kw, &ov->stop)) return -1;
            continue;
        }
        if (exclusive(P, &prev, kw) ||
            keyword_once(P, kw, "tilt-ratio|angle|height|off-pedestal") ||
            read_value(P, kw, ranges[k], units[k], &ov->value))
            return -1;
        ov->kind = (rd_overturn_kind)k;
    }
    return keywords_end(P, k, seen != 0, names);
}

/* `model reference restitution e`: the rigid reference solvers' impact restitution. */
int model_reference(parser *P)
{
    static const char *const names[] = { "restitution", NULL };
    const token *kw;
    unsigned seen = 0;
    int k;
    while ((k = next_keyword(P, names, &seen, &kw)) >= 0)
        if (keyword_once(P, kw, names[k]) ||
            read_value(P, kw, R_FRAC, U_PLAIN, &P->sc->ref_restitution))
            return -1;
    return keywords_end(P, k, seen != 0, names);
}

/* ---- contact ---- */

static int read_spacing(parser *P, const token *kw, double *v)
{
    const token *t = take(P);
    if (!t) return perr(P, kw, "expected a number, auto or vertices after 'spacing'");
    if (tok_is(t, "auto") || tok_is(t, "vertices")) {
        *v = tok_is(t, "auto") ? -1.0 : 0.0;
        return 0;
    }
    if (parse_number(t->s, (size_t)t->len, 0, v))
        return perr(P, t, "expected a number, auto or vertices after 'spacing', got '%.*s'", t->len,
                    t->s);
    char why[128];
    const char *bad = spacing_error(*v, why, sizeof why);
    return bad ? perr(P, t, "'spacing' %.*s %s", t->len, t->s, bad) : 0;
}

/* The keywords of the default `contact property` (no range). */
static const char *const contact_names[] = {
    "stiffness-normal", "stiffness-shear",      "friction", "cohesion", "tension", "spacing",
    "restitution",      "friction-coefficient", NULL
};
#define CK_MU                                                                                      \
    7 /* friction-coefficient: the friction as mu = tan(phi), the same setting as friction */

int contact_property(parser *P)
{
    if (contact_is_range(P)) return contact_joint(P); /* a per-range joint (parse_scene.c) */
    const char *const *names = contact_names;
    rd_contact_def *c = &P->sc->contact;
    const token *kw;
    unsigned seen = 0;
    int k;
    while ((k = next_keyword(P, names, &seen, &kw)) >= 0) {
        int rc = keyword_once(P, kw, names[k == CK_MU ? 2 : k]); /* friction once, either way */
        if (rc) return -1;
        switch (k) {
        case 0: rc = read_value(P, kw, R_POS, U_PLAIN, &c->kn); break;
        case 1: rc = read_value(P, kw, R_POS, U_PLAIN, &c->ks); break;
        case 2: rc = read_value(P, kw, R_ANGLE, U_DEG, &c->friction); break;
        case 3: rc = read_value(P, kw, R_NONNEG, U_PLAIN, &c->cohesion); break;
        case 4: rc = read_value(P, kw, R_NONNEG, U_PLAIN, &c->tension); break;
        case 5: rc = read_spacing(P, kw, &c->spacing); break;
        case CK_MU: rc = read_value(P, kw, R_NONNEG, U_MU, &c->friction); break;
        default: rc = read_value(P, kw, R_UNIT, U_PLAIN, &c->restitution); break;
        }
        if (rc) return -1;
    }
    return k == KW_ERR ? -1 : 0;
}

/* The setting a preset would replace, given before it: its name into what, its line; 0 none. */
static int replaced_by_preset(const parser *P, char *what, size_t size)
{
    for (int i = 0; contact_names[i]; i++) {
        snprintf(what, size, "'%s' of 'contact property'", contact_names[i]);
        int line = setting_line(P, what);
        if (line) return line;
    }
    snprintf(what, size, "'model damping'");
    return setting_line(P, what);
}

/* contact preset rigid|3dec|default: a whole contact setting in one line (rd_contact_preset);
 * `contact property` and `model damping` lines after it change single values, and one before
 * it is refused (the preset would replace it). */
int contact_preset(parser *P)
{
    static const char *const names[] = { "rigid", "3dec", "default", NULL };
    char what[sizeof((setting *)0)->what];
    int k = one_keyword(P, names), line;
    if (k < 0 || command_once(P)) return -1;
    if ((line = replaced_by_preset(P, what, sizeof what)))
        return perr(P, &P->tok[0],
                    "'contact preset' would replace %s given on line %d; give the "
                    "preset first",
                    what, line);
    rd_contact_preset(&P->sc->contact, &P->sc->damping, names[k]);
    return 0;
}

/* Largest seed a generator takes (gsl_rng seeds are unsigned long; 32 bits everywhere). */
#define RD_SEED_MAX 4294967295.0

/* contact interface-perturbation seed S remove F raise H raise-fraction P scatter C
 * keep-corners on|off (src/engine/perturb.c) */
int contact_perturbation(parser *P)
{
    static const char *const names[] = { "seed",    "remove",       "raise", "raise-fraction",
                                         "scatter", "keep-corners", NULL };
    rd_perturb_def *d = &P->sc->contact.perturb;
    const token *kw;
    unsigned seen = 0;
    int k;
    d->line = verb_token(P)->line;
    while ((k = next_keyword(P, names, &seen, &kw)) >= 0) {
        double *v[] = { &d->seed, &d->remove, &d->raise, &d->raise_fraction, &d->scatter };
        if (keyword_once(P, kw, names[k])) return -1;
        if (k == 5 ? read_switch(P, kw, &d->keep_corners)
                   : read_value(P, kw, R_NONNEG, U_PLAIN, v[k]))
            return -1;
        if ((k == 0 && (d->seed != floor(d->seed) || d->seed > RD_SEED_MAX)) ||
            (k == 1 && d->remove >= 1) || (k == 3 && d->raise_fraction > 1))
            return perr(P, kw, "'%s' must be %s", names[k],
                        k == 0   ? "a whole number in [0, 2^32)"
                        : k == 1 ? "below 1"
                                 : "at most 1");
    }
    return k == KW_ERR ? -1 : 0;
}

/* ---- output ---- */

int output_hdf5(parser *P)
{
    static const char *const names[] = { "interval", NULL };
    rd_output_def *o = &P->sc->output;
    const token *kw;
    unsigned seen = 0;
    int k;
    if (command_once(P) || read_text(P, "a file name", o->path, sizeof o->path)) return -1;
    while ((k = next_keyword(P, names, &seen, &kw)) >= 0)
        if (read_value(P, kw, R_POS, U_PLAIN, &o->interval)) return -1;
    return k == KW_ERR ? -1 : 0;
}

/* contact model vertex|surface: vertex subcontacts (the default) or patches from the touching
 * faces (engine/surface.c). */
int contact_model(parser *P)
{
    static const char *const names[] = { "vertex", "surface", NULL };
    int k = one_keyword(P, names);
    if (k < 0 || command_once(P)) return -1;
    P->sc->contact.model = k == 1 ? RD_CONTACT_SURFACE : RD_CONTACT_VERTEX;
    P->sc->contact.model_line = verb_token(P)->line;
    return 0;
}
