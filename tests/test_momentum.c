/* Momentum balance of the contact: two free bodies strike each other with nothing else acting.
 *
 * Action and reaction: whatever the joint law does (impact loss, slip, struck points), every
 * subcontact pushes the two bodies with equal and opposite forces about the same point, so the
 * pair's total linear momentum and its angular momentum about a fixed point keep their values.
 * The contact sums a side's forces once per side: the owner takes sum F and sum ro x F, the
 * other body -sum F and -(sum ro x F + d x sum F), d = xo - xt (contact.c, side_step); leaving
 * out or misplacing the d term breaks the angular balance by |d| |sum F| dt a step.
 *
 * Leapfrog keeps one discrete angular momentum exactly (to round-off): with the forces found at
 * x(n) and the kick v(n+1/2) = v(n-1/2) + F(n) dt / m, L(n+1/2) = L(n-1/2) + T(n) dt,
 *     J = sum over bodies of m x(n) x v(n+1/2) + L(n+1/2)
 * changes by dt sum (x(n) x F + T) = 0 a step (x(n) - x(n-1) = v(n-1/2) dt is parallel to the
 * old velocity). An observer sees x(n+1) = x(n) + v(n+1/2) dt. Tolerance: the round-off of the
 * sums, 2^-52 relative a step, over the run's 7 561 steps and a few dozen operations each:
 * 1e-10 of the momenta's scale. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include "rockdem/rockdem.h"
#include "rockdem/observer.h"
#include "engine/sim.h"
#include "base/vec.h"
#include "check.h"
#include "tmpdir.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define ROUNDOFF 1e-10 /* relative to the momenta's scale */

typedef struct momenta {
    double p0[3], J0[3]; /* at the first sample: kg m/s, kg m^2/s about the origin */
    double dp, dJ;       /* largest change since */
    int n;
} momenta;

/* The free bodies' total momentum p and discrete angular momentum J (see the header). */
static void total_momenta(const rd_sim *s, double p[3], double J[3])
{
    p[0] = p[1] = p[2] = J[0] = J[1] = J[2] = 0;
    for (int i = 0; i < s->nb; i++) {
        if (s->fixed[i]) continue;
        double xn[3], mxv[3];
        for (int k = 0; k < 3; k++) xn[k] = s->x[i][k] - s->v[i][k] * s->dt; /* x(n) */
        rd_cross(xn, s->v[i], mxv);
        for (int k = 0; k < 3; k++) {
            p[k] += s->mass[i] * s->v[i][k];
            J[k] += s->mass[i] * mxv[k] + s->L[i][k];
        }
    }
}

static int momenta_sample(void *user, rd_sim *sim, const rd_sample *smp, rd_error *err)
{
    (void)smp;
    (void)err;
    momenta *mo = user;
    double p[3], J[3];
    total_momenta(sim, p, J);
    if (mo->n++ == 0) {
        memcpy(mo->p0, p, sizeof p);
        memcpy(mo->J0, J, sizeof J);
    }
    for (int k = 0; k < 3; k++) {
        mo->dp = fmax(mo->dp, fabs(p[k] - mo->p0[k]));
        mo->dJ = fmax(mo->dJ, fabs(J[k] - mo->J0[k]));
    }
    return 0;
}

/* A spinning brick thrown obliquely at a resting one, no gravity: it strikes off centre, slides
 * (friction 30 deg), loses energy at the impact (restitution 0.5), and both fly apart tumbling. */
static void test_free_strike_keeps_momentum(void **state)
{
    (void)state;
    const char *text = "model gravity 0\nmodel settle off\n"
                       "block create brick size 0.4 0.4 0.4 position 0 0 0 name target\n"
                       "block create brick size 0.3 0.5 0.2 position -0.36 0.12 0.05 name shot\n"
                       "block initial name shot velocity 1.5 -0.2 0.3 angular-velocity 2 -3 5\n"
                       "contact property stiffness-normal 1e9 stiffness-shear 1e9 friction 30 "
                       "restitution 0.5\n"
                       "model solve time 0.5\noutput hdf5 'x.h5' interval 0.005\n";
    rd_scenario sc;
    rd_error err;
    assert_int_equal(rd_scenario_parse(&sc, "test.dat", text, &err), 0);
    char out[128];
    snprintf(out, sizeof out, "output.file=%s/strike.h5", tmpdir);
    assert_int_equal(rd_scenario_set(&sc, out, &err), 0);
    rd_sim *sim = rd_sim_create(&sc, &err);
    if (!sim) fail_msg("%s", err.msg);
    momenta mo = { .n = 0 };
    rd_observer obs = { .user = &mo, .sample = momenta_sample };
    assert_int_equal(rd_sim_add_observer(sim, &obs, &err), 0);
    assert_int_equal(rd_sim_run(sim), RD_STATUS_DONE);
    double e[7];
    rd_sim_energy(sim, e);
    double pscale = 0, jscale = 0;
    for (int k = 0; k < 3; k++) {
        pscale = fmax(pscale, fabs(mo.p0[k]));
        jscale = fmax(jscale, fabs(mo.J0[k]));
    }
    print_message(
        "free strike: %d samples, friction %.4g J, damping %.4g J; |dp| %.3g of %.3g kg m/s, "
        "|dJ| %.3g of %.3g kg m^2/s\n",
        mo.n, e[3], e[4], mo.dp, pscale, mo.dJ, jscale);
    assert_true(e[3] > 1e-3 && e[4] > 1e-3); /* they met: slid, and lost energy at the impact */
    rd_check_abs("free strike: linear momentum change / its scale", mo.dp / pscale, 0.0, ROUNDOFF,
                 RD_STRICT);
    rd_check_abs("free strike: angular momentum change / its scale", mo.dJ / jscale, 0.0, ROUNDOFF,
                 RD_STRICT);
    rd_sim_free(sim);
    rd_scenario_free(&sc);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_free_strike_keeps_momentum),
    };
    return cmocka_run_group_tests(tests, setup_dir, remove_dir);
}
