/* rockdem — assembly builders: columns and stacks as lists of member shapes (builders.h).
 * Folder geometry/ owns solids, their mass properties, subcontact points and assembly builders;
 * it may call base/ only.
 */
#include "geometry/builders.h"

#include <stdio.h>

/* An echinus widens from the shaft's top radius to this multiple of it: the Doric capitals of
 * the Parthenon flare by roughly 30 % over the shaft (Coulton, Greek Architects at Work). */
#define RD_CAPITAL_FLARE 1.3

int rd_column_members(const rd_column_spec *c) { return c->drums + 3; }

static rd_body_def brick(double w, double h)
{
    return (rd_body_def){ .shape = RD_SHAPE_BRICK, .size = { w, w, h } };
}

static rd_body_def drum(int sides, double r_bottom, double r_top, double h)
{
    return (rd_body_def){ .shape = RD_SHAPE_PRISM,
                          .sides = sides,
                          .radius = r_bottom,
                          .radius_top = r_top,
                          .size = { 0, 0, h } };
}

int rd_build_column(const rd_column_spec *c, rd_body_def *out, char (*suffix)[16])
{
    int n = 0;
    if (c->plinth[0] > 0) {
        snprintf(suffix[n], sizeof suffix[n], "plinth");
        out[n++] = brick(c->plinth[0], c->plinth[1]);
    }
    double r0 = c->diameter / 2, r = r0;
    for (int i = 1; i <= c->drums; i++) {
        double top = r0 * (1 - (1 - c->taper) * i / c->drums);
        snprintf(suffix[n], sizeof suffix[n], "d%d", i);
        out[n++] = drum(c->sides, r, top, c->height);
        r = top;
    }
    if (c->capital > 0) {
        snprintf(suffix[n], sizeof suffix[n], "capital");
        out[n++] = drum(c->sides, r, RD_CAPITAL_FLARE * r, c->capital);
    }
    if (c->abacus[0] > 0) {
        snprintf(suffix[n], sizeof suffix[n], "abacus");
        out[n++] = brick(c->abacus[0], c->abacus[1]);
    }
    return n;
}

void rd_build_stack(const double lower[3], const double upper[3], rd_body_def out[2],
                    char suffix[2][16])
{
    out[0] = (rd_body_def){ .shape = RD_SHAPE_BRICK, .size = { lower[0], lower[1], lower[2] } };
    out[1] = (rd_body_def){ .shape = RD_SHAPE_BRICK, .size = { upper[0], upper[1], upper[2] } };
    snprintf(suffix[0], sizeof suffix[0], "lower");
    snprintf(suffix[1], sizeof suffix[1], "upper");
}
