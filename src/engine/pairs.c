/* rockdem — broad phase and the contact-pair cache.
 *
 * Each step the axis-aligned bounding boxes of the bodies (grown by a margin) are swept along
 * one axis (sort-and-sweep: insertion sort of the nearly sorted order, then a linear sweep), so
 * the cost grows with the number of bodies, not their square; scenes of a few bodies test all
 * pairs directly. A pair that overlaps for the first time gets a slot found again through a
 * hash map keyed by (a, b); its per-point history is appended to growable arrays, so memory
 * is allocated only when two bodies meet for the first time, never in a steady step. A pair
 * whose boxes separate forgets its history (3DEC: a re-created contact starts from zero).
 * Folder engine/ owns the simulation (bodies, contacts, stepping, monitors); it may call base/,
 * geometry/, records/ and scenario/ (validate, copy, free), never io/ or cli/.
 */
#include "engine/sim.h"
#include "base/constants.h"
#include "base/vec.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define RD_BRUTE_MAX 8 /* up to this many bodies, test every pair directly */

static unsigned hash_pair(int a, int b) { return (unsigned)a * 2654435761u ^ (unsigned)b * 40503u; }

static int hash_find(const rd_sim *s, int a, int b)
{
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
    s->hkey = k; s->hcap = cap;
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
    *arr = a; *cap = c;
    return 0;
}

/* New slot for bodies a < b (they can touch); -1 without memory. */
static int pair_create(rd_sim *s, int a, int b)
{
    /* a body's points are tested against the other body only if that one is convex */
    int pa = s->pt0[a + 1] > s->pt0[a] && s->convex[b], pb = s->pt0[b + 1] > s->pt0[b] && s->convex[a];
    int ns = (pa ? s->pt0[a + 1] - s->pt0[a] : 0) + (pb ? s->pt0[b + 1] - s->pt0[b] : 0);
    int nf = (pa ? s->cf0[a + 1] - s->cf0[a] : 0) + (pb ? s->cf0[b + 1] - s->cf0[b] : 0);
    if ((s->npair + 1) * 2 > s->hcap && hash_grow(s)) return -1;
    if (reserve((void **)&s->pair, &s->cap_pair, s->npair + 1, sizeof *s->pair) ||
        reserve((void **)&s->fs, &s->cap_state, s->nstate + ns, sizeof *s->fs) ||
        reserve((void **)&s->face_nactive, &s->cap_face_state, s->nface_state + nf, sizeof *s->face_nactive))
        return -1;
    /* edge subcontacts: the other body's edges, where both bodies are convex and the other one
       carries no points (a fixed pedestal; edge.c says why not between two free bodies) */
    int ea = pa && !pb && s->convex[a] ? rd_edge_count(&s->poly[b]) : 0;
    int eb = pb && !pa && s->convex[b] ? rd_edge_count(&s->poly[a]) : 0;
    if (reserve((void **)&s->efs, &s->cap_efs, s->nedge_state + ea + eb, sizeof *s->efs) ||
        reserve((void **)&s->edepth, &s->cap_edepth, s->nedge_state + ea + eb, sizeof *s->edepth) ||
        reserve((void **)&s->eon, &s->cap_eon, s->nedge_state + ea + eb, sizeof *s->eon))
        return -1;
    int cap = s->cap_state_flags;
    if (reserve((void **)&s->pstate, &cap, s->nstate + ns, sizeof *s->pstate) ||
        reserve((void **)&s->pface, &s->cap_pface, s->nstate + ns, sizeof *s->pface) ||
        reserve((void **)&s->pset, &s->cap_pset, s->nstate + ns, sizeof *s->pset))
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
    pr->a = a; pr->b = b; pr->seen = -1; pr->joint = joint;
    double w = (pa && pb) ? 0.5 : 1.0;
    for (int k = 0; k < 2; k++) {
        int o = k ? b : a;
        if (!(k ? pb : pa)) continue;
        rd_side *sd = &pr->side[pr->nside++];
        sd->owner = o; sd->other = k ? a : b; sd->weight = w;
        sd->state0 = s->nstate; sd->face0 = s->nface_state;
        s->nstate += s->pt0[o + 1] - s->pt0[o];
        s->nface_state += s->cf0[o + 1] - s->cf0[o];
        sd->edge0 = s->nedge_state; sd->nedge = k ? eb : ea;
        s->nedge_state += sd->nedge;
        double area = 0;
        int npt = 0; /* points before merging (merge.c) */
        for (int q = s->pt0[o]; q < s->pt0[o + 1]; q++) { area += s->pa[q]; npt += s->pmult[q]; }
        sd->edge_area = area / npt;
    }
    /* bonds (cohesion, tension) exist only in joints closed before shaking starts */
    const rd_joint *jt = &s->joint[joint];
    unsigned char init = ((jt->cohesion > 0 || jt->tension > 0) && !s->shaking) ? RD_PT_BONDED : 0;
    for (int k = s->nstate - ns; k < s->nstate; k++) s->pstate[k] = init;
    pr->m_eff = s->fixed[a] ? s->mass[b] : s->fixed[b] ? s->mass[a]
                            : s->mass[a] * s->mass[b] / (s->mass[a] + s->mass[b]);
    unsigned mask = (unsigned)s->hcap - 1, h = hash_pair(a, b) & mask;
    while (s->hkey[h] >= 0) h = (h + 1) & mask;
    s->hkey[h] = p;
    return p;
}

/* Bounding box of body i (its hull vertices, refreshed each step as step vertices), grown by the
 * margin. */
static void body_box(rd_sim *s, int i)
{
    double *bx = s->aabb[i];
    bx[0] = bx[1] = bx[2] = INFINITY;
    bx[3] = bx[4] = bx[5] = -INFINITY;
    for (int e = s->hv0[i]; e < s->hv0[i + 1]; e++)
        for (int k = 0, v = s->hv[e]; k < 3; k++) {
            bx[k] = rd_min(bx[k], s->wv[v][k]);
            bx[k + 3] = rd_max(bx[k + 3], s->wv[v][k]);
        }
    for (int k = 0; k < 3; k++) { bx[k] -= s->margin; bx[k + 3] += s->margin; }
}

static int boxes_overlap(const double *p, const double *q)
{
    return p[0] <= q[3] && q[0] <= p[3] && p[1] <= q[4] && q[1] <= p[4] && p[2] <= q[5] && q[2] <= p[5];
}

/* Mark pair (i, j) live this step, creating it on first contact. 0, or -1 out of memory. */
static int touch(rd_sim *s, int i, int j)
{
    if (s->fixed[i] && s->fixed[j]) return 0;
    int a = i < j ? i : j, b = i < j ? j : i;
    int p = hash_find(s, a, b);
    if (p < 0) {
        int pa = s->pt0[a + 1] > s->pt0[a] && s->convex[b], pb = s->pt0[b + 1] > s->pt0[b] && s->convex[a];
        if (!pa && !pb) return 0; /* cannot touch (e.g. two meshes: not modelled) */
        if ((p = pair_create(s, a, b)) < 0) return -1;
    }
    s->pair[p].seen = s->stamp;
    s->live[s->nlive++] = p;
    return 0;
}

static int sweep(rd_sim *s)
{
    int ax = s->sweep_axis, n = s->nb, *o = s->order;
    for (int i = 1; i < n; i++) /* insertion sort: the order barely changes between steps */
        for (int j = i; j > 0 && s->aabb[o[j]][ax] < s->aabb[o[j - 1]][ax]; j--) {
            int t = o[j]; o[j] = o[j - 1]; o[j - 1] = t;
        }
    for (int i = 0; i < n; i++)
        for (int j = i + 1; j < n && s->aabb[o[j]][ax] <= s->aabb[o[i]][ax + 3]; j++)
            if (boxes_overlap(s->aabb[o[i]], s->aabb[o[j]]) && touch(s, o[i], o[j])) return -1;
    return 0;
}

int rd_pairs_update(rd_sim *s)
{
    s->stamp++;
    for (int i = 0; i < s->nb; i++)
        if (!s->fixed[i] || s->stamp == 1) body_box(s, i);
    /* the live list can hold every pair that overlaps: at most all pairs seen so far + n^2 new */
    int maxlive = s->nb <= RD_BRUTE_MAX ? s->nb * s->nb : s->npair + 8 * s->nb;
    if (reserve((void **)&s->live, &s->cap_live, maxlive, sizeof *s->live)) return -1;
    s->nlive = 0;
    if (s->nb <= RD_BRUTE_MAX) {
        for (int i = 0; i < s->nb; i++)
            for (int j = i + 1; j < s->nb; j++)
                if (boxes_overlap(s->aabb[i], s->aabb[j]) && touch(s, i, j)) return -1;
    } else if (sweep(s)) {
        return -1;
    }
    return 0;
}

int rd_pairs_init(rd_sim *s, rd_error *err)
{
    s->order = malloc((size_t)s->nb * sizeof *s->order);
    s->aabb = calloc((size_t)s->nb, sizeof *s->aabb);
    if (!s->order || !s->aabb || hash_grow(s)) return rd_error_set(err, "out of memory");
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY}, rmin = INFINITY;
    for (int i = 0; i < s->nb; i++) {
        s->order[i] = i;
        rmin = rd_min(rmin, s->poly[i].radius);
        for (int k = 0; k < 3; k++) { lo[k] = rd_min(lo[k], s->x[i][k]); hi[k] = rd_max(hi[k], s->x[i][k]); }
    }
    s->sweep_axis = 0; /* sweep along the axis the bodies spread most (a column: z) */
    for (int k = 1; k < 3; k++)
        if (hi[k] - lo[k] > hi[s->sweep_axis] - lo[s->sweep_axis]) s->sweep_axis = k;
    s->margin = RD_BROAD_MARGIN * rmin; /* boxes meet a little before the bodies do */
    return 0;
}
