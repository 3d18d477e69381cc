/* Engine validation against independent values (closed forms and rigid-block mechanics).
 * Each test states its tolerance and why. Scenes are written inline in the scenario language,
 * so these also exercise the parser and the whole create -> settle -> shake path. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include "rockdem/rockdem.h"
#include "rockdem/validate.h"

#include <gsl/gsl_integration.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "rockdem/observer.h"
#include "tmpdir.h"
#include "check.h"

/* Parse `text`, apply NULL-terminated overrides, run; returns the sim (caller frees). */
static rd_sim *run_scene(const char *text, const char *const *sets, rd_scenario *sc, rd_status *st)
{
    rd_error err;
    assert_int_equal(rd_scenario_parse(sc, "test.dat", text, &err), 0);
    char out[128];
    snprintf(out, sizeof out, "output.file=%s/out.h5", tmpdir);
    assert_int_equal(rd_scenario_set(sc, out, &err), 0);
    for (int k = 0; sets && sets[k]; k++) {
        if (rd_scenario_set(sc, sets[k], &err)) fail_msg("%s", err.msg);
    }
    rd_sim *sim = rd_sim_create(sc, &err);
    if (!sim) fail_msg("%s", err.msg);
    *st = rd_sim_run(sim);
    return sim;
}

/* Run a one-block scene; the summary's body array then points at *body, which outlives the
 * simulation (rd_summary.body is borrowed from it). */
static void run_summary(const char *text, const char *const *sets, rd_summary *sum,
                        rd_body_summary *body)
{
    rd_scenario sc;
    rd_status st;
    rd_sim *sim = run_scene(text, sets, &sc, &st);
    rd_sim_summary(sim, sum);
    assert_int_equal(sum->nbodies, 1);
    *body = sum->body[0];
    sum->body = body;
    assert_true(st == RD_STATUS_DONE || st == RD_STATUS_OVERTURNED);
    rd_sim_free(sim);
    rd_scenario_free(&sc);
}

/* 0.4 x 0.4 x 1.6 m granite block on a base: b = 0.2, h = 0.8, alpha = atan(1/4). */
static const char *slender =
    "block create brick size 4 4 1 position 0 0 -0.5 fixed name base\n"
    "block create brick size 0.4 0.4 1.6 position 0 0 0.8 name b\n"
    "contact property stiffness-normal 1e10 stiffness-shear 1e9 friction 40 spacing vertices\n"
    "output hdf5 'x.h5' interval 0.01\n";

/* ---- static tipping threshold a = g tan(alpha) ------------------------------------------ */
/* A 2 s rectangular pulse with Cundall local damping 0.8 is a quasi-static load (the damping
 * removes the dynamic overshoot of a suddenly applied load, as 3DEC's static solve). With
 * corner subcontacts the trailing corners open exactly when the resultant reaches the edge,
 * so the rigid-body threshold holds: 1 % below, the tilt stays elastic (micro-radians); 1 %
 * above, the block tips (tilt grows by orders of magnitude). */
static double tip_tilt(double factor)
{
    char text[1024], amp[64];
    snprintf(text, sizeof text, "%s%s", slender,
             "model damping local 0.8\nground-motion pulse rectangular amplitude 1 duration 2\n"
             "model overturn angle 80\nmodel solve time 2\n");
    snprintf(amp, sizeof amp, "motion.amplitude=%.17g", factor * 9.81 * 0.25);
    const char *sets[] = { amp, NULL };
    rd_summary sum;
    rd_body_summary b0;
    run_summary(text, sets, &sum, &b0);
    return sum.body[0].max_tilt;
}

/* Bounds from the elastic closed form: on four corner points (rotational stiffness KN A b^2 =
 * 1e10 x 0.16 x 0.04 = 6.4e7 N m/rad) the overturning moment m a h of the 0.4 x 0.4 x 1.6 m block
 * (m = 691 kg at 0.99 g tan(alpha), h = 0.8 m) turns it by 2.1e-5 rad = 8.4e-5 alpha: "below"
 * allows 12 x that (1e-3 alpha), "above" asks for 20 x the allowance, reached only by rigid
 * tipping about the corner. */
static void test_static_tipping_threshold(void **state)
{
    (void)state;
    double below = tip_tilt(0.99), above = tip_tilt(1.01);
    double alpha = atan(0.25);
    assert_true(below < 1e-3 * alpha); /* elastic rotation only */
    assert_true(above > 2e-2 * alpha); /* tipping: >= 20x the elastic tilt bound */
    assert_true(above > 100 * below);
}

/* ---- sliding threshold a = mu g ------------------------------------------------------------ */
/* A squat 1 x 1 x 0.25 m block (alpha = 76 deg, cannot tip before it slides) with friction
 * 20 deg under the same quasi-static load: 1 % below mu g only the elastic shear springs and a
 * little local slip at the lightly loaded rear move it (< 0.1 mm); 1 % above it slides
 * (millimetres within 1 s). */
static double slide_at(double factor)
{
    char text[1024], amp[64];
    snprintf(text, sizeof text,
             "block create brick size 4 4 1 position 0 0 -0.5 fixed name base\n"
             "block create brick size 1 1 0.25 position 0 0 0.125 name b\n"
             "contact property stiffness-normal 1e10 stiffness-shear 1e9 friction 20\n"
             "model damping local 0.8\nground-motion pulse rectangular amplitude 1 duration 1\n"
             "model solve time 1\noutput hdf5 'x.h5' interval 0.01\n");
    snprintf(amp, sizeof amp, "motion.amplitude=%.17g", factor * 9.81 * tan(20 * M_PI / 180));
    const char *sets[] = { amp, NULL };
    rd_summary sum;
    rd_body_summary b0;
    run_summary(text, sets, &sum, &b0);
    return sum.body[0].max_slide;
}

/* Bounds: below, the elastic shear deflection mu m g / (KS A) = 0.364 x 675 x 9.81 / 1e9 =
 * 2.4e-6 m; 1e-4 m allows 40 x that for the local slip at the unloaded rear. Above, rigid-plastic
 * sliding with the net force 0.01 mu m g, cut to (1 - 0.8) of it by the local damping (its force
 * is 0.8 |F| against the motion), slides 0.2 x 0.01 x 3.57 m/s^2 x (1 s)^2 / 2 = 3.6e-3 m: 2e-3 m
 * leaves room for the onset and nothing else reaches it. */
static void test_sliding_threshold(void **state)
{
    (void)state;
    double below = slide_at(0.99), above = slide_at(1.01);
    assert_true(below < 1e-4);
    assert_true(above > 2e-3);
}

/* ---- free rocking: first impact time ---------------------------------------------------- */
/* Rigid block released from rest at theta0 about its corner: from the energy integral
 * 1/2 th'^2 + p^2 cos(alpha - th) = p^2 cos(alpha - th0), the time to reach th = 0 is
 * int_0^th0 dth / sqrt(2 p^2 (cos(alpha - th0) - cos(alpha - th))). With th = th0 - s^2 the
 * integrand is smooth; GSL's adaptive quadrature gives it to 1e-12. */
typedef struct {
    double alpha, th0, p2;
} rock_par;

static double rock_integrand(double s, void *v)
{
    const rock_par *r = v;
    double c = cos(r->alpha - r->th0) - cos(r->alpha - r->th0 + s * s);
    if (s == 0) return 2.0 / sqrt(2 * r->p2 * sin(r->alpha - r->th0));
    return 2 * s / sqrt(2 * r->p2 * c);
}

static double rigid_first_impact(double b, double h, double g, double th0)
{
    double R = hypot(b, h);
    rock_par r = { atan2(b, h), th0, 3 * g / (4 * R) };
    gsl_integration_workspace *w = gsl_integration_workspace_alloc(200);
    gsl_function F = { rock_integrand, &r };
    double t, e;
    gsl_integration_qag(&F, 0, sqrt(th0), 1e-13, 1e-12, 200, GSL_INTEG_GAUSS61, w, &t, &e);
    gsl_integration_workspace_free(w);
    return t;
}

static double dem_first_impact(double kn)
{
    char text[1024], set_kn[64], set_ks[64];
    snprintf(text, sizeof text, "%s%s", slender,
             "block initial name b tilt 7.0181217 direction 0\nmodel solve time 0.6\n");
    snprintf(set_kn, sizeof set_kn, "contact.stiffness-normal=%g", kn);
    snprintf(set_ks, sizeof set_ks, "contact.stiffness-shear=%g", 0.1 * kn);
    const char *sets[] = { set_kn, set_ks, NULL };
    rd_scenario sc;
    rd_status st;
    rd_sim *sim = run_scene(text, sets, &sc, &st);
    int n;
    const rd_event *ev = rd_sim_events(sim, &n);
    double t = -1;
    for (int k = 0; k < n && t < 0; k++)
        if (!strcmp(ev[k].type, "impact")) t = ev[k].time;
    rd_sim_free(sim);
    rd_scenario_free(&sc);
    return t;
}

/* Tolerance: the DEM error comes from the contact compliance (the pivot sinks by about
 * m g / (KN A)) and the step, both shrinking with KN; KS = KN / 10 as usual in rock joints (seed
 * 002: 10 and 1 GPa/m). From the convergence study computed here: the error must fall with every
 * tenfold KN, and at KN = 1e10 Pa/m it must be within 1.5 |t(1e10) - t(1e11)| (Richardson with
 * a KN ratio of 10 for an error of order >= 1/2 in KN: 1 / (1 - 10^-0.5) = 1.46), plus the
 * quadrature's 1e-12: the error is then the discretisation error the study measures, not a
 * model error. */
static void test_free_rocking_first_impact(void **state)
{
    (void)state;
    double alpha = atan(0.25), th0 = 7.0181217 * M_PI / 180;
    assert_true(fabs(th0 - 0.5 * alpha) < 1e-8);
    double tr = rigid_first_impact(0.2, 0.8, 9.81, th0);
    const double kns[] = { 1e8, 1e9, 1e10, 1e11 };
    double err[4], tk[4];
    for (int k = 0; k < 4; k++) {
        double t = tk[k] = dem_first_impact(kns[k]);
        assert_true(t > 0);
        err[k] = fabs(t - tr) / tr;
        print_message("KN %-5g first impact %.6f s, rigid %.6f s, error %.3e\n", kns[k], t, tr,
                      err[k]);
    }
    for (int k = 0; k + 1 < 4; k++) assert_true(err[k + 1] < err[k]); /* converges with KN */
    rd_check_rel("first impact time at KN 1e10", tk[2], tr, 1.5 * fabs(tk[2] - tk[3]) / tr + 1e-12,
                 RD_STRICT);
}

/* ---- energy balance, frictionless and undamped ------------------------------------------ */
/* With no friction and no damping, nothing dissipates: kinetic + gravitational + elastic
 * energy must stay constant up to the integration error of the explicit scheme. Tolerance from
 * a step-halving study computed here: if the residual is a discretisation error of order >= 1
 * in dt, the residual at dt is at most 2 |r(dt) - r(dt/2)| (Richardson, 1 / (1 - 2^-1)); plus
 * 1e-12 for round-off. A residual that does not shrink with dt (an energy leak in the contact
 * law) fails. */
static void test_energy_balance_frictionless(void **state)
{
    (void)state;
    char text[1024];
    snprintf(text, sizeof text, "%s%s", slender,
             "block initial name b tilt 7 direction 30\nmodel solve time 1.5\n");
    const char *sets[] = { "contact.friction=0", NULL, NULL };
    rd_summary sum, half;
    rd_body_summary b0, b1;
    run_summary(text, sets, &sum, &b0);
    char dt[64];
    snprintf(dt, sizeof dt, "model.timestep=%.17g", 0.5 * sum.dt);
    sets[1] = dt;
    run_summary(text, sets, &half, &b1);
    print_message("frictionless energy residual %.3e at dt %.3g s, %.3e at dt/2\n",
                  sum.energy_residual_max, sum.dt, half.energy_residual_max);
    rd_check_abs("energy residual (relative to the largest term)", sum.energy_residual_max, 0,
                 2 * fabs(sum.energy_residual_max - half.energy_residual_max) + 1e-12, RD_STRICT);
    assert_true(sum.body[0].uplifted);
}

/* ---- at rest stays at rest -------------------------------------------------------------- */
/* 60 s of a settled block with no motion: the tilt must stay at round-off level and the block
 * must not creep (slide) — any drift from the shear-spring update or the rotation integrator
 * would accumulate over the ~1e6 steps. Bounds: 1e-9 rad and 1e-9 m (round-off is ~1e-15). */
static void test_rest_stays_at_rest(void **state)
{
    (void)state;
    const char *text =
        "block create brick size 2 2 0.5 position 0 0 -0.25 fixed name base\n"
        "block create brick size 0.5 0.5 1.0 position 0.1 -0.2 0.5 rotation 0 0 30 name b\n"
        "contact property stiffness-normal 1e9 stiffness-shear 1e8 friction 40\n"
        "model solve time 60\noutput hdf5 'x.h5' interval 0.5\n";
    rd_scenario sc;
    rd_status st;
    rd_sim *sim = run_scene(text, NULL, &sc, &st);
    rd_summary sum;
    rd_sim_summary(sim, &sum);
    double v[3], w[3];
    rd_sim_body_state(sim, 0, NULL, NULL, v, w);
    print_message("60 s at rest: max tilt %.3e rad, max slide %.3e m, |v| %.3e m/s\n",
                  sum.body[0].max_tilt, sum.body[0].max_slide,
                  sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]));
    assert_int_equal(st, RD_STATUS_DONE);
    assert_true(sum.end_time > 59.99);
    assert_true(sum.body[0].max_tilt < 1e-9);
    assert_true(sum.body[0].max_slide < 1e-9);
    assert_true(sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) < 1e-6);
    int n;
    rd_sim_events(sim, &n);
    assert_int_equal(n, 0); /* no uplift, slip, impact or unsettled event */
    rd_sim_free(sim);
    rd_scenario_free(&sc);
}

/* ---- determinism ------------------------------------------------------------------------ */
static uint64_t fnv1a(uint64_t h, const void *p, size_t n)
{
    const unsigned char *c = p;
    for (size_t i = 0; i < n; i++) h = (h ^ c[i]) * 1099511628211ull;
    return h;
}

static uint64_t final_hash(void)
{
    char text[1024];
    snprintf(text, sizeof text, "%s%s", slender,
             "ground-motion pulse one-sine amplitude 0.5g frequency 2 direction 20\n"
             "model damping viscous 0.1\nmodel solve time 1\n");
    rd_scenario sc;
    rd_status st;
    rd_sim *sim = run_scene(text, NULL, &sc, &st);
    double x[3], q[4], v[3], w[3], e[7];
    rd_sim_body_state(sim, 0, x, q, v, w);
    rd_sim_energy(sim, e);
    uint64_t h = 1469598103934665603ull;
    h = fnv1a(h, x, sizeof x);
    h = fnv1a(h, q, sizeof q);
    h = fnv1a(h, v, sizeof v);
    h = fnv1a(h, w, sizeof w);
    h = fnv1a(h, e, sizeof e);
    int n;
    const rd_event *ev = rd_sim_events(sim, &n);
    for (int k = 0; k < n; k++) h = fnv1a(h, &ev[k].time, sizeof ev[k].time);
    rd_sim_free(sim);
    rd_scenario_free(&sc);
    return h;
}

static void test_determinism(void **state)
{
    (void)state;
    uint64_t a = final_hash(), b = final_hash();
    print_message("final-state hash %016llx\n", (unsigned long long)a);
    assert_true(a == b);
}

/* ---- time step: a fixed step above the limit is refused, just below it is stable -------- */
static void test_fixed_step_limit(void **state)
{
    (void)state;
    rd_scenario sc;
    rd_error err;
    char text[1024];
    snprintf(text, sizeof text, "%s%s", slender,
             "model timestep fixed 1e-3\nmodel solve time 0.1\n");
    assert_int_equal(rd_scenario_parse(&sc, "t.dat", text, &err), 0);
    assert_null(rd_sim_create(&sc, &err));
    assert_non_null(strstr(err.msg, "above the stable limit"));
    rd_scenario_free(&sc);

    /* the estimate is an upper bound on the stiffest frequency, so 0.99 of it must run a hard
       case (stiff contact, impacts) without blowing up */
    snprintf(
        text, sizeof text, "%s%s", slender,
        "block initial name b tilt 10 direction 0\nmodel timestep auto safety 0.99\nmodel solve time 1\n");
    const char *sets[] = { "contact.stiffness-normal=1e12", "contact.stiffness-shear=1e12", NULL };
    rd_status st;
    rd_sim *sim = run_scene(text, sets, &sc, &st);
    assert_int_equal(st, RD_STATUS_DONE);
    rd_sim_free(sim);
    rd_scenario_free(&sc);
}

/* ---- overturning: strong pulse overturns, weak one does not ----------------------------- */
/* Rigid-block theory (Housner): a 2 Hz one-sine pulse must exceed g tan(alpha) = 0.25 g even to
 * uplift this block; at 0.2 g nothing moves, at 3 g it certainly overturns (far above the
 * minimum-overturning curve, which is below 1.5 g at w/p = 3.5 for alpha = 0.245). */
static void test_overturn_strong_not_weak(void **state)
{
    (void)state;
    char text[1024];
    snprintf(text, sizeof text, "%s%s", slender,
             "ground-motion pulse one-sine amplitude 0.2g frequency 2\nmodel damping viscous 0.2\n"
             "model solve time 4\n");
    rd_summary sum;
    rd_body_summary b0;
    run_summary(text, NULL, &sum, &b0);
    assert_false(sum.body[0].overturned);
    assert_true(sum.body[0].max_tilt < 1e-3);
    const char *strong[] = { "motion.amplitude=3g", NULL };
    run_summary(text, strong, &sum, &b0);
    assert_true(sum.body[0].overturned);
    assert_true(sum.body[0].overturn_time > 0);
}

/* ---- 3-D monitoring: a spinning block twists, it does not rock --------------------------- */
/* A 0.5 x 0.5 x 1 m block spun at 3 rad/s about the vertical on its base. Coulomb friction
 * under uniform pressure gives a torque mu m g r_mean, r_mean = a (sqrt 2 + ln(1 + sqrt 2)) / 6
 * for a square of side a, against I_z = m a^2 / 6: it stops after turning
 * w0^2 / (2 mu g r_mean 6 / a^2). The 11 x 11 bed integrates r_mean by the trapezoidal rule and
 * the shear springs store a little twist, so allow 3 %. Rocking must stay at round-off. The bed
 * (spacing auto) is what integrates the pressure: four corners would put it all at r = a / sqrt 2
 * and stop the spin 1.85 times sooner. */
static void test_spin_reports_twist(void **state)
{
    (void)state;
    const char *text =
        "block create brick size 2 2 0.5 position 0 0 -0.25 fixed name base\n"
        "block create brick size 0.5 0.5 1.0 position 0 0 0.5 name b\n"
        "contact property stiffness-normal 1e10 stiffness-shear 1e9 friction 40 spacing auto\n"
        "block initial name b angular-velocity 0 0 3\n"
        "model solve time 0.5\noutput hdf5 'x.h5' interval 0.005\n";
    rd_summary sum;
    rd_body_summary b0;
    run_summary(text, NULL, &sum, &b0);
    double a = 0.5, mu = tan(40 * M_PI / 180), rmean = a * (sqrt(2) + log(1 + sqrt(2))) / 6;
    double expect = 9.0 / (2 * mu * 9.81 * rmean * 6 / (a * a));
    print_message("spin: twist %.5f rad (Coulomb %.5f), rocking %.2e / %.2e rad\n",
                  sum.body[0].final_twist, expect, sum.body[0].max_rocking_in,
                  sum.body[0].max_rocking_out);
    assert_true(fabs(sum.body[0].final_twist - expect) < 0.03 * expect);
    assert_true(sum.body[0].max_rocking_in < 1e-9 && sum.body[0].max_rocking_out < 1e-9);
    assert_false(sum.body[0].uplifted);
}

/* ---- precariousness: tipping angle around the vertical ---------------------------------- */
/* A 0.4 x 0.6 x 1.6 m brick turned 30 deg about z: the least static tipping angle is
 * atan(0.2 / 0.8) leaning along its short axis (30 or 210 deg), the quasi-static tipping
 * acceleration g tan(alpha) = g / 4; the support polygon comes from the contact points at rest,
 * so this is exact up to the settled compression (1e-9 relative). */
static void test_precariousness(void **state)
{
    (void)state;
    const char *text =
        "block create brick size 3 3 0.5 position 0 0 -0.25 fixed name base\n"
        "block create brick size 0.4 0.6 1.6 position 0 0 0.8 rotation 0 0 30 name b\n"
        "model solve time 0.01\noutput hdf5 'x.h5' interval 0.005\n";
    rd_summary sum;
    rd_body_summary b0;
    run_summary(text, NULL, &sum, &b0);
    const rd_body_summary *b = &sum.body[0];
    double dir = fmod(b->alpha_min_direction * 180 / M_PI, 180.0);
    print_message("alpha_min %.9f rad towards %.1f deg, a_tip %.6f m/s^2\n", b->alpha_min,
                  b->alpha_min_direction * 180 / M_PI, b->tip_accel_min);
    assert_true(fabs(b->alpha_min - atan(0.25)) < 1e-6 * atan(0.25));
    assert_true(fabs(dir - 30) < 1e-9);
    assert_true(fabs(b->tip_accel_min - 9.81 * 0.25) < 1e-5);
}

/* ---- bonded joints: tension and cohesion hold a block that tips without them ------------- */
/* The 0.4 x 0.4 x 1.6 m block under a quasi-static 0.35 g (above g tan alpha = 0.25 g): bare,
 * it tips. Bonded, the base is a linear-elastic section until its far edge reaches the tensile
 * strength T: with the weight's pressure p = m g / A = 42 kPa, it carries a moment up to
 * (T + p) I / (b/2), I = 0.4^4 / 12: 5.8 kN m for T = 0.5 MPa, three times the overturning
 * moment m a h = 1.9 kN m, so it stays (elastic tilt only); with T = 0.1 MPa (1.5 kN m) it
 * peels and tips. The closed form is for a continuous section, which the bed (spacing auto)
 * samples: four corners at b/2 with a quarter of the area each would resist (T + p) A b / 2,
 * three times as much (4.5 kN m at T = 0.1 MPa: the weak joint would hold). */
static double glued_tilt(const char *tension)
{
    char text[1024], set[64];
    snprintf(text, sizeof text,
             "block create brick size 4 4 1 position 0 0 -0.5 fixed name base\n"
             "block create brick size 0.4 0.4 1.6 position 0 0 0.8 name b\n"
             "contact property stiffness-normal 1e10 stiffness-shear 1e9 friction 40 spacing auto\n"
             "model damping local 0.8\nground-motion pulse rectangular amplitude 0.35g duration 1\n"
             "model overturn angle 80\nmodel solve time 1\noutput hdf5 'x.h5' interval 0.01\n");
    snprintf(set, sizeof set, "contact.tension=%s", tension);
    const char *sets[] = { set, "contact.cohesion=5e5", NULL };
    rd_summary sum;
    rd_body_summary b0;
    run_summary(text, sets, &sum, &b0);
    return sum.body[0].max_tilt;
}

static void test_bonded_joint(void **state)
{
    (void)state;
    double bare = glued_tilt("0"), weak = glued_tilt("1e5"), glued = glued_tilt("5e5");
    print_message("0.35 g: tilt bare %.3e, T 0.1 MPa %.3e, T 0.5 MPa %.3e rad\n", bare, weak,
                  glued);
    assert_true(bare > 1e-2 && weak > 1e-2);
    assert_true(glued < 1e-3);
}

/* ---- restitution: two measures of one free-rocking run ----------------------------------- */
/* rd_restitution_measure reads r twice from one run: by amplitude decay, and from the speeds at
 * equal |theta| before and after each impact carried to theta = 0 by energy. When the impact is
 * complete within the band the two are the same energy ratio, so they must agree to the 0.5 %
 * of the specification (issue 11, must-have 1; RD_CHECK_RTOL): strict for the rigid preset
 * (the 0.5 x 1 m and the 1/3 x 1 m block), the 11 x 11 bed and the defaults (corners). With the rigid preset at contact
 * restitution 0.5 the new pivot rebounds and the block bounces after each impact, losing energy
 * after the band: a known gap, printed as an expected failure. */
static void restitution_case(const char *what, const char *size, const char *contact, double e,
                             int mode)
{
    char text[512];
    snprintf(text, sizeof text,
             "block create brick size 2 2 0.4 position 0 0 -0.2 fixed name floor\n"
             "block create brick size %s position 0 0 0.5 name b\n%s\n",
             size, contact);
    rd_scenario sc;
    rd_error err;
    assert_int_equal(rd_scenario_parse(&sc, "test.dat", text, &err), 0);
    sc.contact.restitution = e;
    rd_refscene rs;
    assert_int_equal(rd_refscene_map(&sc, &rs, &err), 0);
    rd_restitution m;
    if (rd_restitution_measure(&sc, 0.5 * rs.alpha, &m, &err)) fail_msg("%s", err.msg);
    assert_int_equal(m.n, 3);
    rd_check_rel(what, m.r_speed, m.r, RD_CHECK_RTOL, mode);
    rd_scenario_free(&sc);
}

static void test_restitution_two_measures(void **state)
{
    (void)state;
    restitution_case("restitution: speeds vs amplitude decay, rigid preset 0.5 x 1 m",
                     "0.5 0.5 1.0", "contact preset rigid", 0, RD_STRICT);
    restitution_case("restitution: speeds vs amplitude decay, rigid preset 1/3 x 1 m",
                     "0.3333333 0.3333333 1.0", "contact preset rigid", 0, RD_STRICT);
    restitution_case("restitution: speeds vs amplitude decay, 11 x 11 bed 0.5 x 1 m", "0.5 0.5 1.0",
                     "contact property stiffness-shear 1e9 spacing auto", 0, RD_STRICT);
    restitution_case("restitution: speeds vs amplitude decay, defaults 0.5 x 1 m", "0.5 0.5 1.0",
                     "", 0, RD_STRICT);
    restitution_case("restitution: rigid preset at contact restitution 0.5 (bounces after impact)",
                     "0.5 0.5 1.0", "contact preset rigid", 0.5, RD_XFAIL);
}

/* ---- calibration: a crossing the secant steps cannot resolve is told apart ----------------- */
/* The `3dec` preset (KS = KN / 10, elastic) on the 0.5 x 1 m block: r(e) at e = 0.5 and 0.75 lies
 * on either side of 0.70 (the block slides and bounces, so r(e) jumps between them). The scan
 * must find that crossing: the calibration then reaches the target (0) or says the crossing is
 * too uneven (2), never "no e crosses it" (1), and what it returns as closest is a measured r. */
static void test_calibration_uneven_crossing(void **state)
{
    (void)state;
    const char *text = "block create brick size 2 2 0.4 position 0 0 -0.2 fixed name floor\n"
                       "block create brick size 0.5 0.5 1.0 position 0 0 0.5 name b\n"
                       "contact preset 3dec\n";
    rd_scenario sc;
    rd_error err;
    assert_int_equal(rd_scenario_parse(&sc, "test.dat", text, &err), 0);
    double e = -1, reached = -1;
    int rc = rd_restitution_calibrate(&sc, 0.5 * atan(0.5), 0.70, &e, &reached, &err);
    print_message("3dec preset, target 0.70: return %d, closest r %.4f at e %.4f\n", rc, reached,
                  e);
    assert_true(rc == 0 || rc == 2);
    assert_true(e >= 0 && e <= 1 && reached > 0 && reached < 1);
    rd_scenario_free(&sc);
}

/* ---- defaults: free rocking neither hops nor slides ------------------------------------- */
/* The specification (issue 11, must-have 4): the 0.5 x 0.5 x 1.0 m block released from half
 * its tipping angle with the default contact and mu >= 0.7 neither hops (the whole base in the
 * air) nor slides more than 1 mm. Hop: the lowest vertex, z_c - b sin(tilt) - h cos(tilt) for
 * this in-plane rocking, above the ground top (z = 0); the springs act in compression only, so
 * any height above 0 means no point touches: the bound is 0 itself, not a tolerance. Slide:
 * where the block rests after 5 s (tilt under 3e-5 rad, so its centre stands within 0.02 mm of
 * its footprint's), its centre's horizontal distance from its start, against the specification's
 * 1 mm.
 * mu 0.700 (35 deg) and the default 40 deg. */
typedef struct hop_log {
    double hop, x, y, tilt; /* m: highest lowest vertex; final centre; final tilt, rad */
} hop_log;

static int hop_sample(void *user, rd_sim *sim, const rd_sample *s, rd_error *err)
{
    (void)sim;
    (void)err;
    hop_log *h = user;
    double t = s->tilt[0], low = s->position[2] - 0.25 * sin(t) - 0.5 * cos(t);
    if (low > h->hop) h->hop = low;
    h->x = s->position[0];
    h->y = s->position[1];
    h->tilt = t;
    return 0;
}

static void test_defaults_no_hop_no_slide(void **state)
{
    (void)state;
    static const char *friction[] = { "contact.friction=35", "contact.friction=40" };
    for (int k = 0; k < 2; k++) {
        const char *text = "block create brick size 2 2 0.4 position 0 0 -0.2 fixed name floor\n"
                           "block create brick size 0.5 0.5 1.0 position 0 0 0.5 name b\n"
                           "block initial name b tilt 13.2825 direction 0\n"
                           "model solve time 5\noutput hdf5 'x.h5' interval 0.0005\n";
        rd_scenario sc;
        rd_error err;
        assert_int_equal(rd_scenario_parse(&sc, "test.dat", text, &err), 0);
        char out[128];
        snprintf(out, sizeof out, "output.file=%s/hop.h5", tmpdir);
        assert_int_equal(rd_scenario_set(&sc, out, &err), 0);
        assert_int_equal(rd_scenario_set(&sc, friction[k], &err), 0);
        rd_sim *sim = rd_sim_create(&sc, &err);
        if (!sim) fail_msg("%s", err.msg);
        hop_log h = { -INFINITY, 0, 0, 0 };
        rd_observer obs = { .user = &h, .sample = hop_sample };
        assert_int_equal(rd_sim_add_observer(sim, &obs, &err), 0);
        assert_int_equal(rd_sim_run(sim), RD_STATUS_DONE);
        double slide = hypot(h.x, h.y);
        print_message("defaults, %s: lowest vertex at most %.4f mm above the ground, slide %.4f "
                      "mm, final tilt %.1e rad\n",
                      friction[k], 1e3 * h.hop, 1e3 * slide, h.tilt);
        print_message("CHECK defaults: highest lowest vertex (m; above 0 is a hop): rockdem %.6g, "
                      "reference <= 0\n",
                      h.hop);
        rd_verdict("defaults: hop", h.hop <= 0, h.hop, 0.0, RD_STRICT);
        rd_check_abs("defaults: slide at rest (m)", slide, 0.0, 1e-3, RD_STRICT);
        rd_sim_free(sim);
        rd_scenario_free(&sc);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_static_tipping_threshold),
        cmocka_unit_test(test_sliding_threshold),
        cmocka_unit_test(test_free_rocking_first_impact),
        cmocka_unit_test(test_energy_balance_frictionless),
        cmocka_unit_test(test_rest_stays_at_rest),
        cmocka_unit_test(test_determinism),
        cmocka_unit_test(test_fixed_step_limit),
        cmocka_unit_test(test_overturn_strong_not_weak),
        cmocka_unit_test(test_spin_reports_twist),
        cmocka_unit_test(test_precariousness),
        cmocka_unit_test(test_bonded_joint),
        cmocka_unit_test(test_restitution_two_measures),
        cmocka_unit_test(test_defaults_no_hop_no_slide),
        cmocka_unit_test(test_calibration_uneven_crossing),
    };
    return cmocka_run_group_tests(tests, setup_dir, remove_dir);
}
