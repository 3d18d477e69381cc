/* rockdem — scenario commands of the runout after the topple (docs/RUNOUT.md):
 *   model domain box X0 X1 Y0 Y1 Z0 Z1    a body whose centre of mass leaves the box is out
 *   model fence points X1 Y1 X2 Y2 ... [name N]   a vertical fence on this plan polyline (each
 *                                          command one more, up to RD_MAX_FENCES)
 * (`model solve until rest time-limit T` is read with `model solve`, parse_model.c).
 * Folder scenario/ owns the scenario language; it may call base/, records/ and geometry/.
 */
#include "scenario/parse.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

int model_domain(parser *P)
{
    const token *kw = take(P);
    rd_runout_def *r = &P->sc->runout;
    if (!kw || !tok_is(kw, "box"))
        return perr(P, kw ? kw : verb_token(P),
                    "expected 'box X0 X1 Y0 Y1 Z0 Z1' after 'model domain'");
    double v[6];
    if (command_once(P) || read_values(P, kw, 6, R_ANY, U_PLAIN, v)) return -1;
    for (int k = 0; k < 3; k++) {
        if (!(v[2 * k] < v[2 * k + 1]))
            return perr(P, kw, "domain box: %c0 = %g must be below %c1 = %g", 'x' + k, v[2 * k],
                        'x' + k, v[2 * k + 1]);
        r->lo[k] = v[2 * k];
        r->hi[k] = v[2 * k + 1];
    }
    r->domain = 1;
    r->domain_line = kw->line;
    return expect_end(P);
}

/* Numbers left in the command from the cursor. */
static int numbers_left(const parser *P)
{
    int n = 0;
    double x;
    while (P->cur + n < P->n &&
           parse_number(P->tok[P->cur + n].s, (size_t)P->tok[P->cur + n].len, 0, &x) == 0)
        n++;
    return n;
}

/* model fence points X1 Y1 X2 Y2 ... [name N]: one more fence (up to RD_MAX_FENCES). */
int model_fence(parser *P)
{
    const token *kw = take(P);
    rd_runout_def *r = &P->sc->runout;
    if (!kw || !tok_is(kw, "points"))
        return perr(P, kw ? kw : verb_token(P),
                    "expected 'points X1 Y1 X2 Y2 ... [name N]' after 'model fence'");
    if (r->nfences == RD_MAX_FENCES) return perr(P, kw, "more than %d fences", RD_MAX_FENCES);
    int n = numbers_left(P);
    if (n < 4 || n % 2 || n > 2 * RD_MAX_FENCE_POINTS)
        return perr(P, kw, "'points' needs x y pairs of 2 to %d points, got %d numbers",
                    RD_MAX_FENCE_POINTS, n);
    rd_fence_def *fe = &r->fence[r->nfences];
    memset(fe, 0, sizeof *fe);
    if (read_values(P, kw, n, R_ANY, U_PLAIN, &fe->point[0][0])) return -1;
    for (int k = 0; k + 1 < n / 2; k++)
        if (hypot(fe->point[k + 1][0] - fe->point[k][0], fe->point[k + 1][1] - fe->point[k][1]) ==
            0)
            return perr(P, kw, "fence points %d and %d coincide", k + 1, k + 2);
    fe->npoint = n / 2;
    fe->line = kw->line;
    const token *nk = P->cur < P->n ? &P->tok[P->cur] : NULL, *name = kw;
    if (nk && tok_is(nk, "name")) {
        take(P);
        if (read_name(P, nk, &name, fe->name)) return -1;
    } else
        snprintf(fe->name, sizeof fe->name, "fence%d", r->nfences + 1);
    for (int f = 0; f < r->nfences; f++)
        if (!strcmp(r->fence[f].name, fe->name))
            return perr(P, name, "fence '%s' given twice (line %d)", fe->name, r->fence[f].line);
    r->nfences++;
    return expect_end(P);
}
