/* rockdem — a bounding-volume hierarchy of a body's faces in its own frame (contact/contact.h):
 * built once per body, traversed per step against another body's tree under their relative
 * pose (a box of b's tree is carried into a's frame as the box around the rotated box:
 * centre rot c + tr, half-widths |rot| h), so the candidate face pairs of a step are those near
 * the touching patches.
 * Folder contact/ holds the patch geometry and its law; it may call base/ and geometry/, and is
 * called by engine/.
 */
#include "contact/contact.h"

#include <math.h>
#include <stdlib.h>

/* Builder's scratch: item boxes and centres. */
typedef struct bvh_build {
    const double (*lo)[3], (*hi)[3];
    double (*c)[3];
} bvh_build;

static void swap_int(int *a, int *b)
{
    int t = *a;
    *a = *b;
    *b = t;
}

/* Items item[i0 .. i1) into node k (its box; split when more than a leaf's worth). */
static void build_node(rd_bvh *t, const bvh_build *bb, int k, int i0, int i1)
{
    for (int c = 0; c < 3; c++) {
        t->lo[k][c] = INFINITY;
        t->hi[k][c] = -INFINITY;
    }
    double clo[3] = { INFINITY, INFINITY, INFINITY }, chi[3] = { -INFINITY, -INFINITY, -INFINITY };
    for (int i = i0; i < i1; i++) {
        const int it = t->item[i];
        for (int c = 0; c < 3; c++) {
            t->lo[k][c] = fmin(t->lo[k][c], bb->lo[it][c]);
            t->hi[k][c] = fmax(t->hi[k][c], bb->hi[it][c]);
            clo[c] = fmin(clo[c], bb->c[it][c]);
            chi[c] = fmax(chi[c], bb->c[it][c]);
        }
    }
    if (i1 - i0 <= RD_BVH_LEAF) {
        t->child[k] = -1;
        t->first[k] = i0;
        t->count[k] = i1 - i0;
        return;
    }
    int ax = 0;
    for (int c = 1; c < 3; c++)
        if (chi[c] - clo[c] > chi[ax] - clo[ax]) ax = c;
    /* median split (quickselect of the centres along ax): balanced, depth log2(n / leaf) */
    const int mid = (i0 + i1) / 2;
    int lo = i0, hi = i1 - 1;
    while (lo < hi) {
        const double piv = bb->c[t->item[(lo + hi) / 2]][ax];
        int a = lo, b = hi;
        while (a <= b) {
            while (bb->c[t->item[a]][ax] < piv) a++;
            while (bb->c[t->item[b]][ax] > piv) b--;
            if (a <= b) swap_int(&t->item[a++], &t->item[b--]);
        }
        if (mid <= b)
            hi = b;
        else if (mid >= a)
            lo = a;
        else
            break;
    }
    const int ch = t->nnode;
    t->nnode += 2;
    t->child[k] = ch;
    t->first[k] = t->count[k] = 0;
    build_node(t, bb, ch, i0, mid);
    build_node(t, bb, ch + 1, mid, i1);
}

int rd_bvh_build(rd_bvh *t, int n, const double (*lo)[3], const double (*hi)[3])
{
    *t = (rd_bvh){ 0, NULL, NULL, NULL, NULL, NULL, NULL };
    const int cap = 2 * (n > 0 ? n : 1); /* a binary tree of at most n leaves */
    t->lo = malloc((size_t)cap * sizeof *t->lo);
    t->hi = malloc((size_t)cap * sizeof *t->hi);
    t->child = malloc((size_t)cap * sizeof *t->child);
    t->first = malloc((size_t)cap * sizeof *t->first);
    t->count = malloc((size_t)cap * sizeof *t->count);
    t->item = malloc((size_t)(n > 0 ? n : 1) * sizeof *t->item);
    bvh_build bb = { lo, hi, malloc((size_t)(n > 0 ? n : 1) * sizeof *bb.c) };
    if (!t->lo || !t->hi || !t->child || !t->first || !t->count || !t->item || !bb.c) {
        free(bb.c);
        rd_bvh_free(t);
        return -1;
    }
    for (int k = 0; k < n; k++) {
        t->item[k] = k;
        for (int c = 0; c < 3; c++) bb.c[k][c] = 0.5 * (lo[k][c] + hi[k][c]);
    }
    t->nnode = 1;
    if (n > 0)
        build_node(t, &bb, 0, 0, n);
    else
        t->nnode = 0;
    free(bb.c);
    return 0;
}

void rd_bvh_free(rd_bvh *t)
{
    free(t->lo);
    free(t->hi);
    free(t->child);
    free(t->first);
    free(t->count);
    free(t->item);
    *t = (rd_bvh){ 0, NULL, NULL, NULL, NULL, NULL, NULL };
}

static int push(rd_bvh_pairs *out, int a, int b)
{
    if (out->n == out->cap) {
        int c = out->cap ? 2 * out->cap : 64;
        int(*p)[2] = realloc(out->ab, (size_t)c * sizeof *p);
        if (!p) return -1;
        out->ab = p;
        out->cap = c;
    }
    out->ab[out->n][0] = a;
    out->ab[out->n][1] = b;
    out->n++;
    return 0;
}

/* Do boxes lo .. hi and (centre c, half-widths h) overlap, grown by margin? */
static int meets(const double *lo, const double *hi, const double c[3], const double h[3],
                 double margin)
{
    for (int k = 0; k < 3; k++)
        if (c[k] - h[k] > hi[k] + margin || c[k] + h[k] < lo[k] - margin) return 0;
    return 1;
}

/* Node kb of b carried into a's frame: centre and half-widths. */
static void carry(const rd_bvh *b, int kb, const double rot[9], const double tr[3], double c[3],
                  double h[3])
{
    double cb[3], hb[3];
    for (int k = 0; k < 3; k++) {
        cb[k] = 0.5 * (b->lo[kb][k] + b->hi[kb][k]);
        hb[k] = 0.5 * (b->hi[kb][k] - b->lo[kb][k]);
    }
    for (int r = 0; r < 3; r++) {
        c[r] = tr[r];
        h[r] = 0;
        for (int k = 0; k < 3; k++) {
            c[r] += rot[3 * r + k] * cb[k];
            h[r] += fabs(rot[3 * r + k]) * hb[k];
        }
    }
}

static int pairs_node(const rd_bvh *a, int ka, const rd_bvh *b, int kb, const double rot[9],
                      const double tr[3], double margin, rd_bvh_pairs *out)
{
    double c[3], h[3];
    carry(b, kb, rot, tr, c, h);
    if (!meets(a->lo[ka], a->hi[ka], c, h, margin)) return 0;
    const int la = a->child[ka] < 0, lb = b->child[kb] < 0;
    if (la && lb) {
        for (int i = a->first[ka]; i < a->first[ka] + a->count[ka]; i++)
            for (int j = b->first[kb]; j < b->first[kb] + b->count[kb]; j++)
                if (push(out, a->item[i], b->item[j])) return -1;
        return 0;
    }
    /* descend the larger box (or the one that is not a leaf) */
    double va = 1, vb = 1;
    for (int k = 0; k < 3; k++) {
        va *= a->hi[ka][k] - a->lo[ka][k];
        vb *= b->hi[kb][k] - b->lo[kb][k];
    }
    if (lb || (!la && va >= vb)) {
        if (pairs_node(a, a->child[ka], b, kb, rot, tr, margin, out)) return -1;
        return pairs_node(a, a->child[ka] + 1, b, kb, rot, tr, margin, out);
    }
    if (pairs_node(a, ka, b, b->child[kb], rot, tr, margin, out)) return -1;
    return pairs_node(a, ka, b, b->child[kb] + 1, rot, tr, margin, out);
}

int rd_bvh_overlaps(const rd_bvh *a, const rd_bvh *b, const double rot[9], const double tr[3],
                    double margin, rd_bvh_pairs *out)
{
    if (a->nnode == 0 || b->nnode == 0) return 0;
    return pairs_node(a, 0, b, 0, rot, tr, margin, out);
}

/* Node k of a carried by (rot, tr), |rot| given: centre and half-widths. */
static void carry_abs(const rd_bvh *a, int k, const double rot[9], const double arot[9],
                      const double tr[3], double c[3], double h[3])
{
    const double *lo = a->lo[k], *hi = a->hi[k];
    const double cb[3] = { 0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), 0.5 * (lo[2] + hi[2]) };
    const double hb[3] = { 0.5 * (hi[0] - lo[0]), 0.5 * (hi[1] - lo[1]), 0.5 * (hi[2] - lo[2]) };
    for (int r = 0; r < 3; r++) {
        const double *m = rot + 3 * r, *am = arot + 3 * r;
        c[r] = tr[r] + m[0] * cb[0] + m[1] * cb[1] + m[2] * cb[2];
        h[r] = am[0] * hb[0] + am[1] * hb[1] + am[2] * hb[2];
    }
}

static int carried_node(const rd_bvh *a, int k, const double rot[9], const double arot[9],
                        const double tr[3], const double *lo, const double *hi, double margin,
                        rd_bvh_pairs *out)
{
    double c[3], h[3];
    carry_abs(a, k, rot, arot, tr, c, h);
    if (!meets(lo, hi, c, h, margin)) return 0;
    if (a->child[k] < 0) {
        for (int i = a->first[k]; i < a->first[k] + a->count[k]; i++)
            if (push(out, a->item[i], 0)) return -1;
        return 0;
    }
    if (carried_node(a, a->child[k], rot, arot, tr, lo, hi, margin, out)) return -1;
    return carried_node(a, a->child[k] + 1, rot, arot, tr, lo, hi, margin, out);
}

int rd_bvh_query_carried(const rd_bvh *a, const double rot[9], const double tr[3],
                         const double lo[3], const double hi[3], double margin, rd_bvh_pairs *out)
{
    if (a->nnode == 0) return 0;
    double arot[9];
    for (int k = 0; k < 9; k++) arot[k] = fabs(rot[k]);
    return carried_node(a, 0, rot, arot, tr, lo, hi, margin, out);
}
