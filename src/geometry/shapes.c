/* rockdem — more solids: prisms and frustums (drums), convex hulls (qhull), polyhedra from
 * explicit faces, and the check that a polyhedron is closed, manifold and outward.
 * Folder geometry/ owns solids, their mass properties, subcontact points and assembly builders;
 * it may call base/ only.
 */
#include "geometry/geom.h"
#include "base/vec.h"

#include <libqhull_r/qhull_ra.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int rd_poly_prism(rd_poly *p, int nsides, double radius_bottom, double radius_top, double height,
                  rd_error *err)
{
    int n = nsides;
    if (n < 3) return rd_error_set(err, "prism needs at least 3 sides, got %d", n);
    if (!(radius_bottom > 0 && radius_top > 0 && height > 0))
        return rd_error_set(err, "prism radii and height must be positive (got %g, %g, %g m)",
                            radius_bottom, radius_top, height);
    if (rd_poly_alloc(p, 2 * n, n + 2, 2 * n + 4 * n, err)) return -1;
    for (int k = 0; k < n; k++) {
        double a = 2.0 * M_PI * k / n, c = cos(a), s = sin(a);
        p->v[k][0] = radius_bottom * c;
        p->v[k][1] = radius_bottom * s;
        p->v[k][2] = -0.5 * height;
        p->v[n + k][0] = radius_top * c;
        p->v[n + k][1] = radius_top * s;
        p->v[n + k][2] = 0.5 * height;
    }
    p->fstart[0] = 0;
    p->flen[0] = n; /* base, seen from below: clockwise from above */
    p->fstart[1] = n;
    p->flen[1] = n; /* top */
    for (int k = 0; k < n; k++) {
        p->fidx[k] = n - 1 - k;
        p->fidx[n + k] = n + k;
        int *q = p->fidx + 2 * n + 4 * k, k1 = (k + 1) % n;
        q[0] = k;
        q[1] = k1;
        q[2] = n + k1;
        q[3] = n + k;
        p->fstart[2 + k] = 2 * n + 4 * k;
        p->flen[2 + k] = 4;
    }
    rd_poly_update(p);
    return 0;
}

/* ---- convexity ---- */

static void sub3(const double a[3], const double b[3], double out[3])
{
    for (int k = 0; k < 3; k++) out[k] = a[k] - b[k];
}

/* One side of a face: its vertices (a < b) and the face. */
typedef struct side {
    int a, b, f, k;
} side;

static int by_vertices(const void *x, const void *y)
{
    const side *s = x, *t = y;
    return s->a != t->a ? (s->a > t->a) - (s->a < t->a) : (s->b > t->b) - (s->b < t->b);
}

/* How far face f rises above the plane of face g across their shared side k of f (from vertex
 * fidx[k] to the next), m: the vertex after the side, its height scaled from its distance to
 * the side's line to the face's diameter w[f] (the height is linear across a planar face, so
 * this bounds every vertex of f). */
static double rise(const rd_poly *p, int f, int k, int g, const double *w)
{
    const int *fi = p->fidx + p->fstart[f];
    int n = p->flen[f];
    const double *a = p->v[fi[k]], *b = p->v[fi[(k + 1) % n]], *c = p->v[fi[(k + 2) % n]];
    double h = rd_dot(p->fn[g], c) - p->fd[g], ab[3], ac[3], x[3];
    sub3(b, a, ab);
    sub3(c, a, ac);
    rd_cross(ab, ac, x);
    double d = rd_norm(x) / rd_norm(ab); /* c's distance to the line ab */
    return d > 0 ? h * fmax(1.0, w[f] / d) : h;
}

/* The width bound of every face (the largest distance of its vertices from the first, m), and
 * whether every face is a convex polygon to within tol (no corner more than tol past the line
 * of the side before it): a face of a convex solid is its section by a supporting plane, so a
 * reflex corner makes the solid non-convex. 1 when every face is convex. */
static int face_widths(const rd_poly *p, double tol, double *w)
{
    int ok = 1;
    for (int f = 0; f < p->nf; f++) {
        const int *fi = p->fidx + p->fstart[f];
        int n = p->flen[f];
        double m = 0, d[3], ab[3], x[3];
        for (int k = 0; k < n; k++) {
            sub3(p->v[fi[k]], p->v[fi[0]], d);
            m = fmax(m, rd_norm(d));
            const double *a = p->v[fi[k]], *b = p->v[fi[(k + 1) % n]], *c = p->v[fi[(k + 2) % n]];
            sub3(b, a, ab);
            sub3(c, b, d);
            rd_cross(ab, d, x); /* along the outward normal at a convex corner b */
            if (-rd_dot(x, p->fn[f]) / rd_norm(ab) > tol) ok = 0;
        }
        w[f] = m;
    }
    return ok;
}

/* Volume and area of the convex hull of p's vertices (qhull). 0 or -1. */
static int hull_measure(const rd_poly *p, double *volume, double *area, rd_error *err)
{
    coordT *xyz = malloc((size_t)p->nv * 3 * sizeof *xyz);
    if (!xyz) return rd_error_set(err, "out of memory in the convexity test");
    for (int i = 0; i < p->nv; i++)
        for (int k = 0; k < 3; k++) xyz[3 * i + k] = p->v[i][k];
    qhT qh_qh, *qh = &qh_qh;
    FILE *devnull = fopen("/dev/null", "w");
    qh_zero(qh, devnull);
    int rc = qh_new_qhull(qh, 3, p->nv, xyz, False, (char *)"qhull", NULL, devnull);
    if (rc == 0) {
        qh_getarea(qh, qh->facet_list);
        *volume = qh->totvol;
        *area = qh->totarea;
    }
    int curlong, totlong;
    qh_freeqhull(qh, !qh_ALL);
    qh_memfreeshort(qh, &curlong, &totlong);
    if (devnull) fclose(devnull);
    free(xyz);
    return rc ? rd_error_set(err,
                             "the convex hull of the body's %d vertices failed (qhull code %d)",
                             p->nv, rc)
              : 0;
}

/* Signed volume of p from its triangulation, m^3. */
static double poly_volume(const rd_poly *p)
{
    double v = 0, x[3];
    for (int t = 0; t < p->ntri; t++) {
        rd_cross(p->v[p->tri[t][1]], p->v[p->tri[t][2]], x);
        v += rd_dot(p->v[p->tri[t][0]], x);
    }
    return v / 6.0;
}

/* Up to this many vertex-plane pairs the definition itself (every vertex behind every face
 * plane) is cheaper than the edge sort and qhull (a brick: 48 pairs, 0.2 us, where qhull takes
 * 40 us; 1e5 pairs take about 0.1 ms). */
#define RD_CONVEX_DIRECT 1e5

static int convex_by_definition(const rd_poly *p, double tol)
{
    for (int f = 0; f < p->nf; f++)
        for (int v = 0; v < p->nv; v++)
            if (rd_dot(p->fn[f], p->v[v]) - p->fd[f] > tol) return 0;
    return 1;
}

int rd_poly_convex(const rd_poly *p, double tol, int *convex, rd_error *err)
{
    if ((double)p->nf * p->nv <= RD_CONVEX_DIRECT) {
        *convex = convex_by_definition(p, tol);
        return 0;
    }
    int ns = 0;
    for (int f = 0; f < p->nf; f++) ns += p->flen[f];
    side *e = malloc((size_t)ns * sizeof *e);
    double *w = malloc((size_t)p->nf * sizeof *w);
    if (!e || !w) {
        free(e);
        free(w);
        return rd_error_set(err, "out of memory in the convexity test");
    }
    *convex = face_widths(p, tol, w);
    int m = 0;
    for (int f = 0; f < p->nf; f++)
        for (int k = 0; k < p->flen[f]; k++) {
            int a = p->fidx[p->fstart[f] + k], b = p->fidx[p->fstart[f] + (k + 1) % p->flen[f]];
            e[m++] = (side){ a < b ? a : b, a < b ? b : a, f, k };
        }
    qsort(e, (size_t)m, sizeof *e, by_vertices);
    /* a closed manifold (rd_poly_check): every side meets exactly one other, of another face */
    for (int i = 0; i + 1 < m && *convex; i += 2)
        if (rise(p, e[i].f, e[i].k, e[i + 1].f, w) > tol ||
            rise(p, e[i + 1].f, e[i + 1].k, e[i].f, w) > tol)
            *convex = 0;
    free(e);
    free(w);
    double hv, ha;
    if (!*convex) return 0;
    if (hull_measure(p, &hv, &ha, err)) return -1;
    *convex = hv - poly_volume(p) <= tol * ha;
    return 0;
}

/* ---- convex hull ---- */

typedef struct angled {
    double angle;
    int id;
} angled;

static int by_angle(const void *a, const void *b)
{
    double x = ((const angled *)a)->angle, y = ((const angled *)b)->angle;
    return (x > y) - (x < y);
}

/* Sort the vertices of a convex planar face counter-clockwise about its outward normal n. */
static void order_face(const double (*v)[3], int *ids, int len, const double n[3], angled *buf)
{
    double c[3] = { 0, 0, 0 }, u[3], w[3];
    for (int k = 0; k < len; k++) rd_axpy(1.0 / len, v[ids[k]], c);
    for (int i = 0; i < 3; i++) u[i] = v[ids[0]][i] - c[i];
    rd_cross(n, u, w);
    for (int k = 0; k < len; k++) {
        double d[3] = { v[ids[k]][0] - c[0], v[ids[k]][1] - c[1], v[ids[k]][2] - c[2] };
        buf[k].angle = atan2(rd_dot(d, w), rd_dot(d, u));
        buf[k].id = ids[k];
    }
    qsort(buf, (size_t)len, sizeof *buf, by_angle);
    for (int k = 0; k < len; k++) ids[k] = buf[k].id;
}

/* Copy qhull's facets (merged, outward normals) into p, with the input points' coordinates. */
static int hull_extract(qhT *qh, rd_poly *p, const double (*pts)[3], int n, rd_error *err)
{
    facetT *facet;
    vertexT *vertex, **vertexp;
    int nv = 0, nf = 0, nidx = 0, rc = -1;
    int *map = malloc((size_t)n * sizeof *map);
    angled *buf = malloc((size_t)n * sizeof *buf);
    if (!map || !buf) {
        rd_error_set(err, "out of memory in the convex hull");
        goto done;
    }
    for (int i = 0; i < n; i++) map[i] = -1;
    FORALLvertices map[qh_pointid(qh, vertex->point)] = nv++;
    FORALLfacets
    {
        nf++;
        nidx += qh_setsize(qh, facet->vertices);
    }
    if (rd_poly_alloc(p, nv, nf, nidx, err)) goto done;
    for (int i = 0; i < n; i++)
        if (map[i] >= 0) rd_copy3(pts[i], p->v[map[i]]);
    int f = 0, at = 0;
    FORALLfacets
    {
        p->fstart[f] = at;
        FOREACHvertex_(facet->vertices) p->fidx[at++] = map[qh_pointid(qh, vertex->point)];
        p->flen[f] = at - p->fstart[f];
        order_face((const double(*)[3])p->v, p->fidx + p->fstart[f], p->flen[f], facet->normal,
                   buf);
        f++;
    }
    rd_poly_update(p);
    rc = 0;
done:
    free(map);
    free(buf);
    return rc;
}

/* qhull's hull of n >= 4 points; then p (if not NULL) receives the hull as a polyhedron and
 * on_hull (if not NULL) marks the points that are hull vertices. 0 or -1. */
static int hull_run(const double (*pts)[3], int n, rd_poly *p, char *on_hull, rd_error *err)
{
    if (n < 4) return rd_error_set(err, "convex hull needs at least 4 points, got %d", n);
    double lo[3], hi[3], centre[3];
    rd_copy3(pts[0], lo);
    rd_copy3(pts[0], hi);
    for (int i = 1; i < n; i++)
        for (int k = 0; k < 3; k++) {
            lo[k] = fmin(lo[k], pts[i][k]);
            hi[k] = fmax(hi[k], pts[i][k]);
        }
    for (int k = 0; k < 3; k++) centre[k] = 0.5 * (lo[k] + hi[k]);
    coordT *xyz = malloc((size_t)n * 3 * sizeof *xyz);
    char *msg = NULL;
    size_t msglen = 0;
    FILE *log = open_memstream(&msg, &msglen);
    if (!xyz || !log) {
        free(xyz);
        if (log) fclose(log);
        free(msg);
        return rd_error_set(err, "out of memory in the convex hull");
    }
    for (int i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) xyz[3 * i + k] = pts[i][k] - centre[k]; /* precision */
    qhT qh_qh, *qh = &qh_qh;
    qh_zero(qh, log);
    /* default 3-d options merge coplanar facets (C-0, Qx) into convex polygons */
    int rc = qh_new_qhull(qh, 3, n, xyz, False, (char *)"qhull", NULL, log);
    if (rc == 0) {
        if (on_hull) {
            vertexT *vertex;
            memset(on_hull, 0, (size_t)n);
            FORALLvertices on_hull[qh_pointid(qh, vertex->point)] = 1;
        }
        if (p) rc = hull_extract(qh, p, pts, n, err);
    } else {
        fflush(log);
        char *line = msg ? strstr(msg, "QH") : NULL;
        size_t len = line ? strcspn(line, "\n") : 0;
        rd_error_set(err, "convex hull of %d points failed (coplanar or degenerate?): %.*s", n,
                     (int)len, line ? line : "");
        rc = -1;
    }
    int curlong, totlong;
    qh_freeqhull(qh, !qh_ALL);
    qh_memfreeshort(qh, &curlong, &totlong);
    fclose(log);
    free(msg);
    free(xyz);
    return rc;
}

int rd_poly_hull(rd_poly *p, const double (*pts)[3], int n, rd_error *err)
{
    return hull_run(pts, n, p, NULL, err);
}

int rd_poly_hull_marks(const rd_poly *p, char *on_hull, rd_error *err)
{
    return hull_run((const double(*)[3])p->v, p->nv, NULL, on_hull, err);
}

/* ---- explicit faces and the closed-mesh check ---- */

int rd_poly_from_faces(rd_poly *p, const double (*v)[3], int nv, const int *face_start,
                       const int *face_len, const int *idx, int nf, rd_error *err)
{
    int nidx = 0;
    for (int f = 0; f < nf; f++) {
        if (face_len[f] < 3)
            return rd_error_set(err, "faces: face %d has %d vertices (at least 3 needed)", f,
                                face_len[f]);
        nidx += face_len[f];
    }
    if (nv < 4 || nf < 4)
        return rd_error_set(err,
                            "faces: a closed polyhedron needs at least 4 "
                            "vertices and 4 faces (got %d, %d)",
                            nv, nf);
    if (rd_poly_alloc(p, nv, nf, nidx, err)) return -1;
    memcpy(p->v, v, (size_t)nv * sizeof *p->v);
    for (int f = 0, at = 0; f < nf; f++) {
        p->fstart[f] = at;
        p->flen[f] = face_len[f];
        memcpy(p->fidx + at, idx + face_start[f], (size_t)face_len[f] * sizeof *idx);
        at += face_len[f];
    }
    if (rd_poly_check(p, "faces", 0, err)) {
        rd_poly_free(p);
        return -1;
    }
    rd_poly_update(p);
    return 0;
}

/* Faces of >= 3 vertices with indices in range. */
static int check_indices(const rd_poly *p, const char *what, int base, rd_error *err)
{
    for (int f = 0; f < p->nf; f++) {
        if (p->flen[f] < 3)
            return rd_error_set(err, "%s: face %d has %d vertices (at least 3 needed)", what,
                                f + base, p->flen[f]);
        for (int k = 0; k < p->flen[f]; k++) {
            int i = p->fidx[p->fstart[f] + k];
            if (i < 0 || i >= p->nv)
                return rd_error_set(err, "%s: face %d uses vertex %d but there are %d vertices",
                                    what, f + base, i + base, p->nv);
        }
    }
    return 0;
}

/* Every vertex used by a face (indices already checked). */
static int check_used(const rd_poly *p, const char *what, int base, rd_error *err)
{
    char *used = calloc((size_t)p->nv, 1);
    if (!used) return rd_error_set(err, "%s: out of memory", what);
    for (int f = 0; f < p->nf; f++)
        for (int k = 0; k < p->flen[f]; k++) used[p->fidx[p->fstart[f] + k]] = 1;
    int rc = 0;
    for (int i = 0; i < p->nv && rc == 0; i++)
        if (!used[i]) rc = rd_error_set(err, "%s: vertex %d is used by no face", what, i + base);
    free(used);
    return rc;
}

/* Each face: not degenerate, planar, and its fan triangulation from the first vertex does not
 * fold over (convex faces always pass). L is the bounding-box diagonal, m. */
static int check_faces(const rd_poly *p, const char *what, int base, double L, int *bad,
                       rd_error *err)
{
    for (int f = 0; f < p->nf; f++) {
        *bad = f;
        const int *ix = p->fidx + p->fstart[f];
        double n[3] = { 0, 0, 0 }, tn[3];
        for (int k = 1; k + 1 < p->flen[f]; k++) {
            double a[3], b[3];
            for (int i = 0; i < 3; i++) {
                a[i] = p->v[ix[k]][i] - p->v[ix[0]][i];
                b[i] = p->v[ix[k + 1]][i] - p->v[ix[0]][i];
            }
            rd_cross(a, b, tn);
            rd_axpy(1.0, tn, n);
        }
        double n2 = rd_norm(n), tiny = 2e-12 * L * L;
        if (!(n2 > tiny))
            return rd_error_set(err, "%s: degenerate face %d (zero area)", what, f + base);
        for (int k = 0; k < 3; k++) n[k] /= n2;
        for (int k = 1; k < p->flen[f]; k++) {
            double d[3] = { p->v[ix[k]][0] - p->v[ix[0]][0], p->v[ix[k]][1] - p->v[ix[0]][1],
                            p->v[ix[k]][2] - p->v[ix[0]][2] };
            double off = fabs(rd_dot(n, d));
            if (off > 1e-6 * L)
                return rd_error_set(err,
                                    "%s: face %d is not planar (vertex %d is %.3g m off its plane)",
                                    what, f + base, ix[k] + base, off);
        }
        for (int k = 1; k + 1 < p->flen[f]; k++) {
            double a[3], b[3];
            for (int i = 0; i < 3; i++) {
                a[i] = p->v[ix[k]][i] - p->v[ix[0]][i];
                b[i] = p->v[ix[k + 1]][i] - p->v[ix[0]][i];
            }
            rd_cross(a, b, tn);
            if (!(rd_dot(tn, n) > tiny))
                return rd_error_set(err,
                                    "%s: face %d folds over when fanned from its first vertex "
                                    "(non-convex, or collinear vertices); split it into triangles",
                                    what, f + base);
        }
    }
    *bad = -1;
    return 0;
}

typedef struct edge {
    int lo, hi, from, face;
} edge;

static int by_edge(const void *a, const void *b)
{
    const edge *x = a, *y = b;
    if (x->lo != y->lo) return (x->lo > y->lo) - (x->lo < y->lo);
    if (x->hi != y->hi) return (x->hi > y->hi) - (x->hi < y->hi);
    return (x->face > y->face) - (x->face < y->face);
}

/* Every edge in exactly two faces, traversed in opposite directions. Reports the bad edge
 * whose first face comes first. */
static int check_edges(const rd_poly *p, const char *what, int base, int *bad_face, rd_error *err)
{
    int ne = 0;
    for (int f = 0; f < p->nf; f++) ne += p->flen[f];
    edge *e = malloc((size_t)ne * sizeof *e);
    if (!e) return rd_error_set(err, "%s: out of memory", what);
    for (int f = 0, t = 0; f < p->nf; f++)
        for (int k = 0; k < p->flen[f]; k++, t++) {
            int a = p->fidx[p->fstart[f] + k], b = p->fidx[p->fstart[f] + (k + 1) % p->flen[f]];
            e[t] = (edge){ a < b ? a : b, a < b ? b : a, a, f };
        }
    qsort(e, (size_t)ne, sizeof *e, by_edge);
    int bad = -1, badn = 0;
    for (int i = 0, j; i < ne; i = j) {
        for (j = i + 1; j < ne && e[j].lo == e[i].lo && e[j].hi == e[i].hi;) j++;
        int ok = j - i == 2 && e[i].from != e[i + 1].from;
        if (!ok && (bad < 0 || e[i].face < e[bad].face)) {
            bad = i;
            badn = j - i;
        }
    }
    int rc = 0;
    if (bad >= 0) {
        const edge *x = e + bad;
        *bad_face = x->face;
        if (badn == 1)
            rc =
                rd_error_set(err, "%s: open mesh: edge (%d, %d) belongs to 1 face (first: face %d)",
                             what, x->lo + base, x->hi + base, x->face + base);
        else if (badn > 2)
            rc = rd_error_set(
                err, "%s: non-manifold mesh: edge (%d, %d) belongs to %d faces (first: face %d)",
                what, x->lo + base, x->hi + base, badn, x->face + base);
        else
            rc = rd_error_set(
                err,
                "%s: inconsistent orientation: faces %d and %d both run edge (%d, %d) "
                "from vertex %d; flip one of them",
                what, x->face + base, x[1].face + base, x->lo + base, x->hi + base, x->from + base);
    }
    free(e);
    return rc;
}

/* Root of vertex v's set in the union-find forest up (path halving). */
static int shell_root(int *up, int v)
{
    while (up[v] != v) {
        up[v] = up[up[v]];
        v = up[v];
    }
    return v;
}

/* One closed surface: the faces' edges join every vertex into one shell (after check_edges, so
 * each shell is closed). A file of two shells (two cubes apart, or one cube twice with its own
 * vertices) is no single block: its volume and mass were summed. Reports the first face of
 * another shell than face 0's. */
static int check_shells(const rd_poly *p, const char *what, int base, int *bad_face, rd_error *err)
{
    int *up = malloc((size_t)p->nv * sizeof *up);
    char *seen = calloc((size_t)p->nv, 1);
    if (!up || !seen) {
        free(up);
        free(seen);
        return rd_error_set(err, "%s: out of memory", what);
    }
    for (int v = 0; v < p->nv; v++) up[v] = v;
    for (int f = 0; f < p->nf; f++)
        for (int k = 1; k < p->flen[f]; k++)
            up[shell_root(up, p->fidx[p->fstart[f] + k])] = shell_root(up, p->fidx[p->fstart[f]]);
    int other = -1, shells = 0;
    for (int f = 0; f < p->nf; f++) {
        int r = shell_root(up, p->fidx[p->fstart[f]]);
        if (seen[r]) continue;
        seen[r] = 1;
        if (shells++ == 1) other = f;
    }
    free(up);
    free(seen);
    if (other < 0) return 0;
    *bad_face = other;
    return rd_error_set(
        err,
        "%s: the mesh holds %d separate closed surfaces (face %d starts the second); "
        "a block is one: give each its own block",
        what, shells, other + base);
}

/* Signed volume of the closed surface, m^3 (tetrahedra from the first vertex, for precision). */
static double signed_volume(const rd_poly *p)
{
    double vol = 0;
    const double *o = p->v[0];
    for (int f = 0; f < p->nf; f++) {
        const int *ix = p->fidx + p->fstart[f];
        for (int k = 1; k + 1 < p->flen[f]; k++) {
            double a[3], b[3], c[3], bxc[3];
            for (int i = 0; i < 3; i++) {
                a[i] = p->v[ix[0]][i] - o[i];
                b[i] = p->v[ix[k]][i] - o[i];
                c[i] = p->v[ix[k + 1]][i] - o[i];
            }
            rd_cross(b, c, bxc);
            vol += rd_dot(a, bxc) / 6.0;
        }
    }
    return vol;
}

int rd_poly_check(const rd_poly *p, const char *what, int base, rd_error *err)
{
    int bad;
    return rd_poly_check_at(p, what, base, &bad, err);
}

int rd_poly_check_at(const rd_poly *p, const char *what, int base, int *bad, rd_error *err)
{
    *bad = -1;
    if (p->nv < 4 || p->nf < 4)
        return rd_error_set(err,
                            "%s: empty or too small mesh (%d vertices, %d faces; a closed "
                            "polyhedron needs at least 4 of each)",
                            what, p->nv, p->nf);
    if (check_indices(p, what, base, err)) return -1;
    double lo[3], hi[3], d[3];
    rd_copy3(p->v[0], lo);
    rd_copy3(p->v[0], hi);
    for (int i = 1; i < p->nv; i++)
        for (int k = 0; k < 3; k++) {
            lo[k] = fmin(lo[k], p->v[i][k]);
            hi[k] = fmax(hi[k], p->v[i][k]);
        }
    for (int k = 0; k < 3; k++) d[k] = hi[k] - lo[k];
    if (check_faces(p, what, base, rd_norm(d), bad, err) || check_edges(p, what, base, bad, err) ||
        check_used(p, what, base, err) || check_shells(p, what, base, bad, err))
        return -1;
    double vol = signed_volume(p);
    if (vol < 0)
        return rd_error_set(err, "%s: inside-out mesh (volume %.3g m^3); flip the face orientation",
                            what, vol);
    if (!(vol > 0)) return rd_error_set(err, "%s: mesh encloses no volume", what);
    return 0;
}
