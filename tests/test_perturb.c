/* Interface perturbation (src/engine/perturb.c): removal of all but the corners gives the
 * corner-only static tipping threshold; a random removal lowers it to the remaining points'
 * value; the same seed gives identical points; a scatter of 0 changes nothing; points at one
 * place, perturbed or not, share one kinematics slot (setup.c: share_points); a mesh's co-located
 * points are merged into one that carries their summed area (merge.c). */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include "rockdem/rockdem.h"
#include "engine/sim.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* 0.4 x 0.4 x 1 m brick on a pad, a 5 x 5 bed of points (spacing 0.1), no motion: settle only. */
static const char *brick =
    "block create brick size 2 2 0.2 position 0 0 -0.1 fixed name pad\n"
    "block create brick size 0.4 0.4 1.0 position 0 0 0.5 density 2500 name brick\n"
    "contact property stiffness-normal 1e9 stiffness-shear 1e8 friction 40 spacing %s\n"
    "model damping viscous 0.2\n"
    "model solve time 0.01\n"
    "output hdf5 '%s' interval 0.005\n"
    "%s\n";

static char out[64];
static int nout; /* run files made: one per simulation alive at a time */

static rd_sim *make(const char *spacing, const char *perturb)
{
    char text[2048];
    rd_scenario sc;
    rd_error err;
    char path[80];
    snprintf(path, sizeof path, "%s.%d.h5", out, nout++ % 4);
    snprintf(text, sizeof text, brick, spacing, path, perturb);
    assert_int_equal(rd_scenario_parse(&sc, "perturb.dat", text, &err), 0);
    rd_sim *s = rd_sim_create(&sc, &err);
    if (!s) fprintf(stderr, "%s\n", err.msg);
    rd_scenario_free(&sc);
    assert_non_null(s);
    return s;
}

/* Quasi-static tipping acceleration of the brick at rest, m/s^2. */
static double tip_accel(const char *spacing, const char *perturb)
{
    rd_sim *s = make(spacing, perturb);
    rd_summary sum;
    rd_sim_run(s);
    rd_sim_summary(s, &sum);
    double a = sum.body[0].tip_accel_min;
    rd_sim_free(s);
    return a;
}

static void test_corners_threshold(void **state)
{
    (void)state;
    double g = 9.81, corners = tip_accel("vertices", ""), bed = tip_accel("0.1", "");
    double kept =
        tip_accel("0.1", "contact interface-perturbation seed 7 remove 0.99 keep-corners on");
    double random = tip_accel("0.1", "contact interface-perturbation seed 7 remove 0.9");
    assert_true(fabs(corners - 0.4 * g) < 1e-3 * g); /* g b/h, b/h = 0.4 */
    assert_true(fabs(bed - corners) < 1e-3 * g);
    assert_true(fabs(kept - corners) < 1e-6 * g);
    assert_true(random < 0.9 * corners); /* the outer points are gone: a smaller support */
}

static void test_same_seed_same_points(void **state)
{
    (void)state;
    const char *p = "contact interface-perturbation seed 11 remove 0.3 raise 0.001 scatter 0.4";
    rd_sim *a = make("0.1", p), *b = make("0.1", p), *c = make("0.1", "");
    rd_sim *d =
        make("0.1", "contact interface-perturbation seed 12 remove 0.3 raise 0.001 scatter 0.4");
    assert_int_equal(a->npts, b->npts);
    assert_int_equal(a->npts, c->npts - (int)floor(0.3 * c->npts));
    assert_memory_equal(a->pl, b->pl, (size_t)a->npts * sizeof *a->pl);
    assert_memory_equal(a->pa, b->pa, (size_t)a->npts * sizeof *a->pa);
    assert_true(a->npts != d->npts || memcmp(a->pl, d->pl, (size_t)a->npts * sizeof *a->pl) != 0);
    rd_sim_free(a);
    rd_sim_free(b);
    rd_sim_free(c);
    rd_sim_free(d);
}

static void test_zero_scatter_noop(void **state)
{
    (void)state;
    rd_sim *a = make("0.1", "contact interface-perturbation seed 5 scatter 0");
    rd_sim *b = make("0.1", "");
    assert_int_equal(a->npts, b->npts);
    assert_memory_equal(a->pl, b->pl, (size_t)a->npts * sizeof *a->pl);
    assert_memory_equal(a->pa, b->pa, (size_t)a->npts * sizeof *a->pa);
    rd_sim_free(a);
    rd_sim_free(b);
}

/* Points at the same place share one kinematics slot (rd_sim.pkin, the contact finds their
 * motion once): each point's slot is the least-index point at exactly its coordinates, so the
 * slots are as many as the distinct places (found here by brute force). Corners layout: the
 * brick's base corners are also its side faces' corner points, so there are fewer places than
 * points; after raised, scattered points, every place is checked again. */
static void check_places(rd_sim *s)
{
    int nplaces = 0, sharing = 0;
    for (int i = 0; i < s->nb; i++)
        for (int pt = s->pt0[i]; pt < s->pt0[i + 1]; pt++) {
            int first = pt;
            for (int q = s->pt0[i]; q < pt && first == pt; q++)
                if (!memcmp(s->pl[q], s->pl[pt], sizeof s->pl[0])) first = q;
            assert_int_equal(s->pkin[pt], first - s->pt0[i]);
            nplaces += first == pt;
            sharing += first != pt;
        }
    assert_int_equal(nplaces + sharing, s->npts);
}

static void test_shared_places(void **state)
{
    (void)state;
    rd_sim *a = make("vertices", ""),
           *b = make("0.1",
                     "contact interface-perturbation seed 11 remove 0.3 raise 0.001 scatter 0.4");
    check_places(a);
    check_places(b);
    int shared = 0;
    for (int i = 0; i < a->nb; i++)
        for (int pt = a->pt0[i]; pt < a->pt0[i + 1]; pt++) shared += a->pkin[pt] != pt - a->pt0[i];
    assert_true(shared > 0); /* a base corner is a side face's corner too */
    rd_sim_free(a);
    rd_sim_free(b);
}

/* A mesh vertex is a point of each candidate face around it; merge.c makes it one point with
 * their summed area, or a few where its faces' normals lie more than 60 deg apart. Checked
 * against the mesh itself (independent of the point builder's sums): the points at one vertex
 * stand for pmult faces each, together at most its degree (no face counted twice), and most
 * vertices keep one point; every point is a mesh vertex standing for pmult faces around it; a point that stands for every face around the
 * vertex carries the vertex area, a third of each incident triangle's area (3DEC's rule),
 * computed here from the edges' cross product. Tolerance 1e-12 relative: the two sums differ
 * only in rounding (the builder takes each third through the face centroid's fan). */
static void test_merged_mesh_points(void **state)
{
    (void)state;
    char obj[96], cmd[256], text[1024], path[80];
    snprintf(obj, sizeof obj, "%s.obj", out);
    snprintf(cmd, sizeof cmd, "/usr/bin/python3 tools/make_pbr.py --seed 1 -o %s > /dev/null", obj);
    assert_int_equal(system(cmd), 0);
    snprintf(path, sizeof path, "%s.%d.h5", out, nout++ % 4);
    snprintf(text, sizeof text,
             "block create brick size 1.2 1.2 0.3 position 0 0 -0.15 fixed name pedestal\n"
             "block import mesh '%s' seat-on pedestal density 2750 name rock\n"
             "contact property stiffness-normal 1e10 stiffness-shear 1e9 friction 40\n"
             "model solve time 0.01\noutput hdf5 '%s' interval 0.005\n",
             obj, path);
    rd_scenario sc;
    rd_error err;
    assert_int_equal(rd_scenario_parse(&sc, "merge.dat", text, &err), 0);
    rd_sim *s = rd_sim_create(&sc, &err);
    rd_scenario_free(&sc);
    unlink(obj);
    assert_non_null(s);
    const rd_poly *p = &s->poly[1];
    int full = 0, merged = 0, split = 0;
    for (int pt = s->pt0[1]; pt < s->pt0[2]; pt++) {
        int at_place = 0, first = 1; /* the faces the points at pt's place stand for */
        for (int q = s->pt0[1]; q < s->pt0[2]; q++)
            if (!memcmp(s->pl[q], s->pl[pt], sizeof s->pl[pt])) {
                at_place += s->pmult[q];
                first &= q >= pt;
            }
        split += first && at_place > s->pmult[pt];
        int v = 0;
        while (v < p->nv && memcmp(p->v[v], s->pl[pt], sizeof p->v[v])) v++;
        assert_true(v < p->nv); /* a mesh face's points are its vertices */
        int degree = 0;
        double area = 0;
        for (int f = 0; f < p->nf; f++)
            for (int k = 0; k < p->flen[f]; k++) {
                if (p->fidx[p->fstart[f] + k] != v) continue;
                assert_int_equal(p->flen[f], 3); /* the OBJ's triangles are kept as faces */
                const double *a = p->v[p->fidx[p->fstart[f]]], *b = p->v[p->fidx[p->fstart[f] + 1]],
                             *c = p->v[p->fidx[p->fstart[f] + 2]];
                double e1[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] },
                       e2[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
                double n[3] = { e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                                e1[0] * e2[1] - e1[1] * e2[0] };
                area += sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) / 6.0;
                degree++;
            }
        assert_true(s->pmult[pt] >= 1 && at_place <= degree);
        merged += s->pmult[pt] > 1;
        assert_true(s->pa[pt] <= area * (1 + 1e-12));
        if (s->pmult[pt] == degree) {
            full++;
            assert_true(fabs(s->pa[pt] - area) <= 1e-12 * area);
        }
    }
    print_message(
        "PBR mesh: %d points, %d merged, %d carry their whole vertex area, %d places split\n",
        s->pt0[2] - s->pt0[1], merged, full, split);
    assert_true(merged > 0 && full > 0 && 10 * split < s->pt0[2] - s->pt0[1]);
    rd_sim_free(s);
}

static void test_bad_settings(void **state)
{
    (void)state;
    rd_scenario sc;
    rd_error err;
    assert_int_equal(
        rd_scenario_parse(&sc, "p.dat", "contact interface-perturbation remove 1\n", &err), -1);
    assert_non_null(strstr(err.msg, "p.dat:1:"));
    rd_scenario_free(&sc);
}

int main(void)
{
    snprintf(out, sizeof out, "/tmp/rd_perturb_%d", (int)getpid());
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_corners_threshold),  cmocka_unit_test(test_same_seed_same_points),
        cmocka_unit_test(test_zero_scatter_noop),  cmocka_unit_test(test_shared_places),
        cmocka_unit_test(test_merged_mesh_points), cmocka_unit_test(test_bad_settings),
    };
    int rc = cmocka_run_group_tests(tests, NULL, NULL);
    for (int k = 0; k < 4; k++) {
        char path[80];
        snprintf(path, sizeof path, "%s.%d.h5", out, k);
        unlink(path);
    }
    return rc;
}
