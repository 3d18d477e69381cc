/* rockdem — the static rocking and sliding checks of ASCE/SEI 7-10, EN 1990/1998-1 and
 * KTA 2201.1/2201.4 with the load factors of seed 001 Table 2: the body stays seated when the
 * overturning moment m a_h h is no larger than the resisting moment of the factored dead load
 * less the upward seismic share, (dead g - a_up) m b, and does not slide when the required
 * friction coefficient a_h / (dead g - a_up) is no larger than the available one.
 * Folder assess/ owns the seismic assessment of unanchored bodies; it may call base/,
 * records/, scenario/, engine/ and io/.
 */
#include "rockdem/assess.h"
#include "rockdem/record.h"

#include <math.h>

/* Seed 001 Table 2, row by row: dead-load factor; upward seismic load as a share of the
 * horizontal (ASCE 7-10: two thirds of it) or of the vertical acceleration (EN and KTA: 30 %,
 * the combination rule E_z + 0.3 E_x of EN 1998-1 4.3.3.5.2 read the other way; KTA takes
 * the vertical as two thirds of the horizontal where none is given, which the caller's kv
 * does); EN permits neglecting a vertical PGA under 0.25 g (EN 1998-1 4.3.3.5.2 (1)). */
static const rd_code_factors codes[RD_NCODES] = {
    { "ASCE/SEI 7-10", 0.9, 2.0 / 3.0, 0.0, 0.0 },
    { "EN 1990/1998-1", 1.0, 0.0, 0.3, 0.25 },
    { "KTA 2201.1/2201.4", 0.95, 0.0, 0.3, 0.0 },
};

void rd_code_get(rd_code c, rd_code_factors *f) { *f = codes[c]; }

/* Upward acceleration for a_h, a_v (EN's neglect applied when asked). */
static double upward(const rd_code_factors *f, double a_h, double a_v, int neglect)
{
    if (neglect && a_v < f->neglect_v * RD_G_STANDARD) a_v = 0.0;
    return f->up_h * a_h + f->up_v * a_v;
}

/* Allowable PGA where the vertical is dropped below p = lim: p0 (vertical neglected) holds when
 * below lim; else p_v (vertical counted) when at or above lim; else every p below lim passes
 * and none above: lim. */
static double with_neglect(double p_v, double p0, double lim)
{
    return p0 < lim ? p0 : p_v >= lim ? p_v : lim;
}

void rd_assess_static(const rd_assess_body *b, rd_code c, double a_h, double a_v, double kv,
                      int neglect, double g, rd_static_check *out)
{
    rd_code_factors f;
    rd_code_get(c, &f);
    double hold = f.dead * g - (out->a_up = upward(&f, a_h, a_v, neglect)); /* m/s^2 */
    out->m_over = b->mass * a_h * b->h;
    out->m_resist = b->mass * hold * b->b;
    out->rock_margin = out->m_over > 0 ? out->m_resist / out->m_over : INFINITY;
    out->mu_required = hold > 0 ? a_h / hold : INFINITY;
    out->slide_margin = out->mu_required > 0 ? b->mu / out->mu_required : INFINITY;
    /* allowable PGA p with a_v = kv p: p h = (dead g - (up_h + up_v kv) p) b, and
       p = mu (dead g - (up_h + up_v kv) p); EN's neglect applies when kv p < 0.25 g */
    double k = f.up_h + f.up_v * kv;
    out->pga_rock = f.dead * g * b->b / (b->h + k * b->b);
    out->pga_slide = b->mu * f.dead * g / (1.0 + b->mu * k);
    if (neglect && f.neglect_v > 0) {
        double lim = f.neglect_v * RD_G_STANDARD / fmax(kv, 1e-300); /* p at which a_v = 0.25 g */
        out->pga_rock =
            with_neglect(out->pga_rock, f.dead * g * b->b / (b->h + f.up_h * b->b), lim);
        out->pga_slide =
            with_neglect(out->pga_slide, b->mu * f.dead * g / (1.0 + b->mu * f.up_h), lim);
    }
}
