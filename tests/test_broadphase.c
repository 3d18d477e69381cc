/* Broad phase within its margin (src/engine/pairs.c): bodies keep their boxes between steps and
 * rebuild them only when a pair cannot be decided from the drift bound. The live set must be,
 * at every step, exactly the set of pairs whose boxes (every vertex in the current pose, grown
 * by the margin) overlap, computed here from scratch; and a pair must be live whenever a vertex
 * of one body lies within the contact band of the other (convex) body, i.e. before any contact
 * point can touch. Bodies are moved along seeded random walks: 50 steps of up to 0.4 margin in
 * translation, then 50 in rotation (at the body's radius), with a jump of 3 margins every 37 steps,
 * so pairs appear and part, decisions are taken both lazily and by rebuilding. Both the direct
 * test of every pair (up to RD_BRUTE_MAX bodies, with a scanned mesh whose hull is transformed
 * only on a rebuild) and the sweep (more bodies) are checked. The contact's far planes (skipped
 * while a body cannot have moved past them) are checked against all planes the same way. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include "rockdem/rockdem.h"
#include "engine/sim.h"
#include "base/vec.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define STEPS 1500

static char out[64];

static rd_sim *make(const char *text)
{
    rd_scenario sc;
    rd_error err;
    assert_int_equal(rd_scenario_parse(&sc, "broadphase.dat", text, &err), 0);
    rd_sim *s = rd_sim_create(&sc, &err);
    if (!s) fprintf(stderr, "%s\n", err.msg);
    rd_scenario_free(&sc);
    assert_non_null(s);
    return s;
}

/* The shipped PBR (tools/make_pbr.py, seed 1) seated on a fixed 1.2 m pedestal, with `more`
 * scenario lines (other bodies) after it. */
static rd_sim *make_pbr(const char *more)
{
    char obj[96], cmd[256], text[1024];
    snprintf(obj, sizeof obj, "%s.obj", out);
    snprintf(cmd, sizeof cmd, "/usr/bin/python3 tools/make_pbr.py --seed 1 -o %s > /dev/null", obj);
    assert_int_equal(system(cmd), 0);
    snprintf(text, sizeof text,
             "block create brick size 1.2 1.2 0.3 position 0 0 -0.15 fixed name pedestal\n"
             "block import mesh '%s' seat-on pedestal density 2750 name rock\n"
             "%s"
             "contact property stiffness-normal 1e10 stiffness-shear 1e9 friction 40\n"
             "model solve time 0.01\n",
             obj, more);
    rd_sim *s = make(text);
    unlink(obj);
    return s;
}

static uint64_t rng = 88172645463325252u;
static double uniform(void) /* xorshift64, [-1, 1) */
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return (double)(rng >> 11) / 9007199254740992.0 * 2.0 - 1.0;
}

/* Every vertex of body i in its current pose (rd_body_refresh's expression), boxed and grown by
 * the margin: the exact box, from nothing the broad phase keeps. */
static void exact_box(const rd_sim *s, int i, double bx[6])
{
    double R[9];
    rd_quat_to_mat(s->q[i], R);
    for (int k = 0; k < 3; k++) {
        bx[k] = INFINITY;
        bx[k + 3] = -INFINITY;
    }
    for (int v = 0; v < s->poly[i].nv; v++) {
        double w[3];
        rd_mat_vec(R, s->poly[i].v[v], w);
        rd_axpy(1.0, s->x[i], w);
        for (int k = 0; k < 3; k++) {
            bx[k] = fmin(bx[k], w[k]);
            bx[k + 3] = fmax(bx[k + 3], w[k]);
        }
    }
    for (int k = 0; k < 3; k++) {
        bx[k] -= s->margin;
        bx[k + 3] += s->margin;
    }
}

/* Does some vertex of body i lie within the contact band of convex body j (behind every plane of
 * j, to the band)? */
static int touches(const rd_sim *s, int i, int j)
{
    if (!s->convex[j]) return 0;
    double Ri[9], Rj[9], tol = RD_CONTACT_BAND * fmin(s->poly[i].radius, s->poly[j].radius);
    rd_quat_to_mat(s->q[i], Ri);
    rd_quat_to_mat(s->q[j], Rj);
    for (int v = 0; v < s->poly[i].nv; v++) {
        double w[3], in = 1;
        rd_mat_vec(Ri, s->poly[i].v[v], w);
        rd_axpy(1.0, s->x[i], w);
        for (int f = 0; f < s->poly[j].nf && in; f++) {
            double n[3];
            rd_mat_vec(Rj, s->poly[j].fn[f], n);
            in = rd_dot(n, w) - (s->poly[j].fd[f] + rd_dot(n, s->x[j])) <= tol;
        }
        if (in) return 1;
    }
    return 0;
}

/* Move each free body by a random step: a translation of up to `frac` margins, or (turn) a
 * rotation of up to `frac` margins at the body's radius (a bound with too small a rotation term
 * then decides wrongly). */
static void walk(rd_sim *s, double frac, int turn)
{
    for (int i = 0; i < s->nb; i++) {
        if (s->fixed[i]) continue;
        double phi[3], dq[4], q[4], r = s->poly[i].radius;
        for (int k = 0; k < 3; k++) {
            s->x[i][k] += turn ? 0.0 : frac * s->margin * uniform() / sqrt(3.0);
            phi[k] = turn ? frac * s->margin / r * uniform() / sqrt(3.0) : 0.0;
        }
        rd_quat_from_rotvec(phi, dq);
        rd_quat_mul(dq, s->q[i], q);
        rd_quat_normalize(q);
        memcpy(s->q[i], q, sizeof q);
    }
}

/* Random walks of the scene's free bodies; the live set checked at every step. Returns the box
 * builds made. */
static long check_walk(rd_sim *s, double box0[][3], double spread)
{
    long builds = 0, live_pairs = 0, touching = 0;
    int n = s->nb;
    char *live = calloc((size_t)n * (size_t)n, 1);
    assert_non_null(live);
    for (int step = 0; step < STEPS; step++) {
        walk(s, step % 37 == 36 ? 3.0 : 0.4, step / 50 % 2);
        for (int i = 0; i < n; i++) /* keep the bodies in their region, so pairs meet and part */
            for (int k = 0; k < 3 && !s->fixed[i]; k++)
                if (fabs(s->x[i][k] - box0[i][k]) > spread)
                    s->x[i][k] = box0[i][k] + copysign(spread, s->x[i][k] - box0[i][k]);
        double pose_before[16][7];
        assert_true(n <= 16);
        memcpy(pose_before, s->box_pose, (size_t)n * sizeof *pose_before);
        rd_bodies_refresh_step(s);
        assert_int_equal(rd_pairs_update(s), 0);
        for (int i = 0; i < n; i++)
            builds += memcmp(pose_before[i], s->box_pose[i], sizeof pose_before[i]) != 0;
        memset(live, 0, (size_t)n * (size_t)n);
        for (int k = 0; k < s->nlive; k++)
            live[s->pair[s->live[k]].a * n + s->pair[s->live[k]].b] = 1;
        for (int i = 0; i < n; i++)
            for (int j = i + 1; j < n; j++) {
                if (s->fixed[i] && s->fixed[j]) continue;
                double bi[6], bj[6];
                exact_box(s, i, bi);
                exact_box(s, j, bj);
                int want = bi[0] <= bj[3] && bj[0] <= bi[3] && bi[1] <= bj[4] && bj[1] <= bi[4] &&
                           bi[2] <= bj[5] && bj[2] <= bi[5];
                if (live[i * n + j] != want)
                    fail_msg("step %d: pair %d-%d live %d, exact boxes overlap %d", step, i, j,
                             live[i * n + j], want);
                if ((touches(s, i, j) || touches(s, j, i)) && !live[i * n + j])
                    fail_msg("step %d: bodies %d and %d touch but their pair is not live", step, i,
                             j);
                touching += touches(s, i, j) || touches(s, j, i);
                live_pairs += want;
            }
    }
    free(live);
    print_message(
        "%d bodies, %d steps: %ld live pair-steps (%ld touching), %ld box builds of %ld body-steps\n",
        n, STEPS, live_pairs, touching, builds, (long)STEPS * n);
    assert_true(live_pairs > 0 && touching > 0);
    assert_true(live_pairs < (long)STEPS * n * (n - 1) / 2); /* pairs also part */
    return builds;
}

/* A pad, two bricks and the scanned PBR (non-convex: hull boxed only on a rebuild): the direct
 * pair test. Lazy decisions must dominate: fewer box builds than half the body-steps. */
static void test_direct_pairs_exact(void **state)
{
    (void)state;
    rd_sim *s = make_pbr("block create brick size 0.3 0.3 0.5 position 0.75 0 0.25 name b1\n"
                         "block create brick size 0.3 0.3 0.5 position 0 0.75 0.25 name b2\n");
    assert_true(s->nb <= 8 && !s->convex[1]);
    double box0[4][3];
    for (int i = 0; i < s->nb; i++) memcpy(box0[i], s->x[i], sizeof box0[i]);
    long builds = check_walk(s, box0, 0.3);
    assert_true(builds < (long)STEPS * s->nb / 2);
    rd_sim_free(s);
}

/* Twelve bricks in a ring on a pad: the sweep. */
static void test_sweep_pairs_exact(void **state)
{
    (void)state;
    char text[4096];
    int n = snprintf(text, sizeof text,
                     "block create brick size 3 3 0.2 position 0 0 -0.1 fixed name pad\n");
    for (int k = 0; k < 12; k++)
        n += snprintf(text + n, sizeof text - (size_t)n,
                      "block create brick size 0.3 0.3 0.5 position %.4f %.4f 0.25 name b%d\n",
                      0.85 * cos(k * M_PI / 6), 0.85 * sin(k * M_PI / 6), k);
    snprintf(
        text + n, sizeof text - (size_t)n,
        "contact property stiffness-normal 1e10 stiffness-shear 1e9 friction 40\nmodel solve time 0.01\n");
    rd_sim *s = make(text);
    assert_true(s->nb > 8);
    double box0[13][3];
    for (int i = 0; i < s->nb; i++) memcpy(box0[i], s->x[i], sizeof box0[i]);
    check_walk(s, box0, 0.15);
    rd_sim_free(s);
}

/* Far planes (contact.c: vertex_distances): against the fixed pedestal the rock's candidate
 * vertices skip the planes they clear by a margin while the rock cannot have moved that far.
 * The rock sweeps over the pedestal to its edges and back, with random steps of up to 5 mm (a
 * 10 cm jump every 41 steps) in height and in rotation at its radius: after each contact step every candidate vertex's plane bits must equal the ones found
 * from all planes (its world position against every plane, the bands as in contact.c), and
 * planes must have been skipped. */
static void test_far_planes_exact(void **state)
{
    (void)state;
    rd_sim *s = make_pbr("");
    const int o = 1, t = 0, np = s->poly[t].nf;
    double tol = RD_CONTACT_BAND * fmin(s->poly[o].radius, s->poly[t].radius);
    double raise = s->sc.contact.perturb.raise, reach = 0.5 * tol - raise, out_band = tol + raise;
    long skipped = 0, checked = 0, reused = 0;
    double pose_before[7] = { 0 }, x0[3];
    memcpy(x0, s->x[o], sizeof x0);
    for (int step = 0; step < 600; step++) {
        double phi[3], dq[4], q[4], r = s->poly[o].radius, a = step % 41 == 40 ? 0.1 : 0.005;
        for (int k = 0; k < 3; k++) {
            s->x[o][k] += a * uniform() / sqrt(3.0);
            phi[k] = a / r * uniform() / sqrt(3.0);
        }
        rd_quat_from_rotvec(phi, dq);
        rd_quat_mul(dq, s->q[o], q);
        rd_quat_normalize(q);
        memcpy(s->q[o], q, sizeof q);
        /* sweep over the pedestal to its edges (0.6 m) and back: its side planes come near */
        s->x[o][0] = x0[0] + 0.45 * sin(2 * M_PI * step / 300.0);
        s->x[o][1] = x0[1] + 0.45 * sin(2 * M_PI * step / 470.0);
        s->x[o][2] = fmin(fmax(s->x[o][2], x0[2] - 0.02), x0[2] + 0.05); /* seated, or above */
        rd_bodies_refresh_step(s);
        assert_int_equal(rd_contact_step(s), 0);
        const rd_side *sd = &s->pair[0].side[0];
        if (s->nlive == 0 || sd->owner != o) continue;
        reused += step > 0 && memcmp(pose_before, sd->far_pose, sizeof pose_before) == 0;
        memcpy(pose_before, sd->far_pose, sizeof pose_before);
        const int ncv = s->cv0[s->nb];
        for (int k = s->cv0[o], m = 0; k < s->cv0[o + 1]; k++, m++) {
            const uint64_t *mk = s->cv_mask + (size_t)m * 2 * (size_t)((np + 63) / 64);
            /* the mesh's step keeps its candidate vertices in cv_world (integrate.c) */
            const double x[3] = { s->cv_world[k], s->cv_world[ncv + k], s->cv_world[2 * ncv + k] };
            for (int qp = 0; qp < np; qp++) {
                double dd = rd_dot(s->wn[s->face0[t] + qp], x) - s->wd[s->face0[t] + qp];
                int out_bit = (int)((mk[qp >> 6] >> (qp & 63)) & 1),
                    up_bit = (int)((mk[(np + 63) / 64 + (qp >> 6)] >> (qp & 63)) & 1);
                if (out_bit != !(dd <= out_band) || up_bit != (dd > reach))
                    fail_msg(
                        "step %d vertex %d plane %d: bits %d %d, distance %g (band %g, reach %g)",
                        step, m, qp, out_bit, up_bit, dd, out_band, reach);
                checked++;
            }
        }
        for (int qp = 0; qp < np; qp++)
            skipped += sd->far_clear > 0 && ((sd->far[qp >> 6] >> (qp & 63)) & 1);
    }
    print_message(
        "far planes: %ld vertex-plane bits checked, %ld plane-steps marked far, far planes skipped "
        "in %ld of 600 steps\n",
        checked, skipped, reused);
    assert_true(checked > 0 && skipped > 0 && reused > 0 &&
                reused < 599); /* skipped, and re-measured */
    rd_sim_free(s);
}

int main(void)
{
    snprintf(out, sizeof out, "/tmp/rd_broadphase_%d", (int)getpid());
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_direct_pairs_exact),
        cmocka_unit_test(test_sweep_pairs_exact),
        cmocka_unit_test(test_far_planes_exact),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
