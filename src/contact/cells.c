/* rockdem — coplanar faces merged into convex cells, once at setup (contact/contact.h).
 * A flat region of a mesh (a scanned rock's sawn base: 535 triangles in one plane) is one
 * plane of the surface model, and its patch is the sum of per-polygon integrals, all additive
 * (area moments) or summed over the union's boundary (the torsion): the same polygon cut into
 * fewer convex pieces gives the same patch to round-off at a clip and a moment sum per piece
 * instead of per triangle. Greedy merge across shared edges (Hertel and Mehlhorn's rule: two
 * convex cells sharing an edge are joined when the union is convex), every vertex kept (a
 * vertex of a straight side stays: the cells' vertices are the faces' own, to the bit).
 * Folder contact/ holds the patch geometry and its law; it may call base/ and geometry/, and is
 * called by engine/.
 */
#include "contact/contact.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* The scratch of one merge: the directed edges of the faces (vertex ids u -> v) and the face
 * that brought each; each face's cell (union-find) and each cell's slot list. */
typedef struct cells_work {
    uint64_t *key; /* u << 32 | v, 0 empty (ids are stored + 1) */
    int *owner;    /* the face that brought the edge */
    unsigned mask;
    int *parent;      /* [nface] union-find */
    int **slot, *len; /* [nface] each cell's slots, counter-clockwise (roots only) */
    int merged[2 * RD_PATCH_FACE_MAX + 2];
} cells_work;

static uint64_t edge_key(int u, int v)
{
    return ((uint64_t)(uint32_t)(u + 1) << 32) | (uint32_t)(v + 1);
}

static unsigned key_slot(const cells_work *w, uint64_t k)
{
    uint64_t h = k * 0x9E3779B97F4A7C15ULL;
    unsigned q = (unsigned)(h >> 32) & w->mask;
    while (w->key[q] != 0 && w->key[q] != k) q = (q + 1) & w->mask;
    return q;
}

static int find_root(int *parent, int f)
{
    while (parent[f] != f) f = parent[f] = parent[parent[f]];
    return f;
}

/* Is the closed polygon of slots s[0 .. n) convex and counter-clockwise (no right turn), with
 * no vertex id twice? */
static int convex_ccw(const int *s, int n, const int *vid, const double (*xy)[2])
{
    for (int k = 0; k < n; k++) {
        const double *a = xy[s[k]], *b = xy[s[(k + 1) % n]], *c = xy[s[(k + 2) % n]];
        double cr = (b[0] - a[0]) * (c[1] - b[1]) - (b[1] - a[1]) * (c[0] - b[0]);
        if (!(cr >= 0)) return 0;
        for (int j = k + 1; j < n; j++)
            if (vid[s[j]] == vid[s[k]]) return 0;
    }
    return 1;
}

/* Does A's edge t (slots t -> t + 1) run backwards along an edge of cell B? */
static int shared_with(cells_work *w, int A, int t, int B, const int *vid)
{
    const int n = w->len[A], *sa = w->slot[A];
    const int u = vid[sa[((t % n) + n) % n]], v = vid[sa[(((t + 1) % n) + n) % n]];
    unsigned q = key_slot(w, edge_key(v, u));
    return w->key[q] != 0 && find_root(w->parent, w->owner[q]) == B;
}

/* Cell A joined with cell B across the chain of edges they share that holds A's edge k (an
 * interior vertex of the chain, the last face around a vertex, drops out): A's slots from the
 * chain's end round to its start, then B's beyond the chain. Into w->merged; returns its
 * length, 0 when the union would exceed maxv or the chain is not simple. */
static int join(cells_work *w, int A, int k, int B, const int *vid, int maxv)
{
    const int na = w->len[A], nb = w->len[B], *sa = w->slot[A], *sb = w->slot[B];
    int s = k, e = k + 1, L = 1; /* the chain: A's slots s .. e (mod na), L edges */
    while (L < na && shared_with(w, A, s - 1, B, vid)) s--, L++;
    while (L < na && shared_with(w, A, e, B, vid)) e++, L++;
    if (L >= na || L >= nb || na + nb - 2 * L > maxv) return 0;
    const int ve = vid[sa[((e % na) + na) % na]];
    int jb = -1; /* B's slot of the chain's end: B runs along the chain from there */
    for (int j = 0; j < nb && jb < 0; j++)
        if (vid[sb[j]] == ve) jb = j;
    if (jb < 0 || vid[sb[(jb + L) % nb]] != vid[sa[((s % na) + na) % na]]) return 0;
    int n = 0;
    for (int t = 0; t <= na - L; t++) w->merged[n++] = sa[(((e + t) % na) + na) % na];
    for (int t = L + 1; t < nb; t++) w->merged[n++] = sb[(jb + t) % nb];
    return n;
}

/* One pass of merges into cell A; 1 when it took a neighbour (A changed), 0 when none fits,
 * -1 when out of memory. */
static int grow_cell(cells_work *w, int A, const int *vid, const double (*xy)[2], int maxv)
{
    for (int k = 0; k < w->len[A]; k++) {
        const int *sa = w->slot[A];
        const int u = vid[sa[k]], v = vid[sa[(k + 1) % w->len[A]]];
        unsigned q = key_slot(w, edge_key(v, u));
        if (w->key[q] == 0) continue;
        const int B = find_root(w->parent, w->owner[q]);
        if (B == A) continue;
        int n = join(w, A, k, B, vid, maxv);
        if (!n || !convex_ccw(w->merged, n, vid, xy)) continue;
        int *s = realloc(w->slot[A], (size_t)n * sizeof *s);
        if (!s) return -1;
        memcpy(s, w->merged, (size_t)n * sizeof *s);
        w->slot[A] = s;
        w->len[A] = n;
        free(w->slot[B]);
        w->slot[B] = NULL;
        w->len[B] = 0;
        w->parent[B] = A;
        return 1;
    }
    return 0;
}

static void work_free(cells_work *w, int nface)
{
    for (int f = 0; w->slot && f < nface; f++) free(w->slot[f]);
    free(w->slot);
    free(w->len);
    free(w->parent);
    free(w->key);
    free(w->owner);
}

static int work_init(cells_work *w, int nface, const int *f0, const int *vid)
{
    const int ne = f0[nface];
    unsigned cap = 16;
    while (cap < 2u * (unsigned)ne) cap *= 2;
    w->mask = cap - 1;
    w->key = calloc(cap, sizeof *w->key);
    w->owner = malloc(cap * sizeof *w->owner);
    w->parent = malloc((size_t)(nface ? nface : 1) * sizeof *w->parent);
    w->slot = calloc((size_t)(nface ? nface : 1), sizeof *w->slot);
    w->len = malloc((size_t)(nface ? nface : 1) * sizeof *w->len);
    if (!w->key || !w->owner || !w->parent || !w->slot || !w->len) return -1;
    for (int f = 0; f < nface; f++) {
        const int n = f0[f + 1] - f0[f];
        w->parent[f] = f;
        w->len[f] = n;
        w->slot[f] = malloc((size_t)(n ? n : 1) * sizeof *w->slot[f]);
        if (!w->slot[f]) return -1;
        for (int t = 0; t < n; t++) {
            w->slot[f][t] = f0[f] + t;
            unsigned q = key_slot(w, edge_key(vid[f0[f] + t], vid[f0[f] + (t + 1) % n]));
            if (w->key[q] == 0) { /* a directed edge twice (a folded mesh): the first keeps it */
                w->key[q] = edge_key(vid[f0[f] + t], vid[f0[f] + (t + 1) % n]);
                w->owner[q] = f;
            }
        }
    }
    return 0;
}

int rd_patch_cells(int nface, const int *f0, const int *vid, const double (*xy)[2], int maxv,
                   int *c0, int *cslot)
{
    cells_work w;
    memset(&w, 0, sizeof w);
    if (work_init(&w, nface, f0, vid)) {
        work_free(&w, nface);
        return -1;
    }
    for (int f = 0; f < nface; f++) {
        if (find_root(w.parent, f) != f || !convex_ccw(w.slot[f], w.len[f], vid, xy)) continue;
        int rc;
        while ((rc = grow_cell(&w, f, vid, xy, maxv)) == 1) {}
        if (rc < 0) {
            work_free(&w, nface);
            return -1;
        }
    }
    int nc = 0, m = 0;
    for (int f = 0; f < nface; f++) {
        if (find_root(w.parent, f) != f) continue;
        c0[nc++] = m;
        memcpy(cslot + m, w.slot[f], (size_t)w.len[f] * sizeof *cslot);
        m += w.len[f];
    }
    c0[nc] = m;
    work_free(&w, nface);
    return nc;
}
