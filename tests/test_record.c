/* Tests for acceleration records: the .AT2 and text/CSV readers (and every error message),
 * integration, evaluation, scaling, resampling, padding, baseline correction and the seeded
 * stochastic generator. Input files are written into a mkdtemp() directory by the tests. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "rockdem/record.h"

static char g_dir[64]; /* the mkdtemp() directory */
static char g_path[RD_PATH_MAX];

static int setup_dir(void **state)
{
    (void)state;
    snprintf(g_dir, sizeof g_dir, "/tmp/rockdem_record_XXXXXX");
    return mkdtemp(g_dir) ? 0 : -1;
}

static int remove_dir(void **state)
{
    (void)state;
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", g_dir);
    return system(cmd) == 0 ? 0 : -1;
}

/* Write `text` to <dir>/<name>; returns the path (valid until the next call). */
static const char *write_file(const char *name, const char *text)
{
    snprintf(g_path, sizeof g_path, "%s/%s", g_dir, name);
    FILE *f = fopen(g_path, "w");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
    return g_path;
}

/* The error must be "<path>:<line>: ..." and contain `what`. */
static void assert_error(const rd_error *err, const char *path, long line, const char *what)
{
    char prefix[RD_PATH_MAX + 32];
    snprintf(prefix, sizeof prefix, "%s:%ld: ", path, line);
    if (strncmp(err->msg, prefix, strlen(prefix)) != 0 || !strstr(err->msg, what))
        fail_msg("error \"%s\" is not \"%s...%s...\"", err->msg, prefix, what);
}

/* --- .AT2 ------------------------------------------------------------------------------------ */

static const double at2_g[7] = { 0.1, -0.2, 0.003, 4e-5, 0.0, -1.5e-3, 0.25 }; /* the values, g */

static void check_at2(const char *path, double dt)
{
    rd_record r;
    rd_error err = { "" };
    assert_int_equal(rd_record_read_at2(&r, path, &err), 0);
    assert_int_equal(r.npts, 7);
    assert_true(r.dt == dt);
    /* Same decimal strings and the same single multiplication: bit-identical. */
    for (int i = 0; i < 7; i++) assert_true(r.acc[i] == at2_g[i] * RD_G_STANDARD);
    assert_string_equal(r.source, "Imperial Valley-02, 5/19/1940, El Centro Array #9, 180");
    assert_true(strstr(path, r.name) && r.name[0] != '/');
    rd_record_free(&r);
}

static void test_at2_keyed_header(void **state)
{
    (void)state;
    check_at2(write_file("keyed.AT2",
                         "PEER NGA STRONG MOTION DATABASE RECORD\n"
                         "Imperial Valley-02, 5/19/1940, El Centro Array #9, 180\n"
                         "ACCELERATION TIME SERIES IN UNITS OF G\n"
                         "NPTS=     7, DT=   .0050 SEC\n"
                         "  .1000000E+00 -.2000000E+00  .3000000E-02  .4000000E-04  .0000000E+00\n"
                         " -.1500000E-02  .2500000E+00\n"),
              0.005);
}

static void test_at2_positional_header(void **state)
{
    (void)state;
    check_at2(write_file("positional.AT2",
                         "PEER NGA STRONG MOTION DATABASE RECORD\r\n"
                         "Imperial Valley-02, 5/19/1940, El Centro Array #9, 180\r\n"
                         "ACCELERATION TIME SERIES IN UNITS OF G\r\n"
                         "7    0.0100    NPTS, DT\r\n"
                         "0.1 -0.2 0.003\r\n4E-5 0\r\n-1.5e-3\r\n0.25\r\n"),
              0.01);
}

#define AT2_HEAD "PEER\nevent\nUNITS OF G\n"

static void expect_at2_error(const char *name, const char *text, long line, const char *what)
{
    rd_record r;
    rd_error err = { "" };
    const char *path = write_file(name, text);
    assert_int_equal(rd_record_read_at2(&r, path, &err), -1);
    assert_error(&err, path, line, what);
    assert_null(r.acc);
}

static void test_at2_errors(void **state)
{
    (void)state;
    expect_at2_error("e1.AT2", AT2_HEAD "7 values follow\n0.1\n", 4, "missing NPTS and DT");
    expect_at2_error("e2.AT2", AT2_HEAD "NPTS= 3, DT= .01 SEC\n0.1 0.2\n", 5,
                     "expected 3 values (NPTS), found 2");
    expect_at2_error("e3.AT2", AT2_HEAD "NPTS= 3, DT= .01 SEC\n0.1 0.2\n0.3\n0.4 0.5\n", 7,
                     "expected 3 values (NPTS), found 5");
    expect_at2_error("e4.AT2", AT2_HEAD "NPTS= 3, DT= .01 SEC\n0.1\n0.2 0.3x 0.4\n", 6,
                     "non-numeric value '0.3x'");
    expect_at2_error("e5.AT2", AT2_HEAD "NPTS= 3, DT= 0.0 SEC\n0.1 0.2 0.3\n", 4,
                     "DT must be in [1e-06, 1] s, found 0 s");
    expect_at2_error("e6.AT2", AT2_HEAD "3  -0.01  NPTS, DT\n0.1 0.2 0.3\n", 4,
                     "DT must be in [1e-06, 1] s, found -0.01 s");
    /* issue 17: a step of 1e300 s was accepted and failed later as "a record is zero" */
    expect_at2_error("e10.AT2", AT2_HEAD "NPTS= 3, DT= 1e300 SEC\n0.1 0.2 0.3\n", 4,
                     "DT must be in [1e-06, 1] s, found 1e+300 s");
    expect_at2_error("e11.AT2", AT2_HEAD "NPTS= 1e300, DT= .01 SEC\n0.1\n", 4,
                     "NPTS must be a whole number in [1, 1e+09], found 1e+300");
    expect_at2_error("e7.AT2", "PEER\nevent\n", 2, "expected 4 header lines, found 2");
    expect_at2_error("e8.AT2", AT2_HEAD "NPTS= 2.5, DT= .01 SEC\n0.1 0.2\n", 4,
                     "NPTS must be a whole number in [1, 1e+09]");
    expect_at2_error("e9.AT2", AT2_HEAD "NPTS= 2, DT= .01 SEC\n0.1 nan\n", 5,
                     "non-numeric value 'nan'");
    /* a header number with a junk suffix was read as its prefix */
    expect_at2_error("e12.AT2", AT2_HEAD "NPTS=  3x, DT=   .0100 SEC\n0.1 0.2 0.3\n", 4,
                     "NPTS '3x' is not a number");
    expect_at2_error("e13.AT2", AT2_HEAD "NPTS=  3, DT=   .0100x SEC\n0.1 0.2 0.3\n", 4,
                     "DT '.0100x' is not a number");
    expect_at2_error("e14.AT2", AT2_HEAD "3  .0100x  NPTS, DT\n0.1 0.2 0.3\n", 4,
                     "DT '.0100x' is not a number");
    /* a sample of 1e308 g was accepted (Arias -nan, then "contact forces blew up") */
    expect_at2_error("e15.AT2", AT2_HEAD "NPTS= 3, DT= .01 SEC\n0.1\n1e308 0.3\n", 6,
                     "acceleration '1e308' g is outside the valid |acceleration| <= 1e+06 m/s^2");
    expect_at2_error("e16.AT2", AT2_HEAD "NPTS= 3, DT= .01 SEC\n0.1 -1e200 0.3\n", 5,
                     "acceleration '-1e200' g is outside");

    rd_record r;
    rd_error err = { "" };
    char missing[RD_PATH_MAX];
    snprintf(missing, sizeof missing, "%s/absent.AT2", g_dir);
    assert_int_equal(rd_record_read_at2(&r, missing, &err), -1);
    assert_true(strncmp(err.msg, missing, strlen(missing)) == 0 && strstr(err.msg, "cannot open"));
}

/* --- text / CSV ------------------------------------------------------------------------------ */

static void test_csv_two_columns(void **state)
{
    (void)state;
    const char *path =
        write_file("two.csv", "# a comment\ntime,acc\n0.00,10\n0.01,-20\n\n0.02,30.5\n0.03,0\n");
    rd_record r;
    rd_error err = { "" };
    assert_int_equal(rd_record_read_text(&r, path, RD_UNIT_CM_S2, 0.0, &err), 0);
    assert_int_equal(r.npts, 4);
    assert_true(fabs(r.dt - 0.01) <= 1e-15); /* (0.03 - 0.00)/3 in binary: a few ulp */
    double expect[4] = { 10 * 0.01, -20 * 0.01, 30.5 * 0.01, 0.0 };
    for (int i = 0; i < 4; i++) assert_true(r.acc[i] == expect[i]);
    rd_record_free(&r);
    /* A matching given dt is accepted, a different one refused. */
    assert_int_equal(rd_record_read_text(&r, path, RD_UNIT_CM_S2, 0.01, &err), 0);
    rd_record_free(&r);
    assert_int_equal(rd_record_read_text(&r, path, RD_UNIT_CM_S2, 0.02, &err), -1);
    assert_error(&err, path, 3, "time step 0.01 s in the file, 0.02 s given");
}

static void test_text_one_column(void **state)
{
    (void)state;
    const char *path = write_file("one.txt", "0.5\n -1.25 \n\t2\n");
    rd_record r;
    rd_error err = { "" };
    assert_int_equal(rd_record_read_text(&r, path, RD_UNIT_M_S2, 0.02, &err), 0);
    assert_int_equal(r.npts, 3);
    assert_true(r.dt == 0.02 && r.acc[0] == 0.5 && r.acc[1] == -1.25 && r.acc[2] == 2.0);
    rd_record_free(&r);
    assert_int_equal(rd_record_read_text(&r, path, RD_UNIT_G, 0.02, &err), 0);
    assert_true(r.acc[1] == -1.25 * RD_G_STANDARD);
    rd_record_free(&r);
    /* the samples' bound is in m/s^2: 2e5 m/s^2 passes, 2e5 g does not */
    path = write_file("big.txt", "0.5\n2e5\n");
    assert_int_equal(rd_record_read_text(&r, path, RD_UNIT_M_S2, 0.02, &err), 0);
    rd_record_free(&r);
    assert_int_equal(rd_record_read_text(&r, path, RD_UNIT_G, 0.02, &err), -1);
    assert_error(&err, path, 2, "acceleration '2e5' is outside");
}

static void expect_text_error(const char *name, const char *text, double dt, long line,
                              const char *what)
{
    rd_record r;
    rd_error err = { "" };
    const char *path = write_file(name, text);
    assert_int_equal(rd_record_read_text(&r, path, RD_UNIT_M_S2, dt, &err), -1);
    assert_error(&err, path, line, what);
    assert_null(r.acc);
}

static void test_text_errors(void **state)
{
    (void)state;
    expect_text_error("t1.csv", "t,a\n0,1\n0.01,2\n0.03,3\n", 0.0, 4,
                      "non-uniform time step: 0.02 s here");
    expect_text_error("t2.csv", "0,1\n0.01,2\n0.01,3\n", 0.0, 3, "does not increase");
    expect_text_error("t3.csv", "0,1\n0.01,2\n0.005,3\n", 0.0, 3,
                      "time step -0.005 s must be positive");
    expect_text_error("t4.csv", "t,a\n0,1\n0.01,abc\n", 0.0, 3, "non-numeric value 'abc'");
    expect_text_error("t5.txt", "1\n2\n", 0.0, 1, "needs a time step dt > 0, got 0");
    expect_text_error("t6.txt", "1\n2\n", -0.01, 1, "needs a time step dt > 0, got -0.01");
    expect_text_error("t7.csv", "0,1\n0.01\n", 0.0, 2, "expected 2 columns as on line 1, found 1");
    expect_text_error("t8.csv", "0,1,2\n", 0.0, 1, "expected 1 or 2 columns");
    /* an empty file (or one without numbers) has no line to point at: the message says so */
    rd_record r;
    rd_error err;
    const char *path = write_file("t9.csv", "# only a comment\n");
    assert_int_equal(rd_record_read_text(&r, path, RD_UNIT_G, 0.0, &err), -1);
    assert_true(strstr(err.msg, "t9.csv: no data (1 line, none with numbers)") != NULL);
    /* a folder, device or pipe is refused before it is opened (/dev/zero never ends, a pipe
       without a writer blocks the open) */
    snprintf(g_path, sizeof g_path, "%s/dir.AT2", g_dir);
    assert_int_equal(mkdir(g_path, 0700), 0);
    assert_int_equal(rd_record_read_at2(&r, g_path, &err), -1);
    assert_true(strstr(err.msg, "dir.AT2: not a regular file (a device, folder or pipe)") != NULL);
    assert_int_equal(rd_record_read_at2(&r, "/dev/zero", &err), -1);
    assert_true(strstr(err.msg, "/dev/zero: not a regular file") != NULL);
    rmdir(g_path);
    path = write_file("t9.AT2", "");
    assert_int_equal(rd_record_read_at2(&r, path, &err), -1);
    assert_true(strstr(err.msg, "t9.AT2: empty file: expected 4 header lines") != NULL);
    path = write_file("t11.csv", "0,1\n1e300,2\n");
    assert_int_equal(rd_record_read_text(&r, path, RD_UNIT_G, 0.0, &err), -1);
    assert_true(strstr(err.msg, "t11.csv:1: time step 1e+300 s is outside [1e-06, 1] s") != NULL);
    expect_text_error("t10.csv", "0,1\n", 0.0, 1, "one sample cannot define a time step");
    /* an absurd sample (m/s^2 here) */
    expect_text_error("t12.txt", "0.1\n1e308\n0.2\n", 0.01, 2,
                      "acceleration '1e308' is outside the valid |acceleration| <= 1e+06 m/s^2");
    expect_text_error("t13.csv", "0,0.1\n0.01,2e6\n", 0.0, 2, "acceleration '2e6' is outside");
    /* a bad first data row was dropped as a header */
    expect_text_error("t14.txt", "0.1x 0.2\n0.01 0.1\n0.02 0.1\n", 0.0, 1,
                      "non-numeric value '0.1x'");
    expect_text_error("t15.txt", "O 0.2\n0.01 0.1\n0.02 0.1\n", 0.0, 1,
                      "non-numeric value 'O' (a row of 2 fields like line 2, not a header)");
    expect_text_error("t16.txt", "0.1x\n0.1\n0.2\n", 0.01, 1, "non-numeric value '0.1x'");
    expect_text_error("t17.txt", ".5e\n0.1\n0.2\n", 0.01, 1, "non-numeric value '.5e'");
}

/* --- integration, evaluation, scaling, resampling, padding ---------------------------------- */

/* A record holding samples of f at step dt over [0, T], integrated. */
static rd_record sampled(double (*f)(double), double T, double dt)
{
    rd_record r;
    rd_error err;
    size_t n = (size_t)llround(T / dt) + 1;
    assert_int_equal(rd_record_alloc(&r, n, dt, &err), 0);
    for (size_t i = 0; i < n; i++) r.acc[i] = f((double)i * dt);
    rd_record_integrate(&r);
    return r;
}

static double ramp(double t)
{
    return 3.0 * t - 1.0; /* m/s^2: linear, so the piecewise-linear reading is exact */
}

/* For a = 3t - 1 the integrals are v = 1.5 t^2 - t, d = 0.5 t^3 - 0.5 t^2; the recurrence is exact
 * for linear a, so only rounding (1e-12 of the scale) separates them. */
static void test_integrate_and_eval_exact(void **state)
{
    (void)state;
    rd_record r = sampled(ramp, 2.0, 0.1);
    for (int k = 0; k <= 57; k++) {
        double t = 2.0 * k / 57.0, a, v, d;
        rd_record_eval(&r, t, &a, &v, &d);
        assert_true(fabs(a - ramp(t)) <= 1e-12 * 5.0);
        assert_true(fabs(v - (1.5 * t * t - t)) <= 1e-12 * 4.0);
        assert_true(fabs(d - (0.5 * t * t * t - 0.5 * t * t)) <= 1e-12 * 2.0);
    }
    double a, v, d; /* after the end: a = 0, v = v(2) = 4, d = d(2) + 4 * 0.5 = 2 + 2 */
    rd_record_eval(&r, 2.5, &a, &v, &d);
    assert_true(a == 0.0 && fabs(v - 4.0) <= 1e-12 && fabs(d - 4.0) <= 1e-12);
    rd_record_eval(&r, -0.1, &a, &v, &d);
    assert_true(a == 0.0 && v == 0.0 && d == 0.0);
    rd_record_free(&r);
}

static double wave(double t)
{
    return 2.0 * sin(2.0 * M_PI * 1.3 * t) + 0.7 * cos(2.0 * M_PI * 4.1 * t);
}

static void test_scaling_exact(void **state)
{
    (void)state;
    rd_error err;
    rd_record r = sampled(wave, 3.0, 0.01), ref = sampled(wave, 3.0, 0.01);
    rd_record_scale(&r, 2.5);
    for (size_t i = 0; i < r.npts; i++) /* one multiplication each: exact to rounding */
        assert_true(r.acc[i] == 2.5 * ref.acc[i] && r.vel[i] == 2.5 * ref.vel[i] &&
                    r.disp[i] == 2.5 * ref.disp[i]);
    double peak = 0.0;
    assert_int_equal(rd_record_scale_to_pga(&r, 0.4 * RD_G_STANDARD, &err), 0);
    for (size_t i = 0; i < r.npts; i++) peak = fmax(peak, fabs(r.acc[i]));
    assert_true(fabs(peak - 0.4 * RD_G_STANDARD) <= 4e-16 * peak); /* x * (t/x): at most 2 ulp */
    assert_int_equal(rd_record_scale_to_pgv(&r, 0.3, &err), 0);
    peak = 0.0;
    for (size_t i = 0; i < r.npts; i++) peak = fmax(peak, fabs(r.vel[i]));
    assert_true(fabs(peak - 0.3) <= 4e-16 * peak);
    assert_true(rd_accel_unit_factor(RD_UNIT_G) == 9.80665 &&
                rd_accel_unit_factor(RD_UNIT_CM_S2) == 0.01 &&
                rd_accel_unit_factor(RD_UNIT_M_S2) == 1.0);
    rd_record zero;
    assert_int_equal(rd_record_alloc(&zero, 4, 0.01, &err), 0);
    assert_int_equal(rd_record_scale_to_pga(&zero, 1.0, &err), -1);
    assert_non_null(strstr(err.msg, "the record is zero"));
    rd_record_free(&zero), rd_record_free(&r), rd_record_free(&ref);
}

/* Refining the step keeps the same piecewise-linear history, so a, v and d at every time
 * agree with the original's to rounding (1e-12 of each scale). */
static void test_resample_refine(void **state)
{
    (void)state;
    rd_error err;
    rd_record r = sampled(wave, 2.0, 0.01), ref = sampled(wave, 2.0, 0.01);
    assert_int_equal(rd_record_resample(&r, 0.0025, &err), 0);
    assert_int_equal(r.npts, 801);
    for (size_t i = 0; i < r.npts; i++) {
        double t = (double)i * r.dt, a, v, d;
        rd_record_eval(&ref, t, &a, &v, &d);
        assert_true(fabs(r.acc[i] - a) <= 1e-12 * 3.0);
        assert_true(fabs(r.vel[i] - v) <= 1e-12 * 1.0);
        assert_true(fabs(r.disp[i] - d) <= 1e-12 * 1.0);
    }
    /* Coarsening by 2 keeps every other sample. */
    assert_int_equal(rd_record_resample(&ref, 0.02, &err), 0);
    assert_int_equal(ref.npts, 101);
    assert_true(fabs(ref.acc[50] - wave(1.0)) <= 1e-12);
    assert_int_equal(rd_record_resample(&ref, 0.0, &err), -1);
    rd_record_free(&r), rd_record_free(&ref);
}

/* Padding with zeros: the piecewise-linear acceleration ramps from the last sample to 0 over
 * the first added step (v gains h a_last / 2), then v stays constant and d grows linearly. */
static void test_pad(void **state)
{
    (void)state;
    rd_error err;
    rd_record r = sampled(wave, 1.0, 0.01);
    size_t n = r.npts;
    double h = r.dt, a_end = r.acc[n - 1];
    double v_pad = r.vel[n - 1] + 0.5 * h * a_end;
    double d_pad = r.disp[n - 1] + h * r.vel[n - 1] + h * h * a_end / 3.0;
    assert_int_equal(rd_record_pad(&r, 0.5, &err), 0);
    assert_int_equal(r.npts, n + 50);
    for (size_t i = n; i < r.npts; i++) { /* rounding only: 1e-13 of values of order 1 */
        double s = (double)(i - n) * h;
        assert_true(r.acc[i] == 0.0 && fabs(r.vel[i] - v_pad) <= 1e-13);
        assert_true(fabs(r.disp[i] - (d_pad + v_pad * s)) <= 1e-13);
    }
    assert_int_equal(rd_record_pad(&r, 0.005, &err), 0); /* half a step rounds up to one */
    assert_int_equal(r.npts, n + 51);
    rd_record_free(&r);
}

/* --- baseline correction ------------------------------------------------------------------- */

static double offset_sine(double t)
{
    return 1.5 * sin(2.0 * M_PI * t) + 0.02; /* 0.02 m/s^2 baseline offset */
}

/* Over whole cycles the sampled sine's trapezoid sums vanish, so the constraint v(T) = 0 with
 * degree 2 (a constant acceleration) removes exactly the 0.02 offset: 1e-12 covers rounding. */
static void test_baseline_removes_offset(void **state)
{
    (void)state;
    rd_error err;
    rd_record r = sampled(offset_sine, 4.0, 0.01);
    assert_int_equal(rd_record_baseline(&r, 2, &err), 0);
    for (size_t i = 0; i < r.npts; i++)
        assert_true(fabs(r.acc[i] - 1.5 * sin(2.0 * M_PI * (double)i * r.dt)) <= 1e-12);
    assert_int_equal(rd_record_baseline(&r, 9, &err), -1);
    assert_non_null(strstr(err.msg, "outside [2, 8]"));
    rd_record_free(&r);
}

static double peak_abs(const double *x, size_t n)
{
    double m = 0.0;
    for (size_t i = 0; i < n; i++) m = fmax(m, fabs(x[i]));
    return m;
}

static void test_baseline_stochastic(void **state)
{
    (void)state;
    rd_error err;
    rd_stochastic_def def;
    rd_stochastic_defaults(&def);
    def.seed = 7;
    rd_record r;
    assert_int_equal(rd_record_stochastic(&r, &def, &err), 0);
    size_t n = r.npts;
    assert_int_equal(rd_record_baseline(&r, 6, &err), 0);
    double pgv = peak_abs(r.vel, n), pgd = peak_abs(r.disp, n);
    /* The constraint makes v(T) zero up to rounding of the re-integration. */
    assert_true(fabs(r.vel[n - 1]) < 1e-3 * pgv);

    /* Drift-free: add a baseline error (offset 0.01 m/s^2 and slope 0.002 m/s^3, a drift of
     * ~5 m in displacement, 30x the PGD) and correct again. The drift lies in the polynomial
     * basis and the corrected record is already a least-squares residual, so the correction
     * must return the same displacement. Only rounding in the fit separates them (about 1e-13
     * of PGD seen); 1e-9 PGD leaves room for monomials up to t^6 (condition number ~1e7). */
    double *clean = malloc(n * sizeof *clean);
    assert_non_null(clean);
    memcpy(clean, r.disp, n * sizeof *clean);
    for (size_t i = 0; i < n; i++) r.acc[i] += 0.01 + 0.002 * (double)i * r.dt;
    rd_record_integrate(&r);
    assert_true(fabs(r.disp[n - 1] - clean[n - 1]) > 10.0 * pgd);
    assert_int_equal(rd_record_baseline(&r, 6, &err), 0);
    for (size_t i = 0; i < n; i++) assert_true(fabs(r.disp[i] - clean[i]) <= 1e-9 * pgd);
    free(clean);
    rd_record_free(&r);
}

/* --- stochastic generator ------------------------------------------------------------------- */

static void test_stochastic_deterministic(void **state)
{
    (void)state;
    rd_error err;
    rd_stochastic_def def;
    rd_stochastic_defaults(&def);
    def.duration = 10.0;
    def.seed = 12345;
    rd_record a, b, c;
    assert_int_equal(rd_record_stochastic(&a, &def, &err), 0);
    assert_int_equal(rd_record_stochastic(&b, &def, &err), 0);
    def.seed = 12346;
    assert_int_equal(rd_record_stochastic(&c, &def, &err), 0);
    assert_int_equal(a.npts, 2001);
    assert_memory_equal(a.acc, b.acc, a.npts * sizeof *a.acc);
    assert_memory_equal(a.disp, b.disp, a.npts * sizeof *a.disp);
    assert_memory_not_equal(a.acc, c.acc, a.npts * sizeof *a.acc);
    assert_true(fabs(peak_abs(a.acc, a.npts) - def.pga) <= 4e-16 * def.pga);
    assert_true(a.acc[0] == 0.0); /* the envelope starts at zero */
    rd_record_free(&c);
    def.damping = 1.0;
    assert_int_equal(rd_record_stochastic(&c, &def, &err), -1);
    assert_null(c.acc);
    rd_record_free(&a), rd_record_free(&b);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_at2_keyed_header),
        cmocka_unit_test(test_at2_positional_header),
        cmocka_unit_test(test_at2_errors),
        cmocka_unit_test(test_csv_two_columns),
        cmocka_unit_test(test_text_one_column),
        cmocka_unit_test(test_text_errors),
        cmocka_unit_test(test_integrate_and_eval_exact),
        cmocka_unit_test(test_scaling_exact),
        cmocka_unit_test(test_resample_refine),
        cmocka_unit_test(test_pad),
        cmocka_unit_test(test_baseline_removes_offset),
        cmocka_unit_test(test_baseline_stochastic),
        cmocka_unit_test(test_stochastic_deterministic),
    };
    return cmocka_run_group_tests(tests, setup_dir, remove_dir);
}
