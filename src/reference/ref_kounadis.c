/* rockdem — Kounadis two-block stack (ROCKING-EQUATIONS.md section 2) on CVODE.
 *
 * State y = (theta1, theta2, theta1', theta2'), absolute angles, clockwise positive. Pattern
 * (s1, s2): s1 = ground pivot side (0: lower block flat), s2 = interface pivot side (0: upper
 * block flat on the lower one). Both open: M theta'' + rest = 0 as written in the doc; locked
 * (s1, 0): the composite block about O; lower at rest (0, s2): the upper block about P; (0, 0)
 * rest. Contact forces come from Newton–Euler of each body with the mode's accelerations.
 * Impacts are perfectly plastic with angular momentum conserved about the post-impact pivots,
 * optionally scaled by a restitution factor (rd_kounadis_def.r).
 * Folder reference/ owns the rigid CVODE reference solvers (Housner, Kounadis); it may call
 * base/, records/, io/ and the public API.
 */
#include "rockdem/reference.h"

#include <math.h>
#include <string.h>

#include "reference/ref_cvode.h"

rd_kounadis_def rd_kounadis_def_default(void)
{
    rd_kounadis_def d = {
        .b1 = 0.25, .h1 = 0.5, .m1 = 1.0, .b2 = 0.25, .h2 = 0.5, .m2 = 1.0, .g = 9.81
    };
    return d;
}

void rd_kounadis_matrix(const rd_kounadis_def *d, int s1, int s2, const double th[2],
                        const double om[2], double ug, double vg, double m[2][2], double rest[2])
{
    double b1 = d->b1, h1 = d->h1, m1 = d->m1, b2 = d->b2, h2 = d->h2, m2 = d->m2, g = d->g;
    double sd = sin(th[0] - th[1]), cd = cos(th[0] - th[1]);
    double s1t = sin(th[0]), c1t = cos(th[0]), s2t = sin(th[1]), c2t = cos(th[1]);
    double w1 = om[0] * om[0], w2 = om[1] * om[1];
    double dx = s2 * b2 - s1 * b1;
    m[0][0] = 4.0 / 3.0 * m1 * (b1 * b1 + h1 * h1) + m2 * (dx * dx + 4.0 * h1 * h1);
    m[1][1] = 4.0 / 3.0 * m2 * (b2 * b2 + h2 * h2);
    m[0][1] = m2 * ((s1 * s2 * b1 * b2 - b2 * b2 + 2.0 * h1 * h2) * cd +
                    (s1 * b1 * h2 - 2.0 * s2 * b2 * h1 - s2 * b2 * h2) * sd);
    m[1][0] = m[0][1];
    double gx1 = ug * s1t + vg * c1t, gy1 = ug * c1t - vg * s1t;
    rest[0] = b1 * b2 * m2 * s1 * s2 * w2 * sd + b1 * g * (m1 + m2) * s1 * c1t -
              b1 * h2 * m2 * s1 * w2 * cd + b1 * (m1 + m2) * s1 * gx1 - b2 * b2 * m2 * w2 * sd -
              b2 * g * m2 * s2 * c1t + (2.0 * h1 + h2) * b2 * m2 * s2 * w2 * cd -
              b2 * m2 * s2 * gx1 - g * h1 * (m1 + 2.0 * m2) * s1t + 2.0 * h1 * h2 * m2 * w2 * sd +
              h1 * (m1 + 2.0 * m2) * gy1;
    rest[1] = m2 * (-b1 * b2 * s1 * s2 * w1 * sd + b1 * h2 * s1 * w1 * cd + b2 * b2 * w1 * sd +
                    b2 * g * s2 * c2t - (2.0 * h1 + h2) * b2 * s2 * w1 * cd +
                    b2 * s2 * (ug * s2t + vg * c2t) - g * h2 * s2t - 2.0 * h1 * h2 * w1 * sd +
                    h2 * (ug * c2t - vg * s2t));
}

void rd_kounadis_uplift_thresholds(const rd_kounadis_def *d, double *stack, double *upper)
{
    *stack = d->b1 * (d->m1 + d->m2) / (d->m1 * d->h1 + d->m2 * (2.0 * d->h1 + d->h2));
    *upper = d->b2 / d->h2;
}

/* ---- kinematics and Newton–Euler ---------------------------------------------------------- */

/* Positions (ground frame, origin at the lower block's base centre at rest), velocities and
 * accelerations of the points that matter in pattern (s1, s2). s2 = 0 puts P at the centre of
 * the interface (any point of a closed joint serves). */
typedef struct kin {
    double o[2], c1[2], p[2], q2[2], c2[2]; /* m */
    double v1[2], v2[2];                    /* centre velocities, m/s */
    double a1[2], a2[2];                    /* centre accelerations, m/s^2 */
} kin;

/* Body vector (x, y) turned clockwise by th, added to base. */
static void place(const double base[2], double th, double x, double y, double out[2])
{
    out[0] = base[0] + x * cos(th) + y * sin(th);
    out[1] = base[1] - x * sin(th) + y * cos(th);
}

/* Velocity and acceleration of point x rotating clockwise (om, acc) about z (which has va, aa). */
static void spin(const double x[2], const double z[2], double om, double acc, const double vz[2],
                 const double az[2], double v[2], double a[2])
{
    double r[2] = { x[0] - z[0], x[1] - z[1] };
    v[0] = vz[0] + om * r[1];
    v[1] = vz[1] - om * r[0];
    a[0] = az[0] + acc * r[1] - om * om * r[0];
    a[1] = az[1] - acc * r[0] - om * om * r[1];
}

static void kinematics(const rd_kounadis_def *d, int s1, int s2, const double th[2],
                       const double om[2], const double acc[2], kin *k)
{
    static const double zero[2] = { 0.0, 0.0 };
    double vp[2], ap[2];
    k->o[0] = s1 * d->b1;
    k->o[1] = 0.0;
    place(k->o, th[0], -s1 * d->b1, d->h1, k->c1);
    place(k->o, th[0], s2 * d->b2 - s1 * d->b1, 2.0 * d->h1, k->p);
    place(k->o, th[0], -s1 * d->b1, 2.0 * d->h1, k->q2);
    place(k->p, th[1], -s2 * d->b2, d->h2, k->c2);
    spin(k->c1, k->o, om[0], acc[0], zero, zero, k->v1, k->a1);
    spin(k->p, k->o, om[0], acc[0], zero, zero, vp, ap);
    spin(k->c2, k->p, om[1], acc[1], vp, ap, k->v2, k->a2);
}

/* Clockwise moment of force f applied at arm r (N m). */
static double cw(const double r[2], const double f[2]) { return r[1] * f[0] - r[0] * f[1]; }

static double centroidal_inertia(double m, double b, double h) { return m * (b * b + h * h) / 3.0; }

/* Accelerations of the pattern (s1, s2) from M theta'' + rest = 0 and its constraints. */
static int mode_acc(const rd_kounadis_def *d, int s1, int s2, const double th[2],
                    const double om[2], double ug, double vg, double acc[2], rd_error *err)
{
    double m[2][2], rest[2];
    acc[0] = acc[1] = 0.0;
    if (s1 && s2) {
        rd_kounadis_matrix(d, s1, s2, th, om, ug, vg, m, rest);
        double det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
        if (!(fabs(det) > 0.0))
            return rd_error_set(err, "kounadis: singular mass matrix (m2 = %g)", d->m2);
        acc[0] = (-rest[0] * m[1][1] + rest[1] * m[0][1]) / det;
        acc[1] = (-rest[1] * m[0][0] + rest[0] * m[1][0]) / det;
    } else if (s1) { /* locked: delta theta1 = delta theta2, sum of both equations */
        double t2[2] = { th[0], th[0] }, o2[2] = { om[0], om[0] };
        rd_kounadis_matrix(d, s1, 1, t2, o2, ug, vg, m, rest);
        acc[0] = acc[1] = -(rest[0] + rest[1]) / (m[0][0] + 2.0 * m[0][1] + m[1][1]);
    } else if (s2) { /* lower block at rest: the upper block about P */
        double t2[2] = { 0.0, th[1] }, o2[2] = { 0.0, om[1] };
        rd_kounadis_matrix(d, 1, s2, t2, o2, ug, vg, m, rest);
        acc[1] = -rest[1] / m[1][1];
    }
    return 0;
}

/* Normal force and moment of a joint: at the pivot for an open joint, else the two corner
 * forces N/2 +- M/(2 b) about the joint centre. */
static void joint_forces(int s, double n, double moment, double b, double out[2])
{
    if (s) {
        out[0] = n;
        out[1] = moment;
    } else {
        out[0] = 0.5 * n + moment / (2.0 * b);
        out[1] = 0.5 * n - moment / (2.0 * b);
    }
}

int rd_kounadis_eval_mode(const rd_kounadis_def *d, int s1, int s2, const double th[2],
                          const double om[2], double ug, double vg, rd_kounadis_eval *out,
                          rd_error *err)
{
    if (mode_acc(d, s1, s2, th, om, ug, vg, out->acc, err)) return -1;
    kin k;
    kinematics(d, s1, s2, th, om, out->acc, &k);
    double gx = -ug, gy = -(d->g + vg); /* apparent gravity in the ground frame, m/s^2 */
    double f2[2] = { d->m2 * (k.a2[0] - gx), d->m2 * (k.a2[1] - gy) }; /* lower -> upper, N */
    double f1[2] = { d->m1 * (k.a1[0] - gx), d->m1 * (k.a1[1] - gy) };
    double fg[2] = { f1[0] + f2[0], f1[1] + f2[1] }; /* ground -> lower, N */
    double i1 = centroidal_inertia(d->m1, d->b1, d->h1) * out->acc[0];
    double i2 = centroidal_inertia(d->m2, d->b2, d->h2) * out->acc[1];
    /* ground moment about A = sum of centroidal rates + moments of m (a - g) about A */
    const double *ag = s1 ? k.o : (const double[2]){ 0.0, 0.0 };
    double r1[2] = { k.c1[0] - ag[0], k.c1[1] - ag[1] },
           r2[2] = { k.c2[0] - ag[0], k.c2[1] - ag[1] };
    double mg = i1 + i2 + cw(r1, f1) + cw(r2, f2);
    joint_forces(s1, fg[1], mg, d->b1, out->ground);
    const double *ai = s2 ? k.p : k.q2;
    double ri[2] = { k.c2[0] - ai[0], k.c2[1] - ai[1] };
    double ni = f2[0] * sin(th[0]) + f2[1] * cos(th[0]); /* along the lower block's top normal */
    joint_forces(s2, ni, i2 + cw(ri, f2), d->b2, out->iface);
    return 0;
}

/* ---- impacts ------------------------------------------------------------------------------ */

/* Angular momentum (clockwise, N m s) about a of the upper block (whole = 0) or of the stack. */
static double momentum(const rd_kounadis_def *d, const kin *k, const double om[2],
                       const double a[2], int whole)
{
    double r2[2] = { k->c2[0] - a[0], k->c2[1] - a[1] };
    double mv2[2] = { d->m2 * k->v2[0], d->m2 * k->v2[1] };
    double h = centroidal_inertia(d->m2, d->b2, d->h2) * om[1] + cw(r2, mv2);
    if (whole) {
        double r1[2] = { k->c1[0] - a[0], k->c1[1] - a[1] };
        double mv1[2] = { d->m1 * k->v1[0], d->m1 * k->v1[1] };
        h += centroidal_inertia(d->m1, d->b1, d->h1) * om[0] + cw(r1, mv1);
    }
    return h;
}

/* Rates of pattern (s1, s2) for unit DOF j: both open (1,0),(0,1); locked (1,1); upper (0,1). */
static int basis(int s1, int s2, double e[2][2])
{
    memset(e, 0, 4 * sizeof(double));
    if (s1 && s2) {
        e[0][0] = e[1][1] = 1.0;
        return 2;
    }
    if (s1) {
        e[0][0] = e[0][1] = 1.0;
        return 1;
    }
    if (s2) {
        e[0][1] = 1.0;
        return 1;
    }
    return 0;
}

/* Post-impact rates om_post in pattern (s1, s2) from the pre-impact rates om_pre of pattern
 * (p1, p2): angular momentum of the stack about the new ground pivot (s1 != 0) and of the upper
 * block about the new upper pivot (s2 != 0) are conserved. */
static void plastic_impact(const rd_kounadis_def *d, int p1, int p2, int s1, int s2,
                           const double th[2], const double om_pre[2], double om_post[2])
{
    static const double zero[2] = { 0.0, 0.0 };
    double e[2][2];
    int n = basis(s1, s2, e);
    kin pre, post;
    kinematics(d, p1, p2, th, om_pre, zero, &pre);
    kinematics(d, s1, s2, th, zero, zero, &post);
    const double *pts[2];
    int whole[2], ne = 0;
    if (s1) {
        pts[ne] = post.o;
        whole[ne++] = 1;
    }
    if (s2) {
        pts[ne] = post.p;
        whole[ne++] = 0;
    }
    double a[2][2] = { { 0 } }, rhs[2] = { 0 }, x[2] = { 0 };
    for (int i = 0; i < ne; i++) {
        rhs[i] = momentum(d, &pre, om_pre, pts[i], whole[i]);
        for (int j = 0; j < n; j++) {
            kinematics(d, s1, s2, th, e[j], zero, &post);
            a[i][j] = momentum(d, &post, e[j], pts[i], whole[i]);
        }
    }
    if (n == 2) {
        double det = a[0][0] * a[1][1] - a[0][1] * a[1][0];
        x[0] = (rhs[0] * a[1][1] - rhs[1] * a[0][1]) / det;
        x[1] = (rhs[1] * a[0][0] - rhs[0] * a[1][0]) / det;
    } else if (n == 1) {
        x[0] = rhs[0] / a[0][0];
    }
    for (int c = 0; c < 2; c++) om_post[c] = x[0] * e[0][c] + x[1] * e[1][c];
}

/* ---- the hybrid model --------------------------------------------------------------------- */

enum root_kind {
    R_IMPACT0,
    R_IMPACT1,
    R_LIFT0,
    R_LIFT1,
    R_FALL0,
    R_FALL1,
    R_FALL2,
    R_CORNER0L,
    R_CORNER0R,
    R_CORNER1L,
    R_CORNER1R,
    R_SADDLE,
    R_PEAK0,
    R_PEAK1
};

typedef struct stack {
    rd_kounadis_def d;
    double alpha[2], p1;   /* rad; 1/s of the lower block */
    double alpha_c, p_c;   /* saddle angle and frequency of the locked stack about O */
    double alpha2, p2;     /* the same for the upper block alone */
    double rest_omega;     /* rad/s, joints close below this post-impact rate */
    double kappa;          /* post-impact rates over the plastic law's (1: plastic) */
    double tol_acc, tol_f; /* rad/s^2, N: round-off allowances in admissibility tests */
    const rd_ground *gm;
    rd_ref_result *res;
    rd_error *err;
    int s1, s2;
    int nroots;
    int kind[RD_HYB_MAXROOTS];
    int dir[RD_HYB_MAXROOTS];
} stack;

/* Impose the pattern's constraints on y: closed joints have zero relative angle and rate. */
static void normalize(const stack *m, double *y)
{
    if (!m->s1) { y[0] = y[2] = 0.0; }
    if (!m->s2) {
        y[1] = y[0];
        y[3] = y[2];
    }
}

static int eval_at(const stack *m, int s1, int s2, double t, const double *y, rd_kounadis_eval *ev)
{
    double ug, vg;
    rd_ground_eval(m->gm, t, &ug, &vg);
    return rd_kounadis_eval_mode(&m->d, s1, s2, y, y + 2, ug, vg, ev, m->err);
}

/* What the CVODE callbacks see at (t, y): the state normalised and the current mode there. */
typedef struct state_at {
    double yn[4];
    rd_kounadis_eval ev;
} state_at;

static int eval_state(stack *m, double t, const double *y, state_at *a)
{
    for (int i = 0; i < 4; i++) a->yn[i] = y[i];
    normalize(m, a->yn);
    return eval_at(m, m->s1, m->s2, t, a->yn, &a->ev);
}

static int k_rhs(void *sys, double t, const double *y, double *ydot)
{
    state_at a;
    if (eval_state(sys, t, y, &a)) return -1;
    ydot[0] = a.yn[2];
    ydot[1] = a.yn[3];
    ydot[2] = a.ev.acc[0];
    ydot[3] = a.ev.acc[1];
    return 0;
}

static void add_root(stack *m, int kind, int dir)
{
    m->kind[m->nroots] = kind;
    m->dir[m->nroots] = dir;
    m->nroots++;
}

static void build_roots(stack *m)
{
    m->nroots = 0;
    if (m->s1) {
        add_root(m, R_IMPACT0, -1);
        add_root(m, R_LIFT0, -1);
        add_root(m, R_FALL0, +1);
        add_root(m, R_PEAK0, 0);
    } else {
        add_root(m, R_CORNER0L, -1);
        add_root(m, R_CORNER0R, -1);
    }
    if (m->s2) {
        add_root(m, R_IMPACT1, -1);
        add_root(m, R_LIFT1, -1);
        add_root(m, R_FALL1, +1);
        add_root(m, R_FALL2, +1);
        add_root(m, R_PEAK1, 0);
    } else {
        add_root(m, R_CORNER1L, -1);
        add_root(m, R_CORNER1R, -1);
    }
    if (!m->s1 != !m->s2) add_root(m, R_SADDLE, +1);
}

static int k_nroots(void *sys, int *dirs)
{
    stack *m = sys;
    memcpy(dirs, m->dir, (size_t)m->nroots * sizeof *dirs);
    return m->nroots;
}

static double root_value(const stack *m, int kind, const double *y, const rd_kounadis_eval *ev)
{
    double rel = y[1] - y[0];
    switch (kind) {
    case R_IMPACT0: return m->s1 * y[0];
    case R_IMPACT1: return m->s2 * rel;
    case R_LIFT0: return ev->ground[0];
    case R_LIFT1: return ev->iface[0];
    case R_FALL0: return m->s1 * y[0] - 0.5 * M_PI;
    case R_FALL1: return m->s2 * rel - 0.5 * M_PI;
    case R_FALL2: return y[1] * y[1] - 0.25 * M_PI * M_PI;
    case R_CORNER0L: return ev->ground[0];
    case R_CORNER0R: return ev->ground[1];
    case R_CORNER1L: return ev->iface[0];
    case R_CORNER1R: return ev->iface[1];
    case R_SADDLE: return m->s1 ? m->s1 * y[0] - m->alpha_c : m->s2 * y[1] - m->alpha2;
    case R_PEAK0: return y[2];
    default: return y[3];
    }
}

static int k_roots(void *sys, double t, const double *y, double *g)
{
    stack *m = sys;
    state_at a;
    if (eval_state(m, t, y, &a)) return -1;
    for (int i = 0; i < m->nroots; i++) g[i] = root_value(m, m->kind[i], a.yn, &a.ev);
    return 0;
}

static void note_angles(stack *m, const double *y)
{
    for (int i = 0; i < 2; i++) {
        double r = fabs(y[i]) / m->alpha[i];
        if (r > m->res->summary.max_ratio[i]) m->res->summary.max_ratio[i] = r;
    }
}

static int push_event(stack *m, double t, rd_ref_event_kind kind, int joint, const double *y,
                      const double om_pre[2])
{
    rd_ref_event e;
    memset(&e, 0, sizeof e);
    e.t = t;
    e.kind = kind;
    e.joint = joint;
    e.s1 = m->s1;
    e.s2 = m->s2;
    memcpy(e.theta, y, sizeof e.theta);
    memcpy(e.omega_pre, om_pre ? om_pre : y + 2, sizeof e.omega_pre);
    memcpy(e.omega_post, y + 2, sizeof e.omega_post);
    note_angles(m, y);
    return rd_ref_push_event(m->res, &e, m->err);
}

static int stop(stack *m, double t, const double *y, rd_ref_event_kind kind, int joint)
{
    if (kind == RD_REF_OVERTURN) {
        m->res->summary.overturned = 1;
        m->res->summary.overturn_joint = joint;
        m->res->summary.t_overturn = t;
    } else {
        m->res->summary.lifted_off = 1;
    }
    return push_event(m, t, kind, joint, y, NULL) ? -1 : RD_HYB_STOP;
}

/* Kinematic consistency of one joint with pattern side s: angle a, rate w, acceleration acc;
 * a closed joint also needs both corner forces f compressive. */
static int joint_fits(const stack *m, int s, double a, double w, double acc, const double f[2])
{
    if (!s) return a == 0.0 && w == 0.0 && f[0] > 0.0 && f[1] > 0.0;
    if (a != 0.0) return a * s > 0.0;
    if (w != 0.0) return w * s > 0.0;
    return acc * s >= -m->tol_acc;
}

/* *ok = 1 when pattern (s1, s2) fits the state and its pivots push; *tension |= 1 when it fits
 * but a pivot pulls (lift-off). */
static int mode_fits(stack *m, int s1, int s2, double t, const double *y, int *tension, int *ok)
{
    rd_kounadis_eval ev;
    if (eval_at(m, s1, s2, t, y, &ev)) return -1;
    int fits = joint_fits(m, s1, y[0], y[2], ev.acc[0], ev.ground) &&
               joint_fits(m, s2, y[1] - y[0], y[3] - y[2], ev.acc[1] - ev.acc[0], ev.iface);
    int pulls = (s1 && ev.ground[0] < -m->tol_f) || (s2 && ev.iface[0] < -m->tol_f);
    *ok = fits && !pulls;
    *tension |= fits && pulls;
    return 0;
}

/* Record the joints that opened or closed going from (o1, o2) to the current pattern. */
static int note_switch(stack *m, double t, const double *y, int o1, int o2)
{
    int was[2] = { o1, o2 }, now[2] = { m->s1, m->s2 };
    for (int j = 0; j < 2; j++) {
        if (!was[j] == !now[j]) continue;
        rd_ref_event_kind k = now[j] ? RD_REF_UPLIFT : j ? RD_REF_LOCK : RD_REF_REST;
        if (push_event(m, t, k, j, y, NULL)) return -1;
    }
    return 0;
}

/* Pick the pattern consistent with the state: the current one if it fits, else the first that
 * fits, closed joints first (a joint opens only when it must). */
static int choose_mode(stack *m, double t, double *y)
{
    static const int order[9][2] = { { 0, 0 }, { 1, 0 },  { -1, 0 }, { 0, 1 },  { 0, -1 },
                                     { 1, 1 }, { 1, -1 }, { -1, 1 }, { -1, -1 } };
    int tension = 0, ok = 0;
    if (mode_fits(m, m->s1, m->s2, t, y, &tension, &ok)) return -1;
    for (int i = 0; !ok && i < 9; i++) {
        if (mode_fits(m, order[i][0], order[i][1], t, y, &tension, &ok)) return -1;
        if (ok) {
            int o1 = m->s1, o2 = m->s2;
            m->s1 = order[i][0];
            m->s2 = order[i][1];
            normalize(m, y);
            if (note_switch(m, t, y, o1, o2)) return -1;
        }
    }
    if (ok) return RD_HYB_GO;
    if (tension) return stop(m, t, y, RD_REF_LIFTOFF, 0);
    return rd_error_set(m->err,
                        "kounadis: no configuration fits the state at t = %.9g s "
                        "(theta %g %g, rates %g %g)",
                        t, y[0], y[1], y[2], y[3]);
}

/* Certain overturning: a tilt of pi/2, or the free-motion test of a one-DOF pattern. */
static int overturn_joint(const stack *m, double t, const double *y)
{
    if (fabs(y[0]) >= 0.5 * M_PI) return 0;
    if (fabs(y[1]) >= 0.5 * M_PI || fabs(y[1] - y[0]) >= 0.5 * M_PI) return 1;
    if (!(t >= m->gm->t_quiet)) return -1;
    if (m->s1 && !m->s2 && rd_housner_falls(y[0], y[2], m->alpha_c, m->p_c)) return 0;
    if (!m->s1 && m->s2 && rd_housner_falls(y[1], y[3], m->alpha2, m->p2)) return 1;
    return -1;
}

static int k_settle(void *sys, double t, double *y)
{
    stack *m = sys;
    normalize(m, y);
    int rc = choose_mode(m, t, y);
    if (rc != RD_HYB_GO) return rc;
    int j = overturn_joint(m, t, y);
    if (j >= 0) return stop(m, t, y, RD_REF_OVERTURN, j);
    build_roots(m);
    return RD_HYB_GO;
}

/* Kinetic energy (J) of pattern (s1, s2) at rates om: 0.5 om.M.om, M of the pattern's pivots
 * (a closed joint moves rigidly, so either corner serves as its pivot). */
static double kinetic(const rd_kounadis_def *d, int s1, int s2, const double *y, const double om[2])
{
    double mm[2][2], rest[2], th[2] = { y[0], y[1] };
    rd_kounadis_matrix(d, s1 ? s1 : 1, s2 ? s2 : 1, th, om, 0.0, 0.0, mm, rest);
    return 0.5 *
           (mm[0][0] * om[0] * om[0] + 2.0 * mm[0][1] * om[0] * om[1] + mm[1][1] * om[1] * om[1]);
}

/* Candidate post-impact pattern (s1, s2) fits the velocities: an open joint at zero angle must
 * open faster than the rest threshold; a closed joint needs zero angle. */
static int post_fits(const stack *m, int s1, int s2, const double *y, const double om[2])
{
    double a[2] = { y[0], y[1] - y[0] }, w[2] = { om[0], om[1] - om[0] };
    int s[2] = { s1, s2 };
    for (int j = 0; j < 2; j++) {
        if (!s[j] && a[j] != 0.0) return 0;
        if (s[j] && a[j] != 0.0 && a[j] * s[j] < 0.0) return 0;
        if (s[j] && a[j] == 0.0 && !(w[j] * s[j] > m->rest_omega)) return 0;
    }
    return 1;
}

/* Impact at joint j: plastic, angular momentum about the new pivots; the pattern that rocks on
 * the impacting corner if its velocities fit, else locked, lower at rest, rest. */
static int impact(stack *m, double t, double *y, int j)
{
    const int cand[6][2] = { { j ? m->s1 : -m->s1, j ? -m->s2 : m->s2 },
                             { 1, 0 },
                             { -1, 0 },
                             { 0, 1 },
                             { 0, -1 },
                             { 0, 0 } };
    double pre[2] = { y[2], y[3] };
    double rel = y[1] - y[0];
    y[0] = j ? y[0] : 0.0;
    y[1] = j || !m->s2 ? y[0] : y[0] + rel; /* a closed interface stays closed */
    m->res->summary.nimpacts++;
    for (int i = 0; i < 6; i++) {
        double post[2];
        plastic_impact(&m->d, m->s1, m->s2, cand[i][0], cand[i][1], y, pre, post);
        post[0] *= m->kappa;
        post[1] *= m->kappa;
        if (!post_fits(m, cand[i][0], cand[i][1], y, post)) continue;
        if (m->kappa > 1.0 &&
            kinetic(&m->d, cand[i][0], cand[i][1], y, post) > kinetic(&m->d, m->s1, m->s2, y, pre))
            return rd_error_set(m->err,
                                "kounadis: restitution %g gains energy at the impact at t = %.9g s",
                                m->d.r, t);
        int o1 = m->s1, o2 = m->s2;
        m->s1 = cand[i][0];
        m->s2 = cand[i][1];
        y[2] = post[0];
        y[3] = post[1];
        normalize(m, y);
        if (push_event(m, t, RD_REF_IMPACT, j, y, pre) || note_switch(m, t, y, o1, o2)) return -1;
        return RD_HYB_RESTART;
    }
    return rd_error_set(m->err, "kounadis: no pattern fits the impact at t = %.9g s", t);
}

static int k_event(void *sys, double t, double *y, const int *found)
{
    stack *m = sys;
    normalize(m, y);
    int restart = 0, peak[2] = { 0, 0 };
    for (int i = 0; i < m->nroots; i++) {
        if (!found[i]) continue;
        int k = m->kind[i];
        if (k == R_FALL0 || k == R_FALL1 || k == R_FALL2)
            return stop(m, t, y, RD_REF_OVERTURN, k != R_FALL0);
        if (k == R_LIFT0 || k == R_LIFT1) return stop(m, t, y, RD_REF_LIFTOFF, k == R_LIFT1);
        if (k == R_IMPACT0 || k == R_IMPACT1) return impact(m, t, y, k == R_IMPACT1);
        if (k == R_PEAK0 || k == R_PEAK1)
            peak[k == R_PEAK1] = 1;
        else
            restart = 1; /* a corner force reached 0, or a saddle crossing: settle decides */
    }
    if (restart) return RD_HYB_RESTART;
    for (int j = 0; j < 2; j++)
        if (peak[j] && push_event(m, t, RD_REF_PEAK, j, y, NULL)) return -1;
    return RD_HYB_GO;
}

static int k_sample(void *sys, double t, double *y)
{
    stack *m = sys;
    normalize(m, y);
    rd_ref_sample s;
    memset(&s, 0, sizeof s);
    s.t = t;
    memcpy(s.theta, y, sizeof s.theta);
    memcpy(s.omega, y + 2, sizeof s.omega);
    s.s1 = m->s1;
    s.s2 = m->s2;
    note_angles(m, y);
    return rd_ref_push_sample(m->res, &s, m->err);
}

static int sgn(double x) { return (x > 0.0) - (x < 0.0); }

static int stack_init(stack *m, const rd_kounadis_def *d, const rd_ground *gm, const rd_ref_opts *o,
                      rd_ref_result *res, rd_error *err)
{
    if (!(d->b1 > 0.0 && d->h1 > 0.0 && d->m1 > 0.0 && d->b2 > 0.0 && d->h2 > 0.0 && d->m2 > 0.0 &&
          d->g > 0.0 && d->b2 <= d->b1 && d->r <= 1.0))
        return rd_error_set(err, "kounadis: need positive sizes, masses, g, b2 <= b1 and r <= 1");
    memset(m, 0, sizeof *m);
    m->d = *d;
    m->alpha[0] = rd_housner_alpha(d->b1, d->h1);
    m->kappa = d->r > 0.0 ? d->r / rd_housner_r(m->alpha[0]) : 1.0;
    m->alpha[1] = rd_housner_alpha(d->b2, d->h2);
    m->p1 = rd_housner_p(d->b1, d->h1, d->g);
    double mt = d->m1 + d->m2;
    double hc = (d->m1 * d->h1 + d->m2 * (2.0 * d->h1 + d->h2)) / mt; /* stack centre height */
    double io = 4.0 / 3.0 * d->m1 * (d->b1 * d->b1 + d->h1 * d->h1) +
                d->m2 * (d->b1 * d->b1 + pow(2.0 * d->h1 + d->h2, 2)) +
                centroidal_inertia(d->m2, d->b2, d->h2);
    m->alpha_c = atan2(d->b1, hc);
    m->p_c = sqrt(mt * d->g * hypot(d->b1, hc) / io);
    m->alpha2 = m->alpha[1];
    m->p2 = rd_housner_p(d->b2, d->h2, d->g);
    m->rest_omega = o->rest_factor * m->p1;
    m->tol_acc = 1e-9 * m->p1 * m->p1;
    m->tol_f = 1e-9 * mt * d->g;
    m->gm = gm;
    m->res = res;
    m->err = err;
    double rel = o->theta0[1] - o->theta0[0], relw = o->omega0[1] - o->omega0[0];
    m->s1 = o->theta0[0] != 0.0 ? sgn(o->theta0[0]) : sgn(o->omega0[0]);
    m->s2 = rel != 0.0 ? sgn(rel) : sgn(relw);
    return 0;
}

int rd_kounadis_solve(const rd_kounadis_def *def, const rd_ground *gm, const rd_ref_opts *opts,
                      rd_ref_result *res, rd_error *err)
{
    static const rd_ground still = { .t_quiet = 0.0 };
    stack m;
    rd_ref_result_init(res);
    if ((gm && rd_ground_check(gm, err)) || stack_init(&m, def, gm ? gm : &still, opts, res, err))
        return -1;
    double pmax = fmax(m.p1, m.p2);
    rd_hybrid h = { .n = 4,
                    .hmax = 0.05 / pmax,
                    .sys = &m,
                    .rhs = k_rhs,
                    .nroots = k_nroots,
                    .roots = k_roots,
                    .settle = k_settle,
                    .event = k_event,
                    .sample = k_sample };
    double y[4] = { opts->theta0[0], opts->theta0[1], opts->omega0[0], opts->omega0[1] };
    if (rd_hybrid_run(&h, m.gm, opts, y, &res->summary.t_stop, err)) {
        rd_ref_result_free(res);
        return -1;
    }
    return 0;
}
