/* rockdem — scenario commands of the runout after the topple (docs/RUNOUT.md):
 *   model domain box X0 X1 Y0 Y1 Z0 Z1    a body whose centre of mass leaves the box is out
 *   model fence points X1 Y1 X2 Y2 ...     a vertical fence on this plan polyline
 * (`model solve until rest time-limit T` is read with `model solve`, parse_model.c).
 * Folder scenario/ owns the scenario language; it may call base/, records/ and geometry/.
 */
#include "scenario/parse.h"

#include <math.h>
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

int model_fence(parser *P)
{
    const token *kw = take(P);
    rd_runout_def *r = &P->sc->runout;
    if (!kw || !tok_is(kw, "points"))
        return perr(P, kw ? kw : verb_token(P),
                    "expected 'points X1 Y1 X2 Y2 ...' after 'model fence'");
    int n = numbers_left(P);
    if (n < 4 || n % 2 || n > 2 * RD_MAX_FENCE_POINTS)
        return perr(P, kw, "'points' needs x y pairs of 2 to %d points, got %d numbers",
                    RD_MAX_FENCE_POINTS, n);
    double v[2 * RD_MAX_FENCE_POINTS];
    if (command_once(P) || read_values(P, kw, n, R_ANY, U_PLAIN, v)) return -1;
    for (int k = 0; k + 1 < n / 2; k++)
        if (hypot(v[2 * k + 2] - v[2 * k], v[2 * k + 3] - v[2 * k + 1]) == 0)
            return perr(P, kw, "fence points %d and %d coincide", k + 1, k + 2);
    memcpy(r->fence, v, (size_t)n * sizeof v[0]);
    r->nfence = n / 2;
    r->fence_line = kw->line;
    return expect_end(P);
}
