/* rockdem — edge subcontacts: an edge of one body that crosses the other between the vertex
 * points of both (issue 10: a brick toppling over a pedestal's or a lower block's edge, a drum
 * pivoting on the lower drum's rim between its vertices).
 *
 * The vertex-face points of contact.c hold wherever a vertex of one body enters the other. An
 * edge can enter the other body while its ends stay outside or stay shallower than its middle
 * (it lies across a ridge of the other body), and then the points beside it carry nothing: the
 * edge passes through a face. 3DEC's common plane holds such an edge by the polygon where the
 * two faces overlap, whose corners are the edge crossings. Here, per side (owner o, other body
 * t, both convex) and per edge a + u (b - a) of t, the depth of the edge below o's plane k is a
 * line c_k + s_k u, and its depth inside o is their minimum, a concave function of u; its
 * maximum d (walked exactly along the lower envelope: u = 0, then each next breakpoint while
 * the active plane rises) is at
 *   - a kink, where a rising plane p and a falling plane m meet (an edge across o's ridge):
 *     the gradient of d with respect to the pose is g = (s_p n_m - s_m n_p) / (s_p - s_m)
 *     (n: o's outward normals; moving the edge changes both planes' depths and slides the
 *     meeting point along the edge), or
 *   - the middle of a level part (an edge lying in a face), g the face's normal, or an end.
 * The subcontact at that point, with A' = weight * the owner's mean point area:
 *     Fn = KN A' (d - d0)  against g: -Fn g on o, +Fn g on t (the gradient of 1/2 KN A' (d - d0)^2)
 *     Fs <- proj(Fs) - KS A' dUs, |Fs| <= |Fn g| tan(phi)   (contact.c's Coulomb law, law.h)
 * Where t carries points (two free bodies), its edge's ends are vertex subcontacts: the edge
 * bears only while its deepest point lies deeper than both ends (floor = the deeper end's
 * depth, at least 0: a crossing, not an edge lying in a face, whose ends hold it), and its
 * spring starts from the depth where that began: d0 = floor at onset, kept until it ends. The
 * normal force is then the gradient of a potential of the pose that is 0 at onset, so no
 * energy is made when an edge starts or stops bearing, nor when one of its ends enters and
 * becomes a vertex subcontact (that vertex starts from its own entrance, contact.c); what the
 * spring holds when the edge stops bearing (its deepest point becomes an end) is released and
 * booked as friction, as 3DEC drops a contact's forces; such a contact is elastic.
 * Where t carries no points (a fixed pedestal or base) floor and d0 are 0, and the edge bears at
 * the two ends of its part inside o (plateau), each a spring of area A'/2 that, where its touch
 * is an impact, takes the joint's impact loss at its first unloading, as a vertex subcontact
 * does (edge_spring). So does an edge between two free bodies that crosses o at rest: its part
 * inside o lies level in one face of o (within the contact band) and, at one end of that part
 * at least, the edge runs on beyond the plane it leaves through by ten bands or more (plateau's
 * answer), or at both ends beyond the band (neither end is then held by the edge's own vertex):
 * a corner of the polygon where the two faces overlap that is no vertex of either body (a block
 * offset on, or turned on, a free pedestal of about its own size; every other drum of a column
 * turned by a fraction of a degree to half a sector). At their deepest points, which jumped
 * across the base as it tilted by a hair, such scenes made energy at rest (a block offset by 8
 * and 4 cm on a free pedestal of its size: residual 0.99 of its energy scale at 0.3 g). Between free
 * bodies each end spring starts from the depth where it starts (zero stretch: the rule may
 * first hold where the edge is already inside), an end that is the edge's own vertex bears as
 * a vertex subcontact too (its spring adds A'/2 there), and the two let go (release_deep) once
 * an end lies deeper than the band: the contact is no longer a resting one, and pieces of the
 * envelope coming and going move its ends along the edge at a jump (a 4-drum column falling at
 * 1.6 g made 1.5e-3 of its energy scale so); the edge then bears at its deepest point. The
 * ten bands at one end keep out an edge lying along one of o's edges a few mm off (equal blocks
 * stacked, one slid or turned by a hair; equal drums rocking on each other), whose bearing piece
 * changes between the two faces it lies near: it crosses at one end only, its other end held by
 * its own vertex (the YADE 4-drum column at 0.7 g made 1.9e-3 of its energy scale with one band
 * at one end, 5.0e-4 with ten). A block or drum turned by up to a few degrees on one of its own
 * footprint crosses at both ends by less than ten bands (a 0.5 m block turned 1 degree: 9
 * bands); at their deepest points those edges made a third of the energy scale at rest.
 * Drums laid a few mm off each other rest on rim edges that cross the other drum's side at
 * one end only, a few bands beyond, their other end their own vertex inside: the signature of
 * the edge lying along o's edge. Such an end counts too where the edge crosses that plane
 * steeply (its depth below it changes by RD_EDGE_STEEP bands or more along the edge: 185 for
 * 12-sided drums' rims, 5-7 for the YADE column's edges that lie along each other) and the edge
 * rests on o as the scene was built (at_rest: while settling, or with `model settle off` at the
 * pair's first contact step); an edge that starts bearing later, as the bodies move, still bears
 * at its deepest point (without the rest test the YADE stack at KS 2e10 and 0.3 g made 1.03e-3
 * of its scale; with a rest test by the pair's touch speed during the run, the ladder's 10-drum
 * column kept 1.9e-4 that did not fall with the step, and its 4-drum column walked 4.2 mm).
 * An end spring whose end leaves o while its last stretch is more than two steps of its point's
 * normal speed has left by a jump of its point (the envelope's pieces changed under it), not by
 * the bodies' motion: its stored energy is released and booked as friction (end_jumped), where
 * returned to the bodies as a spring opening by itself it went missing from the balance (0.35 J
 * in one step for a block turned 0.3 degrees rocking at 0.5 g).
 * No dashpot acts on edge subcontacts and bonds never form on them; their spring energy is in
 * the balance (rd_edge_elastic_energy).
 * Cost: the depths of t's vertices below o's planes come from contact.c's side of t (rd_sim.
 * cv_dist, already found) where t carries points; an edge wholly beyond one side of o's box is
 * skipped first (where o's planes fit one mask word, one that may_bear's mask tests reject
 * instead: both ends held, or both beyond one plane, two word operations; on a drum column these
 * are 32 of the 48 edges of each side, and the other 16 are rejected by may_bear's part test
 * before any box test, so no box code is found; none of them ever bears).
 * Folder engine/ owns the simulation (bodies, contacts, stepping, monitors); it may call base/,
 * geometry/, records/ and scenario/ (validate, copy, free), never io/ or cli/.
 */
#include "engine/sim.h"
#include "engine/law.h"
#include "engine/workers.h"
#include "base/vec.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>

/* slopes of a plane's depth along an edge below this fraction of the contact band are level
 * (round-off of a 1 m body is 1e-16 m; 1e-9 of the 1 mm band is 1e-12 m) */
#define RD_EDGE_FLAT       1e-9
/* an edge crosses o's plane at an end of its part inside o when it runs on beyond that plane by
 * at least this many contact bands (plateau) */
#define RD_EDGE_CROSS      10.0
/* ... or, at both ends, by at least this many bands: neither end is then held by the edge's own
 * vertex (a vertex within the band of o bears as a vertex subcontact) (plateau) */
#define RD_EDGE_CROSS_BOTH 1.0
/* ... or, at one end, by at least RD_EDGE_CROSS_BOTH bands through a plane that the edge
 * crosses steeply: its depth below that plane changes by this many bands along the edge, while
 * the edge rests on o (at_rest) (plateau) */
#define RD_EDGE_STEEP      20.0
/* an end spring whose last stretch exceeds this many steps of its point's normal speed when its
 * end leaves o has left by a jump of the point, not by the bodies' motion (end_jumped) */
#define RD_EDGE_JUMP       2.0
/* most vertices and edges of a non-convex body (a mesh) whose edges are tested: each side step
 * touches every vertex of the edges' body (a 128-sided drum has 256 and 384); a convex body's are
 * tested whatever its size */
#define RD_EDGE_MAX_VERTS  512
#define RD_EDGE_MAX_EDGES  1024
/* farthest_out's answer when no plane: the vertex lies within the band of o */
#define RD_PLANE_NONE      INT_MAX
/* rd_sim.eon's bits: the slot bears (or holds its set, below); it has not unloaded since its
   onset (its first unloading takes the joint's impact loss); it is an end of the edge's part
   inside the other body (plateau; area A'/2), not its deepest point */
#define RD_EDGE_ON         1
#define RD_EDGE_VIRGIN     2
#define RD_EDGE_END        4
/* a vertex's box outcode not yet found (outcodes use 6 bits) */
#define RD_EDGE_NO_CODE    0xFF

/* Edges of a convex polyhedron, each once: face f's side (a, b) with a < b. */
int rd_edge_count(const rd_poly *p)
{
    int n = 0;
    for (int f = 0; f < p->nf; f++) n += p->flen[f];
    return n / 2;
}

/* Every body's edges, each once (face f's side from vertex a to b, taken where a < b), in the
 * order of the edge subcontact slots. */
/* edge.c's scratch (rd_edge_init), in one block: a side's edge lines and envelope over the other
 * body's planes (np_max), vinfo's arrays over the edges' body's vertices, the candidate edges. */
struct rd_edge_scratch {
    double *c, *sl, *u0;               /* [np_max] edge_lines, envelope */
    int *k;                            /* [np_max] envelope */
    uint64_t *word;                    /* [nv] vinfo */
    double *d;                         /* [nv] */
    int *out, *vk;                     /* [nv] */
    unsigned char *code, *sure, *done; /* [nv] */
    int *cand;                         /* [ne] rd_edge_side's candidate edges */
};

/* rd_sim.edge_scratch, for the most planes (rd_sim.np_max) and the most vertices and edges of a
 * body whose edges are tested (any convex body; a mesh within RD_EDGE_MAX_VERTS and
 * RD_EDGE_MAX_EDGES); NULL (memory). */
struct rd_edge_scratch *rd_edge_scratch_new(const rd_sim *s)
{
    size_t np = s->np_max > 0 ? (size_t)s->np_max : 1, nv = 1, ne = 1;
    for (int i = 0; i < s->nb; i++) {
        const size_t v = (size_t)s->poly[i].nv, e = (size_t)(s->edge_v0[i + 1] - s->edge_v0[i]);
        const int tested = s->convex[i] || (v <= RD_EDGE_MAX_VERTS && e <= RD_EDGE_MAX_EDGES);
        if (tested && v > nv) nv = v;
        if (tested && e > ne) ne = e;
    }
    const size_t words = 3 * np + (np + 1) / 2 + 2 * nv + nv + (3 * nv + 7) / 8 + (ne + 1) / 2;
    struct rd_edge_scratch *es = calloc(1, sizeof *es + words * sizeof(double));
    if (!es) return NULL;
    /* the struct, then its arrays, each a whole number of 8-byte words */
    double *w = (double *)(es + 1);
    es->c = w;
    es->sl = es->c + np;
    es->u0 = es->sl + np;
    es->word = (uint64_t *)(es->u0 + np);
    es->d = (double *)(es->word + nv);
    es->out = (int *)(es->d + nv);
    es->vk = es->out + nv;
    es->k = es->vk + nv;
    es->cand = es->k + np;
    es->code = (unsigned char *)(es->cand + ne);
    es->sure = es->code + nv;
    es->done = es->sure + nv;
    return es;
}

int rd_edge_init(rd_sim *s, rd_error *err)
{
    int n = 0;
    for (int i = 0; i < s->nb; i++) n += rd_edge_count(&s->poly[i]);
    s->edge_v0 = malloc((size_t)(s->nb + 1) * sizeof *s->edge_v0);
    s->edge_v = malloc((size_t)(n > 0 ? n : 1) * sizeof *s->edge_v);
    if (!s->edge_v0 || !s->edge_v) return rd_error_set(err, "out of memory");
    n = 0;
    for (int i = 0; i < s->nb; i++) {
        const rd_poly *p = &s->poly[i];
        s->edge_v0[i] = n;
        for (int f = 0; f < p->nf; f++) {
            const int *ix = p->fidx + p->fstart[f];
            for (int k = 0, a = ix[p->flen[f] - 1]; k < p->flen[f]; a = ix[k++])
                if (a < ix[k]) {
                    s->edge_v[n][0] = a;
                    s->edge_v[n][1] = ix[k];
                    n++;
                }
        }
    }
    s->edge_v0[s->nb] = n;
    s->edge_scratch = rd_edge_scratch_new(s);
    return s->edge_scratch ? 0 : rd_error_set(err, "out of memory");
}

/* Signed distance of world point x to plane k of body o (> 0 outside), m. */
static double dist(const rd_sim *s, int o, int k, const double x[3])
{
    int j = s->face0[o] + k;
    return rd_dot(s->wn[j], x) - s->wd[j];
}

/* Where x lies against o's box: one bit per side it is beyond (0: inside the box). */
static unsigned outcode(const double box[6], const double x[3])
{
    unsigned code = 0;
    for (int c = 0; c < 3; c++)
        code |= (unsigned)(x[c] < box[c]) << c | (unsigned)(x[c] > box[3 + c]) << (3 + c);
    return code;
}

/* An edge spring's point q (world, m) with depth gradient g: its offsets ro, rt from the owner's
 * and the other body's centres, the owner's velocity against the other's there (vr, m/s) and
 * the unit normal n = g / |g|; returns |g|. g is 0 at the kink of an edge that runs through o
 * across two opposite faces at equal and opposite slopes (a body driven into a thin slab
 * deeper than the slab: its depth, half the slab's chord, does not change as the edge moves):
 * then n = 0, the spring bears nothing (-fn g) and its Coulomb cap fn |g| tan(phi) = 0 lets
 * its shear go as slip; g / |g| made the state NaN and the run "unstable" where it was
 * "penetrated" (a 0.5 m cube at 30 m/s into a free 0.2 m wall at KN 1e6). */
static double edge_point(const rd_sim *s, const rd_side *sd, const double q[3], const double g[3],
                         double ro[3], double rt[3], double vr[3], double n[3])
{
    const int o = sd->owner, t = sd->other;
    double gn = rd_norm(g);
    for (int i = 0; i < 3; i++) {
        ro[i] = q[i] - s->x[o][i];
        rt[i] = q[i] - s->x[t][i];
        n[i] = gn > 0 ? g[i] / gn : 0.0;
    }
    rd_law_relative_velocity(s, o, t, ro, rt, vr);
    return gn;
}

/* The slot stops bearing: its spring energy is released into friction (3DEC drops the forces
 * of a contact that ends). Where its deepest point q (world, m) and depth gradient g are known
 * (its spring has come back to zero stretch, s_now = 0; or, release_deep, it is let go at its
 * stretch s_now, m), the springs are let go at mid-step as a vertex subcontact's (law.h,
 * rd_law_release_energy): the normal one between its last and present stretch, the shear one
 * taken through half the step's displacement at q under its last Coulomb limit (its last
 * stretch's force along g times tan_phi, as edge_force). Else (q NULL: the edge has left o's
 * box in one step) their stored energy. */
static void edge_release(rd_sim *s, const rd_side *sd, const rd_joint *j, int e, const double *q,
                         const double *g, double s_now)
{
    if (!s->eon[e]) return;
    const double A = rd_edge_slot_area(s, sd, e), kA = j->kn * A, sA = j->ks * A,
                 tan_phi = j->tan_phi;
    if (q) {
        double ro[3], rt[3], vr[3], n[3], gn = edge_point(s, sd, q, g, ro, rt, vr, n);
        double lim = kA * s->edepth[e][0] * gn * tan_phi;
        rd_book_fric(s, rd_law_release_energy(kA, s_now > 0 ? s->edepth[e][0] : 0.0, s_now, 0,
                                              s->efs[e], n, vr, rd_dot(vr, n), sA, lim, s->dt));
    } else {
        rd_book_fric(
            s, 0.5 * (kA * s->edepth[e][0] * s->edepth[e][0] + rd_dot(s->efs[e], s->efs[e]) / sA));
    }
    s->efs[e][0] = s->efs[e][1] = s->efs[e][2] = 0;
    s->edepth[e][0] = s->edepth[e][1] = s->edepth[e][2] = 0;
    s->eon[e] = 0;
}

/* One edge of t against o: plane k's depth along it is c[k] + sl[k] u, m (< 0: beyond k). */
typedef struct edge_lines {
    double *c, *sl; /* [np] (rd_edge_scratch) */
    int np;
} edge_lines;

/* The lines of edge a-b; da, db: the ends' distances to o's planes when already found, else
 * NULL. */
static void lines(const rd_sim *s, int o, const double *a, const double *b, const double *da,
                  const double *db, edge_lines *L)
{
    L->np = s->poly[o].nf;
    for (int k = 0; k < L->np; k++) {
        double xa = da ? da[k] : dist(s, o, k, a), xb = db ? db[k] : dist(s, o, k, b);
        L->c[k] = -xa;
        L->sl[k] = xa - xb;
    }
}

/* The deepest point of the edge inside o: position u along it, depth d (m), and the gradient g
 * of d (see the header). */
typedef struct deep {
    double u, d, g[3];
} deep;

/* The plane of L active at u = 0: the nearest, the least rising of ties. */
static int first_plane(const edge_lines *L)
{
    const double *c = L->c, *sl = L->sl;
    int act = 0;
    for (int k = 1; k < L->np; k++)
        if (c[k] < c[act] || (c[k] == c[act] && sl[k] < sl[act])) act = k;
    return act;
}

/* The breakpoint after active plane act: the first plane of smaller slope to cross it, at u =
 * gap / rate (*un; compared as cross products: rates are positive); -1 (*un = INFINITY) when
 * none. */
static int next_plane(const edge_lines *L, int act, double *un)
{
    const double *c = L->c, *sl = L->sl;
    double gn = 1, rn = 0;
    int next = -1;
    for (int k = 0; k < L->np; k++) {
        double rate = sl[act] - sl[k];
        if (!(rate > 0)) continue;
        double gap = c[k] - c[act], lhs = gap * rn, rhs = gn * rate;
        if (next < 0 || lhs < rhs || (lhs == rhs && sl[k] < sl[next])) {
            gn = gap;
            rn = rate;
            next = k;
        }
    }
    *un = next >= 0 ? gn / rn : INFINITY;
    return next;
}

static void deepest(const rd_sim *s, int o, const edge_lines *L, double flat, deep *dp)
{
    const double(*n)[3] = s->wn + s->face0[o];
    const double *c = L->c, *sl = L->sl;
    int act = first_plane(L), prev = -1;
    double u = 0;
    for (;;) {
        if (sl[act] < -flat) { /* falling: the maximum is here */
            dp->u = u;
            dp->d = c[act] + sl[act] * u;
            if (prev < 0) {
                rd_copy3(n[act], dp->g);
                return;
            }
            double sp = sl[prev], sm = sl[act];
            for (int i = 0; i < 3; i++) dp->g[i] = (sp * n[act][i] - sm * n[prev][i]) / (sp - sm);
            return;
        }
        double un;
        int next = next_plane(L, act, &un);
        if (sl[act] <= flat) { /* level: the middle of the level part */
            dp->u = 0.5 * (u + fmin(un, 1.0));
            dp->d = c[act] + sl[act] * dp->u;
            rd_copy3(n[act], dp->g);
            return;
        }
        if (next < 0 || un >= 1) { /* rising to the end b */
            dp->u = 1;
            dp->d = c[act] + sl[act];
            rd_copy3(n[act], dp->g);
            return;
        }
        prev = act;
        act = next;
        u = fmax(u, un);
    }
}

/* The lower envelope of an edge's depth lines: piece i is plane k[i], active from u0[i] to the
 * next piece's u0 (the last one to u = 1). Each next piece's line is less steep, so a plane
 * comes at most once. */
typedef struct envelope {
    int n;
    int *k;     /* [np] (rd_edge_scratch) */
    double *u0; /* [np] */
} envelope;

static void walk(const edge_lines *L, envelope *E)
{
    int act = first_plane(L);
    double u = 0;
    E->n = 0;
    for (;;) {
        E->k[E->n] = act;
        E->u0[E->n++] = u;
        double un;
        int next = next_plane(L, act, &un);
        if (next < 0 || un >= 1 || E->n == L->np) return;
        act = next;
        u = fmax(u, un);
    }
}

/* The two ends of an edge's bearing part, where the other body carries no points (a fixed
 * pedestal's edge in a block's base): the piece of the envelope at its deepest point whose
 * line is the more level of the two there (the plane the edge lies on: the block's base), and
 * its two ends, each a spring as 3DEC's corners of the polygon where the faces overlap. An end
 * of the edge has that plane's normal as its depth gradient; a kink with a piece sloping the
 * other way (an edge across a ridge) the kink's (see the header), bounded by both normals; a
 * kink with a steeper piece sloping the same way (the side of the block the edge runs out
 * through) the plane's normal, the kink's gradient there being ill-conditioned when the two
 * slopes come close (its error is the ratio of the slopes, 0 for an edge across a side). A
 * level edge in the face thus bears at both ends, not at its middle: the depth's largest point
 * jumped from end to end as it tilted by a hair, a kink in the potential at the rest pose, and
 * the shaken slab on a smaller pad that bore on those points made energy (0.8 of its energy
 * scale in 3 s at 0.6 g). Returns whether the edge crosses o there: its bearing piece is level
 * within the contact band tol (m) over the edge, and at one end of it at least the edge leaves
 * o through a plane beyond which its own end lies RD_EDGE_CROSS bands or more, or at both ends
 * RD_EDGE_CROSS_BOTH bands or more (1); or, at one end, RD_EDGE_CROSS_BOTH bands or more beyond a
 * plane it crosses steeply (RD_EDGE_STEEP) (2: the caller's crossing only while the edge rests
 * on o, at_rest); else 0. */
static int plateau(const rd_sim *s, int o, const edge_lines *L, double tol, deep end[2])
{
    int crossing = 0;
    const double(*n)[3] = s->wn + s->face0[o];
    envelope E = { .k = s->edge_scratch->k, .u0 = s->edge_scratch->u0 };
    walk(L, &E);
    int top = 0; /* the first falling piece: the deepest point is its start */
    while (top < E.n && !(L->sl[E.k[top]] < 0)) top++;
    int p = top == E.n                                           ? E.n - 1
            : top == 0                                           ? 0
            : fabs(L->sl[E.k[top - 1]]) <= fabs(L->sl[E.k[top]]) ? top - 1
                                                                 : top;
    const int kp = E.k[p];
    const double sp = L->sl[kp];
    int both = 1, steep = 0;
    for (int j = 0; j < 2; j++) {
        int m = j ? (p + 1 < E.n ? p + 1 : -1) : p - 1; /* the neighbouring piece at this end */
        deep *d = &end[j];
        d->u = j ? (m >= 0 ? E.u0[m] : 1.0) : E.u0[p];
        d->d = L->c[kp] + sp * d->u;
        double sm = m >= 0 ? L->sl[E.k[m]] : 0;
        double over = m >= 0 ? -(L->c[E.k[m]] + L->sl[E.k[m]] * j) : -INFINITY;
        crossing |= over >= RD_EDGE_CROSS * tol;
        both &= over >= RD_EDGE_CROSS_BOTH * tol;
        steep |= over >= RD_EDGE_CROSS_BOTH * tol && m >= 0 &&
                 fabs(L->sl[E.k[m]]) >= RD_EDGE_STEEP * tol;
        if (m >= 0 && sp * sm < 0) {
            const double *nm = n[E.k[m]];
            for (int i = 0; i < 3; i++) d->g[i] = (sp * nm[i] - sm * n[kp][i]) / (sp - sm);
        } else {
            rd_copy3(n[kp], d->g);
        }
    }
    if (!(fabs(sp) <= tol)) return 0;
    return crossing || both ? 1 : steep ? 2 : 0;
}

/* The point q at u along edge a-b (world, m): a + u (b - a). */
static void along(const double *a, const double *b, double u, double q[3])
{
    for (int c = 0; c < 3; c++) q[c] = a[c] + u * (b[c] - a[c]);
}

/* Force of edge slot e at world point q: the normal spring fn = kA * stretch against the depth
 * gradient g, and the Coulomb shear on the plane normal to g. */
static int edge_force(rd_sim *s, const rd_side *sd, const rd_joint *j, int e, const double q[3],
                      const double g[3], double stretch, double kA, double sA)
{
    const int o = sd->owner, t = sd->other;
    double ro[3], rt[3], vr[3], n[3], gn = edge_point(s, sd, q, g, ro, rt, vr, n);
    double *fs = s->efs[e], fn = kA * stretch;
    double *e_fric = &s->e_pair[0]; /* the slip's friction energy: the pair's sum */
    int slips = rd_law_shear(fs, n, vr, rd_dot(vr, n), sA, s->dt, fn * gn * j->tan_phi, e_fric);
    double F[3] = { -fn * g[0] + fs[0], -fn * g[1] + fs[1], -fn * g[2] + fs[2] };
    if (s->tape)
        rd_book_apply(s, F, ro, rt, o, !s->fixed[t], t);
    else
        rd_law_apply(F, ro, rt, s->f[o], s->tq[o], !s->fixed[t], s->f[t], s->tq[t]);
    s->edepth[e][0] = stretch;
    return slips;
}

/* Per vertex of t, found once per side and step when an edge needs it: its distances to o's
 * planes (rd_sim.cv_dist of t's side where t carries points, else NULL: found with dist()),
 * and its depth inside o below its nearest plane (< 0 outside: minus its distance beyond the
 * plane it is most beyond) and that plane. */
typedef struct vinfo {
    const double *dist;
    const uint64_t *mask;  /* rd_sim.cv_mask of t's side, with dist */
    const int *slot;       /* t's vertices' rows in dist and mask (rd_sim.cv_slot; -1: none) */
    int np, nw;            /* o's planes, and the mask words they use */
    double tol;            /* the contact band, m */
    const double (*wv)[3]; /* t's world vertices */
    const rd_sim *s;
    int o;         /* the owner, whose box the outcodes test */
    int box_found; /* box holds o's box (found when the first outcode needs it) */
    double box[6]; /* o's box, grown by the broad phase's margin */
    /* per vertex of t (rd_edge_scratch) */
    unsigned char *code; /* against box (outcode), once found (RD_EDGE_NO_CODE before) */
    unsigned char *sure; /* against o's loose box (rd_pairs_box_loose): its bits are a subset of
                            code's */
    unsigned char *done;
    int *out;       /* vertex_out's answer, once found (-2 before) */
    uint64_t *word; /* its mask word, where o's planes fit one (vertex_word) */
    int *k;
    double *d;
} vinfo;

/* The plane of o that the vertex with distances row and mask words mk (nw of them) lies
 * farthest beyond, among those it lies beyond by more than the contact band (contact.c's masks);
 * RD_PLANE_NONE when none (it lies within the band of o: a vertex subcontact holds it). */
static inline int farthest_out(const double *row, const uint64_t *mk, int nw)
{
    int q = RD_PLANE_NONE;
    for (int w = 0; w < nw; w++)
        for (uint64_t m = mk[w]; m; m &= m - 1) {
            int k = 64 * w + __builtin_ctzll(m);
            if (q == RD_PLANE_NONE || row[k] > row[q]) q = k;
        }
    return q;
}

/* farthest_out of t's vertex v, once per side; -1 when not known (no masks). */
static int vertex_out(vinfo *vi, int v)
{
    if (vi->out[v] != -2) return vi->out[v];
    vi->out[v] = -1;
    if (!vi->mask) return -1;
    int slot = vi->slot[v];
    if (slot < 0) return -1;
    vi->out[v] = farthest_out(vi->dist + (size_t)slot * (size_t)vi->np,
                              vi->mask + (size_t)slot * 2 * (size_t)vi->nw, vi->nw);
    return vi->out[v];
}

/* t's vertex v's mask word (o's planes in one word, t with masks) into vinfo.word, and its
 * vertex_out; returns 0 when v has none (not a vertex of t's candidate faces). may_bear's first
 * tests then read two words: an edge whose ends are both held (both words 0), or both beyond
 * one plane by more than the band (a common bit), cannot start. */
static int vertex_word(vinfo *vi, int v)
{
    int slot = vi->slot[v];
    if (slot < 0) return 0;
    vi->word[v] = vi->mask[(size_t)slot * 2 * (size_t)vi->nw];
    vi->out[v] = farthest_out(vi->dist + (size_t)slot * (size_t)vi->np, &vi->word[v], 1);
    return 1;
}

/* t's vertex v against o's box (outcode), found once per side when a test needs it; o's box too
 * (an edge side whose edges the loose box's codes all reject, a block's on its base, never finds
 * it). */
static unsigned vertex_code(vinfo *vi, int v)
{
    if (vi->code[v] != RD_EDGE_NO_CODE) return vi->code[v];
    if (!vi->box_found) {
        rd_pairs_box_now(vi->s, vi->o, vi->box);
        vi->box_found = 1;
    }
    vi->code[v] = (unsigned char)outcode(vi->box, vi->wv[v]);
    return vi->code[v];
}

/* Every vertex of t against o's loose box (rd_pairs_box_loose, no hull vertex transformed): an
 * edge whose ends share a bit there has both ends beyond one side of o's box. */
static void sure_codes(vinfo *vi, int nv)
{
    double loose[6];
    rd_pairs_box_loose(vi->s, vi->o, loose);
    for (int v = 0; v < nv; v++) vi->sure[v] = (unsigned char)outcode(loose, vi->wv[v]);
}

/* Whether t's vertices va and vb (both with masks) lie beyond one plane of o by more than the
 * band: the whole edge does. */
static int beyond_one(const vinfo *vi, int va, int vb)
{
    const uint64_t *ma = vi->mask + (size_t)vi->slot[va] * 2 * (size_t)vi->nw;
    const uint64_t *mb = vi->mask + (size_t)vi->slot[vb] * 2 * (size_t)vi->nw;
    for (int w = 0; w < vi->nw; w++)
        if (ma[w] & mb[w]) return 1;
    return 0;
}

static const double *vertex_row(const vinfo *vi, int v)
{
    if (!vi->dist) return NULL;
    int slot = vi->slot[v];
    return slot < 0 ? NULL : vi->dist + (size_t)slot * (size_t)vi->np;
}

/* Distance of t's vertex v to o's plane k, m. */
static double vertex_dist(const rd_sim *s, int o, int t, const vinfo *vi, int v, int k)
{
    const double *row = vertex_row(vi, v);
    return row ? row[k] : dist(s, o, k, s->wv[s->vert0[t] + v]);
}

static void vertex_depth(const rd_sim *s, int o, int t, vinfo *vi, int v)
{
    if (vi->done[v]) return;
    const double *row = vertex_row(vi, v), *x = s->wv[s->vert0[t] + v];
    double dmax = -INFINITY;
    int kmax = 0;
    if (row) {
        for (int k = 0; k < vi->np; k++)
            if (row[k] > dmax) {
                dmax = row[k];
                kmax = k;
            }
    } else {
        for (int k = 0; k < vi->np; k++) {
            double e = dist(s, o, k, x);
            if (e > dmax) {
                dmax = e;
                kmax = k;
            }
        }
    }
    vi->d[v] = -dmax;
    vi->k[v] = kmax;
    vi->done[v] = 1;
}

/* Whether edge (va, vb) may bear, from bounds that need no walk. The depth along the edge is at
 * most that below any one plane, a line; so when the depth below an end's nearest plane stays
 * at most `floor` along the edge (the deeper end's depth, at least 0, where the ends are
 * points; 0 otherwise), or the smaller of the two ends' nearest planes' lines does, it cannot
 * exceed floor. Each test only rejects, so their order leaves the answer alone: the box test
 * comes after the tests on points' masks and rows, which reject a drum's edges first (their
 * ends' box codes are then never needed). */
static int may_bear(const rd_sim *s, int o, int t, vinfo *vi, int va, int vb, int t_points)
{
    if (t_points) {
        /* ends within the contact band bear as vertex subcontacts (contact.c): an edge between
           two of them is held by them; so is one whose part inside o lies within the band of
           its held end (it leaves o through plane q, which its other end lies beyond), or whose
           depth falls from its held end along q's line (q is that end's nearest plane) */
        int qa = vertex_out(vi, va), qb = vertex_out(vi, vb);
        if (qa == RD_PLANE_NONE && qb == RD_PLANE_NONE) return 0;
        if (qa >= 0 && qb >= 0 && qa < RD_PLANE_NONE && qb < RD_PLANE_NONE &&
            beyond_one(vi, va, vb))
            return 0;
        int in = qa == RD_PLANE_NONE ? va : qb == RD_PLANE_NONE ? vb : -1;
        int q = in == va ? qb : qa;
        if (in >= 0 && q >= 0) {
            const double *ri = vertex_row(vi, in), *ro = vertex_row(vi, in == va ? vb : va);
            const double *xa = s->wv[s->vert0[t] + va], *xb = s->wv[s->vert0[t] + vb];
            double ab[3] = { xb[0] - xa[0], xb[1] - xa[1], xb[2] - xa[2] };
            double din = -ri[q], dout = -ro[q]; /* depths below q: dout < -band */
            double part = din > 0 ? din : 0,
                   span = vi->tol * (din - dout);                      /* length * part / span */
            if (rd_dot(ab, ab) * part * part <= span * span) return 0; /* the part inside, <= tol */
            int nearest = 1;
            for (int k = 0; k < vi->np; k++) nearest &= ri[k] <= ri[q];
            if (nearest) return 0;
        }
    }
    if (vertex_code(vi, va) & vertex_code(vi, vb)) return 0; /* both beyond one side of o's box */
    int ends[2] = { va, vb };
    for (int i = 0; i < 2; i++) { /* an end in o's box: its nearest plane's line */
        int x = ends[i], y = ends[1 - i];
        if (vertex_code(vi, x)) continue;
        vertex_depth(s, o, t, vi, x);
        double dx = vi->d[x], lb = t_points && dx > 0 ? dx : 0; /* at most floor */
        if (dx <= lb && -vertex_dist(s, o, t, vi, y, vi->k[x]) <= lb) return 0;
    }
    vertex_depth(s, o, t, vi, va);
    vertex_depth(s, o, t, vi, vb);
    int ka = vi->k[va], kb = vi->k[vb];
    double da = vi->d[va], db = vi->d[vb], floor = t_points ? (da > db ? da : db) : 0;
    floor = floor > 0 ? floor : 0;
    /* one plane nearest at both ends: the depth is at most its line, deepest at an end */
    if (ka == kb) return (da > db ? da : db) > floor;
    /* min of plane ka's line (da at a, c1 at b) and plane kb's (c2 at a, db at b) */
    double a1 = da, b1 = -vertex_dist(s, o, t, vi, vb, ka), a2 = -vertex_dist(s, o, t, vi, va, kb),
           b2 = db;
    double s1 = b1 - a1, s2 = b2 - a2, top;
    if (s1 <= 0)
        top = a1 < a2 ? a1 : a2; /* the first falls from a */
    else if (s2 >= 0)
        top = b1 < b2 ? b1 : b2; /* the second rises to b */
    else {
        double u = (a2 - a1) / (s1 - s2);
        u = u < 0 ? 0 : u > 1 ? 1 : u;
        top = a1 + s1 * u;
    }
    return top > floor;
}

/* Whether an edge spring that starts at point q (world, m) with depth gradient g strikes: its
 * depth grows at vr . g / |g| (vr: the owner's velocity against the other body's at q), faster
 * than the pair's touch speed. */
static int impact(const rd_sim *s, const rd_pair *pr, const rd_side *sd, const double q[3],
                  const double g[3])
{
    double ro[3], rt[3], vr[3], n[3], gn = edge_point(s, sd, q, g, ro, rt, vr, n);
    return gn > 0 && rd_dot(vr, g) / gn > rd_law_touch_speed(s, pr);
}

/* Does edge a-b rest on o as the scene was built: the bodies are settling, or (`model settle
 * off`) the pair has not borne yet and both ends of its part inside o (end) move relative to o
 * slower than gravity's speed in one step, g dt? An edge that starts bearing later, as the
 * bodies move, does not (drums rocking on each other, equal blocks sliding). */
static int at_rest(const rd_sim *s, const rd_pair *pr, const rd_side *sd, const double *a,
                   const double *b, const deep end[2])
{
    if (s->settling) return 1;
    if (pr->k_active > 0) return 0;
    const double vt = s->sc.gravity * s->dt;
    for (int k = 0; k < 2; k++) {
        double q[3], ro[3], rt[3], vr[3], n[3];
        along(a, b, end[k].u, q);
        edge_point(s, sd, q, end[k].g, ro, rt, vr, n);
        if (!(rd_norm(vr) < vt)) return 0;
    }
    return 1;
}

/* Has end slot e, whose end now lies outside o at q (depth gradient g), left by a jump of its
 * point rather than by the bodies' motion? Its last stretch is more than RD_EDGE_JUMP steps of
 * the point's normal speed: the pieces of the edge's envelope changed under it. Its spring's
 * stored energy is then released (edge_release without q: booked as friction), not returned to
 * the bodies as a spring that opens by itself (that return is the work its force did, which a
 * jump does not do). */
static int end_jumped(const rd_sim *s, const rd_side *sd, int e, const double q[3],
                      const double g[3])
{
    double ro[3], rt[3], vr[3], n[3];
    edge_point(s, sd, q, g, ro, rt, vr, n);
    return s->edepth[e][0] > RD_EDGE_JUMP * fabs(rd_dot(vr, n)) * s->dt;
}

/* Slot e's spring at point dp of edge a-b (world): it starts once dp lies deeper than floor,
 * from depth d0 (its set), bears while stretched and is let go at zero stretch. Its area A'
 * (m^2) joins the monitor's tally w (may be NULL) while it bears, as a vertex subcontact's.
 * held (an end spring of plateau, d0 = 0): a touch that is an impact (its depth grows faster than
 * the pair's touch speed, rd_law_touch_speed) takes the joint's impact loss at its first
 * unloading as a vertex subcontact does (contact.c): a permanent set (1 - e) times its stretch,
 * the drop of the scheme's spring energy 1/2 KN A' set (s(n) + s(n-1) - set) booked as damping;
 * it then holds the set, idle while shallower, until the edge leaves o (d <= 0), so a block
 * rocking on a smaller pedestal's edges lands on them as on its own corners. A quasi-static
 * touch stays elastic: a pedestal's edge lying in the side of a block of its own footprint
 * comes and goes at a depth of round-off about a thousand times a second, and a set at each
 * moved the block's slide over it by 0.09 mm (tests/cli/edge_slide.sh). */
static void edge_spring(rd_sim *s, const rd_pair *pr, const rd_side *sd, const rd_joint *j, int e,
                        const double *a, const double *b, const deep *dp, double floor, double d0,
                        double A, rd_watch *w, int held)
{
    double kA = j->kn * A, sA = j->ks * A;
    int fresh = !s->eon[e];
    double q[3];
    along(a, b, dp->u, q);
    if (fresh) {
        if (!(dp->d > floor)) return;
        s->eon[e] = held ? RD_EDGE_ON | RD_EDGE_END : RD_EDGE_ON;
        s->edepth[e][1] = d0;
        if (held && impact(s, pr, sd, q, dp->g)) s->eon[e] |= RD_EDGE_VIRGIN;
    }
    double stretch = dp->d - s->edepth[e][1];
    if (!(held ? dp->d > 0 : stretch > 0) && !fresh) {
        edge_release(s, sd, j, e, held && end_jumped(s, sd, e, q, dp->g) ? NULL : q, dp->g, 0.0);
        return;
    }
    const double last = s->edepth[e][0]; /* the stretch it bore last step (0: none) */
    if ((s->eon[e] & RD_EDGE_VIRGIN) && last > 0 && stretch < last && !s->settling) {
        double set = stretch > 0 ? (1.0 - j->restitution) * stretch : 0.0;
        rd_book_damp(s, 0.5 * kA * set * (stretch + last - set));
        s->edepth[e][1] += set;
        stretch -= set;
        s->eon[e] &= (unsigned char)~RD_EDGE_VIRGIN;
    }
    int slips = edge_force(s, sd, j, e, q, dp->g, stretch > 0 ? stretch : 0, kA, sA);
    s->edepth[e][2] = dp->u;
    if (w && stretch > 0) { /* (booked on a thread's view: workers.h) */
        rd_book(s, &w->area, A);
        rd_count(s, &w->nactive, 1);
        rd_count(s, &w->nslip, slips);
        if (s->shaking) __atomic_store_n(&w->touched, 1, __ATOMIC_RELAXED);
    }
}

/* Edge e's two end springs (ends: their points along edge a-b) let go once an end lies deeper
 * than the contact band: no longer a resting contact, its ends can jump along the edge as the
 * envelope's pieces come and go. Their springs are released at their stretch now (booked as
 * friction, edge_release), and the edge bears at its deepest point from there. */
static void release_deep(rd_sim *s, const rd_side *sd, const rd_joint *j, int e, const double *a,
                         const double *b, const deep end[2])
{
    for (int k = 0; k < RD_EDGE_SLOTS; k++) {
        double q[3];
        along(a, b, end[k].u, q);
        edge_release(s, sd, j, e + k, q, end[k].g, end[k].d - s->edepth[e + k][1]);
    }
}

void rd_edge_side(rd_sim *s, const rd_pair *pr, rd_side *sd, const double *dist,
                  const uint64_t *mask)
{
    if (sd->nedge == 0) return;
    const int o = sd->owner, t = sd->other;
    /* a fixed t's edges stay where they were, and o's loose box until it is built again: edges
       that all lay beyond one of its sides (none bearing) still do, and nothing is to be done */
    if (s->fixed[t] && sd->edges_clear == s->box_builds[o] + 1) return;
    const rd_poly *pt = &s->poly[t];
    if (!s->convex[t] && (pt->nv > RD_EDGE_MAX_VERTS || sd->nedge > RD_EDGE_MAX_EDGES)) return;
    struct rd_edge_scratch *es = s->edge_scratch;
    const rd_joint *j = &s->joint[pr->joint];
    const int ends = RD_EDGE_SLOTS;
    const double A = sd->weight * sd->edge_area; /* an edge's spring area A', m^2 */
    double flat = RD_EDGE_FLAT * RD_CONTACT_BAND * fmin(s->poly[o].radius, pt->radius);
    int t_points = pr->nside == 2; /* t's vertices are subcontact points against o */
    vinfo vi;
    vi.dist = dist;
    vi.mask = mask;
    vi.slot = s->cv_slot + s->vert0[t];
    vi.code = es->code;
    vi.sure = es->sure;
    vi.done = es->done;
    vi.out = es->out;
    vi.word = es->word;
    vi.k = es->vk;
    vi.d = es->d;
    vi.tol = RD_CONTACT_BAND * fmin(s->poly[o].radius, pt->radius);
    vi.np = s->poly[o].nf;
    vi.nw = (vi.np + 63) / 64;
    vi.wv = s->wv + s->vert0[t];
    vi.s = s;
    vi.o = o;
    vi.box_found = 0;
    int held = t_points && mask && vi.nw == 1; /* every vertex's mask word known (vertex_word) */
    for (int v = 0; v < pt->nv; v++) {
        vi.code[v] = RD_EDGE_NO_CODE;
        vi.done[v] = 0;
        vi.out[v] = -2;
        if (held) held = vertex_word(&vi, v);
    }
    if (!held) sure_codes(&vi, pt->nv);
    edge_lines L = { .c = es->c, .sl = es->sl };
    rd_watch *w = rd_monitor_contact_watch(s, o, t);
    const int(*ev)[2] = s->edge_v + s->edge_v0[t];
    const unsigned char *on = s->eon + sd->edge0;
    int *cand = es->cand, nc = 0, clear = !held;
    for (int i = 0; i < sd->nedge; i++) { /* bearing, or not settled by may_bear's mask tests (with
                                             masks; else not wholly beyond one side of o's box) */
        const int a = ev[i][0], b = ev[i][1];
        const int loose_out = !held && (vi.sure[a] & vi.sure[b]);
        int keep = held ? (vi.word[a] | vi.word[b]) && !(vi.word[a] & vi.word[b])
                        : !loose_out && !(vertex_code(&vi, a) & vertex_code(&vi, b));
        int bears = on[ends * i] | on[ends * i + 1];
        cand[nc] = i;
        nc += (bears != 0) | keep;
        clear &= loose_out && !bears;
    }
    sd->edges_clear = clear && s->fixed[t] ? s->box_builds[o] + 1 : 0;
    for (int c = 0; c < nc; c++) {
        int i = cand[c], e = sd->edge0 + ends * i, va = ev[i][0], vb = ev[i][1];
        int bears = s->eon[e] | s->eon[e + 1];
        if (bears ? (vertex_code(&vi, va) & vertex_code(&vi, vb)) != 0
                  : !may_bear(s, o, t, &vi, va, vb, t_points)) {
            for (int k = 0; k < ends; k++) /* bearing: wholly beyond one side of o's box; else:
                                              cannot start */
                edge_release(s, sd, j, e + k, NULL, NULL, 0.0);
            continue;
        }
        const double *a = s->wv[s->vert0[t] + va], *b = s->wv[s->vert0[t] + vb];
        lines(s, o, a, b, vertex_row(&vi, va), vertex_row(&vi, vb), &L);
        /* its two ends bear (as 3DEC's corners of the faces' overlap) while they lie within the
           contact band, where t carries no points or the edge crosses o (plateau); any other
           edge at its deepest point (may_bear has found both ends' depths where nothing bore) */
        deep end[2];
        int cross = !bears || (bears & RD_EDGE_END) ? plateau(s, o, &L, vi.tol, end) : 0;
        if (cross == 2) cross = t_points && !bears && at_rest(s, pr, sd, a, b, end);
        int two = bears ? (bears & RD_EDGE_END) != 0 : !t_points || cross;
        if (t_points && two && (end[0].d > vi.tol || end[1].d > vi.tol)) {
            if (bears) release_deep(s, sd, j, e, a, b, end);
            two = 0;
            vertex_depth(s, o, t, &vi,
                         va); /* the deepest point's floor (may_bear found none for a */
            vertex_depth(s, o, t, &vi, vb); /* bearing edge) */
        }
        if (!two) {
            /* onset where the edge lies deeper than both ends: the spring starts from here */
            deep dp;
            deepest(s, o, &L, flat, &dp);
            double floor = vi.d[va] > vi.d[vb] ? vi.d[va] : vi.d[vb];
            edge_spring(s, pr, sd, j, e, a, b, &dp, floor > 0 ? floor : 0, dp.d, A, w, 0);
        } else {
            /* each end of the bearing part from its entry into o (from depth 0 where t is fixed,
               from where it starts where t is free) */
            for (int k = 0; k < 2; k++)
                edge_spring(s, pr, sd, j, e + k, a, b, &end[k], 0, t_points ? end[k].d : 0, 0.5 * A,
                            w, 1);
        }
    }
}

/* Slot e's spring area of side sd, m^2: A' (the weighted mean point area of the owner), or
 * half of it at an end of the edge's part inside the other body. */
double rd_edge_slot_area(const rd_sim *s, const rd_side *sd, int e)
{
    return sd->weight * sd->edge_area * ((s->eon[e] & RD_EDGE_END) ? 0.5 : 1.0);
}

void rd_edge_seat(rd_sim *s)
{
    for (int e = 0; e < s->nedge_state; e++) s->eon[e] &= (unsigned char)~RD_EDGE_VIRGIN;
}

void rd_edge_reset(rd_sim *s, const rd_side *sd)
{
    for (int e = sd->edge0; e < sd->edge0 + RD_EDGE_SLOTS * sd->nedge; e++) {
        s->efs[e][0] = s->efs[e][1] = s->efs[e][2] = 0;
        s->edepth[e][0] = s->edepth[e][1] = s->edepth[e][2] = 0;
        s->eon[e] = 0;
    }
}

double rd_edge_elastic_energy(const rd_sim *s, const rd_pair *pr, const rd_side *sd)
{
    const rd_joint *j = &s->joint[pr->joint];
    double en = 0;
    for (int e = sd->edge0; e < sd->edge0 + RD_EDGE_SLOTS * sd->nedge; e++)
        if (s->eon[e]) {
            double A = rd_edge_slot_area(s, sd, e), kA = j->kn * A, sA = j->ks * A;
            en +=
                0.5 * (kA * s->edepth[e][0] * s->edepth[e][0] + rd_dot(s->efs[e], s->efs[e]) / sA);
        }
    return en;
}
