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

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* Longest outline (edges) that is re-triangulated: ear clipping is quadratic in it. */
#define RD_PATCH_OUTLINE_MAX  1024
/* The re-triangulated outline must hold the faces' area to this fraction (round-off): else a
 * mesh whose coplanar faces overlap or meet at T-junctions keeps the greedy cells. */
#define RD_PATCH_OUTLINE_AREA 1e-9

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

/* The faces merged greedily (Hertel and Mehlhorn) into convex cells. */
static int merge_faces(int nface, const int *f0, const int *vid, const double (*xy)[2], int maxv,
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

/* Twice the signed area of the polygon of slots s[0 .. n). */
static double area2(const int *s, int n, const double (*xy)[2])
{
    double a = 0;
    for (int k = 0; k < n; k++) {
        const double *u = xy[s[k]], *v = xy[s[k + 1 == n ? 0 : k + 1]];
        a += u[0] * v[1] - v[0] * u[1];
    }
    return a;
}

/* Does point p lie inside or on triangle (a, b, c), counter-clockwise? */
static int in_triangle(const double *a, const double *b, const double *c, const double *p)
{
    const double ab = (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]);
    const double bc = (c[0] - b[0]) * (p[1] - b[1]) - (c[1] - b[1]) * (p[0] - b[0]);
    const double ca = (a[0] - c[0]) * (p[1] - c[1]) - (a[1] - c[1]) * (p[0] - c[0]);
    return ab >= 0 && bc >= 0 && ca >= 0;
}

/* Ear clipping of the simple counter-clockwise loop of slots s[0 .. n) into triangles appended
 * to tri (slot triples) from *nt. 0, 1 when it finds no ear (a degenerate loop). */
static int ear_clip(int *s, int n, const int *vid, const double (*xy)[2], int *tri, int *nt)
{
    while (n > 3) {
        int found = 0;
        for (int i = 0; i < n && !found; i++) {
            const int p = s[(i + n - 1) % n], q = s[i], r = s[(i + 1) % n];
            const double *a = xy[p], *b = xy[q], *c = xy[r];
            if (!((b[0] - a[0]) * (c[1] - b[1]) - (b[1] - a[1]) * (c[0] - b[0]) > 0)) continue;
            int blocked = 0;
            for (int j = 0; j < n && !blocked; j++) {
                const int t = s[j];
                if (vid[t] == vid[p] || vid[t] == vid[q] || vid[t] == vid[r]) continue;
                blocked = in_triangle(a, b, c, xy[t]);
            }
            if (blocked) continue;
            tri[3 * *nt] = p;
            tri[3 * *nt + 1] = q;
            tri[3 * *nt + 2] = r;
            (*nt)++;
            memmove(s + i, s + i + 1, (size_t)(n - i - 1) * sizeof *s);
            n--;
            found = 1;
        }
        if (!found) return 1;
    }
    if (n == 3) {
        memcpy(tri + 3 * *nt, s, 3 * sizeof *s);
        (*nt)++;
    }
    return 0;
}

/* The outline of the faces (their edges with no twin), as simple counter-clockwise loops of
 * slots into loop (loop starts in l0), when it is one: every outline vertex starts one outline
 * edge and every loop has positive area (no hole). Returns the loop count, 0 when the outline
 * is none of these or longer than RD_PATCH_OUTLINE_MAX, -1 when out of memory. */
static int outline_loops(const cells_work *w, int nface, const int *f0, const int *vid,
                         const double (*xy)[2], int *loop, int *l0)
{
    const int ne = f0[nface];
    int *from = malloc((size_t)ne * sizeof *from), *used = calloc((size_t)ne, sizeof *used);
    int *next = malloc((size_t)ne * sizeof *next);
    if (!from || !used || !next) {
        free(from);
        free(used);
        free(next);
        return -1;
    }
    int nb = 0, ok = 1;
    for (int f = 0; f < nface; f++)
        for (int q = f0[f]; q < f0[f + 1]; q++) {
            const int q1 = q + 1 == f0[f + 1] ? f0[f] : q + 1;
            if (w->key[key_slot(w, edge_key(vid[q1], vid[q]))] == 0) {
                from[nb] = q;
                next[nb++] = q1;
            }
        }
    if (nb > RD_PATCH_OUTLINE_MAX) ok = 0;
    /* the outline edge that starts where edge k ends: quadratic, nb is small */
    int nl = 0, m = 0;
    for (int k = 0; k < nb && ok; k++) {
        if (used[k]) continue;
        l0[nl++] = m;
        int e = k;
        while (ok && !used[e]) {
            used[e] = 1;
            loop[m++] = from[e];
            int nx = -1, count = 0;
            for (int j = 0; j < nb; j++)
                if (vid[from[j]] == vid[next[e]]) nx = j, count++;
            ok = count == 1;
            e = nx;
        }
        ok = ok && e == k && area2(loop + l0[nl - 1], m - l0[nl - 1], xy) > 0;
    }
    l0[nl] = m;
    free(from);
    free(used);
    free(next);
    return ok ? nl : 0;
}

/* The faces' area, twice (each face's shoelace). */
static double faces_area2(int nface, const int *f0, const double (*xy)[2])
{
    double a = 0;
    for (int f = 0; f < nface; f++) {
        int s[RD_PATCH_FACE_MAX];
        const int n = f0[f + 1] - f0[f];
        for (int k = 0; k < n && k < RD_PATCH_FACE_MAX; k++) s[k] = f0[f] + k;
        a += area2(s, n < RD_PATCH_FACE_MAX ? n : RD_PATCH_FACE_MAX, xy);
    }
    return a;
}

/* The outline re-triangulated (ear clipping, so no interior vertex is left) and the triangles
 * merged: into c0 / cslot when that gives fewer than nc cells within the caller's room and the
 * triangles' area is the faces' to round-off. Returns the cell count (nc when kept), -1 when
 * out of memory. */
static int merge_outline(int nface, const int *f0, const int *vid, const double (*xy)[2], int maxv,
                         int nc, int *c0, int *cslot)
{
    cells_work w;
    memset(&w, 0, sizeof w);
    const int ne = f0[nface];
    int *loop = malloc((size_t)ne * sizeof *loop), *l0 = malloc(((size_t)ne + 1) * sizeof *l0);
    int *tri = malloc(3 * (size_t)ne * sizeof *tri), *t0 = malloc(((size_t)ne + 1) * sizeof *t0);
    int *tc0 = malloc(((size_t)ne + 1) * sizeof *tc0), *tcs = malloc(3 * (size_t)ne * sizeof *tcs);
    int rc = nc, nl = -1;
    if (loop && l0 && tri && t0 && tc0 && tcs && !work_init(&w, nface, f0, vid))
        nl = outline_loops(&w, nface, f0, vid, xy, loop, l0);
    int nt = 0, stuck = nl <= 0;
    for (int l = 0; l < nl && !stuck; l++)
        stuck = ear_clip(loop + l0[l], l0[l + 1] - l0[l], vid, xy, tri, &nt);
    if (!stuck) {
        for (int t = 0; t <= nt; t++) t0[t] = 3 * t;
        double at = 0, af = faces_area2(nface, f0, xy);
        for (int t = 0; t < nt; t++) at += area2(tri + 3 * t, 3, xy);
        /* the triangles as faces of their own slots 3 t + k (tri maps them back) */
        int *tv = malloc(3 * (size_t)(nt ? nt : 1) * sizeof *tv);
        double(*txy)[2] = malloc(3 * (size_t)(nt ? nt : 1) * sizeof *txy);
        for (int q = 0; tv && txy && q < 3 * nt; q++) {
            tv[q] = vid[tri[q]];
            txy[q][0] = xy[tri[q]][0];
            txy[q][1] = xy[tri[q]][1];
        }
        int n2 = !tv || !txy ? -1
                 : fabs(at - af) <= RD_PATCH_OUTLINE_AREA * fabs(af)
                     ? merge_faces(nt, t0, tv, (const double(*)[2])txy, maxv, tc0, tcs)
                     : nc;
        free(tv);
        free(txy);
        if (n2 < 0) rc = -1;
        if (n2 >= 0 && n2 < nc && tc0[n2] <= ne) {
            memcpy(c0, tc0, ((size_t)n2 + 1) * sizeof *c0);
            for (int q = 0; q < tc0[n2]; q++) cslot[q] = tri[tcs[q]];
            rc = n2;
        }
    }
    if (nl < 0) rc = -1;
    work_free(&w, nface);
    free(loop);
    free(l0);
    free(tri);
    free(t0);
    free(tc0);
    free(tcs);
    return rc;
}

int rd_patch_cells(int nface, const int *f0, const int *vid, const double (*xy)[2], int maxv,
                   int *c0, int *cslot)
{
    int nc = merge_faces(nface, f0, vid, xy, maxv, c0, cslot);
    if (nc <= 1) return nc;
    return merge_outline(nface, f0, vid, xy, maxv, nc, c0, cslot);
}
