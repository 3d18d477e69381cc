/* rockdem — convex polyhedra, their mass properties and subcontact points.
 * Folder geometry/ owns solids, their mass properties, subcontact points and assembly builders;
 * it may call base/ only.
 */
#include "geometry/geom.h"
#include "base/vec.h"

#include <gsl/gsl_eigen.h>
#include <gsl/gsl_matrix.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static void poly_zero(rd_poly *p) { memset(p, 0, sizeof *p); }

void rd_poly_free(rd_poly *p)
{
    if (!p) return;
    free(p->v);
    free(p->fstart);
    free(p->flen);
    free(p->fidx);
    free(p->fn);
    free(p->fd);
    free(p->tri);
    poly_zero(p);
}

static void tri_normal(const double a[3], const double b[3], const double c[3], double n[3])
{
    double u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
    double w[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
    rd_cross(u, w, n); /* |n| = twice the triangle area */
}

/* Twice the vector area of face f (sum of its fan triangles' cross products). */
static void area_vector(const rd_poly *p, int f, double n[3])
{
    const int *ix = p->fidx + p->fstart[f];
    n[0] = n[1] = n[2] = 0;
    for (int k = 1; k + 1 < p->flen[f]; k++) {
        double tn[3];
        tri_normal(p->v[ix[0]], p->v[ix[k]], p->v[ix[k + 1]], tn);
        rd_axpy(1.0, tn, n);
    }
}

void rd_poly_update(rd_poly *p)
{
    int t = 0;
    p->radius = 0;
    for (int i = 0; i < p->nv; i++) {
        double r = rd_norm(p->v[i]);
        if (r > p->radius) p->radius = r;
    }
    for (int f = 0; f < p->nf; f++) {
        const int *ix = p->fidx + p->fstart[f];
        double n[3];
        area_vector(p, f, n);
        for (int k = 1; k + 1 < p->flen[f]; k++) {
            p->tri[t][0] = ix[0];
            p->tri[t][1] = ix[k];
            p->tri[t][2] = ix[k + 1];
            t++;
        }
        double len = rd_norm(n);
        for (int i = 0; i < 3; i++) p->fn[f][i] = n[i] / len;
        p->fd[f] = rd_dot(p->fn[f], p->v[ix[0]]);
    }
    p->ntri = t;
}

int rd_poly_alloc(rd_poly *p, int nv, int nf, int nidx, rd_error *err)
{
    poly_zero(p);
    p->nv = nv;
    p->nf = nf;
    p->v = calloc((size_t)nv, sizeof *p->v);
    p->fstart = calloc((size_t)nf, sizeof *p->fstart);
    p->flen = calloc((size_t)nf, sizeof *p->flen);
    p->fidx = calloc((size_t)nidx, sizeof *p->fidx);
    p->fn = calloc((size_t)nf, sizeof *p->fn);
    p->fd = calloc((size_t)nf, sizeof *p->fd);
    p->tri = calloc((size_t)(nidx - 2 * nf), sizeof *p->tri);
    if (!p->v || !p->fstart || !p->flen || !p->fidx || !p->fn || !p->fd || !p->tri) {
        rd_poly_free(p);
        return rd_error_set(err, "out of memory building a polyhedron");
    }
    return 0;
}

int rd_poly_brick(rd_poly *p, const double size[3], rd_error *err)
{
    static const int faces[6][4] = {
        { 0, 2, 3, 1 }, /* -z: bottom */ { 4, 5, 7, 6 }, /* +z: top */
        { 0, 1, 5, 4 }, /* -y */ { 2, 6, 7, 3 },         /* +y */
        { 0, 4, 6, 2 }, /* -x */ { 1, 3, 7, 5 }          /* +x */
    };
    if (rd_poly_alloc(p, 8, 6, 24, err)) return -1;
    for (int i = 0; i < 8; i++) {
        p->v[i][0] = (i & 1 ? 0.5 : -0.5) * size[0];
        p->v[i][1] = (i & 2 ? 0.5 : -0.5) * size[1];
        p->v[i][2] = (i & 4 ? 0.5 : -0.5) * size[2];
    }
    for (int f = 0; f < 6; f++) {
        p->fstart[f] = 4 * f;
        p->flen[f] = 4;
        memcpy(p->fidx + 4 * f, faces[f], sizeof faces[f]);
    }
    rd_poly_update(p);
    return 0;
}

/* Volume integrals over tetrahedra (origin, a, b, c) of each surface triangle:
 * V = a.(b x c)/6 and second moments  int x_i x_j dV = V/20 (sum_k a_i a_j + s_i s_j),
 * s = a + b + c (exact for a tetrahedron with one vertex at the origin). */
int rd_poly_mass(const rd_poly *p, rd_mass *m, rd_error *err)
{
    double vol = 0, c[3] = { 0, 0, 0 }, s2[9] = { 0 };
    for (int t = 0; t < p->ntri; t++) {
        const double *a = p->v[p->tri[t][0]], *b = p->v[p->tri[t][1]], *d = p->v[p->tri[t][2]];
        double bxd[3];
        rd_cross(b, d, bxd);
        double v6 = rd_dot(a, bxd) / 6.0;
        double s[3] = { a[0] + b[0] + d[0], a[1] + b[1] + d[1], a[2] + b[2] + d[2] };
        vol += v6;
        rd_axpy(v6 / 4.0, s, c);
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++)
                s2[3 * i + j] +=
                    v6 / 20.0 * (a[i] * a[j] + b[i] * b[j] + d[i] * d[j] + s[i] * s[j]);
    }
    if (!(vol > 0))
        return rd_error_set(err, "polyhedron has non-positive volume %g (inside out?)", vol);
    for (int i = 0; i < 3; i++) c[i] /= vol;
    double cov[9];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) cov[3 * i + j] = s2[3 * i + j] - vol * c[i] * c[j];
    double tr = cov[0] + cov[4] + cov[8];
    m->volume = vol;
    rd_copy3(c, m->centroid);
    for (int i = 0; i < 9; i++) m->inertia[i] = (i % 4 == 0 ? tr : 0.0) - cov[i];

    gsl_matrix_view A =
        gsl_matrix_view_array(memcpy((double[9]){ 0 }, m->inertia, sizeof m->inertia), 3, 3);
    gsl_vector *eval = gsl_vector_alloc(3);
    gsl_matrix *evec = gsl_matrix_alloc(3, 3);
    gsl_eigen_symmv_workspace *w = gsl_eigen_symmv_alloc(3);
    gsl_eigen_symmv(&A.matrix, eval, evec, w);
    gsl_eigen_symmv_sort(eval, evec, GSL_EIGEN_SORT_VAL_ASC);
    for (int i = 0; i < 3; i++) {
        m->principal[i] = gsl_vector_get(eval, i);
        for (int j = 0; j < 3; j++) m->axes[3 * i + j] = gsl_matrix_get(evec, i, j);
    }
    gsl_eigen_symmv_free(w);
    gsl_matrix_free(evec);
    gsl_vector_free(eval);
    /* keep a right-handed frame, and prefer axes close to the input axes (a brick keeps its
       own axes up to sign): flip each column to have a non-negative largest component */
    for (int j = 0; j < 3; j++) {
        int big = 0;
        for (int i = 1; i < 3; i++)
            if (fabs(m->axes[3 * i + j]) > fabs(m->axes[3 * big + j])) big = i;
        if (m->axes[3 * big + j] < 0)
            for (int i = 0; i < 3; i++) m->axes[3 * i + j] = -m->axes[3 * i + j];
    }
    double c0[3] = { m->axes[0], m->axes[3], m->axes[6] },
           c1[3] = { m->axes[1], m->axes[4], m->axes[7] };
    double c2[3];
    rd_cross(c0, c1, c2);
    for (int i = 0; i < 3; i++) m->axes[3 * i + 2] = c2[i];
    return 0;
}

void rd_poly_to_frame(rd_poly *p, const rd_mass *m)
{
    for (int i = 0; i < p->nv; i++) {
        double d[3] = { p->v[i][0] - m->centroid[0], p->v[i][1] - m->centroid[1],
                        p->v[i][2] - m->centroid[2] };
        rd_mat_tvec(m->axes, d, p->v[i]);
    }
    rd_poly_update(p);
}

double rd_poly_face_area(const rd_poly *p, int f)
{
    double n[3];
    area_vector(p, f, n);
    return 0.5 * rd_norm(n);
}

/* Growable point list used while meshing one face (setup only). A point within tol of an
 * earlier one merges into it (their areas add); the earlier points are found through a hash of
 * cells of size tol (the 27 cells around a point hold every point within tol of it), so a face
 * of a million points meshes in linear time, not quadratic. */
typedef struct pts {
    double (*x)[3];
    double *a;
    int n, cap;
    double tol, tol2;
    int *head, *next;
    size_t nbucket; /* hash chains: head[bucket], next[point]; -1 ends */
} pts;

/* Hash of the cell (ix, iy, iz) into s->nbucket (a power of two) buckets. */
static size_t pts_bucket(const pts *s, const long long c[3])
{
    unsigned long long h = (unsigned long long)c[0] * 73856093ULL ^
                           (unsigned long long)c[1] * 19349663ULL ^
                           (unsigned long long)c[2] * 83492791ULL;
    return (size_t)(h & (s->nbucket - 1));
}

#define PTS_CELL_MAX 1e18 /* |cell index| kept inside a long long (reached only past 1e9 radii) */

static void pts_cell(const pts *s, const double x[3], long long c[3])
{
    for (int k = 0; k < 3; k++)
        c[k] = (long long)fmax(-PTS_CELL_MAX, fmin(PTS_CELL_MAX, floor(x[k] / s->tol)));
}

/* First point (lowest index) within tol of x, or -1. */
static int pts_find(const pts *s, const double x[3])
{
    long long c[3], d[3];
    int best = -1;
    pts_cell(s, x, c);
    for (d[0] = c[0] - 1; d[0] <= c[0] + 1; d[0]++)
        for (d[1] = c[1] - 1; d[1] <= c[1] + 1; d[1]++)
            for (d[2] = c[2] - 1; d[2] <= c[2] + 1; d[2]++)
                for (int i = s->head[pts_bucket(s, d)]; i >= 0; i = s->next[i]) {
                    double e[3] = { s->x[i][0] - x[0], s->x[i][1] - x[1], s->x[i][2] - x[2] };
                    if (rd_dot(e, e) <= s->tol2 && (best < 0 || i < best)) best = i;
                }
    return best;
}

/* Point i into its bucket's chain. */
static void pts_link(pts *s, int i)
{
    long long c[3];
    pts_cell(s, s->x[i], c);
    size_t b = pts_bucket(s, c);
    s->next[i] = s->head[b];
    s->head[b] = i;
}

/* Room for twice the points, the hash rebuilt at twice the buckets. 0 or -1. */
static int pts_grow(pts *s)
{
    int cap = s->cap ? 2 * s->cap : 64;
    double(*nx)[3] = realloc(s->x, (size_t)cap * sizeof *nx);
    if (!nx) return -1;
    s->x = nx;
    double *na = realloc(s->a, (size_t)cap * sizeof *na);
    if (!na) return -1;
    s->a = na;
    int *nn = realloc(s->next, (size_t)cap * sizeof *nn);
    if (!nn) return -1;
    s->next = nn;
    free(s->head);
    s->nbucket = 2 * (size_t)cap;
    if (!(s->head = malloc(s->nbucket * sizeof *s->head))) return -1;
    for (size_t b = 0; b < s->nbucket; b++) s->head[b] = -1;
    s->cap = cap;
    for (int i = 0; i < s->n; i++) pts_link(s, i);
    return 0;
}

static int pts_add(pts *s, const double x[3], double area)
{
    int i = s->n ? pts_find(s, x) : -1;
    if (i >= 0) {
        s->a[i] += area;
        return 0;
    }
    if (s->n == s->cap && pts_grow(s)) return -1;
    rd_copy3(x, s->x[s->n]);
    s->a[s->n] = area;
    pts_link(s, s->n++);
    return 0;
}

/* Grid point (i, j) of triangle (a, b, c) subdivided n times. */
static void grid_point(const double a[3], const double b[3], const double c[3], int n, int i, int j,
                       double out[3])
{
    for (int k = 0; k < 3; k++) out[k] = a[k] + (b[k] - a[k]) * i / n + (c[k] - a[k]) * j / n;
}

static int mesh_triangle(pts *s, const double a[3], const double b[3], const double c[3],
                         double spacing)
{
    double e[3][3], tn[3];
    for (int k = 0; k < 3; k++) {
        e[0][k] = b[k] - a[k];
        e[1][k] = c[k] - b[k];
        e[2][k] = a[k] - c[k];
    }
    double lmax = fmax(rd_norm(e[0]), fmax(rd_norm(e[1]), rd_norm(e[2])));
    int n = spacing > 0 ? (int)ceil(lmax / spacing - 1e-9) : 1;
    if (n < 1) n = 1;
    tri_normal(a, b, c, tn);
    double sub = 0.5 * rd_norm(tn) / ((double)n * n) / 3.0; /* a third of a sub-triangle */
    for (int i = 0; i < n; i++)
        for (int j = 0; i + j < n; j++) {
            int tri[2][3][2] = { { { i, j }, { i + 1, j }, { i, j + 1 } },
                                 { { i + 1, j }, { i + 1, j + 1 }, { i, j + 1 } } };
            int ntri = (i + j < n - 1) ? 2 : 1;
            for (int t = 0; t < ntri; t++)
                for (int v = 0; v < 3; v++) {
                    double x[3];
                    grid_point(a, b, c, n, tri[t][v][0], tri[t][v][1], x);
                    if (pts_add(s, x, sub)) return -1;
                }
        }
    return 0;
}

/* Is face f a parallelogram (v0 + v2 = v1 + v3)? */
static int is_parallelogram(const rd_poly *p, int f, double tol)
{
    if (p->flen[f] != 4) return 0;
    const int *ix = p->fidx + p->fstart[f];
    for (int k = 0; k < 3; k++)
        if (fabs(p->v[ix[0]][k] + p->v[ix[2]][k] - p->v[ix[1]][k] - p->v[ix[3]][k]) > tol) return 0;
    return 1;
}

/* Parallelogram face: a structured nu x nv grid (spacing <= `spacing` along both sides); each
 * node takes a quarter of every cell around it (bilinear elements, the trapezoidal rule), so
 * the point set is symmetric — corner mode gives four points of A/4 each. */
static int mesh_grid(pts *s, const double *o, const double *a, const double *b, double spacing)
{
    double e1[3], e2[3], cr[3];
    for (int k = 0; k < 3; k++) {
        e1[k] = a[k] - o[k];
        e2[k] = b[k] - o[k];
    }
    int nu = spacing > 0 ? (int)ceil(rd_norm(e1) / spacing - 1e-9) : 1;
    int nv = spacing > 0 ? (int)ceil(rd_norm(e2) / spacing - 1e-9) : 1;
    if (nu < 1) nu = 1;
    if (nv < 1) nv = 1;
    rd_cross(e1, e2, cr);
    double cell = rd_norm(cr) / ((double)nu * nv);
    for (int i = 0; i <= nu; i++)
        for (int j = 0; j <= nv; j++) {
            double x[3];
            for (int k = 0; k < 3; k++) x[k] = o[k] + e1[k] * i / nu + e2[k] * j / nv;
            double w = (i == 0 || i == nu ? 0.5 : 1.0) * (j == 0 || j == nv ? 0.5 : 1.0);
            if (pts_add(s, x, w * cell)) return -1;
        }
    return 0;
}

/* Area centroid of face f. */
static void face_centroid(const rd_poly *p, int f, double c[3])
{
    const int *ix = p->fidx + p->fstart[f];
    double a = 0;
    c[0] = c[1] = c[2] = 0;
    for (int k = 1; k + 1 < p->flen[f]; k++) {
        double tn[3];
        tri_normal(p->v[ix[0]], p->v[ix[k]], p->v[ix[k + 1]], tn);
        double t = rd_norm(tn);
        for (int j = 0; j < 3; j++)
            c[j] += t * (p->v[ix[0]][j] + p->v[ix[k]][j] + p->v[ix[k + 1]][j]) / 3;
        a += t;
    }
    for (int j = 0; j < 3; j++) c[j] /= a;
}

/* Other polygons: triangles from the face centroid to each edge (a uniform fan), refined so
 * no edge exceeds the spacing; without spacing, each vertex takes half of the two centroid
 * triangles beside it (a triangle: one third of its area per vertex, 3DEC's rule). */
static int mesh_polygon(pts *s, const rd_poly *p, int f, double spacing)
{
    const int *ix = p->fidx + p->fstart[f];
    int n = p->flen[f];
    double c[3];
    face_centroid(p, f, c);
    for (int k = 0; k < n; k++) {
        const double *a = p->v[ix[k]], *b = p->v[ix[(k + 1) % n]];
        if (spacing > 0) {
            if (mesh_triangle(s, c, a, b, spacing)) return -1;
            continue;
        }
        double tn[3];
        tri_normal(c, a, b, tn);
        double half = 0.25 * rd_norm(tn); /* half of the triangle's area */
        if (pts_add(s, a, half) || pts_add(s, b, half)) return -1;
    }
    return 0;
}

static double dist(const double a[3], const double b[3])
{
    double d[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
    return rd_norm(d);
}

/* Divisions of an edge of length len at the spacing (1 without spacing), as a double: the
 * count a spacing far below the face's size asks for may pass any int. */
static double divisions(double len, double spacing)
{
    return spacing > 0 ? fmax(1.0, ceil(len / spacing - 1e-9)) : 1.0;
}

double rd_poly_face_points_bound(const rd_poly *p, int f, double spacing)
{
    const int *ix = p->fidx + p->fstart[f];
    int n = p->flen[f];
    double tol = 1e-9 * (p->radius > 0 ? p->radius : 1.0);
    if (is_parallelogram(p, f, tol)) {
        double nu = divisions(dist(p->v[ix[0]], p->v[ix[1]]), spacing);
        double nv = divisions(dist(p->v[ix[0]], p->v[ix[3]]), spacing);
        return (nu + 1) * (nv + 1);
    }
    if (!(spacing > 0)) return n;
    double c[3], total = 0;
    face_centroid(p, f, c);
    for (int k = 0; k < n; k++) {
        const double *a = p->v[ix[k]], *b = p->v[ix[(k + 1) % n]];
        double m = divisions(fmax(dist(c, a), fmax(dist(a, b), dist(b, c))), spacing);
        total += (m + 1) * (m + 2) / 2; /* the nodes of a triangle split m times */
    }
    return total;
}

int rd_poly_face_points(const rd_poly *p, int f, double spacing, double (*xyz)[3], double *area,
                        int cap)
{
    const int *ix = p->fidx + p->fstart[f];
    pts s = { 0 };
    s.tol = 1e-9 * (p->radius > 0 ? p->radius : 1.0);
    s.tol2 = s.tol * s.tol;
    double tol = s.tol;
    int rc = 0;
    if (is_parallelogram(p, f, tol))
        rc = mesh_grid(&s, p->v[ix[0]], p->v[ix[1]], p->v[ix[3]], spacing);
    else
        rc = mesh_polygon(&s, p, f, spacing);
    int n = rc ? -1 : s.n;
    if (n > 0 && cap > 0) {
        if (n > cap)
            n = -1;
        else {
            memcpy(xyz, s.x, (size_t)n * sizeof *xyz);
            memcpy(area, s.a, (size_t)n * sizeof *area);
        }
    }
    free(s.x);
    free(s.a);
    free(s.next);
    free(s.head);
    return n;
}
