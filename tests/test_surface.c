/* The surface contact model (`contact model surface`, src/engine/surface.c) on the 0.5 x 0.5 x
 * 1.0 m block (h/b = 2, rho 2700) on a fixed base, tessellated four ways (issue 39, item 4):
 * a brick, and meshes from tools/box_meshes.py in tests/data/surface: the 8 corners, every face
 * cut 10 x 10, an irregular 5,120-triangle remesh.
 *  - free-rocking restitution r (rd_restitution_measure: released at 0.5 alpha, the mean of the
 *    first impacts' amplitude ratios) the same on every tessellation within 1 % (the issue's
 *    tolerance);
 *  - r reachable from Housner's (0.70 for h/b = 2, docs/ROCKING-EQUATIONS.md) to 0.95 by the
 *    joint's loss model (here its dashpot): the requirement, an expected failure while
 *    the dashpot cannot bring r down to Housner's;
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
#include "rockdem/validate.h"

#define HOUSNER_R 0.7000 /* h/b = 2: r = 1 - 1.5 sin^2(alpha), alpha = atan(1/2): 0.70 */
#define R_TOL 0.01       /* issue 39: the same restitution within 1 % on every tessellation */
#define SPIN_TOL 0.02    /* issue 39: spin-down within 2 % of uniform pressure */

static const char *const SHAPES[4] = {
    "block create brick size 0.5 0.5 1.0 position 0 0 0.5 name b",
    "block import mesh 'box8.obj' position 0 0 0.5 name b",
    "block import mesh 'box_cut10.obj' position 0 0 0.5 name b",
    "block import mesh 'box_remesh.obj' position 0 0 0.5 name b",
};
static const char *const SHAPE_NAME[4] = {"brick", "8-vertex mesh", "10 x 10 cut mesh", "5,120-triangle remesh"};

/* The free-rocking restitution of shape k with the surface model, dashpot ratio zeta. */
static double rocking_r(int k, double zeta)
{
    char text[1024];
    snprintf(text, sizeof text,
             "block create brick size 4 4 1 position 0 0 -0.5 fixed name base\n%s\n"
             "contact model surface\n"
             "contact property stiffness-normal 1e10 stiffness-shear 1e11 friction 40 restitution 1\n"
             "%s\nmodel solve time 3\n",
             SHAPES[k], zeta > 0 ? "model damping viscous 0.0" : "");
    if (zeta > 0) { /* the dashpot ratio, written as the scenario's own line */
        char *p = strstr(text, "viscous 0.0");
        char z[32];
        snprintf(z, sizeof z, "viscous %.3f", zeta);
        memcpy(p, z, strlen(z));
    }
    rd_scenario sc;
    rd_error err;
    if (rd_scenario_parse(&sc, "tests/data/surface/rock.dat", text, &err)) fail_msg("%s", err.msg);
    rd_restitution m;
    if (rd_restitution_measure(&sc, 0.5 * atan(0.5), &m, &err)) fail_msg("%s", err.msg);
    rd_scenario_free(&sc);
    return m.r;
}

static void test_restitution_tessellation(void **state)
{
    (void)state;
    double r[4];
    for (int k = 0; k < 4; k++) {
        r[k] = rocking_r(k, 0.0);
        print_message("surface model, elastic joint: %s r = %.4f\n", SHAPE_NAME[k], r[k]);
    }
    for (int k = 1; k < 4; k++) {
        char what[128];
        snprintf(what, sizeof what, "free-rocking r, %s against the brick", SHAPE_NAME[k]);
        rd_check_rel(what, r[k], r[0], R_TOL, RD_STRICT);
    }
}

static void test_restitution_range(void **state)
{
    (void)state;
    const double zeta[3] = {0.0, 0.3, 1.0};
    double r[3];
    for (int k = 0; k < 3; k++) {
        r[k] = rocking_r(0, zeta[k]);
        print_message("surface model, brick, dashpot zeta %.2f: r = %.4f\n", zeta[k], r[k]);
    }
    /* the loss model must reach Housner's r (to the 1 %) and 0.95 */
    double lo = fmin(fmin(r[0], r[1]), r[2]), hi = fmax(fmax(r[0], r[1]), r[2]);
    rd_check_abs("lowest free-rocking r reachable vs Housner's", fmax(lo - HOUSNER_R, 0.0), 0.0, R_TOL * HOUSNER_R,
                 RD_XFAIL);
    rd_check_abs("highest free-rocking r reachable vs 0.95", fmax(0.95 - hi, 0.0), 0.0, R_TOL * 0.95, RD_STRICT);
}

/* Time at which the cube's spin first falls below a thousandth of omega0. */
typedef struct spin_log {
    double w0, t_stop;
} spin_log;

static int spin_sample(void *user, rd_sim *sim, const rd_sample *s, rd_error *err)
{
    (void)sim; (void)err;
    spin_log *lg = user;
    if (lg->t_stop < 0 && fabs(s->angular_velocity[2]) < 1e-3 * lg->w0) lg->t_stop = s->time;
    return 0;
}

static double spin_down(const char *shape, double w0)
{
    char text[1024];
    snprintf(text, sizeof text,
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
    spin_log lg = {w0, -1};
    rd_observer obs = {.user = &lg, .sample = spin_sample};
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
    const double t_uniform = (a * a / 6) * w0 / (mu * g * rho);   /* I = m a^2 / 6 */
    const char *const cubes[2] = {"block create brick size 0.5 0.5 0.5 position 0 0 0.25 name b",
                                  "block import mesh 'cube_cut10.obj' position 0 0 0.25 name b"};
    const char *const names[2] = {"brick", "10 x 10 cut mesh"};
    for (int k = 0; k < 2; k++) {
        double t = spin_down(cubes[k], w0);
        char what[128];
        snprintf(what, sizeof what, "cube spin-down time (s), %s, vs uniform pressure", names[k]);
        rd_check_rel(what, t, t_uniform, SPIN_TOL, RD_STRICT);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_spin_down),
        cmocka_unit_test(test_restitution_tessellation),
        cmocka_unit_test(test_restitution_range),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
