/* The scene families of the mission: drum columns and two-block assemblies, checked against
 * rigid-body statics and simple limits. Each test states its tolerance and why. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include "rockdem/rockdem.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static char tmpdir[64];

static int setup_dir(void **state)
{
    (void)state;
    snprintf(tmpdir, sizeof tmpdir, "/tmp/rd_scenes_XXXXXX");
    return mkdtemp(tmpdir) ? 0 : -1;
}

static int remove_dir(void **state)
{
    (void)state;
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf %s", tmpdir);
    return system(cmd);
}

/* A drum (n-sided prism) seated on the body `on`, axis above (x, y). */
static void add_drum(rd_scenario *sc, const char *name, const char *on, double r, double h, int sides)
{
    rd_body_def *b = &sc->bodies[sc->nbodies++];
    memset(b, 0, sizeof *b);
    snprintf(b->name, sizeof b->name, "%s", name);
    snprintf(b->seat_on, sizeof b->seat_on, "%s", on);
    b->shape = RD_SHAPE_PRISM;
    b->sides = sides;
    b->radius = b->radius_top = r;
    b->size[2] = h;
}

/* Pedestal + a column of n drums (r 0.4 m, h 0.6 m, 16 sides) and a capital (a 1 x 1 x 0.3 m
 * brick) seated on each other; classical proportions: column height ~ 8 diameters for n = 6. */
static void column_scene(rd_scenario *sc, int n, const char *extra)
{
    char text[2048];
    snprintf(text, sizeof text,
             "block create brick size 3 3 0.5 position 0 0 -0.25 fixed name base\n"
             "contact property stiffness-normal 1e10 stiffness-shear 1e9 friction 40 spacing 0.15\n"
             "output hdf5 '%s/col.h5' interval 0.01\n%s", tmpdir, extra);
    rd_error err;
    if (rd_scenario_parse(sc, "column.dat", text, &err)) fail_msg("%s", err.msg);
    char prev[RD_NAME_MAX] = "base", name[RD_NAME_MAX];
    for (int k = 1; k <= n; k++) {
        snprintf(name, sizeof name, "drum%d", k);
        add_drum(sc, name, prev, 0.4, 0.6, 16);
        snprintf(prev, sizeof prev, "%s", name);
    }
    rd_body_def *c = &sc->bodies[sc->nbodies++];
    memset(c, 0, sizeof *c);
    snprintf(c->name, sizeof c->name, "capital");
    snprintf(c->seat_on, sizeof c->seat_on, "%s", prev);
    c->shape = RD_SHAPE_BRICK;
    c->size[0] = c->size[1] = 1.0;
    c->size[2] = 0.3;
}

static rd_sim *run(rd_scenario *sc, rd_status *st)
{
    rd_error err;
    rd_sim *sim = rd_sim_create(sc, &err);
    if (!sim) fail_msg("%s", err.msg);
    *st = rd_sim_run(sim);
    return sim;
}

/* A settled six-drum column left alone for 5 s: nothing may move (round-off level), no event. */
static void test_column_at_rest(void **state)
{
    (void)state;
    rd_scenario sc;
    column_scene(&sc, 6, "model solve time 5\n");
    rd_status st;
    rd_sim *sim = run(&sc, &st);
    rd_summary sum;
    rd_sim_summary(sim, &sum);
    assert_int_equal(st, RD_STATUS_DONE);
    assert_int_equal(sum.nbodies, 7);
    double worst = 0;
    for (int k = 0; k < sum.nbodies; k++) worst = fmax(worst, sum.body[k].max_tilt);
    print_message("column at rest: max tilt %.3e rad over 7 bodies, %d points\n", worst,
                  rd_sim_point_count(sim));
    assert_true(worst < 1e-8);
    int n;
    rd_sim_events(sim, &n);
    assert_int_equal(n, 0);
    rd_sim_free(sim);
    rd_scenario_free(&sc);
}

/* Weak vs strong pulse. The column's whole-body static tipping threshold is
 * a = g b / h_cm = g 0.4 cos(pi/16) / ~2.0 m ~ 0.19 g; 0.1 g at 2 Hz cannot uplift any joint
 * (each joint's threshold is at least that of the whole column above it), while 1.5 g for
 * 0.5 s (a long one-sine at 1 Hz) brings the column down. */
static void test_column_weak_strong(void **state)
{
    (void)state;
    rd_scenario sc;
    column_scene(&sc, 6, "ground-motion pulse one-sine amplitude 0.1g frequency 2\n"
                         "model damping viscous 0.1\nmodel solve time 3\n");
    rd_status st;
    rd_sim *sim = run(&sc, &st);
    rd_summary sum;
    rd_sim_summary(sim, &sum);
    double worst = 0;
    for (int k = 0; k < sum.nbodies; k++) worst = fmax(worst, sum.body[k].max_tilt);
    print_message("0.1 g: max tilt %.3e rad, overturned %d\n", worst, sum.any_overturned);
    assert_false(sum.any_overturned);
    assert_true(worst < 1e-3);
    rd_sim_free(sim);
    rd_scenario_free(&sc);

    column_scene(&sc, 6, "ground-motion pulse one-sine amplitude 1.5g frequency 1\n"
                         "model damping viscous 0.1\nmodel solve time 4\n");
    sim = run(&sc, &st);
    rd_sim_summary(sim, &sum);
    print_message("1.5 g: overturned %d, status %d\n", sum.any_overturned, st);
    assert_true(sum.any_overturned);
    rd_sim_free(sim);
    rd_scenario_free(&sc);
}

/* ---- two-block static uplift thresholds (ROCKING-EQUATIONS.md, transitions item 2) ------- */
/* Under a quasi-static horizontal load (2 s rectangular pulse, local damping 0.8, corner
 * subcontacts, so joints open exactly when the resultant reaches an edge) the stack tips as a
 * whole when a/g > b1 (m1 + m2) / (m1 h1 + m2 (2 h1 + h2)), the upper block alone when
 * a/g > b2 / h2; the lower threshold wins. 1 % below it nothing rotates beyond the elastic
 * level; 1 % above, the predicted body tips (its tilt grows by orders of magnitude) and the
 * other does not rock on its own joint. */
typedef struct { double lower[3], upper[3]; } stack_geom;

static void stack_tilts(const stack_geom *g, double factor, double *t_low, double *t_up)
{
    double b1 = g->lower[0] / 2, h1 = g->lower[2] / 2, b2 = g->upper[0] / 2, h2 = g->upper[2] / 2;
    double m1 = g->lower[0] * g->lower[1] * g->lower[2], m2 = g->upper[0] * g->upper[1] * g->upper[2];
    double stack = b1 * (m1 + m2) / (m1 * h1 + m2 * (2 * h1 + h2)), up = b2 / h2;
    double a = factor * 9.81 * fmin(stack, up);
    char text[2048];
    snprintf(text, sizeof text,
             "block create brick size 4 4 0.5 position 0 0 -0.25 fixed name base\n"
             "block create brick size %g %g %g position 0 0 %g name lower\n"
             "block create brick size %g %g %g position 0 0 %g name upper\n"
             "contact property stiffness-normal 1e10 stiffness-shear 1e9 friction 60 spacing vertices\n"
             "model damping local 0.8\nground-motion pulse rectangular amplitude %.17g duration 2\n"
             "model overturn angle 80\nmodel solve time 2\noutput hdf5 '%s/stack.h5' interval 0.01\n",
             g->lower[0], g->lower[1], g->lower[2], h1, g->upper[0], g->upper[1], g->upper[2],
             2 * h1 + h2, a, tmpdir);
    rd_scenario sc;
    rd_error err;
    if (rd_scenario_parse(&sc, "stack.dat", text, &err)) fail_msg("%s", err.msg);
    rd_status st;
    rd_sim *sim = run(&sc, &st);
    rd_summary sum;
    rd_sim_summary(sim, &sum);
    *t_low = sum.body[0].max_tilt;
    *t_up = sum.body[1].max_tilt;
    rd_sim_free(sim);
    rd_scenario_free(&sc);
}

static void test_stack_upper_tips_first(void **state)
{
    (void)state;
    stack_geom g = {{1.0, 1.0, 1.0}, {0.4, 0.4, 1.2}}; /* upper: 1/3 g; stack: 0.74 g */
    double l0, u0, l1, u1;
    stack_tilts(&g, 0.99, &l0, &u0);
    stack_tilts(&g, 1.01, &l1, &u1);
    print_message("upper-first: 0.99 -> lower %.2e upper %.2e; 1.01 -> lower %.2e upper %.2e rad\n",
                  l0, u0, l1, u1);
    assert_true(u0 < 1e-3 && l0 < 1e-3);
    assert_true(u1 > 1e-2 && u1 > 100 * u0);
    assert_true(l1 < 1e-3);
}

static void test_stack_whole_tips_first(void **state)
{
    (void)state;
    stack_geom g = {{0.4, 0.4, 2.0}, {0.4, 0.4, 0.4}}; /* stack: 0.167 g; upper: 1 g */
    double l0, u0, l1, u1;
    stack_tilts(&g, 0.99, &l0, &u0);
    stack_tilts(&g, 1.01, &l1, &u1);
    print_message("stack-first: 0.99 -> lower %.2e upper %.2e; 1.01 -> lower %.2e upper %.2e rad\n",
                  l0, u0, l1, u1);
    assert_true(u0 < 1e-3 && l0 < 1e-3);
    assert_true(l1 > 2e-3 && l1 > 100 * l0); /* tipping, slowed by the local damping */
    assert_true(fabs(u1 - l1) < 0.05 * l1); /* the upper block rides along: no rocking of its own */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_column_at_rest),
        cmocka_unit_test(test_column_weak_strong),
        cmocka_unit_test(test_stack_upper_tips_first),
        cmocka_unit_test(test_stack_whole_tips_first),
    };
    return cmocka_run_group_tests(tests, setup_dir, remove_dir);
}
