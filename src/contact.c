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
 * of a pair is damped at the ratio zeta of its critical value. */
#include "sim.h"
#include "vec.h"

#include <float.h>
#include <math.h>
#include <string.h>

/* Per-call context for one side of a pair (kept in registers / stack, no allocation). */
typedef struct side_ctx {
    int o, t;                 /* owner and other body */
    double u[3];              /* unit normal from the other body towards the owner */
    double wa;                /* weight */
    const double *tn;         /* other body's world face normals [nf][3] */
    const double *td;         /* other body's world face offsets [nf] */
    int tnf;                  /* its face count */
    double damp_coef;         /* 2 zeta sqrt(m_eff / K_active), s (0 without viscous damping) */
    double k_active;          /* accumulates KN A' over active points, N/m */
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

static void pair_axis(rd_sim *s, rd_pair *pr)
{
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
    if (pr->axis_body >= 0 && prev >= best - hyst) return;
    pr->axis_body = bb;
    pr->axis_face = bf;
    rd_copy3(s->wn[s->face0[bb] + bf], pr->n);
}

/* Gap of world point p from the other body along u (m); +inf when p is beside it. */
static inline double point_gap(const side_ctx *c, const double p[3])
{
    double g = -DBL_MAX;
    for (int f = 0; f < c->tnf; f++) {
        const double *n = c->tn + 3 * f;
        double cu = n[0] * c->u[0] + n[1] * c->u[1] + n[2] * c->u[2];
        double e = n[0] * p[0] + n[1] * p[1] + n[2] * p[2] - c->td[f];
        if (cu > 1e-9) {
            double r = e / cu;
            if (r > g) g = r;
        } else if (e > 0) {
            return DBL_MAX;
        }
    }
    return g;
}

/* Lower bound of the gap over a candidate face: the gap through the other body's face most
 * aligned with u is linear in p, so its minimum over the (convex) face is at a vertex. */
static double face_gap_bound(const rd_sim *s, const side_ctx *c, int cf)
{
    int best = 0;
    double cbest = -2;
    for (int f = 0; f < c->tnf; f++) {
        double cu = rd_dot(c->tn + 3 * f, c->u);
        if (cu > cbest) { cbest = cu; best = f; }
    }
    if (cbest <= 1e-9) return DBL_MAX;
    const rd_poly *po = &s->poly[c->o];
    int f = s->cf_face[cf];
    double lb = DBL_MAX;
    for (int k = 0; k < po->flen[f]; k++) {
        const double *v = s->wv[s->vert0[c->o] + po->fidx[po->fstart[f] + k]];
        double g = (rd_dot(c->tn + 3 * best, v) - c->td[best]) / cbest;
        if (g < lb) lb = g;
    }
    return lb;
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
    double p[3];
    rd_mat_vec(s->R[o], s->pl[pt], p);
    rd_axpy(1.0, s->x[o], p);
    unsigned char *flags = &s->pstate[st];
    double g = point_gap(c, p);
    double A = c->wa * s->pa[pt];
    double kA = s->sc.contact.kn * A;
    if (g >= 0 && !((*flags & RD_PT_BONDED) && g < s->sc.contact.tension / s->sc.contact.kn)) {
        if (*flags & RD_PT_ACTIVE) {
            drop_shear(s, st, s->sc.contact.ks * A);
            *flags &= (unsigned char)~(RD_PT_ACTIVE | RD_PT_SLIP | RD_PT_BONDED);
        }
        return 0;
    }
    const double *u = c->u;
    double ro[3] = {p[0] - s->x[o][0], p[1] - s->x[o][1], p[2] - s->x[o][2]};
    double rt[3] = {p[0] - s->x[t][0], p[1] - s->x[t][1], p[2] - s->x[t][2]};
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
        int bonded = (*flags & RD_PT_BONDED) && fel > -s->sc.contact.tension * A;
        if (!bonded) *flags &= (unsigned char)~RD_PT_BONDED;
        if (!bonded || fn < -s->sc.contact.tension * A) fn = bonded ? -s->sc.contact.tension * A : 0.0;
    }
    s->e_damp -= (fn - fel) * vn * s->dt * (fn != fel);
    c->k_active += kA;

    /* shear: rotate last step's force into the current plane (keep its magnitude), then add
       the elastic increment of the relative tangential displacement */
    double *fs = s->fs[st];
    double f0 = rd_norm(fs);
    rd_axpy(-rd_dot(fs, u), u, fs);
    double f1 = rd_norm(fs);
    if (f1 > 0) { double r = f0 / f1; fs[0] *= r; fs[1] *= r; fs[2] *= r; }
    double sA = s->sc.contact.ks * A;
    for (int k = 0; k < 3; k++) fs[k] -= sA * (vr[k] - vn * u[k]) * s->dt;
    double cohesion = (*flags & RD_PT_BONDED) ? s->sc.contact.cohesion * A : 0.0;
    double lim = fmax(fn, 0.0) * s->tan_phi + cohesion;
    double mag = rd_norm(fs);
    *flags = (unsigned char)((*flags | RD_PT_ACTIVE) & ~RD_PT_SLIP);
    if (mag > lim) {
        double r = mag > 0 ? lim / mag : 0.0;
        s->e_fric += (mag - lim) * lim / sA;   /* slip displacement times the limited force */
        fs[0] *= r; fs[1] *= r; fs[2] *= r;
        *flags = (unsigned char)((*flags | RD_PT_SLIP) & ~RD_PT_BONDED);
    }
    s->e_elastic += 0.5 * fel * fel / kA + 0.5 * rd_dot(fs, fs) / sA;

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

static void clear_face(rd_sim *s, const rd_side *sd, int cf, int k)
{
    int *na = &s->face_nactive[sd->face0 + k];
    if (*na == 0) return;
    int first = sd->state0 + (s->cf_pt0[cf] - s->pt0[sd->owner]);
    int n = s->cf_pt0[cf + 1] - s->cf_pt0[cf];
    for (int j = 0; j < n; j++) {
        drop_shear(s, first + j, s->sc.contact.ks * sd->weight * s->pa[s->cf_pt0[cf] + j]);
        s->pstate[first + j] &= (unsigned char)~(RD_PT_ACTIVE | RD_PT_SLIP);
    }
    *na = 0;
}

static void side_step(rd_sim *s, rd_pair *pr, const rd_side *sd, double *k_active)
{
    side_ctx c;
    c.o = sd->owner; c.t = sd->other; c.wa = sd->weight;
    double sign = (sd->owner == pr->axis_body) ? -1.0 : 1.0;
    for (int k = 0; k < 3; k++) c.u[k] = sign * pr->n[k];
    c.tn = s->wn[s->face0[c.t]];
    c.td = &s->wd[s->face0[c.t]];
    c.tnf = s->poly[c.t].nf;
    c.k_active = 0;
    c.damp_coef = 0;
    if (s->sc.damping.kind == RD_DAMPING_VISCOUS && !s->settling) {
        double K = pr->k_active > 0 ? pr->k_active : 1.0 / 0.0;
        c.damp_coef = 2.0 * s->sc.damping.value * sqrt(pr->m_eff / K);
    }
    for (int cf = s->cf0[c.o], k = 0; cf < s->cf0[c.o + 1]; cf++, k++) {
        if (s->can_cull && face_gap_bound(s, &c, cf) > 0) { clear_face(s, sd, cf, k); continue; }
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
        s->active_point_steps += na;
        rd_monitor_contact(s, c.o, c.t, area, na, nslip);
    }
    *k_active += c.k_active;
}

void rd_contact_step(rd_sim *s)
{
    s->e_elastic = 0;
    for (int p = 0; p < s->npair; p++) {
        rd_pair *pr = &s->pair[p];
        double d[3] = {s->x[pr->b][0] - s->x[pr->a][0], s->x[pr->b][1] - s->x[pr->a][1],
                       s->x[pr->b][2] - s->x[pr->a][2]};
        double reach = s->poly[pr->a].radius + s->poly[pr->b].radius;
        if (rd_dot(d, d) > reach * reach && s->can_cull) {
            if (pr->axis_body >= 0) reset_pair(s, pr);
            continue;
        }
        pair_axis(s, pr);
        double k_active = 0;
        for (int k = 0; k < pr->nside; k++) side_step(s, pr, &pr->side[k], &k_active);
        pr->k_active = k_active;
    }
}
