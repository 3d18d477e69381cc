/* rockdem — intensity measures of an acceleration record: peaks, Arias intensity,
 * significant duration and the pseudo-spectral acceleration.
 * Folder records/ owns ground motions (records, readers, stochastic generation, intensity
 * measures, SDOF); it may call base/ only.
 */
#include "rockdem/record.h"

#include <math.h>
#include <stdlib.h>

static double peak_abs(const double *x, size_t n)
{
    double m = 0.0;
    for (size_t i = 0; i < n; i++) m = fmax(m, fabs(x[i]));
    return m;
}

/* Exact integral of a^2 over one step h of a linear a from a0 to a1, m^2/s^3. */
static double step_a2(double a0, double a1, double h)
{
    return h * (a0 * a0 + a0 * a1 + a1 * a1) / 3.0;
}

/* Time s in [0, h] at which the integral of a^2 over a step (a linear from a0 to a1) reaches
 * `target`: with slope m, int_0^s (a0 + m x)^2 dx = ((a0 + m s)^3 - a0^3) / (3 m). */
static double step_crossing(double a0, double a1, double h, double target)
{
    if (target <= 0.0) return 0.0;
    double m = (a1 - a0) / h;
    if (fabs(m) * h <= 1e-6 * fabs(a0)) /* near-constant a: relative error below 1e-6 */
        return fmin(target / (a0 * a0), h);
    return fmin(fmax((cbrt(a0 * a0 * a0 + 3.0 * m * target) - a0) / m, 0.0), h);
}

/* First time at which the cumulative int a^2 dt reaches `level` (m^2/s^3). */
static double husid_time(const rd_record *r, double level)
{
    double cum = 0.0;
    for (size_t i = 0; i + 1 < r->npts; i++) {
        double inc = step_a2(r->acc[i], r->acc[i + 1], r->dt);
        if (cum + inc >= level)
            return (double)i * r->dt + step_crossing(r->acc[i], r->acc[i + 1], r->dt, level - cum);
        cum += inc;
    }
    return rd_record_duration(r);
}

void rd_im_compute(const rd_record *r, rd_im *im)
{
    im->pga = peak_abs(r->acc, r->npts);
    im->pgv = peak_abs(r->vel, r->npts);
    im->pgd = peak_abs(r->disp, r->npts);
    im->pgv_pga = im->pga > 0.0 ? im->pgv / im->pga : 0.0;
    double total = 0.0; /* int a^2 dt, m^2/s^3 */
    for (size_t i = 0; i + 1 < r->npts; i++) total += step_a2(r->acc[i], r->acc[i + 1], r->dt);
    im->arias = M_PI / (2.0 * RD_G_STANDARD) * total;
    im->t5 = total > 0.0 ? husid_time(r, 0.05 * total) : 0.0;
    im->t95 = total > 0.0 ? husid_time(r, 0.95 * total) : 0.0;
    im->d5_95 = im->t95 - im->t5;
}

int rd_im_psa(const rd_record *r, const double *periods, size_t n, double zeta, double *psa,
              rd_error *err)
{
    double *u = malloc(r->npts * sizeof *u);
    if (!u) return rd_error_set(err, "record %s: out of memory for the response spectrum", r->name);
    int status = 0;
    for (size_t k = 0; k < n && status == 0; k++) {
        if (periods[k] <= 0.0) {
            psa[k] = peak_abs(r->acc, r->npts);
            continue;
        }
        double w = 2.0 * M_PI / periods[k]; /* rad/s */
        status = rd_sdof_response(r, periods[k], zeta, u, NULL, err);
        psa[k] = w * w * peak_abs(u, r->npts);
    }
    free(u);
    return status;
}
