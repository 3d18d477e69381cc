/* rockdem — edge subcontacts: another body's edge that crosses the owner between the vertex
 * points of both bodies (issue 10: a brick toppling over a pedestal's edge, a drum's base
 * pivoting on the lower drum's rim).
 *
 * The vertex-face points of contact.c hold wherever a vertex of one body enters the other. When
 * an edge of the other body enters the owner while both its end vertices stay outside, and the
 * owner's own points are beside it, nothing bears: the edge passes through the owner's face.
 * 3DEC's common plane holds such an edge by the polygon where the two faces overlap, whose
 * corners are the edge crossings. Here, per side (owner o, other body t, both convex, t without
 * points of its own: a fixed pedestal or base) and per edge of t, the part of the edge inside o
 * is clipped against o's face planes; its deepest point, the maximum over the clipped part of
 * the depth below o's nearest plane (a concave function of the position along the edge, found
 * by ternary search; an edge lying level in a face bears at its middle), is a subcontact:
 *     Fn = KN A' depth    along the nearest plane's inward normal (o pushed off the edge)
 *     Fs <- proj(Fs) - KS A' dUs, |Fs| <= Fn tan(phi)   (contact.c's Coulomb law)
 * with A' = weight * the owner's mean point area (as one corner of its faces). The contact is
 * elastic (no impact set, no dashpot) and bonds never form on it. Its spring energy is in the
 * balance (rd_edge_elastic_energy) and released into friction when it stops bearing.
 * Not between two free bodies (both carry points): there an edge's end enters the other body
 * as a vertex subcontact while the edge subcontact lets go, and that handover is not smooth
 * (a new vertex spring starts at the edge's depth): the unequal stack toppling at 0.75 g, 2 Hz
 * (rigid preset, KN 1e10) ended with residual 8.8e-3 (3.1e-4 without), and the 10-drum column
 * ran 40 % slower. Edge crossings between two free bodies are left open.
 * Folder engine/ owns the simulation (bodies, contacts, stepping, monitors); it may call base/,
 * geometry/, records/ and scenario/ (validate, copy, free), never io/ or cli/.
 */
#include "engine/sim.h"
#include "engine/law.h"
#include "base/vec.h"

#include <math.h>

/* ternary-search iterations for the deepest point: (2/3)^40 of an edge, below 1e-7 of it */
#define RD_EDGE_SEARCH 40
/* depths along an edge that differ by less than this fraction of the contact band are level
 * (round-off of a 1 m body is 1e-16 m; 1e-9 of the 1 mm band is 1e-12 m) */
#define RD_EDGE_FLAT 1e-9
/* most vertices of a body whose edges are tested (a 128-sided drum has 256) */
#define RD_EDGE_MAX_VERTS 512

/* Edges of a convex polyhedron, each once: face f's side (a, b) with a < b. */
int rd_edge_count(const rd_poly *p)
{
    int n = 0;
    for (int f = 0; f < p->nf; f++) n += p->flen[f];
    return n / 2;
}

/* Signed distance of world point x to plane k of body o (> 0 outside), m. */
static double dist(const rd_sim *s, int o, int k, const double x[3])
{
    int j = s->face0[o] + k;
    return rd_dot(s->wn[j], x) - s->wd[j];
}

/* Depth of x inside o below its nearest plane (< 0 outside), m; *kmin that plane. */
static double depth_at(const rd_sim *s, int o, const double x[3], int *kmin)
{
    double d = INFINITY;
    for (int k = 0; k < s->poly[o].nf; k++) {
        double e = -dist(s, o, k, x);
        if (e < d) { d = e; *kmin = k; }
    }
    return d;
}

/* Where x lies against o's box: one bit per side it is beyond (0: inside the box). */
static unsigned outcode(const double box[6], const double x[3])
{
    unsigned code = 0;
    for (int c = 0; c < 3; c++) code |= (unsigned)(x[c] < box[c]) << c | (unsigned)(x[c] > box[3 + c]) << (3 + c);
    return code;
}

/* Part [lo, hi] of segment a + u (b - a), u in [0, 1], inside o; 0 when empty. */
static int clip(const rd_sim *s, int o, const double a[3], const double b[3], double *lo, double *hi)
{
    *lo = 0; *hi = 1;
    for (int k = 0; k < s->poly[o].nf; k++) {
        double da = dist(s, o, k, a), db = dist(s, o, k, b);
        if (da > 0 && db > 0) return 0;
        if (da > 0) *lo = fmax(*lo, da / (da - db));
        else if (db > 0) *hi = fmin(*hi, da / (da - db));
        if (*lo >= *hi) return 0;
    }
    return 1;
}

/* The slot stops bearing: its spring energy is released into friction. */
static void edge_release(rd_sim *s, int e, double kA, double sA)
{
    if (!s->eon[e]) return;
    s->e_fric += 0.5 * (kA * s->edepth[e] * s->edepth[e] + rd_dot(s->efs[e], s->efs[e]) / sA);
    s->efs[e][0] = s->efs[e][1] = s->efs[e][2] = 0;
    s->edepth[e] = 0;
    s->eon[e] = 0;
}

/* Force of edge slot e at world point q, depth d below o's plane k. */
static void edge_force(rd_sim *s, const rd_side *sd, const rd_joint *j, int e, const double q[3], double d, int k,
                       double kA, double sA)
{
    const int o = sd->owner, t = sd->other;
    const double *n = s->wn[s->face0[o] + k];
    double ro[3], rt[3], vr[3], tmp[3];
    for (int i = 0; i < 3; i++) { ro[i] = q[i] - s->x[o][i]; rt[i] = q[i] - s->x[t][i]; }
    rd_law_relative_velocity(s, o, t, ro, rt, vr);
    double *fs = s->efs[e], fn = kA * d;
    rd_law_shear(fs, n, vr, rd_dot(vr, n), sA, s->dt, fn * j->tan_phi, &s->e_fric);
    double F[3] = {-fn * n[0] + fs[0], -fn * n[1] + fs[1], -fn * n[2] + fs[2]};
    rd_axpy(1.0, F, s->f[o]);
    rd_cross(ro, F, tmp);
    rd_axpy(1.0, tmp, s->tq[o]);
    if (!s->fixed[t]) {
        rd_axpy(-1.0, F, s->f[t]);
        rd_cross(rt, F, tmp);
        rd_axpy(-1.0, tmp, s->tq[t]);
    }
    s->edepth[e] = d;
    s->eon[e] = 1;
}

void rd_edge_side(rd_sim *s, const rd_pair *pr, const rd_side *sd)
{
    if (sd->nedge == 0) return;
    const int o = sd->owner, t = sd->other;
    const rd_poly *pt = &s->poly[t];
    if (pt->nv > RD_EDGE_MAX_VERTS) return;
    const rd_joint *j = &s->joint[pr->joint];
    double A = sd->weight * sd->edge_area, kA = j->kn * A, sA = j->ks * A;
    double tol = RD_CONTACT_BAND * fmin(s->poly[o].radius, pt->radius);
    double flat = RD_EDGE_FLAT * tol; /* depths closer than this are level */
    unsigned char code[RD_EDGE_MAX_VERTS]; /* vertex of t against o's box */
    double box[6]; /* o's box, grown by the broad phase's margin */
    rd_pairs_box_now(s, o, box);
    for (int v = 0; v < pt->nv; v++) code[v] = (unsigned char)outcode(box, s->wv[s->vert0[t] + v]);
    int e = sd->edge0;
    for (int f = 0; f < pt->nf; f++) {
        const int *ix = pt->fidx + pt->fstart[f];
        for (int i = 0; i < pt->flen[f]; i++) {
            int va = ix[i], vb = ix[(i + 1) % pt->flen[f]];
            if (va > vb) continue;
            double lo, hi;
            const double *a = s->wv[s->vert0[t] + va], *b = s->wv[s->vert0[t] + vb];
            /* both ends beyond one side of o's box */
            if ((code[va] & code[vb]) || !clip(s, o, a, b, &lo, &hi)) {
                edge_release(s, e++, kA, sA);
                continue;
            }
            double q[3], d = -INFINITY;
            int k = 0;
            for (int it = 0; it < RD_EDGE_SEARCH; it++) { /* the deepest point of the clipped part */
                double u1 = lo + (hi - lo) / 3, u2 = hi - (hi - lo) / 3, x1[3], x2[3];
                int k1, k2;
                for (int c = 0; c < 3; c++) { x1[c] = a[c] + u1 * (b[c] - a[c]); x2[c] = a[c] + u2 * (b[c] - a[c]); }
                double d1 = depth_at(s, o, x1, &k1), d2 = depth_at(s, o, x2, &k2);
                if (d1 < d2 - flat) lo = u1;
                else if (d2 < d1 - flat) hi = u2;
                else { lo = u1; hi = u2; } /* level (an edge lying in a face): its middle */
            }
            double u = 0.5 * (lo + hi);
            for (int c = 0; c < 3; c++) q[c] = a[c] + u * (b[c] - a[c]);
            d = depth_at(s, o, q, &k);
            if (d > 0) edge_force(s, sd, j, e, q, d, k, kA, sA);
            else edge_release(s, e, kA, sA);
            e++;
        }
    }
}

void rd_edge_reset(rd_sim *s, const rd_side *sd)
{
    for (int e = sd->edge0; e < sd->edge0 + sd->nedge; e++) {
        s->efs[e][0] = s->efs[e][1] = s->efs[e][2] = 0;
        s->edepth[e] = 0;
        s->eon[e] = 0;
    }
}

double rd_edge_elastic_energy(const rd_sim *s, const rd_pair *pr, const rd_side *sd)
{
    const rd_joint *j = &s->joint[pr->joint];
    double A = sd->weight * sd->edge_area, kA = j->kn * A, sA = j->ks * A, en = 0;
    for (int e = sd->edge0; e < sd->edge0 + sd->nedge; e++)
        if (s->eon[e]) en += 0.5 * (kA * s->edepth[e] * s->edepth[e] + rd_dot(s->efs[e], s->efs[e]) / sA);
    return en;
}
