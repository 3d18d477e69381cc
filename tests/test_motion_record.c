/* Tests for records as scenario ground motions: `ground-motion import` (AT2, text, FEMA P695
 * HDF5) and `ground-motion stochastic` parsed into rd_motion_def, evaluated by rd_motion_eval,
 * rotated, scaled and baseline-corrected; --set overrides; the free-vibration tail of
 * `model solve ... tail`; and every parser error path. Input files go into a mkdtemp()
 * directory; scenarios are parsed under the name "<dir>/s.dat" so record paths resolve there. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "rockdem/motion.h"
#include "rockdem/rockdem.h"

static char g_dir[64];           /* the mkdtemp() directory */
static char g_name[RD_PATH_MAX]; /* "<dir>/s.dat", the scenario's name in messages */

/* at2 values in g; dt = 0.01 s */
static const double at2_g[8] = { 0.0, 0.1, -0.2, 0.05, 0.3, -0.1, 0.02, 0.0 };

static void write_file(const char *name, const char *text)
{
    char path[RD_PATH_MAX + 80];
    snprintf(path, sizeof path, "%s/%s", g_dir, name);
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
}

/* A minimal FEMA P695 layout (uncompressed): /_timeseries/7/{a,b}/{Time,RecordedAcceleration},
 * b = -2 a, a = at2_g, dt 0.01 s. */
static void write_fema(void)
{
    char path[RD_PATH_MAX + 80], name[64];
    double t[8], a[8];
    hsize_t n = 8;
    snprintf(path, sizeof path, "%s/set.h5", g_dir);
    hid_t f = H5Fcreate(path, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    hid_t lcpl = H5Pcreate(H5P_LINK_CREATE);
    H5Pset_create_intermediate_group(lcpl, 1);
    hid_t sp = H5Screate_simple(1, &n, NULL);
    for (int c = 0; c < 2; c++) {
        for (int i = 0; i < 8; i++) {
            t[i] = 0.01 * i;
            a[i] = (c ? -2.0 : 1.0) * at2_g[i];
        }
        const char *what[2] = { "Time", "RecordedAcceleration" };
        for (int k = 0; k < 2; k++) {
            snprintf(name, sizeof name, "/_timeseries/7/%c/%s", c ? 'b' : 'a', what[k]);
            hid_t d = H5Dcreate2(f, name, H5T_IEEE_F64LE, sp, lcpl, H5P_DEFAULT, H5P_DEFAULT);
            H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, k ? a : t);
            H5Dclose(d);
        }
    }
    H5Sclose(sp);
    H5Pclose(lcpl);
    H5Fclose(f);
}

static int setup_dir(void **state)
{
    (void)state;
    snprintf(g_dir, sizeof g_dir, "/tmp/rockdem_motion_record_XXXXXX");
    if (!mkdtemp(g_dir)) return -1;
    snprintf(g_name, sizeof g_name, "%s/s.dat", g_dir);
    char text[1024] = "PEER NGA STRONG MOTION DATABASE RECORD\nHand-made test record\n"
                      "ACCELERATION TIME SERIES IN UNITS OF G\nNPTS=    8, DT=   .0100 SEC\n";
    for (int i = 0; i < 8; i++)
        snprintf(text + strlen(text), sizeof text - strlen(text), "%.3f%s", at2_g[i],
                 i % 4 == 3 ? "\n" : "  ");
    write_file("rec.AT2", text);
    write_file("rec2.csv", "time,acc\n0,0\n0.01,1\n0.02,-1\n0.03,0.5\n0.04,0\n");
    write_fema();
    return 0;
}

static int remove_dir(void **state)
{
    (void)state;
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", g_dir);
    return system(cmd) == 0 ? 0 : -1;
}

static const char *scene = "block create brick size 1 1 0.2 position 0 0 -0.1 fixed name ped\n"
                           "block create brick size 0.3 0.3 0.6 position 0 0 0.3 name b\n"
                           "model solve time 1\n";

/* Parses scene + `motion` (the ground-motion lines); asserts success. */
static void parse_ok(rd_scenario *sc, const char *motion)
{
    char text[2048];
    rd_error err;
    snprintf(text, sizeof text, "%s%s", scene, motion);
    if (rd_scenario_parse(sc, g_name, text, &err)) fail_msg("parse failed: %s", err.msg);
}

/* Parsing must fail with "<name>:line:col: ..." containing `what`. */
static void parse_fails(const char *motion, int line, int col, const char *what)
{
    char text[2048], prefix[RD_PATH_MAX + 32];
    rd_scenario sc;
    rd_error err;
    snprintf(text, sizeof text, "%s%s", scene, motion);
    assert_int_equal(rd_scenario_parse(&sc, g_name, text, &err), -1);
    snprintf(prefix, sizeof prefix, "%s:%d:%d: ", g_name, line, col);
    if (strncmp(err.msg, prefix, strlen(prefix)) != 0 || !strstr(err.msg, what))
        fail_msg("error \"%s\" is not \"%s...%s...\"", err.msg, prefix, what);
}

/* |x - want| <= tol, with the values in the failure message (CMocka 1.1.5 has no double compare). */
#define assert_double_equal(x, want, tol) assert_near((x), (want), (tol), __LINE__)
static void assert_near(double x, double want, double tol, int line)
{
    if (!(fabs(x - want) <= tol))
        fail_msg("line %d: %.17g differs from %.17g by more than %g", line, x, want, tol);
}

static void eval(const rd_scenario *sc, double t, double a[3])
{
    double v[3], d[3];
    rd_motion_eval(&sc->motion, t, a, v, d);
}

/* The AT2 values times standard gravity come back at every sample time along x. Tolerance:
 * t = i*0.01 is not exact in binary, so the linear interpolation inside step i-1 or i may be
 * off by a few ulps of the values (1e-12 m/s^2 is ~1e4 ulps of 3 m/s^2 and far below any
 * error a wrong index or unit would cause, >= 0.05 g). */
static void test_at2_exact_at_samples(void **state)
{
    (void)state;
    rd_scenario sc;
    parse_ok(&sc, "ground-motion import 'rec.AT2' baseline off\n");
    assert_int_equal(sc.motion.record[RD_H1].source, RD_SOURCE_AT2);
    for (int i = 0; i < 8; i++) {
        double a[3];
        eval(&sc, 0.01 * i, a);
        assert_double_equal(a[0], at2_g[i] * 9.80665, 1e-12);
        assert_double_equal(a[1], 0.0, 0.0);
        assert_double_equal(a[2], 0.0, 0.0);
    }
    double a[3];
    eval(&sc, 0.005, a); /* halfway between samples 0 and 1: linear */
    assert_double_equal(a[0], 0.05 * 9.80665, 1e-12);
    eval(&sc, 1.0, a); /* after the end: no acceleration */
    assert_double_equal(a[0], 0.0, 0.0);
    assert_double_equal(rd_motion_end(&sc.motion), 0.07, 1e-15);
    rd_scenario_free(&sc);
}

/* direction 90 turns h1 from +x to +y and h2 from +y to -x: the same numbers, swapped axes
 * (exact: cos 90 deg = 6e-17 times a sample is far below 1e-15 m/s^2). */
static void test_direction_swaps_axes(void **state)
{
    (void)state;
    rd_scenario s0, s90;
    parse_ok(&s0, "ground-motion import 'rec.AT2' baseline off\n"
                  "ground-motion import 'rec2.csv' units m/s2 component h2\n");
    parse_ok(&s90, "ground-motion import 'rec.AT2' baseline off direction 90\n"
                   "ground-motion import 'rec2.csv' units m/s2 component h2\n");
    for (double t = 0; t < 0.08; t += 0.0037) {
        double a0[3], a90[3];
        eval(&s0, t, a0);
        eval(&s90, t, a90);
        assert_double_equal(a90[0], -a0[1], 1e-15);
        assert_double_equal(a90[1], a0[0], 1e-15);
    }
    rd_scenario_free(&s0);
    rd_scenario_free(&s90);
}

/* scale 2 doubles the applied acceleration bit for bit (times 2 is exact in binary). */
static void test_scale_doubles(void **state)
{
    (void)state;
    rd_scenario s1, s2;
    parse_ok(&s1, "ground-motion import 'rec.AT2'\n");
    parse_ok(&s2, "ground-motion import 'rec.AT2' scale 2\n");
    for (double t = 0; t < 0.1; t += 0.0013) {
        double a1[3], a2[3];
        eval(&s1, t, a1);
        eval(&s2, t, a2);
        assert_true(a2[0] == 2.0 * a1[0]);
    }
    rd_scenario_free(&s1);
    rd_scenario_free(&s2);
}

static double peak_acc(const rd_scenario *sc, int c)
{
    const rd_record *r = sc->motion.record[c].applied;
    double p = 0;
    for (size_t i = 0; i < r->npts; i++) p = fmax(p, fabs(r->acc[i]));
    return p;
}

/* scale-pga hits the target to rounding (1e-14 relative: one multiply and one divide); a pair
 * uses the geometric mean of its peaks and keeps its ratio (FEMA b = -2 a: peaks a and 2a). */
static void test_scale_pga(void **state)
{
    (void)state;
    rd_scenario sc;
    rd_error err;
    parse_ok(&sc, "ground-motion import 'rec.AT2' scale-pga 0.5g\n");
    assert_double_equal(peak_acc(&sc, RD_H1), 0.5 * 9.80665, 1e-14 * 4.9);
    assert_int_equal(rd_scenario_set(&sc, "motion.scale-pga=2", &err), 0);
    assert_double_equal(peak_acc(&sc, RD_H1), 2.0, 2e-14);
    rd_scenario_free(&sc);
    parse_ok(&sc, "ground-motion import 'set.h5' record 7 component a scale-pga 1 baseline off\n"
                  "ground-motion import 'set.h5' record 7 component b\n");
    double pa = peak_acc(&sc, RD_H1), pb = peak_acc(&sc, RD_H2);
    assert_double_equal(sqrt(pa * pb), 1.0, 1e-14);
    assert_double_equal(pb / pa, 2.0, 1e-14);
    assert_double_equal(sc.motion.factor * 0.3 * 9.80665 * sqrt(2.0), 1.0, 1e-14);
    rd_scenario_free(&sc);
}

/* FEMA reader: component b = -2 x component a, in g. */
static void test_fema_components(void **state)
{
    (void)state;
    rd_scenario sc;
    parse_ok(&sc, "ground-motion import 'set.h5' record 7 component b baseline off\n");
    assert_null(sc.motion.record[RD_H1].applied);
    for (int i = 0; i < 8; i++) {
        double a[3];
        eval(&sc, 0.01 * i, a);
        assert_double_equal(a[1], -2.0 * at2_g[i] * 9.80665, 1e-12); /* h2 along +y */
    }
    rd_scenario_free(&sc);
}

/* The stochastic record drifts (end velocity well away from 0) until the default baseline
 * correction brings it to 0; 1e-9 of the PGV allows the rounding of ~4000 summed steps. */
static void test_stochastic_baseline(void **state)
{
    (void)state;
    rd_scenario sc;
    rd_error err;
    parse_ok(&sc, "ground-motion stochastic seed 3 pga 0.3g duration 20\n");
    const rd_record *raw = sc.motion.record[RD_H1].raw, *r = sc.motion.record[RD_H1].applied;
    double pgv = 0;
    for (size_t i = 0; i < r->npts; i++) pgv = fmax(pgv, fabs(r->vel[i]));
    assert_true(fabs(raw->vel[raw->npts - 1]) > 1e-4 * pgv);
    assert_double_equal(r->vel[r->npts - 1], 0.0, 1e-9 * pgv);
    double a[3], v[3], d[3];
    rd_motion_eval(&sc.motion, 25.0, a, v, d);
    assert_double_equal(v[0], 0.0, 1e-9 * pgv);
    /* a new seed gives a different record */
    double a0 = r->acc[100];
    assert_int_equal(rd_scenario_set(&sc, "motion.seed=4", &err), 0);
    assert_true(sc.motion.record[RD_H1].applied->acc[100] != a0);
    rd_scenario_free(&sc);
}

/* Peak |h1 acceleration| that drives the bodies: rd_motion_eval at every sample time. */
static double driven_pga(const rd_scenario *sc)
{
    const rd_record *r = sc->motion.record[RD_H1].applied;
    double p = 0, a[3];
    for (size_t i = 0; i < r->npts; i++) {
        eval(sc, (double)i * r->dt, a);
        p = fmax(p, hypot(a[0], a[1]));
    }
    return p;
}

/* A requested PGA is the applied one: the generator's `pga`, times a `scale` factor, after the
 * default degree-4 baseline correction (which moves the peak by ~1.5 %), and a shared
 * scale-pga that replaces it. 1e-9 relative: a few roundings of the scaling and of the sample
 * times in rd_motion_eval, far below the percent-level error of scaling before the correction. */
static void test_stochastic_pga(void **state)
{
    (void)state;
    const double g = 9.80665, tol = 1e-9;
    rd_scenario sc;
    rd_error err;
    parse_ok(&sc, "ground-motion stochastic seed 1 pga 0.3g duration 8\n");
    assert_double_equal(driven_pga(&sc) / (0.3 * g), 1.0, tol);
    assert_int_equal(rd_scenario_set(&sc, "motion.seed=2", &err), 0);
    assert_double_equal(driven_pga(&sc) / (0.3 * g), 1.0, tol);
    assert_int_equal(rd_scenario_set(&sc, "motion.scale=2", &err), 0);
    assert_double_equal(driven_pga(&sc) / (0.6 * g), 1.0, tol);
    assert_int_equal(rd_scenario_set(&sc, "motion.scale-pga=0.5g", &err), 0);
    assert_double_equal(driven_pga(&sc) / (0.5 * g), 1.0, tol);
    assert_int_equal(rd_scenario_set(&sc, "motion.baseline=off", &err), 0);
    assert_double_equal(driven_pga(&sc) / (0.5 * g), 1.0, tol);
    rd_scenario_free(&sc);
    parse_ok(&sc, "ground-motion stochastic seed 3 pga 0.2g duration 20 baseline 6 scale 1.5\n");
    assert_double_equal(driven_pga(&sc) / (0.3 * g), 1.0, tol);
    rd_scenario_free(&sc);
}

static double run_end(const char *solve, double *motion_end)
{
    char text[1024], out[RD_PATH_MAX + 16];
    rd_scenario sc;
    rd_error err;
    snprintf(out, sizeof out, "%s/tail.h5", g_dir);
    snprintf(text, sizeof text,
             "block create brick size 1 1 0.2 position 0 0 -0.1 fixed name ped\n"
             "block create brick size 0.3 0.3 0.6 position 0 0 0.3 name b\n"
             "model damping viscous 0.3\n"
             "ground-motion stochastic seed 1 pga 0.02g duration 0.6\n%s\noutput hdf5 '%s'\n",
             solve, out);
    if (rd_scenario_parse(&sc, g_name, text, &err)) fail_msg("%s", err.msg);
    *motion_end = rd_motion_end(&sc.motion);
    rd_sim *sim = rd_sim_create(&sc, &err);
    if (!sim) fail_msg("%s", err.msg);
    assert_int_equal(rd_sim_run(sim), RD_STATUS_DONE);
    rd_summary s;
    rd_sim_summary(sim, &s);
    rd_sim_free(sim);
    rd_scenario_free(&sc);
    return s.end_time;
}

/* A squat block under a weak (0.02 g) 0.6 s record never uplifts; with `tail` the run goes past
 * `time` 0.3 s to the end of the motion, then stops once the block has been at rest for the
 * 0.1 s hold -- well before the 5 s limit. Without tail it stops at `time`. */
static void test_tail_stops_at_rest(void **state)
{
    (void)state;
    double mend;
    double end = run_end("model solve time 0.3 tail 5", &mend);
    assert_double_equal(mend, 0.6, 1e-9);
    assert_true(end >= mend + 0.1 - 1e-6);
    assert_true(end < mend + 2.0);
    assert_double_equal(run_end("model solve time 0.3", &mend), 0.3, 1e-3);
}

static void test_errors(void **state)
{
    (void)state;
    parse_fails("ground-motion import 'nothere.AT2'\n", 4, 22, "nothere.AT2: cannot open");
    parse_fails("ground-motion import 'rec.AT2' component x\n", 4, 42, "unknown component 'x'");
    parse_fails("ground-motion import 'rec.AT2' scale -2\n", 4, 38, "'scale' must be > 0");
    parse_fails("ground-motion import 'rec.AT2' scale 2 scale-pga 0.3g\n", 4, 40,
                "'scale-pga' cannot be combined with 'scale'");
    parse_fails("ground-motion import 'set.h5' record 99\n", 4, 38, "record id '99' not found");
    parse_fails("ground-motion import 'set.h5' record 7 component h2\n", 4, 50,
                "expected a, b or v");
    parse_fails("ground-motion import 'set.h5'\n", 4, 15, "needs 'record <id>'");
    parse_fails("ground-motion import 'rec.AT2' baseline 9\n", 4, 41, "degree (2 to 8)");
    parse_fails("ground-motion import 'rec.AT2'\nground-motion import 'rec2.csv'\n", 5, 1,
                "h1 record is already defined (line 4)");
    parse_fails(
        "ground-motion pulse one-sine amplitude 1 frequency 2\nground-motion import 'rec.AT2'\n", 5,
        1, "horizontal pulse is already defined");
    parse_fails("ground-motion import 'rec.AT2' direction 10\n"
                "ground-motion import 'rec2.csv' component h2 direction 20\n",
                5, 46, "'direction' already given on line 4");
    parse_fails("ground-motion stochastic seed 1 pga 0.3g\n", 4, 15, "missing 'duration'");
    parse_fails("ground-motion stochastic seed 1.5 pga 0.3g duration 5\n", 4, 31, "whole number");
    parse_fails("model solve tail -1\n", 4, 18, "'tail' must be > 0");
}

/* A FEMA P695 set (uncompressed) <dir>/<name> whose record 1 has component a only: times t,
 * accelerations acc (g), n samples. */
static void write_fema_a(const char *name, const double *t, const double *acc, hsize_t n)
{
    char path[RD_PATH_MAX + 80];
    snprintf(path, sizeof path, "%s/%s", g_dir, name);
    hid_t f = H5Fcreate(path, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    hid_t lcpl = H5Pcreate(H5P_LINK_CREATE);
    H5Pset_create_intermediate_group(lcpl, 1);
    hid_t sp = H5Screate_simple(1, &n, NULL);
    const char *what[2] = { "/_timeseries/1/a/Time", "/_timeseries/1/a/RecordedAcceleration" };
    for (int k = 0; k < 2; k++) {
        hid_t d = H5Dcreate2(f, what[k], H5T_IEEE_F64LE, sp, lcpl, H5P_DEFAULT, H5P_DEFAULT);
        H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, k ? acc : t);
        H5Dclose(d);
    }
    H5Sclose(sp);
    H5Pclose(lcpl);
    H5Fclose(f);
}

/* The FEMA reader refuses what the AT2 and text readers refuse: a sample that is not finite or
 * beyond 1e6 m/s^2, a time that is not finite, a step outside [1e-6, 1] s (a step of 1e-9 s
 * padded the record to 2e9 samples: a hang). */
static void test_fema_checks(void **state)
{
    (void)state;
    enum { N = 8 };
    static const struct {
        const char *name;
        int index;
        double t_step, t_bad, a_bad;
        const char *what;
    } cases[] = {
        { "nan.h5", 3, 0.01, 0, NAN,
          "RecordedAcceleration: acceleration nan g at sample 3 is not a finite number" },
        { "inf.h5", 3, 0.01, 0, INFINITY, "acceleration inf g at sample 3 is not a finite number" },
        { "huge.h5", 5, 0.01, 0, 1e308,
          "acceleration 1e+308 g at sample 5 is outside the valid |acceleration| <= 1e+06" },
        { "tnan.h5", 4, 0.01, NAN, 0,
          "/_timeseries/1/a/Time: time nan s at sample 4 is not a finite number" },
        { "tiny.h5", -1, 1e-9, 0, 0,
          "/_timeseries/1/a/Time: time step 1e-09 s is outside [1e-06, 1] s" },
        { "small.h5", -1, 5e-7, 0, 0, "time step 5e-07 s is outside [1e-06, 1] s" },
        { "long.h5", -1, 100, 0, 0, "time step 100 s is outside [1e-06, 1] s" },
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        double t[N], a[N];
        for (int i = 0; i < N; i++) {
            t[i] = cases[c].t_step * i;
            a[i] = at2_g[i];
        }
        if (cases[c].index >= 0 && cases[c].a_bad != 0) a[cases[c].index] = cases[c].a_bad;
        if (cases[c].index >= 0 && cases[c].t_bad != 0) t[cases[c].index] = cases[c].t_bad;
        write_fema_a(cases[c].name, t, a, N);
        char motion[128];
        snprintf(motion, sizeof motion, "ground-motion import '%s' record 1\n", cases[c].name);
        parse_fails(motion, 4, (int)strlen(motion) - 1, cases[c].what);
    }
}

static void test_set_errors(void **state)
{
    (void)state;
    rd_scenario sc;
    rd_error err;
    parse_ok(&sc, "ground-motion import 'rec.AT2'\n");
    assert_int_equal(rd_scenario_set(&sc, "motion.scale=-1", &err), -1);
    assert_non_null(strstr(err.msg, "--set motion.scale=-1: value must be > 0"));
    assert_int_equal(rd_scenario_set(&sc, "motion.file=missing.AT2", &err), -1);
    assert_non_null(strstr(err.msg, "missing.AT2"));
    assert_int_equal(rd_scenario_set(&sc, "motion.seed=2", &err), -1);
    assert_non_null(strstr(err.msg, "not 'ground-motion stochastic'"));
    assert_int_equal(rd_scenario_set(&sc, "motion.record=7", &err), -1);
    assert_int_equal(rd_scenario_set(&sc, "motion.baseline=off", &err), 0);
    assert_int_equal(rd_scenario_set(&sc, "motion.file=rec2.csv", &err), 0);
    double a[3];
    eval(&sc, 0.01, a); /* rec2.csv in the default unit g: 1 g at 0.01 s */
    assert_double_equal(a[0], 9.80665, 1e-12);
    assert_int_equal(rd_scenario_validate(&sc, &err), 0);
    rd_scenario_free(&sc);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_at2_exact_at_samples), cmocka_unit_test(test_direction_swaps_axes),
        cmocka_unit_test(test_scale_doubles),        cmocka_unit_test(test_scale_pga),
        cmocka_unit_test(test_fema_components),      cmocka_unit_test(test_fema_checks),
        cmocka_unit_test(test_stochastic_baseline),  cmocka_unit_test(test_stochastic_pga),
        cmocka_unit_test(test_tail_stops_at_rest),   cmocka_unit_test(test_errors),
        cmocka_unit_test(test_set_errors),
    };
    return cmocka_run_group_tests(tests, setup_dir, remove_dir);
}
