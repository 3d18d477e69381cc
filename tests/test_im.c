/* Tests for intensity measures (src/records/im.c) and the exact oscillator response
 * (src/records/sdof.c): peaks and Arias intensity of a sampled sine against closed forms,
 * significant duration against a root of the analytic Husid curve, the Nigam-Jennings recurrence
 * against a GSL ODE solution, and spectral acceleration against steady-state amplification. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>
#include <gsl/gsl_roots.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "rockdem/record.h"

#define AMP  2.0 /* sine amplitude, m/s^2 */
#define FREQ 1.0 /* sine frequency, Hz */

/* A * sin(2 pi f t) sampled at dt for `cycles` whole periods. */
static rd_record sine_record(double amp, double f, double cycles, double dt)
{
    rd_record r;
    rd_error err;
    size_t n = (size_t)llround(cycles / f / dt) + 1;
    assert_int_equal(rd_record_alloc(&r, n, dt, &err), 0);
    for (size_t i = 0; i < n; i++) r.acc[i] = amp * sin(2.0 * M_PI * f * (double)i * dt);
    rd_record_integrate(&r);
    return r;
}

/* Peaks of a 5-cycle sine at dt = 1 ms. Closed forms: PGA = A; v = A/w (1 - cos wt) so
 * PGV = 2A/w; v >= 0 so d grows and PGD = d(T) = 5 A/(w f). The record is read as piecewise
 * linear, whose trapezoid integrals differ from the sine's by O((w dt)^2 / 12) = 3.3e-6;
 * 1e-5 relative covers that and fails for any wrong factor. */
static void test_peaks_of_sine(void **state)
{
    (void)state;
    rd_record r = sine_record(AMP, FREQ, 5.0, 0.001);
    rd_im im;
    rd_im_compute(&r, &im);
    double w = 2.0 * M_PI * FREQ;
    assert_true(fabs(im.pga - AMP) <= 1e-5 * AMP);
    assert_true(fabs(im.pgv - 2.0 * AMP / w) <= 1e-5 * 2.0 * AMP / w);
    assert_true(fabs(im.pgd - 5.0 * AMP / (w * FREQ)) <= 1e-5 * 5.0 * AMP / (w * FREQ));
    assert_true(fabs(im.pgv_pga - im.pgv / im.pga) <= 1e-15);
    rd_record_free(&r);
}

/* Arias intensity pi/(2g) A^2 T/2 for a sine over whole periods T. The squared linear
 * interpolant of the sine integrates to the sine's value within O((w dt)^2) = 4e-5 at
 * dt = 1 ms; 1e-4 relative. */
static void test_arias_of_sine(void **state)
{
    (void)state;
    rd_record r = sine_record(AMP, FREQ, 5.0, 0.001);
    rd_im im;
    rd_im_compute(&r, &im);
    double expect = M_PI / (2.0 * 9.80665) * AMP * AMP * 5.0 / 2.0;
    assert_true(fabs(im.arias - expect) <= 1e-4 * expect);
    rd_record_free(&r);
}

/* Husid fraction of a sine over 3 whole periods T: H(t) = (t/2 - sin(2wt)/(4w)) / (T/2). */
typedef struct husid_ctx {
    double w, T, level;
} husid_ctx;

static double husid_minus_level(double t, void *p)
{
    const husid_ctx *c = p;
    return (0.5 * t - sin(2.0 * c->w * t) / (4.0 * c->w)) / (0.5 * c->T) - c->level;
}

static double husid_root(husid_ctx *c)
{
    gsl_root_fsolver *s = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
    gsl_function fn = { husid_minus_level, c };
    gsl_root_fsolver_set(s, &fn, 0.0, c->T);
    double lo, hi;
    do {
        gsl_root_fsolver_iterate(s);
        lo = gsl_root_fsolver_x_lower(s);
        hi = gsl_root_fsolver_x_upper(s);
    } while (hi - lo > 1e-13);
    gsl_root_fsolver_free(s);
    return 0.5 * (lo + hi);
}

/* t5, t95 of the sampled sine against the roots of the analytic Husid curve. The record's
 * cumulative a^2 differs from the sine's by O((w dt)^2) relative (4e-5 at 1 ms), moving the
 * crossing by about that fraction of T / 0.9 (H' ~ 1/T): 1e-4 s is a safe bound here. */
static void test_significant_duration_sine(void **state)
{
    (void)state;
    rd_record r = sine_record(AMP, FREQ, 3.0, 0.001);
    rd_im im;
    rd_im_compute(&r, &im);
    husid_ctx c = { 2.0 * M_PI * FREQ, 3.0 / FREQ, 0.05 };
    double t5 = husid_root(&c);
    c.level = 0.95;
    double t95 = husid_root(&c);
    assert_true(fabs(im.t5 - t5) <= 1e-4);
    assert_true(fabs(im.t95 - t95) <= 1e-4);
    assert_true(fabs(im.d5_95 - (t95 - t5)) <= 2e-4);
    rd_record_free(&r);
}

/* Constant acceleration over [0, T] (read as linear, so exact): the Husid curve is t/T and
 * D5-95 = 0.9 T; the crossings solve a cubic in closed form, exact to rounding (1e-12 s). Also
 * a ramp a = t: cumulative t^3/3 gives t5 = T 0.05^(1/3), t95 = T 0.95^(1/3). */
static void test_significant_duration_closed_forms(void **state)
{
    (void)state;
    rd_record r;
    rd_error err;
    assert_int_equal(rd_record_alloc(&r, 101, 0.1, &err), 0);
    for (size_t i = 0; i < r.npts; i++) r.acc[i] = 1.5;
    rd_record_integrate(&r);
    rd_im im;
    rd_im_compute(&r, &im);
    assert_true(fabs(im.t5 - 0.5) <= 1e-12 && fabs(im.t95 - 9.5) <= 1e-12 &&
                fabs(im.d5_95 - 9.0) <= 1e-12);
    for (size_t i = 0; i < r.npts; i++) r.acc[i] = (double)i * r.dt;
    rd_record_integrate(&r);
    rd_im_compute(&r, &im);
    assert_true(fabs(im.t5 - 10.0 * cbrt(0.05)) <= 1e-12);
    assert_true(fabs(im.t95 - 10.0 * cbrt(0.95)) <= 1e-12);
    rd_record_free(&r);
}

/* --- oscillator ------------------------------------------------------------------------------- */

typedef struct sdof_ctx {
    const rd_record *r;
    double w, zeta;
} sdof_ctx;

static int sdof_rhs(double t, const double y[], double dydt[], void *p)
{
    const sdof_ctx *c = p;
    double a, v, d;
    rd_record_eval(c->r, t, &a, &v, &d);
    dydt[0] = y[1];
    dydt[1] = -2.0 * c->zeta * c->w * y[1] - c->w * c->w * y[0] - a;
    return GSL_SUCCESS;
}

static double irregular(size_t i)
{
    return 3.0 * sin(0.7 * (double)i) + 1.3 * cos(2.3 * (double)i * (double)i) - 0.4; /* m/s^2 */
}

/* The recurrence is exact for piecewise-linear input, so it must match an independent
 * high-order ODE solution (gsl rk8pd, 1e-12 tolerances, restarted at every sample where the
 * input has a kink) to ~1e-9 of the response scale, for a step not small against the period
 * (dt = 0.04 s, T = 0.3 s) and for zero damping. */
static void check_sdof_vs_ode(double period, double zeta)
{
    rd_record r;
    rd_error err;
    assert_int_equal(rd_record_alloc(&r, 80, 0.04, &err), 0);
    for (size_t i = 0; i < r.npts; i++) r.acc[i] = irregular(i);
    rd_record_integrate(&r);
    double *u = malloc(r.npts * sizeof *u), *du = malloc(r.npts * sizeof *du);
    assert_int_equal(rd_sdof_response(&r, period, zeta, u, du, &err), 0);
    sdof_ctx c = { &r, 2.0 * M_PI / period, zeta };
    gsl_odeiv2_system sys = { sdof_rhs, NULL, 2, &c };
    gsl_odeiv2_driver *drv =
        gsl_odeiv2_driver_alloc_y_new(&sys, gsl_odeiv2_step_rk8pd, 1e-4, 1e-13, 1e-13);
    double y[2] = { 0.0, 0.0 }, t = 0.0, scale = 3.0 / (c.w * c.w);
    for (size_t i = 1; i < r.npts; i++) {
        gsl_odeiv2_driver_reset(drv);
        assert_int_equal(gsl_odeiv2_driver_apply(drv, &t, (double)i * r.dt, y), GSL_SUCCESS);
        assert_true(fabs(u[i] - y[0]) <= 1e-9 * scale);
        assert_true(fabs(du[i] - y[1]) <= 1e-9 * scale * c.w);
    }
    gsl_odeiv2_driver_free(drv);
    free(u), free(du);
    rd_record_free(&r);
}

static void test_sdof_matches_ode(void **state)
{
    (void)state;
    check_sdof_vs_ode(0.3, 0.05);
    check_sdof_vs_ode(0.3, 0.0);
    check_sdof_vs_ode(2.0, 0.2);
}

/* Steady-state amplitude of u'' + 2 zeta w u' + w^2 u = -A sin(W t): A / w^2 / sqrt((1-r^2)^2 +
 * (2 zeta r)^2), r = W/w. A 1 Hz sine for 80 s; the transient decays as exp(-zeta w t) (below
 * 4e-6 after 75 s for the slowest case, T = 2 s), so the largest |u| over the last 5 s is the
 * steady amplitude. Error sources: the linear interpolation of the sampled sine (its 1 Hz
 * component is scaled by sinc^2(W dt/2) ~ 1 - 8e-5 at dt = 5 ms) and picking the peak at a
 * sample (1 - cos(W dt/2) ~ 1.2e-4): 5e-4 relative bounds both. */
static void test_steady_state_amplification(void **state)
{
    (void)state;
    double zeta = 0.05, periods[3] = { 0.5, 1.0, 2.0 };
    rd_record r = sine_record(AMP, FREQ, 80.0, 0.005);
    double *u = malloc(r.npts * sizeof *u);
    rd_error err;
    for (int k = 0; k < 3; k++) {
        double w = 2.0 * M_PI / periods[k], ratio = 2.0 * M_PI * FREQ / w;
        double steady = AMP / (w * w) / hypot(1.0 - ratio * ratio, 2.0 * zeta * ratio);
        assert_int_equal(rd_sdof_response(&r, periods[k], zeta, u, NULL, &err), 0);
        double peak = 0.0;
        for (size_t i = r.npts - 1000; i < r.npts; i++) peak = fmax(peak, fabs(u[i]));
        assert_true(fabs(peak - steady) <= 5e-4 * steady);
    }
    free(u);
    rd_record_free(&r);
}

/* At resonance (T = 1 s for a 1 Hz sine) the response grows monotonically from rest towards
 * A/(2 zeta w^2) (the transient shares the frequency and only decays), so the pseudo-spectral
 * acceleration over the whole record is A/(2 zeta) = 10 A; 5e-4 relative as above (the
 * remaining transient, exp(-zeta w 80 s) = 1e-11, is negligible). T = 0 gives the PGA. */
static void test_psa_resonance(void **state)
{
    (void)state;
    rd_record r = sine_record(AMP, FREQ, 80.0, 0.005);
    rd_error err;
    double periods[2] = { 1.0, 0.0 }, psa[2];
    assert_int_equal(rd_im_psa(&r, periods, 2, 0.05, psa, &err), 0);
    assert_true(fabs(psa[0] - AMP / (2.0 * 0.05)) <= 5e-4 * AMP / (2.0 * 0.05));
    assert_true(fabs(psa[1] - AMP) <= 1e-9 * AMP);
    assert_int_equal(rd_im_psa(&r, periods, 1, 1.0, psa, &err), -1);
    assert_non_null(strstr(err.msg, "damping ratio 1 outside [0, 1)"));
    rd_record_free(&r);
}

static void test_zero_record(void **state)
{
    (void)state;
    rd_record r;
    rd_error err;
    assert_int_equal(rd_record_alloc(&r, 10, 0.01, &err), 0);
    rd_im im;
    rd_im_compute(&r, &im);
    assert_true(im.pga == 0.0 && im.pgv_pga == 0.0 && im.arias == 0.0 && im.d5_95 == 0.0);
    rd_record_free(&r);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_peaks_of_sine),
        cmocka_unit_test(test_arias_of_sine),
        cmocka_unit_test(test_significant_duration_sine),
        cmocka_unit_test(test_significant_duration_closed_forms),
        cmocka_unit_test(test_sdof_matches_ode),
        cmocka_unit_test(test_steady_state_amplification),
        cmocka_unit_test(test_psa_resonance),
        cmocka_unit_test(test_zero_record),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
