/* rockdem — scene-control commands: joint ranges, histories, checkpoints.
 *
 *   contact property stiffness-normal 5e9 stiffness-shear 1.7e9 friction 20 damping 0 &
 *       range group 'pad' group 'cask'
 *       A joint for the pairs of a body of group 'pad' (block create ... group 'pad') and a body
 *       of group 'cask'; `range group 'pad'` alone: every pair with a body of group 'pad';
 *       `range block 'cask' block 'pedestal'`: one pair by block names. Properties not given
 *       come from the default (`contact property` without range, `model damping viscous`);
 *       a later range wins where two set the same property. damping: ratio of critical damping
 *       of the joint's normal dashpot.
 *   history interval 0.001
 *   history body 'cask' position rotation velocity angular-velocity
 *   history joint 'pad' 'cask' normal-force shear-force opening slip area pressure-centre
 *       (or `all`)
 *   history energy
 *   model save 'settled.h5'     checkpoint after settling (the run goes on)
 *   model restore 'settled.h5'  start from a checkpoint instead of settling
 *
 * Folder scenario/ owns the scenario language (parse, --set overrides, validation); it may call
 * base/, records/ and geometry/, never engine/, io/ or cli/.
 */
#include "scenario/parse.h"

#include <stdio.h>
#include <string.h>

/* Does the command hold the bare word w after the verb? */
static int has_word(const parser *P, const char *w)
{
    for (int i = 2; i < P->n; i++)
        if (!P->tok[i].quoted && tok_is(&P->tok[i], w)) return 1;
    return 0;
}

int contact_is_range(const parser *P) { return has_word(P, "range"); }

/* "group NAME" or "block NAME" after `range`; 1 read, 0 at the end of the command, -1 error. */
static int read_selector(parser *P, const token *range, rd_range_def *r)
{
    static const char *const kinds[] = { "group", "block", NULL };
    const token *t = take(P), *name;
    if (!t) return 0;
    int k = find_word(t, kinds);
    if (k < 0)
        return perr(P, t, "expected group or block after '%.*s', got '%.*s'", range->len, range->s,
                    t->len, t->s);
    r->kind = k == 0 ? RD_RANGE_GROUP : RD_RANGE_BLOCK;
    return read_name(P, t, &name, r->name) ? -1 : 1;
}

static int read_range(parser *P, const token *kw, rd_joint_def *j)
{
    int n = 0, rc;
    while (n < 2 && (rc = read_selector(P, kw, &j->range[n])) == 1) n++;
    if (n < 2 && rc < 0) return -1;
    if (n == 0) return perr(P, kw, "expected group NAME or block NAME after 'range'");
    return expect_end(P); /* the range closes the command */
}

/* "group 'A' group 'B'" for range r of one or two selectors, the two in name order (a
 * pair's range reads the same either way round). */
static void range_text(const rd_range_def r[2], char *buf, size_t size)
{
    char one[2][RD_NAME_MAX + 16] = { "", "" };
    for (int i = 0; i < 2 && r[i].kind != RD_RANGE_ANY; i++)
        snprintf(one[i], sizeof one[i], "%s '%s'", r[i].kind == RD_RANGE_GROUP ? "group" : "block",
                 r[i].name);
    int swap = one[1][0] && strcmp(one[0], one[1]) > 0;
    snprintf(buf, size, "%s%s%s", one[swap], one[1][0] ? " " : "", one[!swap]);
}

/* Each property of joint j (its keywords at kw[]) given once per range: a later range wins
 * where it overlaps another, but the same range twice left the first's value dead. */
static int joint_once(parser *P, const rd_joint_def *j, const char *const *names,
                      const token *const *kw)
{
    char range[2 * RD_NAME_MAX + 40], what[sizeof((setting *)0)->what];
    range_text(j->range, range, sizeof range);
    for (int k = 0; names[k]; k++) {
        if (!kw[k]) continue;
        const char *name =
            strcmp(names[k], "friction-coefficient") ? names[k] : "friction"; /* one setting */
        snprintf(what, sizeof what, "'%s' of 'contact property ... range %s'", name, range);
        if (setting_once(P, kw[k], what)) return -1;
    }
    return 0;
}

/* contact property ... range ...: one per-range joint override. */
int contact_joint(parser *P)
{
    static const char *const names[] = { "stiffness-normal",
                                         "stiffness-shear",
                                         "friction",
                                         "cohesion",
                                         "tension",
                                         "damping",
                                         "range",
                                         "spacing",
                                         "restitution",
                                         "friction-coefficient",
                                         NULL };
    static const unsigned bit[] = { RD_JOINT_KN,
                                    RD_JOINT_KS,
                                    RD_JOINT_FRICTION,
                                    RD_JOINT_COHESION,
                                    RD_JOINT_TENSION,
                                    RD_JOINT_DAMPING,
                                    0,
                                    0,
                                    RD_JOINT_RESTITUTION,
                                    RD_JOINT_FRICTION };
    static const range ranges[] = { R_POS,    R_POS, R_ANGLE, R_NONNEG, R_NONNEG,
                                    R_NONNEG, R_ANY, R_ANY,   R_UNIT,   R_NONNEG };
    enum { JK_FRICTION = 2, JK_MU = 9 }; /* the friction as an angle (deg) or as mu = tan(phi) */
    rd_scenario *sc = P->sc;
    if (sc->njoints == RD_MAX_JOINTS)
        return perr(P, verb_token(P), "too many contact property ranges (at most %d)",
                    RD_MAX_JOINTS);
    rd_joint_def j = { .line = P->tok[0].line };
    double *field[] = { &j.kn,      &j.ks, &j.friction, &j.cohesion,    &j.tension,
                        &j.damping, NULL,  NULL,        &j.restitution, &j.friction };
    const token *kw, *given[sizeof names / sizeof names[0]] = { NULL };
    unsigned seen = 0;
    int k;
    while ((k = next_keyword(P, names, &seen, &kw)) >= 0) {
        if (k != 6) given[k] = kw;
        if (k == 7)
            return perr(P, kw,
                        "'spacing' belongs to the bodies, not to a joint range: give it "
                        "in a contact property without range");
        if (k == 6) {
            if (read_range(P, kw, &j)) return -1;
            break;
        }
        if ((k == JK_MU && given[JK_FRICTION]) || (k == JK_FRICTION && given[JK_MU]))
            return perr(
                P, kw,
                "give the friction once: 'friction' (degrees) or 'friction-coefficient' (mu)");
        if (read_value(P, kw, ranges[k],
                       k == JK_FRICTION ? U_DEG
                       : k == JK_MU     ? U_MU
                                        : U_PLAIN,
                       field[k]))
            return -1;
        if (k == 5 && j.damping > 10)
            return perr(P, kw, "'damping' is a ratio of critical damping, at most 10");
        j.set |= bit[k];
    }
    if (k == KW_ERR) return -1;
    if (!j.set)
        return perr(P, verb_token(P),
                    "a contact property range sets no property (expected "
                    "stiffness-normal, stiffness-shear, friction, friction-coefficient, cohesion, "
                    "tension, damping or restitution)");
    if (joint_once(P, &j, names, given)) return -1;
    sc->joint[sc->njoints++] = j;
    return 0;
}

/* ---- history ---- */

int history_interval(parser *P)
{
    if (command_once(P) || read_value(P, verb_token(P), R_POS, U_PLAIN, &P->sc->history_interval))
        return -1;
    return expect_end(P);
}

/* The history for (kind, a, b), merged with an earlier one of the same subject. */
static rd_history_def *history_slot(parser *P, rd_history_kind kind, const char *a, const char *b)
{
    rd_scenario *sc = P->sc;
    for (int h = 0; h < sc->nhistories; h++) {
        rd_history_def *d = &sc->history[h];
        if (d->kind == kind && !strcmp(d->a, a) && !strcmp(d->b, b)) return d;
    }
    if (sc->nhistories == RD_MAX_HISTORIES) {
        perr(P, verb_token(P), "too many histories (at most %d)", RD_MAX_HISTORIES);
        return NULL;
    }
    rd_history_def *d = &sc->history[sc->nhistories++];
    memset(d, 0, sizeof *d);
    d->kind = kind;
    d->line = P->tok[0].line;
    snprintf(d->a, sizeof d->a, "%s", a);
    snprintf(d->b, sizeof d->b, "%s", b);
    return d;
}

/* Quantities after the names: words of `names` (bits in order), or `all`. */
static int history_what(parser *P, const char *const *names, unsigned all, unsigned *what)
{
    const token *t;
    *what = 0;
    while ((t = take(P))) {
        if (tok_is(t, "all")) {
            *what |= all;
            continue;
        }
        int k = find_word(t, names);
        if (k < 0) {
            char list[256];
            join(list, sizeof list, names);
            return perr(P, t, "unknown quantity '%.*s' for '%s' (expected %s or all)", t->len, t->s,
                        P->ctx, list);
        }
        *what |= 1u << k;
    }
    if (!*what) return missing_keyword(P, names);
    return 0;
}

int history_body(parser *P)
{
    static const char *const names[] = { "position", "rotation", "velocity", "angular-velocity",
                                         NULL };
    char a[RD_NAME_MAX];
    const token *t;
    unsigned what;
    if (read_name(P, verb_token(P), &t, a) || history_what(P, names, 15u, &what)) return -1;
    rd_history_def *d = history_slot(P, RD_HISTORY_BODY, a, "");
    if (!d) return -1;
    d->what |= what;
    return 0;
}

int history_joint(parser *P)
{
    static const char *const names[] = { "normal-force", "shear-force",     "opening", "slip",
                                         "area",         "pressure-centre", NULL };
    char a[RD_NAME_MAX], b[RD_NAME_MAX];
    const token *ta, *tb;
    unsigned what;
    if (read_name(P, verb_token(P), &ta, a) || read_name(P, ta, &tb, b)) return -1;
    if (!strcmp(a, b)) return perr(P, tb, "a joint needs two different blocks, got '%s' twice", a);
    if (history_what(P, names, 63u, &what)) return -1;
    rd_history_def *d = history_slot(P, RD_HISTORY_JOINT, a, b);
    if (!d) return -1;
    d->what |= what;
    return 0;
}

int history_energy(parser *P)
{
    if (expect_end(P)) return -1;
    return history_slot(P, RD_HISTORY_ENERGY, "", "") ? 0 : -1;
}

/* ---- checkpoints ---- */

/* The file name as written: relative to the working directory, like `output hdf5`. */
static int checkpoint_path(parser *P, char *dst)
{
    if (read_text(P, "a checkpoint file name", dst, RD_PATH_MAX)) return -1;
    return expect_end(P);
}

int model_save(parser *P)
{
    if (P->sc->restore_path[0])
        return perr(P, verb_token(P),
                    "'model save' and 'model restore' in one scenario: a restored "
                    "state is already saved");
    return command_once(P) || checkpoint_path(P, P->sc->save_path) ? -1 : 0;
}

int model_restore(parser *P)
{
    if (P->sc->save_path[0])
        return perr(P, verb_token(P),
                    "'model save' and 'model restore' in one scenario: a restored "
                    "state is already saved");
    return command_once(P) || checkpoint_path(P, P->sc->restore_path) ? -1 : 0;
}
