/* rockdem — tests of the rigid-block reference solvers (Housner 1-DOF, Kounadis 2-DOF) against
 * closed forms, quadrature, energy integrals, limits and an independent finite-difference
 * Lagrangian (the checks listed in docs/ROCKING-EQUATIONS.md). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "rockdem/reference.h"

#define G 9.81

/* ---- ground inputs ------------------------------------------------------------------------ */

typedef struct sine_pulse {
    double a, w; /* amplitude m/s^2, circular frequency rad/s; one cycle from t = 0 */
} sine_pulse;

static void sine_fn(void *ctx, double t, double *ug, double *vg)
{
    const sine_pulse *p = ctx;
    *ug = t <= 2.0 * M_PI / p->w ? p->a * sin(p->w * t) : 0.0;
    *vg = 0.0;
}

static void ramp_fn(void *ctx, double t, double *ug, double *vg)
{
    *ug = *(const double *)ctx * t; /* m/s^3 times s */
    *vg = 0.0;
}

/* A one-sine ground with its end as break and quiet time. */
static rd_ground sine_ground(sine_pulse *p, double *brk)
{
    *brk = 2.0 * M_PI / p->w;
    rd_ground gm = { .fn = sine_fn, .ctx = p, .breaks = brk, .nbreaks = 1, .t_quiet = *brk };
    return gm;
}

/* Times of the impact events at joint j (at most n), returns how many. */
static size_t impact_times(const rd_ref_result *r, int j, double *t, size_t n)
{
    size_t k = 0;
    for (size_t i = 0; i < r->nevents && k < n; i++)
        if (r->events[i].kind == RD_REF_IMPACT && r->events[i].joint == j) t[k++] = r->events[i].t;
    return k;
}

static const rd_ref_event *first_event(const rd_ref_result *r, rd_ref_event_kind kind)
{
    for (size_t i = 0; i < r->nevents; i++)
        if (r->events[i].kind == kind) return &r->events[i];
    return NULL;
}

static rd_ref_result run_housner(const rd_housner_def *d, const rd_ground *gm, const rd_ref_opts *o)
{
    rd_ref_result r;
    rd_error err = { "" };
    int rc = rd_housner_solve(d, gm, o, &r, &err);
    if (rc) print_error("%s\n", err.msg);
    assert_int_equal(rc, 0);
    return r;
}

static rd_ref_result run_stack(const rd_kounadis_def *d, const rd_ground *gm, const rd_ref_opts *o)
{
    rd_ref_result r;
    rd_error err = { "" };
    int rc = rd_kounadis_solve(d, gm, o, &r, &err);
    if (rc) print_error("%s\n", err.msg);
    assert_int_equal(rc, 0);
    return r;
}

/* ---- Housner ------------------------------------------------------------------------------ */

/* Free rocking from rest at theta0 reaches theta = 0 at the quadrature time. Both are accurate
 * to ~1e-10 (CVODE rtol 1e-11, QAGS 1e-13), so 1e-7 relative leaves margin and still catches
 * any error in p, the equation of motion or the integrand (those move it by >= 1e-3). */
static void test_housner_quarter_period(void **state)
{
    (void)state;
    const double geom[2][2] = { { 0.25, 0.5 }, { 0.1, 1.0 } };
    const double frac[3] = { 0.1, 0.5, 0.95 };
    for (int g = 0; g < 2; g++) {
        rd_housner_def d = rd_housner_def_default();
        d.b = geom[g][0];
        d.h = geom[g][1];
        double alpha = rd_housner_alpha(d.b, d.h), p = rd_housner_p(d.b, d.h, d.g);
        for (int i = 0; i < 3; i++) {
            rd_ref_opts o = rd_ref_opts_default();
            o.rtol = 1e-11;
            o.atol = 1e-13;
            o.theta0[0] = frac[i] * alpha;
            o.t_end = 20.0 / p;
            o.dt_out = 0.0;
            rd_ref_result r = run_housner(&d, NULL, &o);
            double t_imp = -1.0, t_q = 0.0;
            rd_error err;
            assert_int_equal(impact_times(&r, 0, &t_imp, 1), 1);
            assert_int_equal(rd_housner_free_time(alpha, p, o.theta0[0], &t_q, &err), 0);
            assert_true(fabs(t_imp - t_q) <= 1e-7 * t_q);
            rd_ref_result_free(&r);
        }
    }
}

/* Slender limit: the exact quarter period tends to acosh(1/(1 - theta0/alpha))/p. Replacing
 * sin(alpha - theta) by (alpha - theta) changes the restoring moment by at most alpha^2/6
 * relative, so the time differs by O(alpha^2): below alpha^2 (1% at alpha = 0.1), and the error
 * must shrink about 4x when alpha halves (it is a true limit, not a coincidence). */
static void test_housner_slender_limit(void **state)
{
    (void)state;
    double errs[2];
    const double alphas[2] = { 0.2, 0.1 };
    for (int i = 0; i < 2; i++) {
        double alpha = alphas[i], h = 1.0, b = tan(alpha) * h;
        double p = rd_housner_p(b, h, G), theta0 = 0.5 * alpha, t;
        rd_error err;
        assert_int_equal(rd_housner_free_time(alpha, p, theta0, &t, &err), 0);
        double t_lin = acosh(1.0 / (1.0 - theta0 / alpha)) / p;
        errs[i] = fabs(t - t_lin) / t;
        assert_true(errs[i] < alpha * alpha);
    }
    assert_true(errs[1] < 0.35 * errs[0] && errs[1] > 0.15 * errs[0]);
}

/* Restitution: after each impact the rocking energy above the rest state scales by e^2, so the
 * peaks obey cos(alpha - th_{n+1}) - cos(alpha) = e^2 (cos(alpha - th_n) - cos(alpha)); each
 * impact event has omega+ = e omega-. Energy between impacts is conserved to ~1e-10, hence 1e-7. */
static void test_housner_restitution(void **state)
{
    (void)state;
    rd_housner_def d = rd_housner_def_default();
    double alpha = rd_housner_alpha(d.b, d.h);
    const double es[2] = { -1.0, 0.85 };
    for (int k = 0; k < 2; k++) {
        d.e = es[k];
        double e = es[k] < 0.0 ? rd_housner_r(alpha) : es[k];
        assert_true(fabs(rd_housner_r(atan(0.5)) - 0.7) < 1e-15); /* h/b = 2: r = 0.7 */
        rd_ref_opts o = rd_ref_opts_default();
        o.theta0[0] = 0.8 * alpha;
        o.t_end = 3.0;
        o.dt_out = 0.0;
        rd_ref_result r = run_housner(&d, NULL, &o);
        double prev = o.theta0[0];
        int npeaks = 0, nimp = 0;
        for (size_t i = 0; i < r.nevents && npeaks < 5; i++) {
            const rd_ref_event *ev = &r.events[i];
            if (ev->kind == RD_REF_IMPACT && ev->s1 != 0) {
                assert_true(fabs(ev->omega_post[0] - e * ev->omega_pre[0]) <= 1e-14);
                nimp++;
            }
            if (ev->kind != RD_REF_PEAK) continue;
            double th = fabs(ev->theta[0]);
            double ratio = (cos(alpha - th) - cos(alpha)) / (cos(alpha - prev) - cos(alpha));
            assert_true(fabs(ratio - e * e) < 1e-7);
            prev = th;
            npeaks++;
        }
        assert_int_equal(npeaks, 5);
        assert_true(nimp >= 5);
        rd_ref_result_free(&r);
    }
}

/* Free rocking without loss (e = 1): 0.5 theta'^2 + p^2 cos(alpha - |theta|) is constant; at
 * rtol 1e-12 the drift relative to p^2 must stay below 1e-8 over several cycles. */
static void test_housner_energy(void **state)
{
    (void)state;
    rd_housner_def d = rd_housner_def_default();
    d.e = 1.0;
    double alpha = rd_housner_alpha(d.b, d.h), p = rd_housner_p(d.b, d.h, d.g);
    rd_ref_opts o = rd_ref_opts_default();
    o.rtol = 1e-12;
    o.atol = 1e-14;
    o.theta0[0] = -0.7 * alpha;
    o.t_end = 4.0;
    o.dt_out = 0.01;
    rd_ref_result r = run_housner(&d, NULL, &o);
    double e0 = p * p * cos(alpha - 0.7 * alpha);
    assert_true(r.nsamples > 300);
    for (size_t i = 0; i < r.nsamples; i++) {
        double th = r.samples[i].theta[0], om = r.samples[i].omega[0];
        double e = 0.5 * om * om + p * p * cos(alpha - fabs(th));
        assert_true(fabs(e - e0) < 1e-8 * p * p);
    }
    assert_false(r.summary.overturned);
    assert_true(fabs(r.summary.max_ratio[0] - 0.7) < 1e-9);
    rd_ref_result_free(&r);
}

/* Static uplift: under ug'' = k t the block uplifts when k t = g tan(alpha), on the side
 * s = -sgn(ug''); root location is ~1e-12 s accurate, 1e-9 relative is the test. */
static void test_housner_static_uplift(void **state)
{
    (void)state;
    rd_housner_def d = rd_housner_def_default();
    double alpha = rd_housner_alpha(d.b, d.h);
    const double rates[2] = { 2.0, -5.0 };
    for (int i = 0; i < 2; i++) {
        double k = rates[i];
        rd_ground gm = { .fn = ramp_fn, .ctx = &k, .t_quiet = INFINITY };
        rd_ref_opts o = rd_ref_opts_default();
        o.t_end = 1.1 * G * tan(alpha) / fabs(k);
        rd_ref_result r = run_housner(&d, &gm, &o);
        const rd_ref_event *up = first_event(&r, RD_REF_UPLIFT);
        assert_non_null(up);
        double t_exp = G * tan(alpha) / fabs(k);
        assert_true(fabs(up->t - t_exp) < 1e-9 * t_exp);
        assert_int_equal(up->s1, k > 0.0 ? -1 : 1);
        assert_true(r.samples[r.nsamples - 1].theta[0] * up->s1 > 0.0);
        rd_ref_result_free(&r);
    }
}

static int sine_overturns(const rd_housner_def *d, double a, double f)
{
    sine_pulse sp = { .a = a, .w = 2.0 * M_PI * f };
    double brk;
    rd_ground gm = sine_ground(&sp, &brk);
    rd_ref_opts o = rd_ref_opts_default();
    o.t_end = 6.0;
    o.dt_out = 0.0;
    o.rtol = 1e-9;
    rd_ref_result r = run_housner(d, &gm, &o);
    int ov = r.summary.overturned;
    rd_ref_result_free(&r);
    return ov;
}

/* A second, independent implementation of Housner's block (docs/ROCKING-EQUATIONS.md, section 1)
 * for the threshold check: classical RK4 at a fixed step, the theta = 0 crossing located by
 * linear interpolation within the step, theta'+ = e theta'- there, uplift from rest when
 * |ug''| > g tan(alpha); overturned when |theta| reaches pi/2 within 6 s (a block past the saddle
 * after the pulse falls well within that). It shares no code with src/reference/. */
static double rk4_acc(double p2, double alpha, int s, double th, double ug)
{
    return -p2 * (sin(s * alpha - th) + (ug / G) * cos(s * alpha - th));
}

static int rk4_overturns(double b, double h, double e, double a, double f, double dt)
{
    double alpha = atan2(b, h), p2 = 0.75 * G / hypot(b, h), w = 2 * M_PI * f, T = 1 / f;
    double th = 0, om = 0;
    int s = 0;
    for (long n = 0; n * dt < 6.0; n++) {
        double t = n * dt, ug0 = t <= T ? a * sin(w * t) : 0;
        if (s == 0) {
            if (fabs(ug0) <= G * tan(alpha)) continue;
            s = ug0 > 0 ? -1 : 1;
        }
#define UG(tt) ((tt) <= T ? a * sin(w * (tt)) : 0.0)
        double k1t = om, k1w = rk4_acc(p2, alpha, s, th, UG(t));
        double k2t = om + 0.5 * dt * k1w,
               k2w = rk4_acc(p2, alpha, s, th + 0.5 * dt * k1t, UG(t + 0.5 * dt));
        double k3t = om + 0.5 * dt * k2w,
               k3w = rk4_acc(p2, alpha, s, th + 0.5 * dt * k2t, UG(t + 0.5 * dt));
        double k4t = om + dt * k3w, k4w = rk4_acc(p2, alpha, s, th + dt * k3t, UG(t + dt));
#undef UG
        double th1 = th + dt * (k1t + 2 * k2t + 2 * k3t + k4t) / 6,
               om1 = om + dt * (k1w + 2 * k2w + 2 * k3w + k4w) / 6;
        if (th1 * s < 0) { /* impact inside the step: restart on the other corner at theta = 0 */
            double fr = th / (th - th1);
            om = e * (om + fr * (om1 - om));
            th = 0;
            s = om > 0 ? 1 : om < 0 ? -1 : 0;
            continue;
        }
        th = th1;
        om = om1;
        if (fabs(th) >= M_PI / 2) return 1;
    }
    return 0;
}

typedef int (*overturn_fn)(const rd_housner_def *d, double a, double f, double dt);

static int cvode_overturns(const rd_housner_def *d, double a, double f, double dt)
{
    (void)dt;
    return sine_overturns(d, a, f);
}

static int rk4_overturns_def(const rd_housner_def *d, double a, double f, double dt)
{
    return rk4_overturns(d->b, d->h, d->e, a, f, dt);
}

/* Bisection of the least overturning amplitude in [0.6, 1.4] g to RES (m/s^2). */
#define THR_RES (1e-4 * G)
static double bisect_threshold(overturn_fn fn, const rd_housner_def *d, double f, double dt)
{
    double lo = 0.6 * G, hi = 1.4 * G;
    assert_false(fn(d, lo, f, dt));
    assert_true(fn(d, hi, f, dt));
    while (hi - lo > THR_RES) {
        double mid = 0.5 * (lo + hi);
        if (fn(d, mid, f, dt))
            hi = mid;
        else
            lo = mid;
    }
    return 0.5 * (lo + hi);
}

/* One-sine overturning threshold by bisection for the 0.5 x 1.0 m block under a 2 Hz pulse, with
 * Housner's r = 0.7 and with e = 0.8. Consistency: 0.2 % above the threshold overturns, 0.2 %
 * below does not (the response is not monotone in amplitude in general, so this is a real
 * check). Value: the same bisection on the independent RK4 implementation above, at two steps
 * (2e-5 and 1e-5 s). Tolerance: both bisection resolutions (1e-4 g each) plus the RK4 answer's
 * change when its step is halved (its discretisation error, order 4). */
static void test_housner_sine_threshold(void **state)
{
    (void)state;
    const double es[2] = { -1.0, 0.8 };
    for (int k = 0; k < 2; k++) {
        rd_housner_def d = rd_housner_def_default();
        d.e = es[k];
        double a = bisect_threshold(cvode_overturns, &d, 2.0, 0);
        assert_true(sine_overturns(&d, a * 1.002, 2.0));
        assert_false(sine_overturns(&d, a * 0.998, 2.0));
        rd_housner_def dr = d;
        if (dr.e < 0) dr.e = rd_housner_r(rd_housner_alpha(d.b, d.h));
        double r1 = bisect_threshold(rk4_overturns_def, &dr, 2.0, 2e-5);
        double r2 = bisect_threshold(rk4_overturns_def, &dr, 2.0, 1e-5);
        print_message(
            "one-sine 2 Hz threshold, e = %g: CVODE %.5f g, RK4 %.5f g (dt 2e-5) %.5f g (dt 1e-5)\n",
            dr.e, a / G, r1 / G, r2 / G);
        double tol = 2 * THR_RES + fabs(r1 - r2);
        assert_true(fabs(a - r2) <= tol);
    }
}

/* ---- Kounadis: an independent finite-difference Lagrangian -------------------------------- */

/* Rotate body vector (x, y) clockwise by th. */
static void rot(double th, double x, double y, double out[2])
{
    out[0] = x * cos(th) + y * sin(th);
    out[1] = -x * sin(th) + y * cos(th);
}

/* d/dth of rot(th, x, y). */
static void drot(double th, double x, double y, double out[2])
{
    out[0] = -x * sin(th) + y * cos(th);
    out[1] = -x * cos(th) - y * sin(th);
}

/* Centres of mass (ground frame) and their velocities for pivots (s1, s2). */
static void centres(const rd_kounadis_def *d, int s1, int s2, const double q[2], const double w[2],
                    double c1[2], double c2[2], double v1[2], double v2[2])
{
    double r[2], dr[2], pr[2], dpr[2], cr[2], dcr[2];
    rot(q[0], -s1 * d->b1, d->h1, r);
    drot(q[0], -s1 * d->b1, d->h1, dr);
    rot(q[0], s2 * d->b2 - s1 * d->b1, 2.0 * d->h1, pr);
    drot(q[0], s2 * d->b2 - s1 * d->b1, 2.0 * d->h1, dpr);
    rot(q[1], -s2 * d->b2, d->h2, cr);
    drot(q[1], -s2 * d->b2, d->h2, dcr);
    for (int i = 0; i < 2; i++) {
        double o = i == 0 ? s1 * d->b1 : 0.0;
        c1[i] = o + r[i];
        v1[i] = dr[i] * w[0];
        c2[i] = o + pr[i] + cr[i];
        v2[i] = dpr[i] * w[0] + dcr[i] * w[1];
    }
}

static double kinetic(const rd_kounadis_def *d, int s1, int s2, const double q[2],
                      const double w[2])
{
    double c1[2], c2[2], v1[2], v2[2];
    centres(d, s1, s2, q, w, c1, c2, v1, v2);
    double i1 = d->m1 * (d->b1 * d->b1 + d->h1 * d->h1) / 3.0;
    double i2 = d->m2 * (d->b2 * d->b2 + d->h2 * d->h2) / 3.0;
    return 0.5 * (d->m1 * (v1[0] * v1[0] + v1[1] * v1[1]) +
                  d->m2 * (v2[0] * v2[0] + v2[1] * v2[1]) + i1 * w[0] * w[0] + i2 * w[1] * w[1]);
}

/* Potential of gravity and of the pseudo-force -m a_g in the ground frame. */
static double potential(const rd_kounadis_def *d, int s1, int s2, const double q[2], double ug,
                        double vg)
{
    double c1[2], c2[2], v1[2], v2[2], w[2] = { 0.0, 0.0 };
    centres(d, s1, s2, q, w, c1, c2, v1, v2);
    return d->m1 * ((d->g + vg) * c1[1] + ug * c1[0]) + d->m2 * ((d->g + vg) * c2[1] + ug * c2[0]);
}

/* Five-point derivative of f at 0 with step h (error ~h^4 f^(5)/30). */
static double d5(double fm2, double fm1, double fp1, double fp2, double h)
{
    return (fm2 - 8.0 * fm1 + 8.0 * fp1 - fp2) / (12.0 * h);
}

/* dT/dw_i: exact by polarisation because T is quadratic in w. */
static double dtdw(const rd_kounadis_def *d, int s1, int s2, const double q[2], const double w[2],
                   int i)
{
    double wp[2] = { w[0], w[1] }, wm[2] = { w[0], w[1] };
    wp[i] += 1.0;
    wm[i] -= 1.0;
    return 0.5 * (kinetic(d, s1, s2, q, wp) - kinetic(d, s1, s2, q, wm));
}

/* Lagrange residual E_i = d/dt dT/dw_i - dT/dq_i + dV/dq_i along q + w t + a t^2/2. */
static double lagrange_residual(const rd_kounadis_def *d, int s1, int s2, const double q[2],
                                const double w[2], const double a[2], double ug, double vg, int i)
{
    const double h = 1e-3;
    double f[4], gt[4], gv[4];
    const double steps[4] = { -2.0, -1.0, 1.0, 2.0 };
    for (int k = 0; k < 4; k++) {
        double t = steps[k] * h;
        double qt[2] = { q[0] + w[0] * t + 0.5 * a[0] * t * t,
                         q[1] + w[1] * t + 0.5 * a[1] * t * t };
        double wt[2] = { w[0] + a[0] * t, w[1] + a[1] * t };
        f[k] = dtdw(d, s1, s2, qt, wt, i);
        double qi[2] = { q[0], q[1] };
        qi[i] += t;
        gt[k] = kinetic(d, s1, s2, qi, w);
        gv[k] = potential(d, s1, s2, qi, ug, vg);
    }
    return d5(f[0], f[1], f[2], f[3], h) - d5(gt[0], gt[1], gt[2], gt[3], h) +
           d5(gv[0], gv[1], gv[2], gv[3], h);
}

static double urand(unsigned *s, double lo, double hi)
{
    *s = *s * 1103515245u + 12345u;
    return lo + (hi - lo) * ((*s >> 8) & 0xffff) / 65535.0;
}

/* All eight patterns at random states: the solver's accelerations satisfy the Lagrange
 * equations built from T and V by finite differences (independent of the printed M and rest).
 * The residual is compared with the size of the generalized forces m g R; five-point
 * differences with h = 1e-3 are accurate to ~1e-11 of that, so 1e-8 is the bound. For open
 * pivots the Newton–Euler moment about the pivot must vanish to round-off (1e-10 m g R). The
 * locked and lower-at-rest patterns are checked with the other pivot choice than the code uses. */
static void test_kounadis_lagrange(void **state)
{
    (void)state;
    const int pats[8][2] = { { 1, 1 }, { 1, -1 }, { -1, 1 }, { -1, -1 },
                             { 1, 0 }, { -1, 0 }, { 0, 1 },  { 0, -1 } };
    unsigned seed = 12345u;
    for (int n = 0; n < 40; n++) {
        rd_kounadis_def d = { .b1 = urand(&seed, 0.1, 0.5),
                              .h1 = urand(&seed, 0.2, 1.0),
                              .m1 = urand(&seed, 0.5, 3.0),
                              .b2 = 0.0,
                              .h2 = urand(&seed, 0.2, 1.0),
                              .m2 = urand(&seed, 0.2, 3.0),
                              .g = G };
        d.b2 = d.b1 * urand(&seed, 0.3, 1.0);
        double scale = (d.m1 + d.m2) * d.g * (hypot(d.b1, d.h1) + hypot(d.b2, d.h2));
        for (int k = 0; k < 8; k++) {
            int s1 = pats[k][0], s2 = pats[k][1];
            double th[2] = { urand(&seed, -0.4, 0.4), urand(&seed, -0.4, 0.4) };
            double om[2] = { urand(&seed, -3.0, 3.0), urand(&seed, -3.0, 3.0) };
            double ug = urand(&seed, -8.0, 8.0), vg = urand(&seed, -4.0, 4.0);
            if (!s2) {
                th[1] = th[0];
                om[1] = om[0];
            }
            if (!s1) th[0] = om[0] = 0.0;
            rd_kounadis_eval ev;
            rd_error err;
            assert_int_equal(rd_kounadis_eval_mode(&d, s1, s2, th, om, ug, vg, &ev, &err), 0);
            int p1 = s1 ? s1 : -1, p2 = s2 ? s2 : -1; /* pivots for T and V */
            double e0 = lagrange_residual(&d, p1, p2, th, om, ev.acc, ug, vg, 0);
            double e1 = lagrange_residual(&d, p1, p2, th, om, ev.acc, ug, vg, 1);
            if (s1 && s2) {
                assert_true(fabs(e0) < 1e-8 * scale);
                assert_true(fabs(e1) < 1e-8 * scale);
            } else if (s1) {
                assert_true(fabs(ev.acc[1] - ev.acc[0]) == 0.0);
                assert_true(fabs(e0 + e1) < 1e-8 * scale);
            } else {
                assert_true(ev.acc[0] == 0.0);
                assert_true(fabs(e1) < 1e-8 * scale);
            }
            if (s1) assert_true(fabs(ev.ground[1]) < 1e-10 * scale);
            if (s2) assert_true(fabs(ev.iface[1]) < 1e-10 * scale);
        }
    }
}

/* The static thresholds of item 2 from the rest-pattern corner forces (linear in ug'': two
 * evaluations locate the zero to round-off, 1e-9), for a stack that tips as a whole and one
 * whose upper block tips first; the solver under a slow ramp uplifts in the right pattern at
 * the lower threshold (root location ~1e-12 s; 1e-6 relative). */
static void test_kounadis_static_thresholds(void **state)
{
    (void)state;
    rd_kounadis_def defs[2] = { rd_kounadis_def_default(), rd_kounadis_def_default() };
    defs[1].b2 = 0.1; /* slender upper block: b2/h2 = 0.2 < stack 0.25/0.75 */
    defs[1].m2 = 0.5;
    for (int k = 0; k < 2; k++) {
        const rd_kounadis_def *d = &defs[k];
        double lam_stack, lam_upper;
        rd_kounadis_uplift_thresholds(d, &lam_stack, &lam_upper);
        double th[2] = { 0.0, 0.0 }, om[2] = { 0.0, 0.0 };
        rd_kounadis_eval e0, e1;
        rd_error err;
        assert_int_equal(rd_kounadis_eval_mode(d, 0, 0, th, om, 0.0, 0.0, &e0, &err), 0);
        assert_int_equal(rd_kounadis_eval_mode(d, 0, 0, th, om, G, 0.0, &e1, &err), 0);
        /* ug'' > 0 unloads the right corners (index 1) */
        double zg = e0.ground[1] / (e0.ground[1] - e1.ground[1]);
        double zi = e0.iface[1] / (e0.iface[1] - e1.iface[1]);
        assert_true(fabs(zg - lam_stack) < 1e-9 * lam_stack);
        assert_true(fabs(zi - lam_upper) < 1e-9 * lam_upper);
        assert_true(fabs(e0.ground[0] + e0.ground[1] - (d->m1 + d->m2) * G) < 1e-9 * G);

        double rate = 1.0;
        rd_ground gm = { .fn = ramp_fn, .ctx = &rate, .t_quiet = INFINITY };
        rd_ref_opts o = rd_ref_opts_default();
        double lam = fmin(lam_stack, lam_upper);
        o.t_end = 1.05 * lam * G / rate;
        rd_ref_result r = run_stack(d, &gm, &o);
        const rd_ref_event *up = first_event(&r, RD_REF_UPLIFT);
        assert_non_null(up);
        assert_true(fabs(up->t - lam * G / rate) < 1e-6 * lam * G / rate);
        if (lam_stack < lam_upper) {
            assert_int_equal(up->s1, -1);
            assert_int_equal(up->s2, 0);
        } else {
            assert_int_equal(up->s1, 0);
            assert_int_equal(up->s2, -1);
        }
        rd_ref_result_free(&r);
    }
}

/* Total energy T + V (no ground motion) from the test's own kinematics. */
static double stack_energy(const rd_kounadis_def *d, int s1, int s2, const rd_ref_sample *s)
{
    return kinetic(d, s1, s2, s->theta, s->omega) + potential(d, s1, s2, s->theta, 0.0, 0.0);
}

/* Both blocks rocking freely with no impact yet: T + V is conserved. At rtol 1e-12 the drift
 * relative to the potential at rest stays below 1e-8 (~1e-10 expected). */
static void test_kounadis_energy(void **state)
{
    (void)state;
    rd_kounadis_def d = rd_kounadis_def_default();
    d.b2 = 0.15;
    d.m2 = 0.7;
    rd_ref_opts o = rd_ref_opts_default();
    o.rtol = 1e-12;
    o.atol = 1e-14;
    o.theta0[0] = 0.05;
    o.theta0[1] = 0.15;
    o.omega0[0] = 0.1;
    o.omega0[1] = -0.4;
    o.t_end = 2.0;
    o.dt_out = 0.002;
    rd_ref_result r = run_stack(&d, NULL, &o);
    double t_first = r.summary.t_stop;
    for (size_t i = 0; i < r.nevents; i++)
        if (r.events[i].kind != RD_REF_PEAK) {
            t_first = r.events[i].t;
            break;
        }
    double scale = d.g * (d.m1 * d.h1 + d.m2 * (2.0 * d.h1 + d.h2));
    double e0 = stack_energy(&d, 1, 1, &r.samples[0]);
    size_t n = 0;
    for (size_t i = 0; i < r.nsamples && r.samples[i].t < t_first; i++, n++) {
        assert_int_equal(r.samples[i].s1, 1);
        assert_int_equal(r.samples[i].s2, 1);
        assert_true(fabs(stack_energy(&d, 1, 1, &r.samples[i]) - e0) < 1e-8 * scale);
    }
    assert_true(n > 20);
    rd_ref_result_free(&r);
}

/* m2 -> 0 (1e-9 m1, a squat upper block that stays locked): the ground impacts of the stack
 * happen when the lone lower block's do (Housner with e = r). The perturbation is O(m2/m1) and
 * both solvers are accurate to ~1e-9, hence 1e-6 relative, free and under a pulse. */
static void test_kounadis_light_top(void **state)
{
    (void)state;
    rd_kounadis_def d = rd_kounadis_def_default();
    d.b2 = 0.2;
    d.h2 = 0.05;
    d.m2 = 1e-9;
    rd_housner_def h = rd_housner_def_default();
    sine_pulse sp = { .a = 0.9 * G, .w = 2.0 * M_PI * 2.0 };
    double brk;
    rd_ground pulse = sine_ground(&sp, &brk);
    for (int k = 0; k < 2; k++) {
        rd_ref_opts o = rd_ref_opts_default();
        o.t_end = 3.0;
        o.theta0[0] = o.theta0[1] = k ? 0.0 : 0.3;
        const rd_ground *gm = k ? &pulse : NULL;
        rd_ref_result rs = run_stack(&d, gm, &o);
        rd_ref_result rh = run_housner(&h, gm, &o);
        double ts[8], th[8];
        size_t ns = impact_times(&rs, 0, ts, 8), nh = impact_times(&rh, 0, th, 8);
        assert_true(nh >= 3);
        assert_int_equal(ns, nh);
        for (size_t i = 0; i < nh; i++) assert_true(fabs(ts[i] - th[i]) < 1e-6 * th[i]);
        assert_int_equal(rs.summary.overturned, rh.summary.overturned);
        assert_true(first_event(&rs, RD_REF_UPLIFT) == NULL || k == 1);
        rd_ref_result_free(&rs);
        rd_ref_result_free(&rh);
    }
}

/* Two 2b x 2h blocks of equal density, locked, rock exactly like one 2b x 4h block: with
 * plastic impacts the tall block's Housner r, with restitution r (the lower block's Housner e)
 * every post-impact rate is r / r_H1 times the plastic one, so the tall block's e is
 * r_H(tall) r / r_H1 (less and more loss than plastic). Same samples (1e-7 rad, solver accuracy)
 * and impact times. */
static void test_kounadis_locked_is_one_block(void **state)
{
    (void)state;
    const double alpha1 = rd_housner_alpha(0.25, 0.5), alpha_t = rd_housner_alpha(0.25, 1.0);
    const double rs_[3] = { 0.0, 0.6, 0.75 };
    for (int k = 0; k < 3; k++) {
        rd_kounadis_def d = {
            .b1 = 0.25, .h1 = 0.5, .m1 = 1.0, .b2 = 0.25, .h2 = 0.5, .m2 = 1.0, .g = G, .r = rs_[k]
        };
        double e = k ? rd_housner_r(alpha_t) * rs_[k] / rd_housner_r(alpha1) : -1.0;
        rd_housner_def h = { .b = 0.25, .h = 1.0, .g = G, .e = e };
        rd_ref_opts o = rd_ref_opts_default();
        o.theta0[0] = o.theta0[1] = 0.04;
        o.t_end = 1.5; /* before r = 0.6's rates fall to the rest threshold (Zeno end) */
        o.dt_out = 0.01;
        rd_ref_result rs = run_stack(&d, NULL, &o);
        rd_ref_result rh = run_housner(&h, NULL, &o);
        assert_null(first_event(&rs, RD_REF_UPLIFT));
        assert_int_equal(rs.nsamples, rh.nsamples);
        for (size_t i = 0; i < rs.nsamples; i++) {
            assert_true(fabs(rs.samples[i].theta[0] - rh.samples[i].theta[0]) < 1e-7);
            assert_true(rs.samples[i].theta[1] == rs.samples[i].theta[0]);
        }
        double ts[6], th[6];
        size_t n = impact_times(&rh, 0, th, 6);
        assert_true(n >= 3);
        assert_int_equal(impact_times(&rs, 0, ts, 6), n);
        for (size_t i = 0; i < n; i++) assert_true(fabs(ts[i] - th[i]) < 1e-8 * th[i]);
        rd_ref_result_free(&rs);
        rd_ref_result_free(&rh);
    }
}

/* A restitution that would gain energy at an impact is refused with a message, not integrated:
 * r = 1 for the lower block (kappa = 1 / 0.7) on a locked stack of Housner r 0.44 is no gain,
 * but the upper block alone rocking on a resting lower block keeps more than it had when its
 * own r_H is above r_H1 (a squat top: r_H2 0.9). */
static void test_kounadis_restitution_gain(void **state)
{
    (void)state;
    rd_kounadis_def d = {
        .b1 = 0.25, .h1 = 0.5, .m1 = 1.0, .b2 = 0.1, .h2 = 0.4, .m2 = 0.01, .g = G, .r = 1.0
    };
    rd_ref_opts o = rd_ref_opts_default();
    o.theta0[0] = 0.0;
    o.theta0[1] = 0.1;
    o.t_end = 2.0;
    rd_ref_result r;
    rd_error err = { "" };
    int rc = rd_kounadis_solve(&d, NULL, &o, &r, &err);
    assert_int_equal(rc, -1);
    assert_non_null(strstr(err.msg, "gains energy"));
    rd_ref_result_free(&r);
}

/* Reversing ug'' mirrors theta1, theta2 (the equations are odd under theta -> -theta,
 * s -> -s, ug'' -> -ug''). libm's sin is odd and CVODE's norms symmetric, so the two runs agree
 * to round-off; 1e-12 rad allows for the accumulated last-bit differences. */
static void test_kounadis_mirror(void **state)
{
    (void)state;
    rd_kounadis_def d = rd_kounadis_def_default();
    d.b2 = 0.15;
    sine_pulse sp[2] = { { .a = 0.8 * G, .w = 2.0 * M_PI * 2.5 },
                         { .a = -0.8 * G, .w = 2.0 * M_PI * 2.5 } };
    rd_ref_result r[2];
    for (int k = 0; k < 2; k++) {
        double brk;
        rd_ground gm = sine_ground(&sp[k], &brk);
        rd_ref_opts o = rd_ref_opts_default();
        o.t_end = 2.0;
        r[k] = run_stack(&d, &gm, &o);
    }
    assert_true(r[0].summary.nimpacts >= 2);
    assert_int_equal(r[0].nsamples, r[1].nsamples);
    assert_int_equal(r[0].nevents, r[1].nevents);
    for (size_t i = 0; i < r[0].nsamples; i++) {
        for (int j = 0; j < 2; j++)
            assert_true(fabs(r[0].samples[i].theta[j] + r[1].samples[i].theta[j]) < 1e-12);
        assert_int_equal(r[0].samples[i].s1, -r[1].samples[i].s1);
        assert_int_equal(r[0].samples[i].s2, -r[1].samples[i].s2);
    }
    rd_ref_result_free(&r[0]);
    rd_ref_result_free(&r[1]);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_housner_quarter_period),
        cmocka_unit_test(test_housner_slender_limit),
        cmocka_unit_test(test_housner_restitution),
        cmocka_unit_test(test_housner_energy),
        cmocka_unit_test(test_housner_static_uplift),
        cmocka_unit_test(test_housner_sine_threshold),
        cmocka_unit_test(test_kounadis_lagrange),
        cmocka_unit_test(test_kounadis_static_thresholds),
        cmocka_unit_test(test_kounadis_energy),
        cmocka_unit_test(test_kounadis_light_top),
        cmocka_unit_test(test_kounadis_locked_is_one_block),
        cmocka_unit_test(test_kounadis_mirror),
        cmocka_unit_test(test_kounadis_restitution_gain),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
