/* rockdem — Housner single rocking block (ROCKING-EQUATIONS.md section 1) on CVODE.
 *
 * State y = (theta, theta'); pivot side s = sgn(theta) (0: resting flat). In rocking,
 *   theta'' = -p^2 [ (1 + vg''/g) sin(s alpha - theta) + (ug''/g) cos(s alpha - theta) ],
 * impacts at theta = 0 give theta'+ = e theta'-, uplift from rest when
 * |ug''| > (g + vg'') tan(alpha) on the side s = -sgn(ug'').
 * Folder reference/ owns the rigid CVODE reference solvers (Housner, Kounadis); it may call
 * base/, records/, io/ and the public API.
 */
#include "rockdem/reference.h"

#include <math.h>
#include <string.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>

#include "reference/ref_cvode.h"

rd_housner_def rd_housner_def_default(void)
{
    rd_housner_def d = { .b = 0.25, .h = 0.5, .g = 9.81, .e = -1.0 };
    return d;
}

double rd_housner_alpha(double b, double h) { return atan2(b, h); }

double rd_housner_p(double b, double h, double g) { return sqrt(0.75 * g / hypot(b, h)); }

double rd_housner_r(double alpha)
{
    double s = sin(alpha);
    return 1.0 - 1.5 * s * s;
}

int rd_housner_falls(double theta, double omega, double alpha, double p)
{
    double a = fabs(theta);
    int outward = theta != 0.0 ? theta * omega > 0.0 : omega != 0.0;
    double energy = 0.5 * omega * omega + p * p * cos(alpha - a); /* per unit I_O, 1/s^2 */
    if (outward) return a >= alpha || energy >= p * p;
    /* inward beyond the saddle: it turns back (and falls) unless it has the energy to pass */
    return a > alpha && energy < p * p;
}

/* ---- exact free-rocking time ------------------------------------------------------------ */

typedef struct free_time_ctx {
    double a; /* alpha - theta0, rad */
    double p; /* 1/s */
} free_time_ctx;

/* Integrand after theta = theta0 - u^2, q = u^2/2: sqrt(2) / (p sqrt(sin(a + q) sin(q)/q)),
 * from cos(a) - cos(a + u^2) = 2 sin(a + q) sin(q); finite at u = 0. */
static double free_time_integrand(double u, void *vctx)
{
    const free_time_ctx *c = vctx;
    double q = 0.5 * u * u;
    double sinc = q > 1e-8 ? sin(q) / q : 1.0 - q * q / 6.0;
    return M_SQRT2 / (c->p * sqrt(sin(c->a + q) * sinc));
}

int rd_housner_free_time(double alpha, double p, double theta0, double *t, rd_error *err)
{
    if (!(theta0 > 0.0 && theta0 < alpha) || !(p > 0.0) || !(alpha < 0.5 * M_PI))
        return rd_error_set(err,
                            "free rocking time: need 0 < theta0 (%g) < alpha (%g) < pi/2, "
                            "p > 0",
                            theta0, alpha);
    free_time_ctx c = { .a = alpha - theta0, .p = p };
    gsl_function f = { .function = free_time_integrand, .params = &c };
    gsl_integration_workspace *w = gsl_integration_workspace_alloc(200);
    if (!w) return rd_error_set(err, "free rocking time: out of memory");
    gsl_error_handler_t *old = gsl_set_error_handler_off();
    double abserr;
    int st = gsl_integration_qags(&f, 0.0, sqrt(theta0), 0.0, 1e-13, 200, w, t, &abserr);
    gsl_set_error_handler(old);
    gsl_integration_workspace_free(w);
    if (st && st != GSL_EROUND)
        return rd_error_set(err, "free rocking time: quadrature failed (%s)", gsl_strerror(st));
    return 0;
}

/* ---- the hybrid model --------------------------------------------------------------------- */

enum root_kind { R_IMPACT, R_PEAK, R_SADDLE, R_FALLEN, R_LIFTOFF, R_UPLIFT_POS, R_UPLIFT_NEG };

typedef struct housner {
    double b, h, g, e; /* m, m, m/s^2, - */
    double alpha, p;   /* rad, 1/s */
    double rest_omega; /* rad/s: post-impact rate below which the block comes to rest */
    const rd_ground *gm;
    rd_ref_result *res;
    rd_error *err;
    int s; /* pivot side: +1 right corner, -1 left, 0 at rest */
    int nroots;
    int kind[RD_HYB_MAXROOTS];
    int dir[RD_HYB_MAXROOTS];
} housner;

/* theta'' (rad/s^2) rocking on side s. */
static double rock_acc(const housner *m, int s, double th, double ug, double vg)
{
    double x = s * m->alpha - th;
    return -m->p * m->p * ((1.0 + vg / m->g) * sin(x) + (ug / m->g) * cos(x));
}

/* Pivot normal force per unit mass (m/s^2): g + vg'' + y_C'', y_C = s b sin(th) + h cos(th). */
static double pivot_normal(const housner *m, double th, double om, double acc, double vg)
{
    double sb = m->s * m->b;
    double ycdd = (sb * cos(th) - m->h * sin(th)) * acc - (sb * sin(th) + m->h * cos(th)) * om * om;
    return m->g + vg + ycdd;
}

static int h_rhs(void *sys, double t, const double *y, double *ydot)
{
    housner *m = sys;
    double ug, vg;
    rd_ground_eval(m->gm, t, &ug, &vg);
    ydot[0] = m->s ? y[1] : 0.0;
    ydot[1] = m->s ? rock_acc(m, m->s, y[0], ug, vg) : 0.0;
    return 0;
}

static void add_root(housner *m, int kind, int dir)
{
    m->kind[m->nroots] = kind;
    m->dir[m->nroots] = dir;
    m->nroots++;
}

/* Root functions of the current state: impacts, turning points, saddle crossings, the pi/2
 * tilt and lift-off when rocking; the two uplift conditions and lift-off at rest. */
static void build_roots(housner *m)
{
    m->nroots = 0;
    if (m->s) {
        add_root(m, R_IMPACT, -1);
        add_root(m, R_PEAK, 0);
        add_root(m, R_SADDLE, +1);
        add_root(m, R_FALLEN, +1);
        add_root(m, R_LIFTOFF, -1);
    } else {
        add_root(m, R_UPLIFT_POS, +1);
        add_root(m, R_UPLIFT_NEG, +1);
        add_root(m, R_LIFTOFF, -1);
    }
}

static int h_nroots(void *sys, int *dirs)
{
    housner *m = sys;
    memcpy(dirs, m->dir, (size_t)m->nroots * sizeof *dirs);
    return m->nroots;
}

static double root_value(const housner *m, int kind, const double *y, double ug, double vg)
{
    double th = y[0], om = y[1];
    switch (kind) {
    case R_IMPACT: return m->s * th;
    case R_PEAK: return om;
    case R_SADDLE: return m->s * th - m->alpha;
    case R_FALLEN: return m->s * th - 0.5 * M_PI;
    case R_LIFTOFF:
        return m->s ? pivot_normal(m, th, om, rock_acc(m, m->s, th, ug, vg), vg) : m->g + vg;
    case R_UPLIFT_POS: return ug - (m->g + vg) * tan(m->alpha);
    default: return -ug - (m->g + vg) * tan(m->alpha);
    }
}

static int h_roots(void *sys, double t, const double *y, double *g)
{
    housner *m = sys;
    double ug, vg;
    rd_ground_eval(m->gm, t, &ug, &vg);
    for (int i = 0; i < m->nroots; i++) g[i] = root_value(m, m->kind[i], y, ug, vg);
    return 0;
}

static void note_angle(housner *m, double th)
{
    double r = fabs(th) / m->alpha;
    if (r > m->res->summary.max_ratio[0]) m->res->summary.max_ratio[0] = r;
}

static int push_event(housner *m, double t, rd_ref_event_kind kind, const double *y, double om_pre)
{
    rd_ref_event e;
    memset(&e, 0, sizeof e);
    e.t = t;
    e.kind = kind;
    e.s1 = m->s;
    e.theta[0] = y[0];
    e.omega_pre[0] = om_pre;
    e.omega_post[0] = y[1];
    note_angle(m, y[0]);
    return rd_ref_push_event(m->res, &e, m->err);
}

/* End the run: overturning became certain or the pivot lifted off. */
static int stop(housner *m, double t, const double *y, rd_ref_event_kind kind)
{
    if (kind == RD_REF_OVERTURN) {
        m->res->summary.overturned = 1;
        m->res->summary.overturn_joint = 0;
        m->res->summary.t_overturn = t;
    } else {
        m->res->summary.lifted_off = 1;
    }
    return push_event(m, t, kind, y, y[1]) ? -1 : RD_HYB_STOP;
}

static int h_settle(void *sys, double t, double *y)
{
    housner *m = sys;
    double ug, vg;
    rd_ground_eval(m->gm, t, &ug, &vg);
    if (!m->s) {
        if (m->g + vg < 0.0) return stop(m, t, y, RD_REF_LIFTOFF);
        if (fabs(ug) > (m->g + vg) * tan(m->alpha)) {
            m->s = ug > 0.0 ? -1 : 1;
            if (push_event(m, t, RD_REF_UPLIFT, y, y[1])) return -1;
        }
    } else {
        double acc = rock_acc(m, m->s, y[0], ug, vg);
        if (pivot_normal(m, y[0], y[1], acc, vg) < 0.0) return stop(m, t, y, RD_REF_LIFTOFF);
        int quiet = t >= m->gm->t_quiet;
        if (fabs(y[0]) >= 0.5 * M_PI || (quiet && rd_housner_falls(y[0], y[1], m->alpha, m->p)))
            return stop(m, t, y, RD_REF_OVERTURN);
    }
    build_roots(m);
    return RD_HYB_GO;
}

/* Impact at theta = 0: theta'+ = e theta'-, or rest below the threshold (Zeno). */
static int impact(housner *m, double t, double *y)
{
    double pre = y[1];
    y[0] = 0.0;
    y[1] = m->e * pre;
    m->res->summary.nimpacts++;
    int rest = fabs(y[1]) < m->rest_omega;
    m->s = rest ? 0 : -m->s;
    if (rest) y[1] = 0.0;
    if (push_event(m, t, RD_REF_IMPACT, y, pre)) return -1;
    if (rest && push_event(m, t, RD_REF_REST, y, 0.0)) return -1;
    return RD_HYB_RESTART;
}

static int h_event(void *sys, double t, double *y, const int *found)
{
    housner *m = sys;
    int saddle = 0, peak = 0;
    for (int i = 0; i < m->nroots; i++) {
        if (!found[i]) continue;
        switch (m->kind[i]) {
        case R_FALLEN: return stop(m, t, y, RD_REF_OVERTURN);
        case R_LIFTOFF: return stop(m, t, y, RD_REF_LIFTOFF);
        case R_IMPACT: return impact(m, t, y);
        case R_SADDLE: saddle = 1; break;
        case R_PEAK: peak = 1; break;
        default: /* uplift condition met (the root may sit exactly on it): open now */
            m->s = m->kind[i] == R_UPLIFT_POS ? -1 : 1;
            return push_event(m, t, RD_REF_UPLIFT, y, y[1]) ? -1 : RD_HYB_RESTART;
        }
    }
    if (saddle && t >= m->gm->t_quiet)
        return stop(m, t, y, RD_REF_OVERTURN); /* crossing alpha outward in free motion */
    if (peak && push_event(m, t, RD_REF_PEAK, y, y[1])) return -1;
    return RD_HYB_GO;
}

static int h_sample(void *sys, double t, double *y)
{
    housner *m = sys;
    rd_ref_sample s;
    memset(&s, 0, sizeof s);
    s.t = t;
    s.theta[0] = y[0];
    s.omega[0] = y[1];
    s.s1 = m->s;
    note_angle(m, y[0]);
    return rd_ref_push_sample(m->res, &s, m->err);
}

static int housner_init(housner *m, const rd_housner_def *d, const rd_ground *gm,
                        const rd_ref_opts *o, rd_ref_result *res, rd_error *err)
{
    if (!(d->b > 0.0 && d->h > 0.0 && d->g > 0.0) || !(d->e <= 1.0))
        return rd_error_set(err, "housner: need b, h, g > 0 and e <= 1 (got %g %g %g %g)", d->b,
                            d->h, d->g, d->e);
    memset(m, 0, sizeof *m);
    m->b = d->b;
    m->h = d->h;
    m->g = d->g;
    m->alpha = rd_housner_alpha(d->b, d->h);
    m->p = rd_housner_p(d->b, d->h, d->g);
    m->e = d->e < 0.0 ? rd_housner_r(m->alpha) : d->e;
    m->rest_omega = o->rest_factor * m->p;
    m->gm = gm;
    m->res = res;
    m->err = err;
    double th = o->theta0[0], om = o->omega0[0];
    m->s = th > 0.0 ? 1 : th < 0.0 ? -1 : om > 0.0 ? 1 : om < 0.0 ? -1 : 0;
    return 0;
}

int rd_housner_solve(const rd_housner_def *def, const rd_ground *gm, const rd_ref_opts *opts,
                     rd_ref_result *res, rd_error *err)
{
    static const rd_ground still = { .t_quiet = 0.0 };
    housner m;
    rd_ref_result_init(res);
    if ((gm && rd_ground_check(gm, err)) || housner_init(&m, def, gm ? gm : &still, opts, res, err))
        return -1;
    rd_hybrid h = { .n = 2,
                    .hmax = 0.05 / m.p,
                    .sys = &m,
                    .rhs = h_rhs,
                    .nroots = h_nroots,
                    .roots = h_roots,
                    .settle = h_settle,
                    .event = h_event,
                    .sample = h_sample };
    double y[2] = { opts->theta0[0], opts->omega0[0] };
    if (rd_hybrid_run(&h, m.gm, opts, y, &res->summary.t_stop, err)) {
        rd_ref_result_free(res);
        return -1;
    }
    return 0;
}
