/* rockdem — exact response of a damped linear oscillator to a sampled ground acceleration.
 *
 * u'' + 2 zeta w u' + w^2 u = -a(t) with a(t) linear between samples has a closed-form
 * solution over each step; Nigam & Jennings (1969, BSSA 59(2)) write it as the recurrence
 *   [u; u']_{i+1} = A [u; u']_i + B [a_i; a_{i+1}],
 * exact for any step (no stability or accuracy limit on dt/period).
 *
 * Folder records/ owns ground motions (records, readers, stochastic generation, intensity
 * measures, SDOF); it may call base/ only.
 */
#include "rockdem/record.h"

#include <math.h>

/* Step matrices A (2x2) and B (2x2) of the recurrence for w (rad/s), zeta, step h (s). */
static void nigam_jennings(double w, double zeta, double h, double A[2][2], double B[2][2])
{
    double q = sqrt(1.0 - zeta * zeta), wd = w * q; /* damped frequency, rad/s */
    double e = exp(-zeta * w * h), s = sin(wd * h), c = cos(wd * h);
    double w2 = w * w, t1 = (2.0 * zeta * zeta - 1.0) / (w2 * h), t2 = 2.0 * zeta / (w2 * w * h);
    double cs = c - zeta / q * s, ws = wd * s + zeta * w * c;
    A[0][0] = e * (zeta / q * s + c);
    A[0][1] = e * s / wd;
    A[1][0] = -w / q * e * s;
    A[1][1] = e * cs;
    B[0][0] = e * ((t1 + zeta / w) * s / wd + (t2 + 1.0 / w2) * c) - t2;
    B[0][1] = -e * (t1 * s / wd + t2 * c) - 1.0 / w2 + t2;
    B[1][0] = e * ((t1 + zeta / w) * cs - (t2 + 1.0 / w2) * ws) + 1.0 / (w2 * h);
    B[1][1] = -e * (t1 * cs - t2 * ws) - 1.0 / (w2 * h);
}

int rd_sdof_response(const rd_record *r, double period, double zeta, double *u, double *du,
                     rd_error *err)
{
    if (!(period > 0.0) || !isfinite(period))
        return rd_error_set(err, "oscillator period %g s must be positive", period);
    if (!(zeta >= 0.0 && zeta < 1.0))
        return rd_error_set(err, "oscillator damping ratio %g outside [0, 1)", zeta);
    double A[2][2], B[2][2];
    nigam_jennings(2.0 * M_PI / period, zeta, r->dt, A, B);
    double x = 0.0, v = 0.0; /* m, m/s: at rest at t = 0 */
    for (size_t i = 0; i < r->npts; i++) {
        if (i > 0) {
            double a0 = r->acc[i - 1], a1 = r->acc[i];
            double xn = A[0][0] * x + A[0][1] * v + B[0][0] * a0 + B[0][1] * a1;
            v = A[1][0] * x + A[1][1] * v + B[1][0] * a0 + B[1][1] * a1;
            x = xn;
        }
        if (u) u[i] = x;
        if (du) du[i] = v;
    }
    return 0;
}
