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

#include "tmpdir.h"
#include "check.h"

/* A drum (n-sided prism) seated on the body `on`, axis above (x, y). */
static void add_drum(rd_scenario *sc, const char *name, const char *on, double r, double h,
                     int sides)
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
             "output hdf5 '%s/col.h5' interval 0.01\n%s",
             tmpdir, extra);
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

/* A settled six-drum column left alone for 5 s: nothing may move (round-off level), no event.
 * Bound 1e-8 rad: far above the round-off a symmetric column accumulates (1e-16 per step over
 * 5e4 steps, random-walk 2e-14) and far below the elastic tilt of the smallest real disturbance
 * (a 0.01 g lateral load: 3700 kg x 0.098 m/s^2 x 2 m on a joint of rotational stiffness
 * KN pi r^4 / 4 = 2e8 N m/rad gives 3.6e-6 rad). */
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
 * 0.5 s (a long one-sine at 1 Hz) brings the column down. Bound at 0.1 g, 1e-3 rad: the
 * elastic tilt summed over the six joints with the dynamic factor 2 of a sudden load is
 * 6 x 2 x 3.6e-5 rad = 4.3e-4 rad (the joint stiffness of the rest test above, 0.1 g); an
 * uplifting joint goes past it. */
static void test_column_weak_strong(void **state)
{
    (void)state;
    rd_scenario sc;
    column_scene(&sc, 6,
                 "ground-motion pulse one-sine amplitude 0.1g frequency 2\n"
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

    column_scene(&sc, 6,
                 "ground-motion pulse one-sine amplitude 1.5g frequency 1\n"
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
typedef struct {
    double lower[3], upper[3];
} stack_geom;

static void stack_tilts(const stack_geom *g, double factor, double *t_low, double *t_up)
{
    double b1 = g->lower[0] / 2, h1 = g->lower[2] / 2, b2 = g->upper[0] / 2, h2 = g->upper[2] / 2;
    double m1 = g->lower[0] * g->lower[1] * g->lower[2],
           m2 = g->upper[0] * g->upper[1] * g->upper[2];
    double stack = b1 * (m1 + m2) / (m1 * h1 + m2 * (2 * h1 + h2)), up = b2 / h2;
    double a = factor * 9.81 * fmin(stack, up);
    char text[2048];
    snprintf(
        text, sizeof text,
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
    stack_geom g = { { 1.0, 1.0, 1.0 }, { 0.4, 0.4, 1.2 } }; /* upper: 1/3 g; stack: 0.74 g */
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
    stack_geom g = { { 0.4, 0.4, 2.0 }, { 0.4, 0.4, 0.4 } }; /* stack: 0.167 g; upper: 1 g */
    double l0, u0, l1, u1;
    stack_tilts(&g, 0.99, &l0, &u0);
    stack_tilts(&g, 1.01, &l1, &u1);
    print_message("stack-first: 0.99 -> lower %.2e upper %.2e; 1.01 -> lower %.2e upper %.2e rad\n",
                  l0, u0, l1, u1);
    assert_true(u0 < 1e-3 && l0 < 1e-3);
    assert_true(l1 > 2e-3 && l1 > 100 * l0); /* tipping, slowed by the local damping */
    /* the upper block rides along: its own joint turns only elastically, m2 a h2 / (KN A2 b2^2)
       = 173 kg x 1.65 m/s^2 x 0.2 m / 6.4e7 N m = 9e-7 rad (corner points), while a block rocking
       on its own joint differs from the lower by its uplift tilt, of the order of l1 itself:
       5 % of l1 (> 1e-4 rad) separates the two */
    assert_true(fabs(u1 - l1) < 0.05 * l1);
}

/* ---- a scanned-style rock: the seeded PBR mesh on its pedestal ----------------------------- */
/* The generator (tools/make_pbr.py, seed 1) gives a 354 kg granite rock with a flat base at
 * z = 0. Independent precariousness: the hull of the mesh's lowest vertices (the flat base) and
 * the centroid from the mesh's mass properties, ray-cast every 5 degrees; the engine's table
 * comes from the subcontact points in contact after settling, so the two agree to the settled
 * compression over the base (micrometres in ~0.2 m: 1e-3 relative). At rest for 1 s the rock
 * must not move (tilt < 1e-7 rad). */
static int cmp2(const void *a, const void *b)
{
    const double *p = a, *q = b;
    return p[0] < q[0] ? -1 : p[0] > q[0] ? 1 : p[1] < q[1] ? -1 : p[1] > q[1];
}

static int hull(double (*p)[2], int n, double (*h)[2])
{
    qsort(p, (size_t)n, sizeof p[0], cmp2);
    int k = 0;
    for (int pass = 0; pass < 2; pass++, k--)
        for (int c = 0, start = k; c < n; c++) {
            int i = pass ? n - 1 - c : c;
            while (k >= start + 2 &&
                   (h[k - 1][0] - h[k - 2][0]) * (p[i][1] - h[k - 2][1]) -
                           (h[k - 1][1] - h[k - 2][1]) * (p[i][0] - h[k - 2][0]) <=
                       0)
                k--;
            h[k][0] = p[i][0];
            h[k][1] = p[i][1];
            k++;
        }
    return k;
}

static double ray(double (*h)[2], int n, const double c[2], double dx, double dy)
{
    double best = INFINITY;
    for (int i = 0; i < n; i++) {
        const double *a = h[i], *b = h[(i + 1) % n];
        double ex = b[0] - a[0], ey = b[1] - a[1], den = dx * ey - dy * ex;
        if (fabs(den) < 1e-15) continue;
        double t = ((a[0] - c[0]) * ey - (a[1] - c[1]) * ex) / den,
               u = ((a[0] - c[0]) * dy - (a[1] - c[1]) * dx) / den;
        if (t >= 0 && u >= -1e-9 && u <= 1 + 1e-9) best = fmin(best, t);
    }
    return best;
}

static void test_pbr_mesh(void **state)
{
    (void)state;
    char cmd[256], obj[128];
    snprintf(obj, sizeof obj, "%s/pbr.obj", tmpdir);
    snprintf(cmd, sizeof cmd, "/usr/bin/python3 tools/make_pbr.py --seed 1 -o %s > /dev/null", obj);
    assert_int_equal(system(cmd), 0);
    /* independent: lowest vertices and the centroid (volume-weighted tetrahedra) from the OBJ */
    FILE *f = fopen(obj, "r");
    assert_non_null(f);
    static double v[20000][3];
    static int tri[40000][3];
    int nv = 0, nt = 0;
    char line[256];
    while (fgets(line, sizeof line, f)) {
        if (line[0] == 'v' && line[1] == ' ' && nv < 20000)
            sscanf(line + 2, "%lf %lf %lf", &v[nv][0], &v[nv][1], &v[nv][2]), nv++;
        if (line[0] == 'f' && line[1] == ' ' && nt < 40000)
            sscanf(line + 2, "%d %d %d", &tri[nt][0], &tri[nt][1], &tri[nt][2]), nt++;
    }
    fclose(f);
    double vol = 0, c[3] = { 0 }, zmin = INFINITY;
    for (int t = 0; t < nt; t++) {
        const double *a = v[tri[t][0] - 1], *b = v[tri[t][1] - 1], *d = v[tri[t][2] - 1];
        double v6 = (a[0] * (b[1] * d[2] - b[2] * d[1]) - a[1] * (b[0] * d[2] - b[2] * d[0]) +
                     a[2] * (b[0] * d[1] - b[1] * d[0])) /
                    6;
        vol += v6;
        for (int k = 0; k < 3; k++) c[k] += v6 * (a[k] + b[k] + d[k]) / 4;
    }
    for (int k = 0; k < 3; k++) c[k] /= vol;
    for (int i = 0; i < nv; i++) zmin = fmin(zmin, v[i][2]);
    static double base[20000][2], h[40002][2];
    int nb = 0;
    for (int i = 0; i < nv; i++)
        if (v[i][2] < zmin + 1e-9) {
            base[nb][0] = v[i][0];
            base[nb][1] = v[i][1];
            nb++;
        }
    int nh = hull(base, nb, h);
    double amin = INFINITY;
    for (int d = 0; d < 72; d++)
        amin =
            fmin(amin, atan2(ray(h, nh, c, cos(d * M_PI / 36), sin(d * M_PI / 36)), c[2] - zmin));

    char text[1024];
    snprintf(text, sizeof text,
             "block create brick size 1.2 1.2 0.3 position 0 0 -0.15 fixed name pedestal\n"
             "block import mesh '%s' seat-on pedestal density 2750 name rock\n"
             "contact property stiffness-normal 1e10 stiffness-shear 1e9 friction 40\n"
             "model solve time 1\noutput hdf5 '%s/pbr.h5' interval 0.01\n",
             obj, tmpdir);
    rd_scenario sc;
    rd_error err;
    if (rd_scenario_parse(&sc, "pbr.dat", text, &err)) fail_msg("%s", err.msg);
    rd_status st;
    rd_sim *sim = run(&sc, &st);
    rd_summary sum;
    rd_sim_summary(sim, &sum);
    const rd_body_summary *b = &sum.body[0];
    print_message("PBR: alpha_min %.6f (independent %.6f) rad, rest tilt %.2e rad\n", b->alpha_min,
                  amin, b->max_tilt);
    assert_int_equal(st, RD_STATUS_DONE);
    assert_true(fabs(b->alpha_min - amin) < 1e-3 * amin);
    assert_true(b->max_tilt < 1e-7);
    rd_sim_free(sim);
    rd_scenario_free(&sc);
}

/* ---- off its pedestal --------------------------------------------------------------------- */
/* A 0.5 x 0.5 x 0.3 m block on a 0.6 m square pedestal, friction 15 deg, under a 0.5 g step
 * (rectangular pulse): it slides at a = (0.5 - tan 15) g (rigid-plastic closed form). Checks:
 * 1. kinematics: after 0.4 s (before its centre of mass reaches the edge) it has slid a t^2 / 2.
 *    Tolerance: a two-KN convergence study computed here (KN and KS x 10): if the DEM's error is
 *    a discretisation error of order >= 1/2 in KN, it is at most 1.5 |x(KN) - x(10 KN)|
 *    (Richardson, 1 / (1 - 10^-0.5) = 1.46); plus 1e-6 m for the elastic shear preload
 *    mu m g / (KS A) = 2e-6 m that both runs share only in part.
 * 2. the off-pedestal verdict comes after the centre of mass passes the pedestal's edge (0.3 m:
 *    before that the block is supported) and before its trailing edge leaves the pedestal
 *    (0.3 + 0.25 m: after that nothing can touch it). Both bounds are statics and kinematics;
 *    where in between the engine notices the lost contact is its own detection choice, not a
 *    physical quantity, so it is not pinned.
 * The block carries the default corner subcontacts: a fixed pedestal carries no points, so
 * once the leading corners pass the pedestal's edge the overhang is held by the pedestal's top
 * edges bearing on the block's base (edge subcontacts, src/engine/edge.c). Without them the
 * block tipped over the edge (0.48 rad at 0.4 s, where the rigid block stays flat). 3. hence
 * the tilt at 0.4 s stays below 1e-3 rad: the rigid block stays flat, and the elastic rock of
 * a 0.5 m base on KN 1e10 under the step's torque is of order m a h / (KN b^3) ~ 1e-6 rad. */
static rd_sim *off_pedestal_sim(double duration, double kn_factor, rd_status *st)
{
    char text[1024];
    snprintf(
        text, sizeof text,
        "block create brick size 0.6 0.6 0.5 position 0 0 -0.25 fixed name pedestal\n"
        "block create brick size 0.5 0.5 0.3 position 0 0 0.15 name b\n"
        "contact property stiffness-normal %g stiffness-shear %g friction 15\n"
        "ground-motion pulse rectangular amplitude 0.5g duration 1.5\n"
        "model settle on\nmodel overturn off-pedestal 0\nmodel solve time %g\noutput hdf5 '%s/off.h5' interval 0.01\n",
        1e10 * kn_factor, 1e9 * kn_factor, duration, tmpdir);
    rd_scenario sc;
    rd_error err;
    if (rd_scenario_parse(&sc, "off.dat", text, &err)) fail_msg("%s", err.msg);
    rd_sim *sim = run(&sc, st);
    rd_scenario_free(&sc);
    return sim;
}

static void test_off_pedestal(void **state)
{
    (void)state;
    const double g = 9.80665; /* the scenario's default gravity */
    double a = (0.5 - tan(15 * M_PI / 180)) * g;
    rd_status st;
    double slid[2], tilt = 0, t_end = 0.4;
    for (int k = 0; k < 2; k++) {
        rd_sim *s = off_pedestal_sim(t_end, k ? 10.0 : 1.0, &st);
        assert_int_equal(st, RD_STATUS_DONE);
        double x[3];
        rd_summary sum;
        rd_sim_body_state(s, 0, x, NULL, NULL, NULL);
        rd_sim_summary(s, &sum);
        slid[k] = fabs(x[0]);
        if (k == 0) tilt = sum.body[0].max_tilt;
        rd_sim_free(s);
    }
    double want = 0.5 * a * t_end * t_end;
    rd_check_abs("slide in 0.4 s under a 0.5 g step (m)", slid[0], want,
                 1.5 * fabs(slid[0] - slid[1]) + 1e-6, RD_STRICT);
    rd_check_abs("max tilt over the pedestal's edge by 0.4 s (rad)", tilt, 0.0, 1e-3, RD_STRICT);

    rd_sim *sim = off_pedestal_sim(3, 1.0, &st);
    rd_summary sum;
    rd_sim_summary(sim, &sum);
    double t_edge = sqrt(2 * 0.3 / a), t_gone = sqrt(2 * 0.55 / a);
    print_message(
        "off pedestal at %.4f s (centre of mass over the edge %.4f s, trailing edge off %.4f s)\n",
        sum.body[0].overturn_time, t_edge, t_gone);
    assert_int_equal(st, RD_STATUS_OVERTURNED);
    assert_true(sum.body[0].overturn_time > t_edge && sum.body[0].overturn_time < t_gone);
    rd_sim_free(sim);
}

/* ---- crossing edges: a brick turned 45 degrees on another ---------------------------------- */
/* The upper block's base crosses the lower block's top face edges (an octagonal contact made
 * by edge-crossings, not a face inside a face). After settling it must stay at rest (tilt
 * below 1e-9 rad over 2 s) and both blocks must press on their supports with their weight:
 * the settled sinking of each joint equals its load over KN times the contact area (a static
 * check of the point areas on a clipped face), to 2 %. */
static void test_crossing_edges(void **state)
{
    (void)state;
    char text[1024];
    snprintf(text, sizeof text,
             "block create brick size 3 3 0.5 position 0 0 -0.25 fixed name base\n"
             "block create brick size 1 1 0.5 position 0 0 0.25 name lower\n"
             "block create brick size 1 1 0.5 position 0 0 0.75 rotation 0 0 45 name upper\n"
             "contact property stiffness-normal 1e8 stiffness-shear 1e7 friction 40 spacing 0.02\n"
             "model solve time 2\noutput hdf5 '%s/cross.h5' interval 0.01\n",
             tmpdir);
    rd_scenario sc;
    rd_error err;
    if (rd_scenario_parse(&sc, "cross.dat", text, &err)) fail_msg("%s", err.msg);
    rd_status st;
    rd_sim *sim = run(&sc, &st);
    rd_summary sum;
    rd_sim_summary(sim, &sum);
    double xl[3], xu[3];
    rd_sim_body_state(sim, 0, xl, NULL, NULL, NULL);
    rd_sim_body_state(sim, 1, xu, NULL, NULL, NULL);
    double w = 2700 * 0.5 * 9.81;                    /* weight of one block, N */
    double sink_lower = 0.25 - xl[2];                /* base joint: area 1 m^2, load 2 w */
    double sink_joint = (0.75 - xu[2]) - sink_lower; /* octagon: 2 (sqrt 2 - 1) = 0.8284 m^2 */
    double oct = 2 * (sqrt(2) - 1);
    print_message(
        "crossing: tilt %.2e / %.2e rad, base sink %.4e (expect %.4e), joint %.4e (expect %.4e) m\n",
        sum.body[0].max_tilt, sum.body[1].max_tilt, sink_lower, 2 * w / 1e8, sink_joint,
        w / (1e8 * oct));
    assert_int_equal(st, RD_STATUS_DONE);
    assert_true(sum.body[0].max_tilt < 1e-9 && sum.body[1].max_tilt < 1e-9);
    assert_true(fabs(sink_lower - 2 * w / 1e8) < 0.02 * 2 * w / 1e8);
    assert_true(fabs(sink_joint - w / (1e8 * oct)) < 0.02 * w / (1e8 * oct));
    rd_sim_free(sim);
    rd_scenario_free(&sc);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_column_at_rest),
        cmocka_unit_test(test_column_weak_strong),
        cmocka_unit_test(test_stack_upper_tips_first),
        cmocka_unit_test(test_stack_whole_tips_first),
        cmocka_unit_test(test_pbr_mesh),
        cmocka_unit_test(test_off_pedestal),
        cmocka_unit_test(test_crossing_edges),
    };
    return cmocka_run_group_tests(tests, setup_dir, remove_dir);
}
