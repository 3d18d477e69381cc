/* rockdem — contacts: common-plane normal, subcontact gaps and the Coulomb-slip joint law.
 *
 * For each pair of bodies that may touch, the contact normal is the face normal (of either
 * body) that maximises the separation of the other body's vertices — the separating-axis
 * choice, kept from the last step unless another axis is clearly better (hysteresis), in the
 * spirit of 3DEC's common plane. Each subcontact point p of the owner body, with tributary area
 * A, is tested against the other (convex) body: its gap along the normal u (pointing from the
 * other body to the owner) is the distance travelled along -u to enter that body,
 *     g = max over faces f with n_f.u > 0 of (n_f.p - d_f) / (n_f.u),
 * provided p lies within the other body's faces that are parallel or facing away (n_f.u <= 0).
 * Law (seed 002 eqs. 1-2, 3DEC Coulomb slip), per subcontact, with A' = weight * A:
 *     Fn = KN A' (-g)              compression only (tension up to T A' while bonded)
 *     Fs <- rot(Fs) - KS A' dUs    incremental, kept in the current contact plane
 *     |Fs| <= Fn tan(phi) + c A'   scaled back along its direction when exceeded
 * An opening subcontact drops its forces; the first slip or opening breaks its bond (c, T -> 0).
 * Optional normal dashpot: Fd = -2 zeta KN A' sqrt(m_eff / K_active) vn, so the active contact
 * of a pair is damped at the ratio zeta of its critical value.
 * Folder engine/ owns the simulation (bodies, contacts, stepping, monitors); it may call base/,
 * geometry/, records/ and scenario/ (validate, copy, free), never io/ or cli/.
 */
#include "engine/sim.h"
#include "base/vec.h"

#include <float.h>

#define RD_AXIS_EVERY 8 /* steps between full searches for the common-plane face */
/* A face of the other body whose normal makes less than acos(0.2) = 78 deg with the contact
 * normal measures the gap (the ray along the normal exits there); steeper faces only bound it
 * sideways. Without this cut a point on the rim of a tapered drum, lying on a side face that
 * leans by a fraction of a degree, gets a round-off gap e / (n.u) that hides its overlap. */
#define RD_ALIGNED 0.2
#include <math.h>
#include <string.h>

/* Per-face context for one side of a pair: the other body's face planes that matter for this
 * candidate face, expressed in the owner's body frame so a point's gap needs no transform.
 * Aligned planes (n.u > 0) are pre-divided by n.u: gap = max_k (a_k . p - b_k). Lateral planes
 * (n.u <= 0) only bound the other body sideways: the point must satisfy n . p <= d. Lateral
 * planes that every vertex of the face already satisfies are dropped (linear, so no point of
 * the face can cross them). */
typedef struct side_ctx {
    int o, t;                 /* owner and other body */
    double u[3];              /* unit normal from the other body towards the owner, ground frame */
    double wa;                /* weight */
    const rd_joint *j;        /* the pair's joint properties */
    double damp_coef;         /* 2 zeta sqrt(m_eff / K_active), s (0 without viscous damping) */
    double k_active;          /* accumulates KN A' over active points, N/m */
    int nal, nlat;            /* aligned and lateral planes kept */
    double al[RD_MAX_PLANES][4];  /* a (3), b: gap through an aligned plane, owner frame */
    double lat[RD_MAX_PLANES][4]; /* n (3), d: a lateral plane, owner frame */
    double rot[9];            /* rotation of stored shear forces (normal moved since last step) */
    int rotate;               /* 1 when rot must be applied */
} side_ctx;

/* Forget a pair's contact history (shear forces, active flags); bonds are kept. */
static void reset_pair(rd_sim *s, rd_pair *pr)
{
    for (int k = 0; k < pr->nside; k++) {
        const rd_side *sd = &pr->side[k];
        int n = s->pt0[sd->owner + 1] - s->pt0[sd->owner];
        memset(s->fs + sd->state0, 0, (size_t)n * sizeof *s->fs);
        for (int j = 0; j < n; j++) s->pstate[sd->state0 + j] &= RD_PT_BONDED;
        int nf = s->cf0[sd->owner + 1] - s->cf0[sd->owner];
        memset(s->face_nactive + sd->face0, 0, (size_t)nf * sizeof(int));
    }
    pr->axis_body = -1;
    pr->k_active = 0;
}

void rd_contact_reset_body(rd_sim *s, int body)
{
    for (int p = 0; p < s->npair; p++)
        if (s->pair[p].a == body || s->pair[p].b == body) reset_pair(s, &s->pair[p]);
}

/* Pairs that were live last step but whose boxes no longer overlap lose their history. */
static void reset_departed(rd_sim *s)
{
    for (int k = 0; k < s->nlive_prev; k++) {
        rd_pair *pr = &s->pair[s->live_prev[k]];
        if (pr->seen != s->stamp) reset_pair(s, pr);
    }
}

/* Separation of body `y` from the plane of face f of body `x` (negative = overlap), m. */
static double face_separation(const rd_sim *s, int x, int f, int y)
{
    const double *n = s->wn[s->face0[x] + f];
    double d = s->wd[s->face0[x] + f], sep = DBL_MAX;
    for (int k = s->vert0[y]; k < s->vert0[y + 1]; k++) {
        double e = rd_dot(n, s->wv[k]) - d;
        if (e < sep) sep = e;
    }
    return sep;
}

/* Choose the common-plane face (full separating-axis search every RD_AXIS_EVERY steps or when
 * the pair has no axis yet); in between the chosen face's normal simply follows its body. */
static void pair_axis(rd_sim *s, rd_pair *pr)
{
    if (pr->axis_body >= 0 && ++pr->axis_age < RD_AXIS_EVERY) {
        rd_copy3(s->wn[s->face0[pr->axis_body] + pr->axis_face], pr->n);
        return;
    }
    pr->axis_age = 0;
    double best = -DBL_MAX, prev = -DBL_MAX;
    int bb = -1, bf = -1;
    for (int side = 0; side < 2; side++) {
        int x = side ? pr->b : pr->a, y = side ? pr->a : pr->b;
        double c[3] = {s->x[y][0] - s->x[x][0], s->x[y][1] - s->x[x][1], s->x[y][2] - s->x[x][2]};
        for (int f = 0; f < s->poly[x].nf; f++) {
            int current = (x == pr->axis_body && f == pr->axis_face);
            if (!current && rd_dot(s->wn[s->face0[x] + f], c) <= 0) continue; /* faces away */
            double sep = face_separation(s, x, f, y);
            if (current) prev = sep;
            if (sep > best) { best = sep; bb = x; bf = f; }
        }
    }
    double hyst = 1e-4 * (s->poly[pr->a].radius + s->poly[pr->b].radius);
    if (pr->axis_body >= 0 && prev >= best - hyst) {
        rd_copy3(s->wn[s->face0[pr->axis_body] + pr->axis_face], pr->n);
        return;
    }
    pr->axis_body = bb;
    pr->axis_face = bf;
    rd_copy3(s->wn[s->face0[bb] + bf], pr->n);
}

/* Keep the other body's planes that matter for candidate face cf (owner frame, see side_ctx).
 * Returns the lower bound of the gap over the face (the gap through any aligned plane is
 * linear in p, so its minimum over the convex face is at a vertex). */
static double face_planes(const rd_sim *s, side_ctx *c, int cf)
{
    const rd_poly *po = &s->poly[c->o];
    const double *R = s->R[c->o], *xo = s->x[c->o];
    int f = s->cf_face[cf], nv = po->flen[f];
    const int *ix = po->fidx + po->fstart[f];
    const double (*wv)[3] = s->wv + s->vert0[c->o];
    /* a point on the other body's edge (coincident faces of equal blocks) is inside it: lateral
       planes get a tolerance far above round-off and far below any subcontact spacing */
    double tol = 1e-9 * (1.0 + s->poly[c->t].radius);
    double lb = -DBL_MAX;
    c->nal = c->nlat = 0;
    for (int k = s->face0[c->t]; k < s->face0[c->t + 1]; k++) {
        const double *n = s->wn[k];
        double cu = rd_dot(n, c->u);
        double emin = DBL_MAX, emax = -DBL_MAX;
        for (int j = 0; j < nv; j++) { /* the face's vertices against this plane, world frame */
            double e = rd_dot(n, wv[ix[j]]) - s->wd[k];
            emin = rd_min(emin, e); emax = rd_max(emax, e);
        }
        if (cu <= RD_ALIGNED && emax <= tol) continue; /* lateral plane no point of the face crosses */
        double nb[3], db = s->wd[k] - rd_dot(n, xo);
        rd_mat_tvec(R, n, nb);
        if (cu > RD_ALIGNED) {
            double *a = c->al[c->nal++];
            for (int j = 0; j < 3; j++) a[j] = nb[j] / cu;
            a[3] = db / cu;
            lb = rd_max(lb, emin / cu); /* the gap is at least this plane's, whose min is emin/cu */
        } else {
            if (emin > tol) return DBL_MAX; /* the whole face is beside the other body */
            double *l = c->lat[c->nlat++];
            rd_copy3(nb, l);
            l[3] = db + tol;
        }
    }
    return c->nal ? lb : DBL_MAX;
}

/* Gap of a point (owner frame) from the other body along u, m; +inf when beside it. */
static inline double point_gap(const side_ctx *c, const double p[3])
{
    double g = -DBL_MAX;
    for (int k = 0; k < c->nal; k++) {
        const double *a = c->al[k];
        double r = a[0] * p[0] + a[1] * p[1] + a[2] * p[2] - a[3];
        if (r > g) g = r;
    }
    for (int k = 0; k < c->nlat; k++) {
        const double *l = c->lat[k];
        if (l[0] * p[0] + l[1] * p[1] + l[2] * p[2] > l[3]) return DBL_MAX;
    }
    return g;
}

/* An opening subcontact loses its shear force (3DEC); the spring energy it held is dissipated
 * by the joint model and booked as friction so the energy balance stays closed. */
static inline void drop_shear(rd_sim *s, int st, double sA)
{
    s->e_fric += 0.5 * rd_dot(s->fs[st], s->fs[st]) / sA;
    s->fs[st][0] = s->fs[st][1] = s->fs[st][2] = 0;
}

/* Force of one subcontact on the owner; returns 1 if active. */
static int subcontact(rd_sim *s, side_ctx *c, int pt, int st)
{
    const int o = c->o, t = c->t;
    unsigned char *flags = &s->pstate[st];
    double g = point_gap(c, s->pl[pt]);
    double A = c->wa * s->pa[pt];
    double kA = c->j->kn * A;
    s->pj[st][0] = 0;
    s->pj[st][1] = g;
    if (g >= 0 && !((*flags & RD_PT_BONDED) && g < c->j->tension / c->j->kn)) {
        if (*flags & RD_PT_ACTIVE) {
            drop_shear(s, st, c->j->ks * A);
            *flags &= (unsigned char)~(RD_PT_ACTIVE | RD_PT_SLIP | RD_PT_BONDED);
        }
        return 0;
    }
    const double *u = c->u;
    double ro[3];
    rd_mat_vec(s->R[o], s->pl[pt], ro);
    double rt[3] = {ro[0] + s->x[o][0] - s->x[t][0], ro[1] + s->x[o][1] - s->x[t][1],
                    ro[2] + s->x[o][2] - s->x[t][2]};
    double vr[3], tmp[3];
    rd_cross(s->w[o], ro, vr);
    rd_axpy(1.0, s->v[o], vr);
    if (!s->fixed[t]) {
        rd_cross(s->w[t], rt, tmp);
        rd_axpy(-1.0, tmp, vr);
        rd_axpy(-1.0, s->v[t], vr);
    }
    double vn = rd_dot(vr, u);
    double fel = -kA * g;                      /* elastic normal force, N (< 0: tension) */
    double fn = fel - c->damp_coef * kA * vn;  /* plus the dashpot */
    if (fn < 0) {
        int bonded = (*flags & RD_PT_BONDED) && fel > -c->j->tension * A;
        if (!bonded) *flags &= (unsigned char)~RD_PT_BONDED;
        if (!bonded || fn < -c->j->tension * A) fn = bonded ? -c->j->tension * A : 0.0;
    }
    s->e_damp -= (fn - fel) * vn * s->dt * (fn != fel);
    c->k_active += kA;

    /* shear: turn last step's force with the contact plane, then add the elastic increment
       of the relative tangential displacement */
    double *fs = s->fs[st];
    if (c->rotate) rd_mat_vec(c->rot, fs, fs);
    double prev2 = rd_dot(fs, fs);
    double sA = c->j->ks * A;
    for (int k = 0; k < 3; k++) fs[k] -= sA * (vr[k] - vn * u[k]) * s->dt;
    double cohesion = (*flags & RD_PT_BONDED) ? c->j->cohesion * A : 0.0;
    double lim = rd_max(fn, 0.0) * c->j->tan_phi + cohesion;
    double mag2 = rd_dot(fs, fs);
    *flags = (unsigned char)((*flags | RD_PT_ACTIVE) & ~RD_PT_SLIP);
    if (mag2 > lim * lim) {
        /* slip d = (|F_trial| - F_lim) / (KS A) happens at a force between F_lim and the
           smaller of |F_prev|, |F_trial|: this books lim*d when sliding steadily, the released
           spring energy when the limit drops, and nothing when frictionless */
        double mag = sqrt(mag2), r = lim / mag;
        s->e_fric += (mag - lim) * (lim + rd_min(sqrt(prev2), mag)) / (2.0 * sA);
        fs[0] *= r; fs[1] *= r; fs[2] *= r;
        mag2 = lim * lim;
        *flags = (unsigned char)((*flags | RD_PT_SLIP) & ~RD_PT_BONDED);
    }
    s->e_elastic += 0.5 * (kA * g * g + mag2 / sA);

    s->pj[st][0] = fn;
    double F[3] = {fn * u[0] + fs[0], fn * u[1] + fs[1], fn * u[2] + fs[2]};
    rd_axpy(1.0, F, s->f[o]);
    rd_cross(ro, F, tmp);
    rd_axpy(1.0, tmp, s->tq[o]);
    if (!s->fixed[t]) {
        rd_axpy(-1.0, F, s->f[t]);
        rd_cross(rt, F, tmp);
        rd_axpy(-1.0, tmp, s->tq[t]);
    }
    return 1;
}

static void clear_face(rd_sim *s, const rd_side *sd, const rd_joint *jt, int cf, int k)
{
    int *na = &s->face_nactive[sd->face0 + k];
    if (*na == 0) return;
    int first = sd->state0 + (s->cf_pt0[cf] - s->pt0[sd->owner]);
    int n = s->cf_pt0[cf + 1] - s->cf_pt0[cf];
    for (int j = 0; j < n; j++) {
        drop_shear(s, first + j, jt->ks * sd->weight * s->pa[s->cf_pt0[cf] + j]);
        s->pstate[first + j] &= (unsigned char)~(RD_PT_ACTIVE | RD_PT_SLIP);
    }
    *na = 0;
}

/* Rotation matrix taking unit vector a to unit vector b about a x b (Rodrigues). */
static void rotation_between(const double a[3], const double b[3], double m[9])
{
    double k[3], c = rd_dot(a, b);
    rd_cross(a, b, k);
    double f = c > -1 + 1e-12 ? 1.0 / (1.0 + c) : 0.0;
    m[0] = c + f * k[0] * k[0];        m[1] = -k[2] + f * k[0] * k[1]; m[2] = k[1] + f * k[0] * k[2];
    m[3] = k[2] + f * k[1] * k[0];     m[4] = c + f * k[1] * k[1];     m[5] = -k[0] + f * k[1] * k[2];
    m[6] = -k[1] + f * k[2] * k[0];    m[7] = k[0] + f * k[2] * k[1];  m[8] = c + f * k[2] * k[2];
}

static void side_step(rd_sim *s, rd_pair *pr, rd_side *sd, double *k_active)
{
    side_ctx c;
    c.o = sd->owner; c.t = sd->other; c.wa = sd->weight; c.j = &s->joint[pr->joint];
    double sign = (sd->owner == pr->axis_body) ? -1.0 : 1.0;
    for (int k = 0; k < 3; k++) c.u[k] = sign * pr->n[k];
    c.rotate = rd_dot(sd->u_prev, sd->u_prev) > 0 && memcmp(c.u, sd->u_prev, sizeof c.u) != 0;
    if (c.rotate) rotation_between(sd->u_prev, c.u, c.rot);
    rd_copy3(c.u, sd->u_prev);
    c.k_active = 0;
    c.damp_coef = 0;
    if (c.j->damping > 0 && !s->settling) {
        double K = pr->k_active > 0 ? pr->k_active : INFINITY; /* a new contact: undamped step */
        c.damp_coef = 2.0 * c.j->damping * sqrt(pr->m_eff / K);
    }
    for (int cf = s->cf0[c.o], k = 0; cf < s->cf0[c.o + 1]; cf++, k++) {
        double lb = face_planes(s, &c, cf);
        /* beside the other body (plane lists incomplete): no contact, bonds or not; otherwise
           a face wholly above the other body is skipped unless bonds may act across gaps */
        if (lb == DBL_MAX || (s->can_cull && lb > 0)) {
            clear_face(s, sd, c.j, cf, k);
            rd_joint_face_open(s, sd, cf, lb);
            continue;
        }
        int na = 0, nslip = 0;
        int st = sd->state0 + (s->cf_pt0[cf] - s->pt0[c.o]);
        double area = 0;
        for (int pt = s->cf_pt0[cf]; pt < s->cf_pt0[cf + 1]; pt++, st++) {
            if (subcontact(s, &c, pt, st)) {
                na++;
                area += c.wa * s->pa[pt];
                nslip += (s->pstate[st] & RD_PT_SLIP) != 0;
            }
        }
        s->face_nactive[sd->face0 + k] = na;
        if (!s->settling) s->active_point_steps += na;
        rd_monitor_contact(s, c.o, c.t, area, na, nslip);
    }
    *k_active += c.k_active;
}

/* Broad phase, then every live pair: common plane and subcontact forces. 0, or -1 when the
 * broad phase ran out of memory growing the pair cache. */
int rd_contact_step(rd_sim *s)
{
    s->e_elastic = 0;
    if (rd_pairs_update(s)) return -1;
    reset_departed(s);
    for (int k = 0; k < s->nlive; k++) {
        rd_pair *pr = &s->pair[s->live[k]];
        pair_axis(s, pr);
        double k_active = 0;
        for (int q = 0; q < pr->nside; q++) side_step(s, pr, &pr->side[q], &k_active);
        pr->k_active = k_active;
    }
    int *t = s->live_prev; s->live_prev = s->live; s->live = t;
    int c = s->cap_live_prev; s->cap_live_prev = s->cap_live; s->cap_live = c;
    s->nlive_prev = s->nlive;
    return 0;
}
