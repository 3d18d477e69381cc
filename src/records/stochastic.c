/* rockdem — synthetic earthquake-like records: Kanai-Tajimi filtered white noise shaped by a
 * Saragoni-Hart envelope, with an optional Clough-Penzien high-pass stage.
 *
 * Kanai-Tajimi: the ground is an oscillator (frequency w_g, damping zeta_g) on bedrock shaken
 * by white noise n(t): x'' + 2 zeta_g w_g x' + w_g^2 x = -n; the ground's absolute acceleration
 * is x'' + n = -(2 zeta_g w_g x' + w_g^2 x), whose spectrum peaks near w_g. The noise samples
 * are Gaussian (gsl_rng_mt19937, gsl_ran_gaussian), linear between samples, and the filter is
 * solved exactly (rd_sdof_response). The Kanai-Tajimi spectrum stays finite at zero frequency,
 * which gives a random-walk displacement; Clough & Penzien (1975) pass the result through a
 * second oscillator (w_f, zeta_f) and take its relative acceleration
 * y'' = -(2 zeta_f w_f y' + w_f^2 y) - a_KT, a high-pass of transfer w^2/(w_f^2 - w^2 + 2i zeta_f w_f w)
 * that removes that long-period content. Saragoni-Hart envelope in tau = t/T (Boore 2003 form):
 * e = (e_/eps)^b tau^b exp(-b tau/eps), peak 1 at tau = eps, value eta at tau = 1 when
 * b = -eps ln(eta) / (1 + eps (ln eps - 1)).
 *
 * Folder records/ owns ground motions (records, readers, stochastic generation, intensity
 * measures, SDOF); it may call base/ only.
 */
#include "rockdem/record.h"

#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

/* Valid generator settings: a step between 1 us and 1 s (as for read records, record.c), at
 * most one hour of shaking (the longest recorded strong motion lasts a few minutes) and at most
 * 1e7 samples (240 MB of acceleration, velocity and displacement; 20 s at 0.005 s is 4001). */
#define STOCH_DT_MIN       1e-6
#define STOCH_DT_MAX       1.0
#define STOCH_DURATION_MAX 3600.0
#define STOCH_NPTS_MAX     1e7

void rd_stochastic_defaults(rd_stochastic_def *def)
{
    def->duration = 20.0;
    def->dt = 0.005;
    def->frequency = 2.5;
    def->damping = 0.6;
    def->highpass = 0.25;
    def->highpass_damping = 0.6;
    def->peak_time = 0.2;
    def->end_level = 0.05;
    def->pga = 0.3 * RD_G_STANDARD;
    def->seed = 1;
}

static int check_def(const rd_stochastic_def *d, rd_error *err)
{
    if (!(d->dt > 0.0) || !(d->duration > d->dt) || !isfinite(d->duration))
        return rd_error_set(err, "stochastic record: need 0 < dt (%g s) < duration (%g s)", d->dt,
                            d->duration);
    if (!(d->dt >= STOCH_DT_MIN && d->dt <= STOCH_DT_MAX) || d->duration > STOCH_DURATION_MAX ||
        d->duration / d->dt > STOCH_NPTS_MAX)
        return rd_error_set(
            err,
            "stochastic record: dt %g s must be in [%g, %g] s, the duration %g s at most %g s "
            "and at most %g samples",
            d->dt, STOCH_DT_MIN, STOCH_DT_MAX, d->duration, STOCH_DURATION_MAX, STOCH_NPTS_MAX);
    if (!(d->frequency > 0.0) || !(d->damping > 0.0 && d->damping < 1.0))
        return rd_error_set(
            err, "stochastic record: ground frequency %g Hz must be > 0 and damping %g in (0, 1)",
            d->frequency, d->damping);
    if (!(d->highpass >= 0.0) || !(d->highpass_damping > 0.0 && d->highpass_damping < 1.0))
        return rd_error_set(
            err,
            "stochastic record: high-pass frequency %g Hz must be >= 0 and damping %g in (0, 1)",
            d->highpass, d->highpass_damping);
    if (!(d->peak_time > 0.0 && d->peak_time < 1.0) || !(d->end_level > 0.0 && d->end_level < 1.0))
        return rd_error_set(
            err, "stochastic record: envelope peak time %g and end level %g must be in (0, 1)",
            d->peak_time, d->end_level);
    if (!(d->pga > 0.0) || !isfinite(d->pga))
        return rd_error_set(err, "stochastic record: target PGA %g m/s^2 must be positive", d->pga);
    return 0;
}

/* Saragoni-Hart envelope at tau = t/T for peak time eps and end level eta. */
static double envelope(double tau, double eps, double eta)
{
    double b = -eps * log(eta) / (1.0 + eps * (log(eps) - 1.0));
    return pow(M_E / eps, b) * pow(tau, b) * exp(-b * tau / eps);
}

/* Fill r->acc with unit-variance Gaussian noise from the seeded Mersenne Twister. */
static int white_noise(rd_record *r, unsigned long seed, rd_error *err)
{
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    if (!rng) return rd_error_set(err, "stochastic record: cannot allocate the random generator");
    gsl_rng_set(rng, seed);
    for (size_t i = 0; i < r->npts; i++) r->acc[i] = gsl_ran_gaussian(rng, 1.0);
    gsl_rng_free(rng);
    return 0;
}

/* Replace r->acc by the absolute (Kanai-Tajimi) or relative (Clough-Penzien, relative = 1)
 * acceleration of an oscillator driven by it; r->vel and r->disp are used as scratch. */
static int filter(rd_record *r, double f, double zeta, int relative, rd_error *err)
{
    if (rd_sdof_response(r, 1.0 / f, zeta, r->disp, r->vel, err)) return -1;
    double w = 2.0 * M_PI * f; /* rad/s */
    for (size_t i = 0; i < r->npts; i++)
        r->acc[i] =
            -(2.0 * zeta * w * r->vel[i] + w * w * r->disp[i]) - (relative ? r->acc[i] : 0.0);
    return 0;
}

int rd_record_stochastic(rd_record *r, const rd_stochastic_def *def, rd_error *err)
{
    memset(r, 0, sizeof *r);
    if (check_def(def, err)) return -1;
    size_t n = (size_t)floor(def->duration / def->dt * (1.0 + 1e-12)) + 1;
    if (rd_record_alloc(r, n, def->dt, err)) return -1;
    double T = rd_record_duration(r);
    if (white_noise(r, def->seed, err) || filter(r, def->frequency, def->damping, 0, err) ||
        (def->highpass > 0.0 && filter(r, def->highpass, def->highpass_damping, 1, err))) {
        rd_record_free(r);
        return -1;
    }
    for (size_t i = 0; i < n; i++)
        r->acc[i] *= envelope((double)i * def->dt / T, def->peak_time, def->end_level);
    rd_record_integrate(r);
    snprintf(r->name, sizeof r->name, "kanai-tajimi-%lu", def->seed);
    snprintf(
        r->source, sizeof r->source,
        "Kanai-Tajimi f_g=%g Hz zeta_g=%g, high-pass f_f=%g Hz zeta_f=%g, Saragoni-Hart eps=%g eta=%g, T=%g s, "
        "dt=%g s, seed=%lu",
        def->frequency, def->damping, def->highpass, def->highpass_damping, def->peak_time,
        def->end_level, def->duration, def->dt, def->seed);
    return rd_record_scale_to_pga(r, def->pga, err);
}
