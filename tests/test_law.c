/* The joint law's energy booking (src/engine/law.h) against closed forms (issue 10, item 3).
 *
 * Leapfrog's kinetic energy changes over a step by the mean of a force's values at the step's
 * two ends times the step's displacement, so the dissipation that closes the balance over a
 * step is that trapezoid work less the springs' energy change:
 *  - the Coulomb cap: -(f0 + f).dU / 2 - (|f|^2 - |f0|^2) / (2 KS A'), which is lim * d for a
 *    steady slide and the released spring energy for a dropping limit;
 *  - a released subcontact: its springs at mid-step, the shear one taken through half the
 *    step's displacement under its last limit (a slipping spring gives up 1/2 lim^2 / KS A' plus
 *    lim |dU| / 2, however stiff: the uncapped half step credited (KS A' dU)^2 / 8 more);
 *  - a dashpot: -(Fd(n-1) + Fd(n)) vn dt / 2;
 *  - an elastic spring switching within a step: the mean of max(stretch, 0) over the step.
 * Each reference is worked out by hand from these definitions; the tolerance is round-off,
 * 1e-12 relative (a few operations on numbers of order 1). */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include "check.h"
#include "engine/law.h"

#define ROUNDOFF 1e-12 /* relative: a handful of double operations */

static const double N_Z[3] = { 0, 0, 1 }; /* the joint plane's normal */

/* Steady slide: last force -lim x (resisting motion along +x), displacement d along +x. */
static void test_cap_steady_slide(void **state)
{
    (void)state;
    const double sA = 2e7, lim = 3e3, d = 4e-5;
    double fs[3] = { -lim, 0, 0 }, vr[3] = { d, 0, 0 }, e = 0;
    int slip = rd_law_shear(fs, N_Z, vr, 0.0, sA, 1.0, lim, &e);
    assert_int_equal(slip, 1);
    rd_check_rel("steady slide books lim d (J)", e, lim * d, ROUNDOFF, RD_STRICT);
    rd_check_rel("steady slide keeps the force at the limit (N)", -fs[0], lim, ROUNDOFF, RD_STRICT);
}

/* The limit drops with no motion: the spring gives up (F0^2 - lim^2) / (2 KS A'). */
static void test_cap_limit_drops(void **state)
{
    (void)state;
    const double sA = 1e6, f0 = 500, lim = 200;
    double fs[3] = { f0, 0, 0 }, vr[3] = { 0, 0, 0 }, e = 0;
    rd_law_shear(fs, N_Z, vr, 0.0, sA, 1e-4, lim, &e);
    rd_check_rel("dropping limit books the released spring energy (J)", e,
                 (f0 * f0 - lim * lim) / (2 * sA), ROUNDOFF, RD_STRICT);
}

/* A slide that turns: last force -lim x, displacement d along +y with KS A' d = lim. Trapezoid
 * work less the (unchanged) spring energy: -(f0 + f).dU / 2 with f = lim t / |t|, t = (-lim,
 * -lim): lim d / (2 sqrt 2). The former formula booked (sqrt 2 - 1) lim d, 17 % more. */
static void test_cap_turning_slide(void **state)
{
    (void)state;
    const double lim = 1e3, sA = 1e7, d = lim / sA;
    double fs[3] = { -lim, 0, 0 }, vr[3] = { 0, d, 0 }, e = 0;
    rd_law_shear(fs, N_Z, vr, 0.0, sA, 1.0, lim, &e);
    rd_check_rel("turning slide books the trapezoid work (J)", e, lim * d / (2 * sqrt(2.0)),
                 ROUNDOFF, RD_STRICT);
}

/* A stiff spring slipping at its limit lets go: 1/2 lim^2 / sA + lim v dt / 2 (its energy, and
 * the half step's slide), not the uncapped (lim + sA v dt / 2)^2 / (2 sA). The normal spring
 * (still compressed, sideways exit) at its mean stretch; one that crossed zero gives nothing. */
static void test_release(void **state)
{
    (void)state;
    const double lim = 2e3, sA = 1e12, v = 0.1, dt = 5e-5, kA = 3e8;
    const double fs[3] = { -lim, 0, 0 }, vr[3] = { v, 0, 0 };
    double e = rd_law_release_energy(0.0, 0.0, 0.0, 0, fs, N_Z, vr, 0.0, sA, lim, dt);
    rd_check_rel("released slipping shear spring (J)", e, 0.5 * lim * lim / sA + 0.5 * lim * v * dt,
                 ROUNDOFF, RD_STRICT);
    const double zero[3] = { 0, 0, 0 }, still[3] = { 0, 0, 0 };
    e = rd_law_release_energy(kA, 1e-4, 0.8e-4, 0, zero, N_Z, still, 0.0, sA, lim, dt);
    rd_check_rel("released compressed normal spring (J)", e, 0.5 * kA * 0.9e-4 * 0.9e-4, ROUNDOFF,
                 RD_STRICT);
    e = rd_law_release_energy(kA, 1e-6, -2e-6, 0, zero, N_Z, still, 0.0, sA, lim, dt);
    rd_check_abs("normal spring that opened by itself (J)", e, 0.0, 0.0, RD_STRICT);
}

/* A dashpot's work over a step: the mean of its two end forces times the displacement. */
static void test_dashpot(void **state)
{
    (void)state;
    const double fd0 = -40, fd1 = -10, vn = 0.2, dt = 1e-4; /* opening: the dashpot pulls back */
    rd_check_rel("dashpot work, trapezoid (J)", rd_law_dashpot_work(fd0, fd1, vn, dt),
                 0.5 * 50 * vn * dt, ROUNDOFF, RD_STRICT);
}

/* A spring that switches within a step bears the mean of max(stretch, 0) over the step, the
 * stretch moving linearly through sn by w: checked against that mean by the midpoint rule on
 * 100000 sub-intervals (error below 1e-9 of w here), and it joins zero and the linear spring at
 * sn = -w/2 and w/2. */
static void test_switch_stretch(void **state)
{
    (void)state;
    const double w = 3e-5; /* m: 0.6 m/s over 5e-5 s */
    const double sn[] = { -1.4e-5, -5e-6, 0.0, 7e-6, 1.3e-5 };
    for (size_t k = 0; k < sizeof sn / sizeof sn[0]; k++) {
        const int n = 100000;
        double mean = 0;
        for (int i = 0; i < n; i++) {
            double s = sn[k] + w * ((i + 0.5) / n - 0.5);
            mean += (s > 0 ? s : 0.0) / n;
        }
        rd_check_abs("mean stretch over the step (m)", rd_law_switch_stretch(sn[k], w), mean,
                     1e-9 * w, RD_STRICT);
    }
    rd_check_abs("zero at -w/2 (m)", rd_law_switch_stretch(-0.5 * w, w), 0.0, 0.0, RD_STRICT);
    rd_check_rel("the linear spring at w/2 (m)", rd_law_switch_stretch(0.5 * w, w), 0.5 * w,
                 ROUNDOFF, RD_STRICT);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_cap_steady_slide),  cmocka_unit_test(test_cap_limit_drops),
        cmocka_unit_test(test_cap_turning_slide), cmocka_unit_test(test_release),
        cmocka_unit_test(test_dashpot),           cmocka_unit_test(test_switch_stretch),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
