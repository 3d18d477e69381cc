/* rockdem — terrain from a height grid (docs/RUNOUT.md): an ESRI ASCII grid (.asc) or gridded
 * XYZ points (.xyz: one "x y z" per line, every node of a rectilinear grid once, any order)
 * made into a closed solid a fixed body can be: the surface (two triangles per cell, split
 * along the same diagonal), vertical side walls down to a flat base one cell below the lowest
 * point, and the base as a fan about its centre. Cells are in metres; NODATA is refused.
 * Folder geometry/ owns shapes and their files; it may call base/ only.
 */
#include "geometry/terrain.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define RD_GRID_MAX_NODES 4000000 /* nodes of one grid (8e6 surface triangles) */

void rd_grid_free(rd_grid *g)
{
    free(g->x);
    free(g->y);
    free(g->z);
    memset(g, 0, sizeof *g);
}

static int grid_alloc(rd_grid *g, int nx, int ny, const char *path, rd_error *err)
{
    if (nx < 2 || ny < 2 || (double)nx * ny > RD_GRID_MAX_NODES)
        return rd_error_set(err,
                            "%s: a %d x %d grid (need 2 to %d nodes a side, at most %d in all)",
                            path, nx, ny, RD_GRID_MAX_NODES, RD_GRID_MAX_NODES);
    g->nx = nx;
    g->ny = ny;
    g->x = malloc((size_t)nx * sizeof *g->x);
    g->y = malloc((size_t)ny * sizeof *g->y);
    g->z = malloc((size_t)nx * ny * sizeof *g->z);
    if (!g->x || !g->y || !g->z) return rd_error_set(err, "%s: out of memory", path);
    return 0;
}

/* Next line of text from *p: [s, e) without its newline; the line number advances. */
static int next_line(const char **p, const char **s, const char **e, int *line)
{
    if (!**p) return 0;
    *s = *p;
    while (**p && **p != '\n') (*p)++;
    *e = *p;
    if (**p) (*p)++;
    (*line)++;
    return 1;
}

/* A number token in [*s, e): 0 and *s after it, or -1. */
static int number(const char **s, const char *e, double *v)
{
    while (*s < e && (isspace((unsigned char)**s) || **s == ',')) (*s)++;
    if (*s >= e) return -1;
    char *end;
    *v = strtod(*s, &end);
    if (end == *s || end > e || (end < e && !isspace((unsigned char)*end) && *end != ',') ||
        !isfinite(*v))
        return -1;
    *s = end;
    return 0;
}

static int blank(const char *s, const char *e)
{
    while (s < e && isspace((unsigned char)*s)) s++;
    return s == e || *s == '#';
}

/* ---- ESRI ASCII grid ---- */

enum {
    H_NCOLS,
    H_NROWS,
    H_XLLCORNER,
    H_YLLCORNER,
    H_XLLCENTER,
    H_YLLCENTER,
    H_CELLSIZE,
    H_NODATA,
    H_N
};

static int asc_header(const char *path, const char **p, int *line, double h[H_N], int seen[H_N],
                      rd_error *err)
{
    static const char *const names[H_N] = { "ncols",     "nrows",     "xllcorner", "yllcorner",
                                            "xllcenter", "yllcenter", "cellsize",  "nodata_value" };
    for (;;) {
        const char *q = *p, *s, *e;
        int l = *line;
        if (!next_line(&q, &s, &e, &l)) break;
        while (s < e && isspace((unsigned char)*s)) s++;
        if (s == e || !isalpha((unsigned char)*s)) break; /* the first row of heights */
        const char *w = s;
        while (s < e && !isspace((unsigned char)*s)) s++;
        int k = 0;
        while (k < H_N &&
               ((size_t)(s - w) != strlen(names[k]) || strncasecmp(w, names[k], (size_t)(s - w))))
            k++;
        double v;
        if (k == H_N)
            return rd_error_set(err,
                                "%s:%d: unknown ESRI grid header '%.*s' (expected ncols, nrows, "
                                "xllcorner|xllcenter, yllcorner|yllcenter, cellsize, NODATA_value)",
                                path, l, (int)(s - w), w);
        if (seen[k]) return rd_error_set(err, "%s:%d: '%s' given twice", path, l, names[k]);
        if (number(&s, e, &v) || !blank(s, e))
            return rd_error_set(err, "%s:%d: '%s' needs one number", path, l, names[k]);
        seen[k] = 1;
        h[k] = v;
        *p = q;
        *line = l;
    }
    if (!seen[H_NCOLS] || !seen[H_NROWS] || !seen[H_CELLSIZE] ||
        !(seen[H_XLLCORNER] ^ seen[H_XLLCENTER]) || !(seen[H_YLLCORNER] ^ seen[H_YLLCENTER]))
        return rd_error_set(err,
                            "%s: ESRI grid header incomplete (needs ncols, nrows, cellsize and "
                            "one of xllcorner/xllcenter and of yllcorner/yllcenter)",
                            path);
    if (!(h[H_CELLSIZE] > 0) || h[H_NCOLS] != floor(h[H_NCOLS]) || h[H_NROWS] != floor(h[H_NROWS]))
        return rd_error_set(err, "%s: ESRI grid: whole ncols and nrows and a cellsize > 0 needed",
                            path);
    return 0;
}

static int asc_read(const char *path, const char *buf, rd_grid *g, rd_error *err)
{
    double h[H_N] = { 0 };
    int seen[H_N] = { 0 }, line = 0;
    const char *p = buf;
    if (asc_header(path, &p, &line, h, seen, err)) return -1;
    int nx = (int)h[H_NCOLS], ny = (int)h[H_NROWS];
    if (grid_alloc(g, nx, ny, path, err)) return -1;
    /* heights sit at the cell centres */
    double c = h[H_CELLSIZE], x0 = seen[H_XLLCENTER] ? h[H_XLLCENTER] : h[H_XLLCORNER] + 0.5 * c;
    double y0 = seen[H_YLLCENTER] ? h[H_YLLCENTER] : h[H_YLLCORNER] + 0.5 * c;
    for (int i = 0; i < nx; i++) g->x[i] = x0 + i * c;
    for (int j = 0; j < ny; j++) g->y[j] = y0 + j * c;
    long n = 0, total = (long)nx * ny;
    const char *s, *e;
    while (n < total && next_line(&p, &s, &e, &line)) {
        double v;
        while (n < total && number(&s, e, &v) == 0) {
            if (seen[H_NODATA] && v == h[H_NODATA])
                return rd_error_set(err,
                                    "%s:%d: a NODATA cell (%g) at row %ld, column %ld: "
                                    "terrain needs every height (fill or crop the grid)",
                                    path, line, v, n / nx + 1, n % nx + 1);
            long row = n / nx, col = n % nx; /* rows run north to south */
            g->z[(size_t)(ny - 1 - row) * nx + col] = v;
            n++;
        }
        if (!blank(s, e))
            return rd_error_set(err, "%s:%d: '%.*s' is not a height", path, line,
                                (int)strcspn(s, " \t\r\n,"), s);
    }
    if (n < total)
        return rd_error_set(err, "%s: %ld heights for a %d x %d grid (%ld expected)", path, n, nx,
                            ny, total);
    while (next_line(&p, &s, &e, &line))
        if (!blank(s, e))
            return rd_error_set(err, "%s:%d: more heights than ncols x nrows", path, line);
    return 0;
}

/* ---- XYZ points ---- */

static int by_value(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Sorted distinct values of v[0..n) (equal within tol) into *out: their count. */
static int distinct(const double *v, long n, double tol, double **out)
{
    double *s = malloc((size_t)n * sizeof *s);
    if (!s) return -1;
    memcpy(s, v, (size_t)n * sizeof *s);
    qsort(s, (size_t)n, sizeof *s, by_value);
    int m = 0;
    for (long k = 0; k < n; k++)
        if (m == 0 || s[k] - s[m - 1] > tol) s[m++] = s[k];
    *out = s;
    return m;
}

static int find(const double *v, int n, double x, double tol)
{
    int lo = 0, hi = n - 1;
    while (lo <= hi) {
        int mid = (lo + hi) / 2;
        if (fabs(v[mid] - x) <= tol) return mid;
        if (v[mid] < x)
            lo = mid + 1;
        else
            hi = mid - 1;
    }
    return -1;
}

static int xyz_points(const char *path, const char *buf, double **pts, long *n, int **lines,
                      rd_error *err)
{
    long cap = 1024;
    *pts = malloc((size_t)cap * 3 * sizeof **pts);
    *lines = malloc((size_t)cap * sizeof **lines);
    *n = 0;
    const char *p = buf, *s, *e;
    int line = 0, oom = !*pts || !*lines;
    while (!oom && next_line(&p, &s, &e, &line)) {
        if (blank(s, e)) continue;
        double v[3];
        const char *q = s;
        if (number(&q, e, &v[0]) || number(&q, e, &v[1]) || number(&q, e, &v[2]) || !blank(q, e))
            return rd_error_set(err, "%s:%d: expected 'x y z' (three numbers)", path, line);
        if (*n == cap) {
            cap *= 2;
            double *np = realloc(*pts, (size_t)cap * 3 * sizeof **pts);
            int *nl = realloc(*lines, (size_t)cap * sizeof **lines);
            if (np) *pts = np;
            if (nl) *lines = nl;
            oom = !np || !nl;
            if (oom) break;
        }
        memcpy(*pts + 3 * *n, v, sizeof v);
        (*lines)[(*n)++] = line;
        if (*n > RD_GRID_MAX_NODES)
            return rd_error_set(err, "%s: more than %d points", path, RD_GRID_MAX_NODES);
    }
    if (oom) return rd_error_set(err, "%s: out of memory", path);
    return 0;
}

static int xyz_read(const char *path, const char *buf, rd_grid *g, rd_error *err)
{
    double *pts = NULL, *xs = NULL, *ys = NULL;
    int *lines = NULL, rc = -1;
    long n = 0;
    if (xyz_points(path, buf, &pts, &n, &lines, err)) goto out;
    if (n < 4) {
        rd_error_set(err, "%s: %ld points; a grid needs at least 2 x 2", path, n);
        goto out;
    }
    double *cx = malloc((size_t)n * sizeof *cx), *cy = malloc((size_t)n * sizeof *cy), span = 0;
    if (!cx || !cy) {
        free(cx);
        free(cy);
        rd_error_set(err, "%s: out of memory", path);
        goto out;
    }
    for (long k = 0; k < n; k++) {
        cx[k] = pts[3 * k];
        cy[k] = pts[3 * k + 1];
        span = fmax(span, fmax(fabs(cx[k]), fabs(cy[k])));
    }
    double tol = 1e-9 * (1 + span); /* the same node written with round-off */
    int nx = distinct(cx, n, tol, &xs), ny = distinct(cy, n, tol, &ys);
    free(cx);
    free(cy);
    if (nx < 0 || ny < 0) {
        rd_error_set(err, "%s: out of memory", path);
        goto out;
    }
    if ((long)nx * ny != n) {
        rd_error_set(err,
                     "%s: %ld points on %d distinct x and %d distinct y: not one point per "
                     "node of a grid (scattered points must be gridded first, e.g. with "
                     "scipy.interpolate.griddata)",
                     path, n, nx, ny);
        goto out;
    }
    if (grid_alloc(g, nx, ny, path, err)) goto out;
    memcpy(g->x, xs, (size_t)nx * sizeof *xs);
    memcpy(g->y, ys, (size_t)ny * sizeof *ys);
    for (long k = 0; k < (long)nx * ny; k++) g->z[k] = NAN;
    for (long k = 0; k < n; k++) {
        int i = find(xs, nx, pts[3 * k], tol), j = find(ys, ny, pts[3 * k + 1], tol);
        double *z = &g->z[(size_t)j * nx + i];
        if (!isnan(*z)) {
            rd_error_set(err, "%s:%d: node (%g, %g) given twice", path, lines[k], pts[3 * k],
                         pts[3 * k + 1]);
            goto out;
        }
        *z = pts[3 * k + 2];
    }
    rc = 0;
out:
    free(pts);
    free(lines);
    free(xs);
    free(ys);
    return rc;
}

int rd_grid_read(const char *path, const char *buf, rd_grid *g, rd_error *err)
{
    const char *dot = strrchr(path, '.');
    memset(g, 0, sizeof *g);
    int rc =
        dot && !strcasecmp(dot, ".asc") ? asc_read(path, buf, g, err) : xyz_read(path, buf, g, err);
    if (rc) rd_grid_free(g);
    return rc;
}

/* ---- the solid ---- */

int rd_grid_solid(const rd_grid *g, rd_grid_mesh *m, rd_error *err)
{
    int nx = g->nx, ny = g->ny, nb = 2 * (nx - 1) + 2 * (ny - 1); /* boundary nodes */
    double zmin = INFINITY, cell = INFINITY;
    for (long k = 0; k < (long)nx * ny; k++) zmin = fmin(zmin, g->z[k]);
    for (int i = 0; i + 1 < nx; i++) cell = fmin(cell, g->x[i + 1] - g->x[i]);
    for (int j = 0; j + 1 < ny; j++) cell = fmin(cell, g->y[j + 1] - g->y[j]);
    double base = zmin - cell;
    m->nv = nx * ny + nb + 1;
    m->ntri = 2 * (nx - 1) * (ny - 1) + 2 * nb + nb;
    m->v = malloc((size_t)m->nv * sizeof *m->v);
    m->tri = malloc((size_t)m->ntri * sizeof *m->tri);
    if (!m->v || !m->tri) return rd_error_set(err, "out of memory for the terrain solid");
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) {
            double *v = m->v[j * nx + i];
            v[0] = g->x[i];
            v[1] = g->y[j];
            v[2] = g->z[(size_t)j * nx + i];
        }
    int t = 0;
    for (int j = 0; j + 1 < ny; j++)
        for (int i = 0; i + 1 < nx; i++) { /* counter-clockwise from above: normal up */
            int a = j * nx + i, b = a + 1, c = a + nx + 1, d = a + nx;
            m->tri[t][0] = a, m->tri[t][1] = b, m->tri[t++][2] = c;
            m->tri[t][0] = a, m->tri[t][1] = c, m->tri[t++][2] = d;
        }
    /* the boundary counter-clockwise from above: south, east, north, west */
    int *ring = malloc((size_t)nb * sizeof *ring), r = 0;
    if (!ring) return rd_error_set(err, "out of memory for the terrain solid");
    for (int i = 0; i + 1 < nx; i++) ring[r++] = i;
    for (int j = 0; j + 1 < ny; j++) ring[r++] = j * nx + nx - 1;
    for (int i = nx - 1; i > 0; i--) ring[r++] = (ny - 1) * nx + i;
    for (int j = ny - 1; j > 0; j--) ring[r++] = j * nx;
    int b0 = nx * ny, centre = b0 + nb;
    for (int k = 0; k < nb; k++) {
        memcpy(m->v[b0 + k], m->v[ring[k]], sizeof m->v[0]);
        m->v[b0 + k][2] = base;
    }
    m->v[centre][0] = 0.5 * (g->x[0] + g->x[nx - 1]);
    m->v[centre][1] = 0.5 * (g->y[0] + g->y[ny - 1]);
    m->v[centre][2] = base;
    for (int k = 0; k < nb; k++) { /* wall quad (top k, top k+1, base k+1, base k), outward */
        int k1 = (k + 1) % nb, ta = ring[k], tb = ring[k1], ba = b0 + k, bb = b0 + k1;
        m->tri[t][0] = ta, m->tri[t][1] = ba, m->tri[t++][2] = bb;
        m->tri[t][0] = ta, m->tri[t][1] = bb, m->tri[t++][2] = tb;
        m->tri[t][0] = centre, m->tri[t][1] = bb, m->tri[t++][2] = ba; /* base, facing down */
    }
    free(ring);
    return 0;
}

void rd_grid_mesh_free(rd_grid_mesh *m)
{
    free(m->v);
    free(m->tri);
    memset(m, 0, sizeof *m);
}
