/* The surface contact model (`contact model surface`, src/engine/surface.c) on the 0.5 x 0.5 x
 * 1.0 m block (h/b = 2, rho 2700) on a fixed base, tessellated four ways (issue 39, item 4):
 * a brick, and meshes from tools/box_meshes.py in tests/data/surface: the 8 corners, every face
 * cut 10 x 10, an irregular 5,120-triangle remesh.
 *  - free-rocking restitution r (rd_restitution_measure: released at 0.5 alpha, the mean of the
 *    first impacts' amplitude ratios) the same on every tessellation within 1 % (the issue's
 *    tolerance);
 *  - r reachable from Housner's (0.70 for h/b = 2, docs/ROCKING-EQUATIONS.md) to 0.95 by the
 *    joint's loss model (its dashpot, integrated implicitly: src/engine/dashpot.c), the issue's
 *    requirement: Housner's r on every tessellation at the elastic joint's step, within 1 %;
 *    0.95 an expected failure (the highest steady r is 0.913, docs/CONTACT.md section 8.6);
 *  - the 2 Hz one-sine overturning threshold the same within 2 % (the tolerance);
 *  - a flat 0.5 m cube spun about the vertical at omega0 stops in t = I omega0 / T, with the
 *    friction torque of a uniform pressure T = tan(phi) m g rho, rho = a (sqrt 2 + ln(1 +
 *    sqrt 2)) / 6 the mean distance from the centre of a square of side a (tests/test_patch.c
 *    checks that closed form); within 2 % (the tolerance), as a brick and as the cut
 *    mesh. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "rockdem/rockdem.h"
#include "rockdem/observer.h"

#define HOUSNER_R 0.7000 /* h/b = 2: r = 1 - 1.5 sin^2(alpha), alpha = atan(1/2): 0.70 */
#define R_TOL     0.01   /* issue 39: the same restitution within 1 % on every tessellation */
#define SPIN_TOL  0.02   /* issue 39: spin-down within 2 % of uniform pressure */
#define HOUSNER_ZETA                                                                               \
    3.2 /* the patch dashpot's ratio that gives Housner's r (r falls with the
                            ratio: 0.7194 at 2.5, 0.6975 at 3.3; docs/CONTACT.md section 8.6) */

static const char *const SHAPES[4] = {
    "block create brick size 0.5 0.5 1.0 position 0 0 0.5 name b",
    "block import mesh 'box8.obj' position 0 0 0.5 name b",
    "block import mesh 'box_cut10.obj' position 0 0 0.5 name b",
    "block import mesh 'box_remesh.obj' position 0 0 0.5 name b",
};
static const char *const SHAPE_NAME[4] = { "brick", "8-vertex mesh", "10 x 10 cut mesh",
                                           "5,120-triangle remesh" };

/* Free rocking from theta0 toward +x: the signed in-plane rocking at every sample, its swings
 * (runs of one sign beyond a thousandth of theta0) and their amplitudes. */
typedef struct rock_log {
    double eps;
    int sign, swings;
    double amp[8]; /* amplitude of each swing, rad (the release angle first) */
} rock_log;

static int rock_sample(void *user, rd_sim *sim, const rd_sample *s, rd_error *err)
{
    (void)sim;
    (void)err;
    rock_log *lg = user;
    double th = s->rotation[0];
    int sg = th > lg->eps ? 1 : th < -lg->eps ? -1 : 0;
    if (sg != 0 && sg != lg->sign && lg->swings < 8) {
        lg->sign = sg;
        lg->amp[lg->swings++] = 0;
    }
    if (lg->swings > 0 && lg->swings <= 8)
        lg->amp[lg->swings - 1] = fmax(lg->amp[lg->swings - 1], fabs(th));
    return 0;
}

/* Restitution of one impact from the amplitudes before and after it (energy ratio, Housner's
 * r = sqrt of it; src/ensembles/restitution.c decay_ratio). */
static double decay_ratio(double alpha, double a0, double a1)
{
    double e0 = cos(alpha - a0) - cos(alpha), e1 = cos(alpha - a1) - cos(alpha);
    return sqrt(e1 / e0);
}

/* The free-rocking scene of shape k with the surface model and dashpot ratio zeta (0: none),
 * released at half the tipping angle (as `rockdem restitution`, whose reference scene needs a
 * brick): created, not run. */
static rd_sim *rock_sim(int k, double zeta, rd_scenario *sc)
{
    const double theta0 = 0.5 * atan(0.5);
    char damping[64] = "";
    if (zeta > 0) snprintf(damping, sizeof damping, "model damping viscous %.4g\n", zeta);
    char text[1024];
    snprintf(
        text, sizeof text,
        "block create brick size 4 4 1 position 0 0 -0.5 fixed name base\n%s\n"
        "contact model surface\n"
        "contact property stiffness-normal 1e10 stiffness-shear 1e11 friction 40 restitution 1\n"
        "%sblock initial name b tilt %.10g direction 0\nmodel solve time 3\n"
        "output hdf5 'rock.h5' interval 0.0002\n",
        SHAPES[k], damping, theta0 * 180 / M_PI);
    rd_error err;
    if (rd_scenario_parse(sc, "tests/data/surface/rock.dat", text, &err)) fail_msg("%s", err.msg);
    rd_sim *sim = rd_sim_create(sc, &err);
    if (!sim) fail_msg("%s", err.msg);
    return sim;
}

/* The free-rocking restitution of shape k with dashpot ratio zeta: the geometric mean of the
 * first three impacts' ratios; the step into *dt when dt is not NULL. */
static double rocking_r(int k, double zeta, double *dt)
{
    const double alpha = atan(0.5), theta0 = 0.5 * alpha;
    rd_scenario sc;
    rd_error err;
    rd_sim *sim = rock_sim(k, zeta, &sc);
    rock_log lg = { 1e-3 * theta0, 0, 0, { 0 } };
    rd_observer obs = { .user = &lg, .sample = rock_sample };
    assert_int_equal(rd_sim_add_observer(sim, &obs, &err), 0);
    rd_status st = rd_sim_run(sim);
    assert_false(rd_status_failed(st));
    if (dt) *dt = rd_sim_dt(sim);
    rd_sim_free(sim);
    rd_scenario_free(&sc);
    if (lg.swings < 4) fail_msg("%d swings only", lg.swings);
    double logsum = 0;
    for (int q = 1; q <= 3; q++) logsum += log(decay_ratio(alpha, lg.amp[q - 1], lg.amp[q]));
    return exp(logsum / 3);
}

/* The step of shape k's scene without a dashpot, s. */
static double elastic_dt(int k)
{
    rd_scenario sc;
    rd_sim *sim = rock_sim(k, 0.0, &sc);
    double dt = rd_sim_dt(sim);
    rd_sim_free(sim);
    rd_scenario_free(&sc);
    return dt;
}

static void test_restitution_tessellation(void **state)
{
    (void)state;
    double r[4];
    for (int k = 0; k < 4; k++) {
        r[k] = rocking_r(k, 0.0, NULL);
        print_message("surface model, elastic joint: %s r = %.4f\n", SHAPE_NAME[k], r[k]);
    }
    for (int k = 1; k < 4; k++) {
        char what[128];
        snprintf(what, sizeof what, "free-rocking r, %s against the brick", SHAPE_NAME[k]);
        rd_check_rel(what, r[k], r[0], R_TOL, RD_STRICT);
    }
}

/* Housner's r at the normal step on every tessellation: the implicit patch dashpot
 * (src/engine/dashpot.c) at ratio HOUSNER_ZETA, the step the same as the elastic joint's (an
 * explicit dashpot of that ratio took a step 19 times shorter). */
static void test_restitution_housner(void **state)
{
    (void)state;
    for (int k = 0; k < 4; k++) {
        double dt, r = rocking_r(k, HOUSNER_ZETA, &dt);
        print_message("surface model, %s, dashpot zeta %.2f: r = %.4f at dt %.3g s\n",
                      SHAPE_NAME[k], HOUSNER_ZETA, r, dt);
        char what[128];
        snprintf(what, sizeof what, "free-rocking r vs Housner's, %s", SHAPE_NAME[k]);
        rd_check_abs(what, r, HOUSNER_R, R_TOL * HOUSNER_R, RD_STRICT);
        assert_true(dt == elastic_dt(k));
    }
}

static void test_restitution_range(void **state)
{
    (void)state;
    const double zeta[3] = { 0.05, 0.3, 1.0 };
    double r[3];
    for (int k = 0; k < 3; k++) {
        r[k] = rocking_r(0, zeta[k], NULL);
        print_message("surface model, brick, dashpot zeta %.2f: r = %.4f\n", zeta[k], r[k]);
    }
    /* r falls as the dashpot grows (a monotone map, so any r between is reached) */
    assert_true(r[0] > r[1] && r[1] > r[2]);
    /* the least dashpot that still damps the block's vibration on its joint between impacts
       (below about 0.05 the impacts' ratios scatter: docs/CONTACT.md section 8.6) gives the
       highest steady r: 0.95 stays out of reach */
    rd_check_abs("highest free-rocking r reachable vs 0.95", fmax(0.95 - r[0], 0.0), 0.0,
                 R_TOL * 0.95, RD_XFAIL);
}

/* Time at which the cube's spin first falls below a thousandth of omega0. */
typedef struct spin_log {
    double w0, t_stop;
} spin_log;

static int spin_sample(void *user, rd_sim *sim, const rd_sample *s, rd_error *err)
{
    (void)sim;
    (void)err;
    spin_log *lg = user;
    if (lg->t_stop < 0 && fabs(s->angular_velocity[2]) < 1e-3 * lg->w0) lg->t_stop = s->time;
    return 0;
}

static double spin_down(const char *shape, double w0)
{
    char text[1024];
    snprintf(
        text, sizeof text,
        "block create brick size 4 4 1 position 0 0 -0.5 fixed name base\n%s\n"
        "contact model surface\n"
        "contact property stiffness-normal 1e10 stiffness-shear 1e11 friction 40 restitution 1\n"
        "block initial name b angular-velocity 0 0 %.6g\n"
        "model solve time 0.2\noutput hdf5 'spin.h5' interval 0.0001\n",
        shape, w0);
    rd_scenario sc;
    rd_error err;
    if (rd_scenario_parse(&sc, "tests/data/surface/spin.dat", text, &err)) fail_msg("%s", err.msg);
    rd_sim *sim = rd_sim_create(&sc, &err);
    if (!sim) fail_msg("%s", err.msg);
    spin_log lg = { w0, -1 };
    rd_observer obs = { .user = &lg, .sample = spin_sample };
    assert_int_equal(rd_sim_add_observer(sim, &obs, &err), 0);
    rd_status st = rd_sim_run(sim);
    assert_false(rd_status_failed(st));
    rd_sim_free(sim);
    rd_scenario_free(&sc);
    return lg.t_stop;
}

static void test_spin_down(void **state)
{
    (void)state;
    const double a = 0.5, w0 = 4.0, mu = tan(40 * M_PI / 180), g = 9.81;
    const double rho = a * (sqrt(2.0) + log(1 + sqrt(2.0))) / 6; /* mean |r| over the square */
    const double t_uniform = (a * a / 6) * w0 / (mu * g * rho);  /* I = m a^2 / 6 */
    const char *const cubes[2] = { "block create brick size 0.5 0.5 0.5 position 0 0 0.25 name b",
                                   "block import mesh 'cube_cut10.obj' position 0 0 0.25 name b" };
    const char *const names[2] = { "brick", "10 x 10 cut mesh" };
    for (int k = 0; k < 2; k++) {
        double t = spin_down(cubes[k], w0);
        char what[128];
        snprintf(what, sizeof what, "cube spin-down time (s), %s, vs uniform pressure", names[k]);
        rd_check_rel(what, t, t_uniform, SPIN_TOL, RD_STRICT);
    }
}

/* Does shape k overturn under a 2 Hz one-sine of amplitude a (g)? Any other status than done or
 * overturned fails the test. */
static int overturns(int k, double a)
{
    char text[1024];
    snprintf(
        text, sizeof text,
        "block create brick size 4 4 1 position 0 0 -0.5 fixed name base\n%s\n"
        "contact model surface\n"
        "contact property stiffness-normal 1e10 stiffness-shear 1e11 friction 40 restitution 1\n"
        "ground-motion pulse one-sine amplitude %.6gg frequency 2 direction 0\nmodel solve time 4\n",
        SHAPES[k], a);
    rd_scenario sc;
    rd_error err;
    if (rd_scenario_parse(&sc, "tests/data/surface/pulse.dat", text, &err)) fail_msg("%s", err.msg);
    rd_sim *sim = rd_sim_create(&sc, &err);
    if (!sim) fail_msg("%s", err.msg);
    rd_status st = rd_sim_run(sim);
    rd_sim_free(sim);
    rd_scenario_free(&sc);
    if (st != RD_STATUS_DONE && st != RD_STATUS_OVERTURNED)
        fail_msg("status %s at %g g", rd_status_name(st), a);
    return st == RD_STATUS_OVERTURNED;
}

/* The 2 Hz one-sine overturning threshold the same within 2 % (issue 39) on every tessellation:
 * the brick's by bisection (0.5 to 1.6 g, 7 halvings: +-0.0043 g, a fifth of the tolerance),
 * then each mesh stands at 0.98 and overturns at 1.02 times it. */
static void test_threshold_tessellation(void **state)
{
    (void)state;
    double lo = 0.5, hi = 1.6;
    assert_false(overturns(0, lo));
    assert_true(overturns(0, hi));
    for (int k = 0; k < 7; k++) {
        double mid = 0.5 * (lo + hi);
        if (overturns(0, mid))
            hi = mid;
        else
            lo = mid;
    }
    const double thr = 0.5 * (lo + hi);
    print_message("surface model, brick: 2 Hz one-sine threshold %.4f g (+- %.4f)\n", thr,
                  0.5 * (hi - lo));
    for (int k = 1; k < 4; k++) {
        char what[160];
        int stands = !overturns(k, 0.98 * thr), falls = overturns(k, 1.02 * thr);
        snprintf(what, sizeof what,
                 "%s stands at 0.98 and overturns at 1.02 times the brick's threshold",
                 SHAPE_NAME[k]);
        rd_check_abs(what, (double)(!stands + !falls), 0.0, 0.5, RD_STRICT);
    }
}

/* A joint made between two free bodies of unequal faces (a 0.4 x 0.4 x 0.8 m block on the 0.5
 * x 0.5 x 1.0 m one) has the stiffness of its whole patch, KN times the 0.16 m^2 overlap (the
 * vertex model's half-weight sets kept half of it: README, known gaps). Settled under a 0.5
 * dashpot, each joint's closure is the Winkler closed form m g / (KN A); tolerance 1e-3
 * relative (a tenth of the 1 % tessellation tolerance; a half weight is 100 %). */
static void test_free_joint_stiffness(void **state)
{
    (void)state;
    const char *text =
        "block create brick size 4 4 1 position 0 0 -0.5 fixed name base\n"
        "block create brick size 0.5 0.5 1.0 position 0 0 0.5 name lower\n"
        "block create brick size 0.4 0.4 0.8 position 0 0 1.4 name upper\n"
        "contact model surface\n"
        "contact property stiffness-normal 1e10 stiffness-shear 1e11 friction 40 restitution 1\n"
        "model damping viscous 0.5\nmodel solve time 0.3\n";
    rd_scenario sc;
    rd_error err;
    if (rd_scenario_parse(&sc, "tests/data/surface/stack.dat", text, &err)) fail_msg("%s", err.msg);
    rd_sim *sim = rd_sim_create(&sc, &err);
    if (!sim) fail_msg("%s", err.msg);
    assert_false(rd_status_failed(rd_sim_run(sim)));
    double xl[3], xu[3], q[4], v[3], w[3];
    rd_sim_body_state(sim, 0, xl, q, v, w);
    rd_sim_body_state(sim, 1, xu, q, v, w);
    rd_sim_free(sim);
    rd_scenario_free(&sc);
    const double g = 9.81, KN = 1e10, ml = 0.25 * 1.0 * 2700, mu = 0.16 * 0.8 * 2700;
    rd_check_rel("lower block's closure on the base (m)", 0.5 - xl[2], (ml + mu) * g / (KN * 0.25),
                 1e-3, RD_STRICT);
    rd_check_rel("upper block's closure on the lower (m)", xl[2] + 0.5 + 0.4 - xu[2],
                 mu * g / (KN * 0.16), 1e-3, RD_STRICT);
}

/* What the surface model cannot model yet is refused with one line, never run silently. */
static void test_refusals(void **state)
{
    (void)state;
    static const char *const scenes[1][2] = {
        { "block create brick size 4 4 1 position 0 0 -0.5 fixed name base\n"
          "block create brick size 0.5 0.5 1.0 position 0 0 0.5 name b\ncontact model surface\n"
          "model solve time 0.1\n",
          "restitution 0 is not modelled" },
    };
    for (int k = 0; k < 1; k++) {
        rd_scenario sc;
        rd_error err;
        if (rd_scenario_parse(&sc, "tests/data/surface/refuse.dat", scenes[k][0], &err))
            fail_msg("%s", err.msg);
        rd_sim *sim = rd_sim_create(&sc, &err);
        assert_null(sim);
        if (!strstr(err.msg, scenes[k][1])) fail_msg("unexpected message: %s", err.msg);
        print_message("refused: %s\n", err.msg);
        rd_scenario_free(&sc);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_refusals),
        cmocka_unit_test(test_free_joint_stiffness),
        cmocka_unit_test(test_spin_down),
        cmocka_unit_test(test_restitution_tessellation),
        cmocka_unit_test(test_threshold_tessellation),
        cmocka_unit_test(test_restitution_housner),
        cmocka_unit_test(test_restitution_range),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
