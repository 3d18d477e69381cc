/* rockdem — broad phase and the contact-pair cache.
 *
 * A pair is live in a step when the axis-aligned bounding boxes of the two bodies' hull
 * vertices, grown by a margin, overlap in that step's pose. The boxes are swept along one axis
 * (sort-and-sweep: insertion sort of the nearly sorted order, then a linear sweep), so the cost
 * grows with the number of bodies, not their square; scenes of a few bodies test all pairs
 * directly.
 * Boxes within their margin: a scene of a few bodies does not rebuild a box every step. Each
 * body keeps the box of its last build and the pose it was built in; each step bounds how far
 * any hull vertex can have moved since (box_drift, d), and a pair whose boxes certainly overlap
 * or certainly part, even with each box moved by its d, is decided without rebuilding. Only an
 * uncertain pair rebuilds its two boxes (d = 0: the exact test), and a body whose d exceeds the
 * margin rebuilds at once, so certain decisions stay the rule. The live set is therefore the
 * one exact boxes rebuilt every step give, bit for bit: no pair is found later (pair_live says
 * why). A mesh body's hull (727 of the shipped PBR's 1,986 vertices) is transformed only when
 * its box is rebuilt. A scene swept along an axis rebuilds every moving box each step, since
 * the live list's order follows the exact boxes' order and sets the order of the force sums.
 * Found before a point bears: a subcontact point lies in its body's hull and bears only within
 * the contact band of the other (convex) body, tol = RD_CONTACT_BAND min(r_a, r_b) beyond its
 * planes (plus a bond's slack T / KN), so the two hull boxes lie within about tol of each other
 * (sqrt(3) tol at a right-angled corner), while each is grown by margin = RD_BROAD_MARGIN r_min:
 * the grown boxes overlap before a point can bear while the pair's smaller body is at most 57
 * times the smallest body's radius (2 RD_BROAD_MARGIN >= sqrt(3) RD_CONTACT_BAND x 57) and a
 * bond's slack stays below the margin.
 * tests/test_broadphase.c checks that a vertex within the band of another body has its pair
 * live. A pair that overlaps for the first time gets a slot found again through a hash map
 * keyed by (a, b); its per-point history is appended to growable arrays, so memory is allocated
 * only when two bodies meet for the first time, never in a steady step. A pair whose boxes
 * separate forgets its history (3DEC: a re-created contact starts from zero).
 * Folder engine/ owns the simulation (bodies, contacts, stepping, monitors); it may call base/,
 * geometry/, records/ and scenario/ (validate, copy, free), never io/ or cli/.
 */
#include "engine/sim.h"
#include "engine/workers.h"
#include "base/assert.h"
#include "base/constants.h"
#include "base/vec.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#define RD_BRUTE_MAX 8 /* up to this many bodies, test every pair directly */

static unsigned hash_pair(int a, int b) { return (unsigned)a * 2654435761u ^ (unsigned)b * 40503u; }

static int hash_find(const rd_sim *s, int a, int b)
{
    RD_ASSERT(a < b && s->hcap > 0 && (s->hcap & (s->hcap - 1)) == 0);
    unsigned mask = (unsigned)s->hcap - 1;
    for (unsigned h = hash_pair(a, b) & mask;; h = (h + 1) & mask) {
        int p = s->hkey[h];
        if (p < 0) return -1;
        if (s->pair[p].a == a && s->pair[p].b == b) return p;
    }
}

static int hash_grow(rd_sim *s)
{
    int cap = s->hcap ? 2 * s->hcap : 64;
    int *k = malloc((size_t)cap * sizeof *k);
    if (!k) return -1;
    for (int i = 0; i < cap; i++) k[i] = -1;
    free(s->hkey);
    s->hkey = k;
    s->hcap = cap;
    for (int p = 0; p < s->npair; p++) {
        unsigned mask = (unsigned)cap - 1, h = hash_pair(s->pair[p].a, s->pair[p].b) & mask;
        while (k[h] >= 0) h = (h + 1) & mask;
        k[h] = p;
    }
    return 0;
}

/* Grow an array of `size`-byte items to hold at least n. */
static int reserve(void **arr, int *cap, int n, size_t size)
{
    if (n <= *cap) return 0;
    int c = *cap ? *cap : 16;
    while (c < n) c *= 2;
    void *a = realloc(*arr, (size_t)c * size);
    if (!a) return -1;
    memset((char *)a + (size_t)*cap * size, 0, (size_t)(c - *cap) * size);
    *arr = a;
    *cap = c;
    return 0;
}

/* Does body o lie on body t with every face it lies on within t's, in their current poses? 1
 * when some face of o lies on a face of t (antiparallel normals, every vertex within tol of t's
 * plane) and every vertex of every such face lies within tol of t's planes or inside them. */
static int faces_within(const rd_sim *s, int o, int t)
{
    const rd_poly *po = &s->poly[o], *pt = &s->poly[t];
    const double tol = RD_FACE_TOL * (1.0 + fmax(po->radius, pt->radius));
    const double(*wn)[3] = s->wn + s->face0[t];
    const double *wd = s->wd + s->face0[t];
    int lies = 0;
    const double(*v)[3] = s->wv + s->vert0[o];
    for (int f = 0; f < po->nf; f++) {
        const int *ix = po->fidx + po->fstart[f];
        for (int g = 0; g < pt->nf; g++) {
            if (!rd_face_lies_on(s, o, f, t, g, tol)) continue;
            lies = 1;
            for (int k = 0; k < po->flen[f]; k++)
                for (int h = 0; h < pt->nf; h++)
                    if (rd_dot(wn[h], v[ix[k]]) - wd[h] > tol) return 0;
        }
    }
    return lies;
}

/* New slot for bodies a < b (they can touch); -1 without memory. */
static int pair_create(rd_sim *s, int a, int b)
{
    /* a body's points are tested against the other body only if that one is convex */
    int pa = s->pt0[a + 1] > s->pt0[a] && s->convex[b],
        pb = s->pt0[b + 1] > s->pt0[b] && s->convex[a];
    /* Where two free bodies both carry points, each set integrates its own face over the
       joint and the two at half weight carry the shared area (3DEC's averaging), when both
       faces cover it. A body lying on the other within that one's face (a statue on a wider
       pedestal) covers the joint with its own points, while the wider face's points lie
       outside it: with vertex subcontacts none of them bore and the joint had half its KN and
       KS; with a bed, those under the statue bore, its area only to within the bed's spacing (a
       0.45 m statue on a 1 m pedestal's 11 x 11 bed: 1.23 times it). Such a pair is
       one-sided: the contained body's points at full weight, the other's edges bearing on it
       as a pedestal's do (edge.c), the fixed pedestal's model with both bodies free. Decided
       when the pair is made (as built, for bodies placed on each other); bodies that meet
       later keep both sets. */
    if (pa && pb) {
        int wa = faces_within(s, a, b), wb = faces_within(s, b, a);
        if (wa && !wb)
            pb = 0;
        else if (wb && !wa)
            pa = 0;
    }
    int ns = (pa ? s->pt0[a + 1] - s->pt0[a] : 0) + (pb ? s->pt0[b + 1] - s->pt0[b] : 0);
    int nf = (pa ? s->cf0[a + 1] - s->cf0[a] : 0) + (pb ? s->cf0[b + 1] - s->cf0[b] : 0);
    if ((s->npair + 1) * 2 > s->hcap && hash_grow(s)) return -1;
    if (reserve((void **)&s->pair, &s->cap_pair, s->npair + 1, sizeof *s->pair) ||
        reserve((void **)&s->fs, &s->cap_state, s->nstate + ns, sizeof *s->fs) ||
        reserve((void **)&s->face_nactive, &s->cap_face_state, s->nface_state + nf,
                sizeof *s->face_nactive))
        return -1;
    /* edge subcontacts (edge.c): the other body's edges, where both bodies are convex */
    const int ends = RD_EDGE_SLOTS;
    int ea = pa && s->convex[a] ? rd_edge_count(&s->poly[b]) : 0;
    int eb = pb && s->convex[b] ? rd_edge_count(&s->poly[a]) : 0;
    int nslot = ends * (ea + eb);
    if (reserve((void **)&s->efs, &s->cap_efs, s->nedge_state + nslot, sizeof *s->efs) ||
        reserve((void **)&s->edepth, &s->cap_edepth, s->nedge_state + nslot, sizeof *s->edepth) ||
        reserve((void **)&s->eon, &s->cap_eon, s->nedge_state + nslot, sizeof *s->eon))
        return -1;
    int cap = s->cap_state_flags;
    if (reserve((void **)&s->pstate, &cap, s->nstate + ns, sizeof *s->pstate) ||
        reserve((void **)&s->pface, &s->cap_pface, s->nstate + ns, sizeof *s->pface) ||
        reserve((void **)&s->pset, &s->cap_pset, s->nstate + ns, sizeof *s->pset) ||
        reserve((void **)&s->pstrike, &s->cap_pstrike, s->nstate + ns, sizeof *s->pstrike))
        return -1;
    s->cap_state_flags = cap;
    cap = s->cap_state_joint;
    if (reserve((void **)&s->pj, &cap, s->nstate + ns, sizeof *s->pj)) return -1;
    s->cap_state_joint = cap;
    int joint = rd_joint_resolve(s, a, b);
    if (joint < 0) return -1;
    int p = s->npair++;
    rd_pair *pr = &s->pair[p];
    memset(pr, 0, sizeof *pr);
    pr->a = a;
    pr->b = b;
    pr->seen = -1;
    pr->joint = joint;
    double w = (pa && pb) ? 0.5 : 1.0;
    for (int k = 0; k < 2; k++) {
        int o = k ? b : a;
        if (!(k ? pb : pa)) continue;
        rd_side *sd = &pr->side[pr->nside++];
        sd->owner = o;
        sd->other = k ? a : b;
        sd->weight = w;
        sd->state0 = s->nstate;
        sd->face0 = s->nface_state;
        s->nstate += s->pt0[o + 1] - s->pt0[o];
        s->nface_state += s->cf0[o + 1] - s->cf0[o];
        sd->edge0 = s->nedge_state;
        sd->nedge = k ? eb : ea;
        s->nedge_state += ends * sd->nedge;
        double area = 0;
        int npt = 0; /* points before merging (merge.c) */
        for (int q = s->pt0[o]; q < s->pt0[o + 1]; q++) {
            area += s->pa[q];
            npt += s->pmult[q];
        }
        sd->edge_area = area / npt;
    }
    /* bonds (cohesion, tension) exist only in joints closed before shaking starts */
    const rd_joint *jt = &s->joint[joint];
    unsigned char init = ((jt->cohesion > 0 || jt->tension > 0) && !s->shaking) ? RD_PT_BONDED : 0;
    for (int k = s->nstate - ns; k < s->nstate; k++) s->pstate[k] = init;
    pr->m_eff = s->fixed[a]   ? s->mass[b]
                : s->fixed[b] ? s->mass[a]
                              : s->mass[a] * s->mass[b] / (s->mass[a] + s->mass[b]);
    unsigned mask = (unsigned)s->hcap - 1, h = hash_pair(a, b) & mask;
    while (s->hkey[h] >= 0) h = (h + 1) & mask;
    s->hkey[h] = p;
    return p;
}

/* A box's drift bound carries this relative allowance for round-off: the world vertices
 * (R v + x), the box's min and max and the tests' sums are each within a few ulp (1e-16
 * relative) of exact; 1e-12 of the coordinates' size covers them many times over and is far
 * below any margin (5 % of a body's radius). */
#define RD_BOX_ROUNDOFF 1e-12

/* World position of vertex v of body i in its current pose (rd_body_refresh's expression). */
static void vertex_now(const rd_sim *s, int i, int v, double w[3])
{
    rd_mat_vec(s->R[i], s->poly[i].v[v - s->vert0[i]], w);
    rd_axpy(1.0, s->x[i], w);
}

/* Box of body i's hull vertices in its current pose, grown by the margin, m. A free non-convex
 * body's step leaves its hull vertices alone (integrate.c): their positions are found here, and
 * stored into store (rd_sim.wv) unless it is NULL. */
static void hull_box(const rd_sim *s, int i, double (*store)[3], double bx[6])
{
    int stale = !s->convex[i] && !s->fixed[i];
    double b[6] = { INFINITY, INFINITY, INFINITY, -INFINITY, -INFINITY, -INFINITY }; /* a local: the
                                                       stores into store cannot alias it */
    for (int e = s->hv0[i]; e < s->hv0[i + 1]; e++) {
        int v = s->hv[e];
        double now[3];
        const double *w = s->wv[v];
        if (stale) {
            double *to = store ? store[v] : now;
            vertex_now(s, i, v, to);
            w = to;
        }
        for (int k = 0; k < 3; k++) {
            b[k] = rd_min(b[k], w[k]);
            b[k + 3] = rd_max(b[k + 3], w[k]);
        }
    }
    for (int k = 0; k < 3; k++) {
        bx[k] = b[k] - s->margin;
        bx[k + 3] = b[k + 3] + s->margin;
    }
}

/* Rebuild body i's box in its current pose. */
static void box_build(rd_sim *s, int i)
{
    hull_box(s, i, s->wv, s->aabb[i]);
    rd_copy3(s->x[i], s->box_pose[i]);
    for (int k = 0; k < 4; k++) s->box_pose[i][3 + k] = s->q[i][k];
    s->box_drift[i] = 0;
    s->box_builds[i]++;
}

/* Bound on the distance any hull vertex of body i moved since its box was built, m (NaN: never
 * built). A vertex at r (body frame, |r| <= rho) is at x + R r: it moved by at most
 * |x - x0| + |R - R0| rho, and for unit quaternions |R - R0| = 2 sin(theta / 2) <=
 * 2 min(|q - q0|, |q + q0|) (theta the rotation between the poses; |q - q0| = 2 sin(theta / 4)
 * when q . q0 >= 0). Both poses unchanged bit for bit: 0. */
static double box_drift(const rd_sim *s, int i) { return rd_pairs_drift(s, i, s->box_pose[i]); }

/* Bound on the distance any hull vertex of body i (so any of its vertices) moved since it was at
 * pose p (position, quaternion), m; see box_drift. */
double rd_pairs_drift(const rd_sim *s, int i, const double p[7])
{
    double dx2 = 0, dm2 = 0, dp2 = 0, x2 = 0, x02 = 0;
    for (int k = 0; k < 3; k++) {
        double d = s->x[i][k] - p[k];
        dx2 += d * d;
        x2 += s->x[i][k] * s->x[i][k];
        x02 += p[k] * p[k];
    }
    for (int k = 0; k < 4; k++) {
        double m = s->q[i][k] - p[3 + k], a = s->q[i][k] + p[3 + k];
        dm2 += m * m;
        dp2 += a * a;
    }
    if (dx2 == 0 && dm2 == 0) return 0; /* NaN (never built) fails this test */
    double rho = s->box_rho[i];
    return sqrt(dx2) + 2.0 * rho * sqrt(rd_min(dm2, dp2)) +
           RD_BOX_ROUNDOFF * (sqrt(x2) + sqrt(x02) + rho);
}

/* Body i's box (hull vertices grown by the margin) in its current pose, m: the stored one when
 * it is exact this step, else computed as box_build would (the same expression, the same bits).
 * For users of the box between broad-phase updates (edge subcontacts, the off-support overturn
 * criterion). */
void rd_pairs_box_now(const rd_sim *s, int i, double bx[6])
{
    if (s->box_drift[i] == 0) {
        memcpy(bx, s->aabb[i], 6 * sizeof *bx);
        return;
    }
    hull_box(s, i, NULL, bx);
}

/* Body i's stored box grown by the margin, m: the exact box (rd_pairs_box_now) lies within the
 * stored box grown by the drift (pair_live's bound), which rd_pairs_update holds at most the
 * margin, so a point beyond one of its sides lies beyond that side of the exact box too. Found
 * without the hull vertices, and the same until the box is built again (rd_sim.box_builds). */
void rd_pairs_box_loose(const rd_sim *s, int i, double bx[6])
{
    for (int k = 0; k < 3; k++) {
        bx[k] = s->aabb[i][k] - s->margin;
        bx[k + 3] = s->aabb[i][k + 3] + s->margin;
    }
}

static int boxes_overlap(const double *p, const double *q)
{
    return p[0] <= q[3] && q[0] <= p[3] && p[1] <= q[4] && q[1] <= p[4] && p[2] <= q[5] &&
           q[2] <= p[5];
}

/* Do the exact boxes of bodies i and j overlap this step? Each exact box B (its hull vertices
 * now, grown by the margin) lies within the stored box S grown by the drift d, and contains S
 * shrunk by d (the vertex that set each face of S moved at most d): B.lo in [S.lo - d, S.lo + d],
 * B.hi in [S.hi - d, S.hi + d]. So the boxes certainly overlap when, on every axis,
 * S_i.lo + d_i <= S_j.hi - d_j and S_j.lo + d_j <= S_i.hi - d_i, and certainly part when on some
 * axis S_i.lo - d_i > S_j.hi + d_j or S_j.lo - d_j > S_i.hi + d_i (the floating-point sums are
 * within RD_BOX_ROUNDOFF, included in d, of the exact ones). Otherwise both boxes are rebuilt
 * and tested exactly. The answer is always the exact boxes' overlap, as if rebuilt every step. */
static int pair_live(rd_sim *s, int i, int j)
{
    const double *p = s->aabb[i], *q = s->aabb[j];
    double d = s->box_drift[i] + s->box_drift[j];
    if (d == 0) return boxes_overlap(p, q);
    int sure = 1;
    for (int k = 0; k < 3; k++) {
        if (p[k] - d > q[k + 3] || q[k] - d > p[k + 3]) return 0;
        sure = sure && p[k] + d <= q[k + 3] && q[k] + d <= p[k + 3];
    }
    if (sure) return 1;
    if (s->box_drift[i] != 0) box_build(s, i);
    if (s->box_drift[j] != 0) box_build(s, j);
    return boxes_overlap(s->aabb[i], s->aabb[j]);
}

/* Bodies a and b within reach of each other, neither with points the vertex model can test
 * against the other (two non-convex bodies, or a body with no subcontact points against a
 * non-convex one): the vertex model cannot make their contact, and carrying on would let one
 * fall through the other. The run stops with an error (status error, one line); 0. */
static int unmodelled(rd_sim *s, int a, int b)
{
    if (s->status != RD_STATUS_DONE) return 0; /* the first error stands */
    snprintf(s->errmsg, sizeof s->errmsg,
             "blocks '%s' and '%s' are within reach of each other at t = %.6g s, and the vertex "
             "contact model cannot touch them (its subcontact points bear only on a convex body, "
             "and neither is convex with points on the other): give 'contact model surface' "
             "(docs/CONTACT.md section 8.5)",
             s->sc.bodies[a].name, s->sc.bodies[b].name, s->t);
    s->status = RD_STATUS_ERROR;
    return 0;
}

/* Mark pair (a < b) live this step, p its slot (hash_find's answer), creating it on first
 * contact. 0, or -1 out of memory. */
static int touch_found(rd_sim *s, int a, int b, int p)
{
    if (p < 0) {
        int pa = s->pt0[a + 1] > s->pt0[a] && s->convex[b],
            pb = s->pt0[b + 1] > s->pt0[b] && s->convex[a];
        /* the surface model takes any pair (surface.c: a non-convex body's planes against a
           convex partner, a rock on a terrain mesh; two meshes face against face), with no
           subcontact points; the vertex model cannot touch two meshes */
        if (!pa && !pb && s->sc.contact.model != RD_CONTACT_SURFACE) return unmodelled(s, a, b);
        if ((p = pair_create(s, a, b)) < 0) return -1;
    }
    s->pair[p].seen = s->stamp;
    s->live[s->nlive++] = p;
    return 0;
}

/* Mark pair (i, j) live this step, creating it on first contact. 0, or -1 out of memory. */
static int touch(rd_sim *s, int i, int j)
{
    if (s->fixed[i] && s->fixed[j]) return 0;
    int a = i < j ? i : j, b = i < j ? j : i;
    return touch_found(s, a, b, hash_find(s, a, b));
}

/* Body i's drift since its box was built, and the box rebuilt when the drift passes the margin
 * or, in a swept scene, when the body moved at all. */
static void box_update(rd_sim *s, int i, int sweeping)
{
    double d = box_drift(s, i); /* 0 for a body that has not moved (a fixed one) */
    s->box_drift[i] = d;
    if (!(d <= s->margin) || (sweeping && d > 0)) box_build(s, i);
}

static void sort_order(rd_sim *s)
{
    int ax = s->sweep_axis, n = s->nb, *o = s->order;
    for (int i = 1; i < n; i++) /* insertion sort: the order barely changes between steps */
        for (int j = i; j > 0 && s->aabb[o[j]][ax] < s->aabb[o[j - 1]][ax]; j--) {
            int t = o[j];
            o[j] = o[j - 1];
            o[j - 1] = t;
        }
}

static int sweep(rd_sim *s)
{
    int ax = s->sweep_axis, n = s->nb, *o = s->order;
    sort_order(s);
    for (int i = 0; i < n; i++)
        for (int j = i + 1; j < n && s->aabb[o[j]][ax] <= s->aabb[o[i]][ax + 3]; j++)
            if (boxes_overlap(s->aabb[o[i]], s->aabb[o[j]]) && touch(s, o[i], o[j])) return -1;
    return 0;
}

#ifdef _OPENMP
/* One pair a threaded sweep found overlapping: bodies a < b, p their slot or -1 (new). */
typedef struct rd_sweep_hit {
    int a, b, p;
} rd_sweep_hit;

/* One thread's finds, in the serial sweep's order; on cache lines of its own. */
typedef struct rd_sweep_part {
    _Alignas(RD_CACHE_LINE) rd_sweep_hit *hit;
    int n, cap;
    int failed; /* 1: out of memory growing hit */
} rd_sweep_part;

static void part_add(rd_sweep_part *pt, int a, int b, int p)
{
    if (pt->n == pt->cap && reserve((void **)&pt->hit, &pt->cap, pt->n + 1, sizeof *pt->hit)) {
        pt->failed = 1;
        return;
    }
    pt->hit[pt->n++] = (rd_sweep_hit){ a, b, p };
}

/* The sweep over bodies order[i0 .. i1) of the sorted order: each overlap's slot looked up
 * (the hash map and the pairs only read) and a known pair marked seen (each pair is found once
 * a sweep, so by one thread), into pt. */
static void sweep_part(rd_sim *s, int i0, int i1, rd_sweep_part *pt)
{
    int ax = s->sweep_axis, n = s->nb, *o = s->order;
    pt->n = 0;
    pt->failed = 0;
    for (int i = i0; i < i1; i++)
        for (int j = i + 1; j < n && s->aabb[o[j]][ax] <= s->aabb[o[i]][ax + 3]; j++) {
            int u = o[i], w = o[j];
            if (!boxes_overlap(s->aabb[u], s->aabb[w]) || (s->fixed[u] && s->fixed[w])) continue;
            int a = u < w ? u : w, b = u < w ? w : u, p = hash_find(s, a, b);
            if (p >= 0) s->pair[p].seen = s->stamp;
            part_add(pt, a, b, p);
        }
}

/* The box updates and the sweep on nt threads, in one team: the boxes (each body's its own),
 * the sort on one thread, then the sorted order split into one range of bodies per thread,
 * each thread's finds in sweep order; the finds are then appended to the live list thread by
 * thread and the new pairs made in that order (the serial sweep's live list and slots, bit for
 * bit). */
static int sweep_threaded(rd_sim *s, int nt)
{
    if (!s->sweep_part) {
        s->sweep_part = aligned_alloc(RD_CACHE_LINE, RD_THREADS_MAX * sizeof *s->sweep_part);
        if (!s->sweep_part) return -1;
        memset(s->sweep_part, 0, RD_THREADS_MAX * sizeof *s->sweep_part);
    }
    const int n = s->nb;
    int team = 1;
    RD_OMP(omp parallel num_threads(nt))
    {
        RD_OMP(omp for schedule(static))
        for (int i = 0; i < n; i++) box_update(s, i, 1);
        RD_OMP(omp single)
        sort_order(s);
        const int t = omp_get_thread_num(), k = omp_get_num_threads();
        if (t == 0) team = k;
        sweep_part(s, (int)((long)n * t / k), (int)((long)n * (t + 1) / k), &s->sweep_part[t]);
    }
    for (int t = 0; t < team; t++) {
        const rd_sweep_part *pt = &s->sweep_part[t];
        if (pt->failed) return -1;
        for (int h = 0; h < pt->n; h++) {
            const rd_sweep_hit *e = &pt->hit[h];
            if (e->p >= 0)
                s->live[s->nlive++] = e->p;
            else if (touch_found(s, e->a, e->b, -1))
                return -1;
        }
    }
    return 0;
}
#endif

void rd_pairs_free(rd_sim *s)
{
#ifdef _OPENMP
    for (int t = 0; s->sweep_part && t < RD_THREADS_MAX; t++) free(s->sweep_part[t].hit);
#endif
    free(s->sweep_part);
    s->sweep_part = NULL;
}

int rd_pairs_update(rd_sim *s)
{
    s->stamp++;
    int sweeping = s->nb > RD_BRUTE_MAX;
    /* the live list can hold every pair that overlaps: at most all pairs seen so far + n^2 new */
    int maxlive = s->nb <= RD_BRUTE_MAX ? s->nb * s->nb : s->npair + 8 * s->nb;
    if (reserve((void **)&s->live, &s->cap_live, maxlive, sizeof *s->live)) return -1;
    s->nlive = 0;
#ifdef _OPENMP
    const int nt = sweeping ? rd_threads_for(s, s->nb) : 1;
    if (nt > 1) return sweep_threaded(s, nt);
#endif
    for (int i = 0; i < s->nb; i++) box_update(s, i, sweeping);
    if (sweeping) return sweep(s);
    for (int i = 0; i < s->nb; i++)
        for (int j = i + 1; j < s->nb; j++)
            if (pair_live(s, i, j) && touch(s, i, j)) return -1;
    return 0;
}

int rd_pairs_init(rd_sim *s, rd_error *err)
{
    s->order = malloc((size_t)s->nb * sizeof *s->order);
    s->aabb = calloc((size_t)s->nb, sizeof *s->aabb);
    s->box_pose = malloc((size_t)s->nb * sizeof *s->box_pose);
    s->box_rho = calloc((size_t)s->nb, sizeof *s->box_rho);
    s->box_drift = calloc((size_t)s->nb, sizeof *s->box_drift);
    s->box_builds = calloc((size_t)s->nb, sizeof *s->box_builds);
    if (!s->order || !s->aabb || !s->box_pose || !s->box_rho || !s->box_drift || !s->box_builds ||
        hash_grow(s))
        return rd_error_set(err, "out of memory");
    double lo[3] = { INFINITY, INFINITY, INFINITY }, hi[3] = { -INFINITY, -INFINITY, -INFINITY },
           rmin = INFINITY;
    for (int i = 0; i < s->nb; i++) {
        for (int k = 0; k < 7; k++) s->box_pose[i][k] = NAN; /* built at the first update */
        for (int e = s->hv0[i]; e < s->hv0[i + 1]; e++)
            s->box_rho[i] = rd_max(s->box_rho[i], rd_norm(s->poly[i].v[s->hv[e] - s->vert0[i]]));
        s->order[i] = i;
        rmin = rd_min(rmin, s->poly[i].radius);
        for (int k = 0; k < 3; k++) {
            lo[k] = rd_min(lo[k], s->x[i][k]);
            hi[k] = rd_max(hi[k], s->x[i][k]);
        }
    }
    s->sweep_axis = 0; /* sweep along the axis the bodies spread most (a column: z) */
    for (int k = 1; k < 3; k++)
        if (hi[k] - lo[k] > hi[s->sweep_axis] - lo[s->sweep_axis]) s->sweep_axis = k;
    s->margin = RD_BROAD_MARGIN * rmin; /* boxes meet a little before the bodies do */
    return 0;
}
