/* Tests for the built-in pulses (src/records/motion.c): closed-form integrals against GSL
 * quadrature, values at key instants, direction splitting, zero outside the window, end times. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <gsl/gsl_integration.h>
#include <math.h>
#include <string.h>

#include "rockdem/motion.h"

/* Quadrature workspace size (subintervals) for gsl_integration_qag. */
#define QUAD_LIMIT 1000

static rd_pulse_def pulse(rd_pulse_kind kind)
{
    rd_pulse_def p;
    memset(&p, 0, sizeof p);
    p.kind = kind;
    p.amplitude = 3.7; /* m/s^2 */
    p.frequency = 2.5; /* Hz */
    p.duration = 0.3;  /* s */
    p.cycles = 3.0;
    p.start = 0.4; /* s */
    return p;
}

static double pulse_a(double t, void *ctx)
{
    double a, v, d;
    rd_pulse_eval(ctx, t, &a, &v, &d);
    return a;
}

static double pulse_v(double t, void *ctx)
{
    double a, v, d;
    rd_pulse_eval(ctx, t, &a, &v, &d);
    return v;
}

/* Integral of f over [lo, hi] with GSL's adaptive Gauss-Kronrod rule; epsabs is set from the
 * value's scale because v and d cross zero (a pure relative target cannot be met there). */
static double quad(double (*f)(double, void *), rd_pulse_def *p, double lo, double hi, double scale)
{
    gsl_integration_workspace *w = gsl_integration_workspace_alloc(QUAD_LIMIT);
    gsl_function fn = { f, p };
    double result, abserr;
    int status = gsl_integration_qag(&fn, lo, hi, 1e-13 * scale, 1e-13, QUAD_LIMIT,
                                     GSL_INTEG_GAUSS61, w, &result, &abserr);
    gsl_integration_workspace_free(w);
    assert_int_equal(status, 0);
    return result;
}

/* Integral of f from 0 to t, split where the pulse has a kink or jump (start, apex, end) so
 * that every piece is smooth and the quadrature converges to rounding level. */
static double integrate(double (*f)(double, void *), rd_pulse_def *p, double t, double scale)
{
    double end = rd_pulse_end(p);
    double breaks[5] = { 0.0, p->start, 0.5 * (p->start + end), end, INFINITY };
    double sum = 0.0;
    for (int k = 0; k < 4 && breaks[k] < t; k++)
        sum += quad(f, p, breaks[k], fmin(breaks[k + 1], t), scale);
    return sum;
}

/* v and d equal the quadrature of a and of v at 60 times across and after the pulse. Both sides
 * are exact up to quadrature/rounding error (~1e-13 of the scale), so 1e-9 of the velocity scale
 * a*T and displacement scale a*T*(T + t) is a tight yet safe bound. */
static void check_integrals(rd_pulse_kind kind)
{
    rd_pulse_def p = pulse(kind);
    double end = rd_pulse_end(&p);
    double T = end - p.start;
    for (int k = 1; k <= 60; k++) {
        double t = 1.5 * end * k / 60.0;
        double a, v, d;
        rd_pulse_eval(&p, t, &a, &v, &d);
        double vs = fabs(p.amplitude) * T, ds = vs * (T + t);
        assert_true(fabs(v - integrate(pulse_a, &p, t, vs)) <= 1e-9 * vs);
        assert_true(fabs(d - integrate(pulse_v, &p, t, ds)) <= 1e-9 * ds);
    }
}

static void test_integrals_one_sine(void **state)
{
    (void)state;
    check_integrals(RD_PULSE_ONE_SINE);
}

static void test_integrals_one_cosine(void **state)
{
    (void)state;
    check_integrals(RD_PULSE_ONE_COSINE);
}

static void test_integrals_rectangular(void **state)
{
    (void)state;
    check_integrals(RD_PULSE_RECTANGULAR);
}

static void test_integrals_triangle(void **state)
{
    (void)state;
    check_integrals(RD_PULSE_TRIANGLE);
}

static void test_integrals_harmonic(void **state)
{
    (void)state;
    check_integrals(RD_PULSE_HARMONIC);
}

/* Closed-form values are evaluated in a different arrangement of the same formulas, so only
 * rounding (a few ulp of the scale) separates them: 1e-12 relative. */
#define KEY_TOL 1e-12

static void assert_close(double x, double expect, double scale)
{
    assert_true(fabs(x - expect) <= KEY_TOL * scale);
}

static void test_key_instants_sine_cosine(void **state)
{
    (void)state;
    rd_pulse_def p = pulse(RD_PULSE_ONE_SINE);
    double A = p.amplitude, f = p.frequency, w = 2.0 * M_PI * f, a, v, d;
    rd_pulse_eval(&p, p.start + 0.25 / f, &a, &v, &d); /* quarter period: peak acceleration */
    assert_close(a, A, A);
    rd_pulse_eval(&p, p.start + 0.5 / f, &a, &v, &d); /* half period: peak velocity 2A/w */
    assert_close(v, 2.0 * A / w, A / w);
    rd_pulse_eval(&p, p.start + 1.0 / f, &a, &v, &d); /* end: v = 0, d = A/(w f) */
    assert_close(v, 0.0, A / w);
    assert_close(d, A / (w * f), A / (w * f));

    p = pulse(RD_PULSE_ONE_COSINE);
    rd_pulse_eval(&p, p.start + 0.5 / f, &a, &v, &d); /* half period: a = -A, d = 2A/w^2 */
    assert_close(a, -A, A);
    assert_close(d, 2.0 * A / (w * w), A / (w * w));
    rd_pulse_eval(&p, p.start + 2.0 / f, &a, &v, &d); /* after the end: at rest at d = 0 */
    assert_close(v, 0.0, A / w);
    assert_close(d, 0.0, A / (w * w));
}

static void test_key_instants_rect_triangle(void **state)
{
    (void)state;
    rd_pulse_def p = pulse(RD_PULSE_RECTANGULAR);
    double A = p.amplitude, D = p.duration, a, v, d;
    rd_pulse_eval(&p, p.start + D + 0.2, &a, &v, &d); /* v = A D, d = A D^2/2 + A D * 0.2 */
    assert_close(a, 0.0, A);
    assert_close(v, A * D, A * D);
    assert_close(d, 0.5 * A * D * D + A * D * 0.2, A * D);

    p = pulse(RD_PULSE_TRIANGLE);
    rd_pulse_eval(&p, p.start + 0.5 * D, &a, &v, &d); /* apex: a = A, v = A D/4 */
    assert_close(a, A, A);
    assert_close(v, 0.25 * A * D, A * D);
    rd_pulse_eval(&p, p.start + D, &a, &v, &d); /* end: v = A D/2 (area), d = A D^2/4 */
    assert_close(a, 0.0, A);
    assert_close(v, 0.5 * A * D, A * D);
    assert_close(d, 0.25 * A * D * D, A * D * D);
}

static void test_harmonic_cycles(void **state)
{
    (void)state;
    rd_pulse_def p = pulse(RD_PULSE_HARMONIC);
    double A = p.amplitude, f = p.frequency, w = 2.0 * M_PI * f, a, v, d;
    assert_close(rd_pulse_end(&p), p.start + p.cycles / f, 1.0);
    rd_pulse_eval(&p, p.start + 2.25 / f, &a, &v, &d); /* third crest */
    assert_close(a, A, A);
    rd_pulse_eval(&p, p.start + 10.0, &a, &v, &d); /* after 3 cycles: v = 0, d = 3 A/(w f) */
    assert_close(a, 0.0, A);
    assert_close(v, 0.0, A / w);
    assert_close(d, 3.0 * A / (w * f), A / (w * f));
}

static void test_zero_outside(void **state)
{
    (void)state;
    rd_pulse_kind kinds[] = { RD_PULSE_ONE_SINE, RD_PULSE_ONE_COSINE, RD_PULSE_RECTANGULAR,
                              RD_PULSE_TRIANGLE, RD_PULSE_HARMONIC,   RD_PULSE_NONE };
    for (size_t k = 0; k < sizeof kinds / sizeof kinds[0]; k++) {
        rd_pulse_def p = pulse(kinds[k]);
        double a, v, d;
        rd_pulse_eval(&p, p.start - 0.1, &a, &v, &d);
        assert_true(a == 0.0 && v == 0.0 && d == 0.0);
        rd_pulse_eval(&p, p.start, &a, &v, &d);
        assert_true(v == 0.0 && d == 0.0);
        rd_pulse_eval(&p, rd_pulse_end(&p) + 1.0, &a, &v, &d);
        assert_true(a == 0.0);
    }
    rd_pulse_def none = pulse(RD_PULSE_NONE);
    assert_true(rd_pulse_end(&none) == 0.0);
}

static void test_pulse_end(void **state)
{
    (void)state;
    rd_pulse_def p = pulse(RD_PULSE_ONE_SINE);
    assert_close(rd_pulse_end(&p), 0.4 + 1.0 / 2.5, 1.0);
    p = pulse(RD_PULSE_ONE_COSINE);
    assert_close(rd_pulse_end(&p), 0.4 + 1.0 / 2.5, 1.0);
    p = pulse(RD_PULSE_RECTANGULAR);
    assert_close(rd_pulse_end(&p), 0.7, 1.0);
    p = pulse(RD_PULSE_TRIANGLE);
    assert_close(rd_pulse_end(&p), 0.7, 1.0);
}

static void test_motion_direction(void **state)
{
    (void)state;
    rd_motion_def m;
    memset(&m, 0, sizeof m);
    m.horizontal = pulse(RD_PULSE_ONE_SINE);
    m.horizontal.direction = M_PI / 6.0; /* 30 degrees from +x */
    m.vertical = pulse(RD_PULSE_TRIANGLE);
    m.vertical.direction = 1.0; /* ignored for the vertical pulse */
    double t = 0.53, acc[3], vel[3], disp[3], a, v, d;
    rd_motion_eval(&m, t, acc, vel, disp);
    rd_pulse_eval(&m.horizontal, t, &a, &v, &d);
    assert_close(acc[0], a * sqrt(3.0) / 2.0, fabs(a));
    assert_close(acc[1], a * 0.5, fabs(a));
    assert_close(vel[0], v * sqrt(3.0) / 2.0, fabs(v));
    assert_close(vel[1], v * 0.5, fabs(v));
    assert_close(disp[0], d * sqrt(3.0) / 2.0, fabs(d));
    assert_close(disp[1], d * 0.5, fabs(d));
    rd_pulse_eval(&m.vertical, t, &a, &v, &d);
    assert_true(acc[2] == a && vel[2] == v && disp[2] == d);
    assert_close(rd_motion_end(&m), 0.8, 1.0);

    rd_motion_def none;
    memset(&none, 0, sizeof none);
    assert_true(rd_motion_end(&none) == 0.0);
    rd_motion_eval(&none, 1.0, acc, vel, disp);
    for (int i = 0; i < 3; i++) assert_true(acc[i] == 0.0 && vel[i] == 0.0 && disp[i] == 0.0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_integrals_one_sine),
        cmocka_unit_test(test_integrals_one_cosine),
        cmocka_unit_test(test_integrals_rectangular),
        cmocka_unit_test(test_integrals_triangle),
        cmocka_unit_test(test_integrals_harmonic),
        cmocka_unit_test(test_key_instants_sine_cosine),
        cmocka_unit_test(test_key_instants_rect_triangle),
        cmocka_unit_test(test_harmonic_cycles),
        cmocka_unit_test(test_zero_outside),
        cmocka_unit_test(test_pulse_end),
        cmocka_unit_test(test_motion_direction),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
