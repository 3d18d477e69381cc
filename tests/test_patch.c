/* The contact patch's geometry (src/contact/patch.c) against closed forms (issue 39, item 1).
 *
 *  - polygon moments of a rectangle: integrals of 1, x, y, x^2, x y, y^2 by hand;
 *  - an affine depth over a rectangle, wholly and partly compressed (a rocking block's base: the
 *    compressed strip of d = delta - theta x ends at x* = delta / theta), force and both moments
 *    by hand;
 *  - the twisting lever of a uniform pressure, the integral of |r| over a square of side a about
 *    its centre, a^3 (sqrt 2 + ln(1 + sqrt 2)) / 6, and over a regular N-gon of apothem h (polar
 *    coordinates: N h^3 (sec b tan b + ln(sec b + tan b)) / 3, b = pi / N); for an affine
 *    pressure about an off-centre point, a midpoint-rule sum on a grid, whose error bound is its
 *    own change from n to 2n cells a side (second order: the finer sum's error is about a third
 *    of that change);
 *  - tessellation: a square face as one quad, 2 and 200 triangles against one reference face
 *    gives the same force, moments, energy and (about the common centroid) twisting lever to
 *    round-off;
 *  - rd_patch_faces: a square face half over a reference face's edge, and a tilted face;
 *  - rd_patch_cells: a rectangle cut into 2 n^2 triangles (interior vertices on the grid, and
 *    moved off it) and an L of six triangles merged into convex cells whose moments are the
 *    region's to round-off;
 *  - rd_patch_torsion_bound: between 0 and the twisting lever on the square, the 12-gon and an
 *    affine pressure off the centre (the inequality |r - c| >= |r - c|^2 / rmax), and on the
 *    square its closed-form ratio sqrt 2 / (sqrt 2 + ln(1 + sqrt 2)) = 0.616;
 *  - rd_patch_torsion_disc: likewise, also under a wedge of pressure, and on the square its
 *    closed-form ratio 4 / (sqrt(3 pi) (sqrt 2 + ln(1 + sqrt 2))) = 0.568;
 *  - rd_plane_group: the same planes, face by face, as the first-fit scan of every plane, on
 *    faces scattered about a few planes across the tolerances' edges (normals turned by up to
 *    twice the angle tolerance, offsets moved by up to twice dtol: both sides of both bounds).
 * Round-off tolerance: 1e-12 relative (sums of a few hundred terms of order 1). */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "check.h"
#include "contact/contact.h"

#define ROUNDOFF 1e-12

static rd_poly2 rect(double x0, double y0, double x1, double y1)
{
    rd_poly2 p = { 4, { { x0, y0 }, { x1, y0 }, { x1, y1 }, { x0, y1 } } };
    return p;
}

static void test_moments_rectangle(void **state)
{
    (void)state;
    const double x0 = 0.3, y0 = -0.2, x1 = 1.1, y1 = 0.45;
    rd_poly2 p = rect(x0, y0, x1, y1);
    rd_moments m;
    rd_patch_moments(&p, &m);
    const double w = x1 - x0, h = y1 - y0;
    rd_check_rel("rectangle area (m^2)", m.a, w * h, ROUNDOFF, RD_STRICT);
    rd_check_rel("rectangle Sx (m^3)", m.sx, h * (x1 * x1 - x0 * x0) / 2, ROUNDOFF, RD_STRICT);
    rd_check_rel("rectangle Sy (m^3)", m.sy, w * (y1 * y1 - y0 * y0) / 2, ROUNDOFF, RD_STRICT);
    rd_check_rel("rectangle Sxx (m^4)", m.sxx, h * (pow(x1, 3) - pow(x0, 3)) / 3, ROUNDOFF,
                 RD_STRICT);
    rd_check_rel("rectangle Syy (m^4)", m.syy, w * (pow(y1, 3) - pow(y0, 3)) / 3, ROUNDOFF,
                 RD_STRICT);
    rd_check_rel("rectangle Sxy (m^4)", m.sxy, (x1 * x1 - x0 * x0) * (y1 * y1 - y0 * y0) / 4,
                 ROUNDOFF, RD_STRICT);
}

/* d = d0 + gx x + gy y > 0 everywhere on [0, L] x [0, W]. */
static void test_load_affine_compressed(void **state)
{
    (void)state;
    const double L = 0.5, W = 0.4, d0 = 1e-4, gx = 2e-5, gy = -1e-4;
    rd_poly2 p = rect(0, 0, L, W);
    rd_patch_load ld;
    rd_patch_load_of(&p, d0, gx, gy, &ld, NULL);
    double f = d0 * L * W + gx * L * L * W / 2 + gy * L * W * W / 2;
    double mx = d0 * L * L * W / 2 + gx * L * L * L * W / 3 + gy * L * L * W * W / 4;
    double my = d0 * L * W * W / 2 + gx * L * L * W * W / 4 + gy * L * W * W * W / 3;
    rd_check_rel("affine force / KN (m^3)", ld.f, f, ROUNDOFF, RD_STRICT);
    rd_check_rel("affine x-moment / KN (m^4)", ld.mx, mx, ROUNDOFF, RD_STRICT);
    rd_check_rel("affine y-moment / KN (m^4)", ld.my, my, ROUNDOFF, RD_STRICT);
    rd_check_rel("compressed area (m^2)", ld.area, L * W, ROUNDOFF, RD_STRICT);
    rd_check_rel("polar moment about the centroid (m^4)", ld.polar, L * W * (L * L + W * W) / 12,
                 ROUNDOFF, RD_STRICT);
}

/* A rocking block's base: d = delta - theta x on [0, L] x [0, W], compressed on [0, x*]. */
static void test_load_rocking_base(void **state)
{
    (void)state;
    const double L = 0.5, W = 0.5, delta = 3e-5, theta = 1e-3, xs = delta / theta;
    rd_poly2 p = rect(0, 0, L, W);
    rd_patch_load ld;
    rd_patch_load_of(&p, delta, -theta, 0.0, &ld, NULL);
    rd_check_rel("rocking base: compressed area (m^2)", ld.area, W * xs, ROUNDOFF, RD_STRICT);
    rd_check_rel("rocking base: force / KN (m^3)", ld.f, W * delta * xs / 2, ROUNDOFF, RD_STRICT);
    rd_check_rel("rocking base: x-moment / KN (m^4)", ld.mx, W * delta * xs * xs / 6, ROUNDOFF,
                 RD_STRICT);
    rd_check_rel("rocking base: energy integral (m^4)", ld.e2, W * delta * delta * xs / 3, ROUNDOFF,
                 RD_STRICT);
    rd_patch_load open;
    rd_patch_load_of(&p, -1e-6, -theta, 0.0, &open, NULL);
    assert_true(open.area == 0 && open.f == 0);
}

static void test_torsion_square(void **state)
{
    (void)state;
    const double a = 0.5;
    rd_poly2 p = rect(-a / 2, -a / 2, a / 2, a / 2);
    rd_patch_load ld;
    rd_patch_load_of(&p, 1.0, 0.0, 0.0, &ld, NULL);
    double want = a * a * a * (sqrt(2.0) + log(1 + sqrt(2.0))) / 6;
    rd_check_rel("square: integral of |r| (m^3)", ld.tors, want, ROUNDOFF, RD_STRICT);
    /* the mean lever, a (sqrt 2 + ln(1 + sqrt 2)) / 6 = 0.38260 a */
    rd_check_rel("square: mean |r| / a", ld.tors / ld.area / a,
                 (sqrt(2.0) + log(1 + sqrt(2.0))) / 6, ROUNDOFF, RD_STRICT);
}

static void test_torsion_regular_polygon(void **state)
{
    (void)state;
    const int nsides[3] = { 3, 12, 64 };
    for (int k = 0; k < 3; k++) {
        const int N = nsides[k];
        const double R = 0.7, b = M_PI / N, h = R * cos(b);
        rd_poly2 p = { N, { { 0 } } };
        for (int i = 0; i < N; i++) {
            p.p[i][0] = R * cos(2 * b * i);
            p.p[i][1] = R * sin(2 * b * i);
        }
        const double c[2] = { 0, 0 };
        double got = rd_patch_torsion(&p, c, 1.0, 0.0, 0.0);
        double want = N * h * h * h * (tan(b) / cos(b) + log(1 / cos(b) + tan(b))) / 3;
        rd_check_rel("regular polygon: integral of |r| (m^3)", got, want, ROUNDOFF, RD_STRICT);
    }
}

/* Midpoint sum of (d0 + gx x + gy y) |r - c| on n x n cells of the rectangle. */
static double grid_torsion(double x0, double y0, double x1, double y1, int n, const double c[2],
                           double d0, double gx, double gy)
{
    double hx = (x1 - x0) / n, hy = (y1 - y0) / n, sum = 0;
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) {
            double x = x0 + (i + 0.5) * hx, y = y0 + (j + 0.5) * hy;
            sum += (d0 + gx * x + gy * y) * hypot(x - c[0], y - c[1]);
        }
    return sum * hx * hy;
}

static void test_torsion_affine_grid(void **state)
{
    (void)state;
    const double x0 = -0.2, y0 = -0.1, x1 = 0.3, y1 = 0.35, d0 = 1.0, gx = 0.8, gy = -1.1;
    const double c[2] = { 0.05, 0.02 };
    rd_poly2 p = rect(x0, y0, x1, y1);
    double got = rd_patch_torsion(&p, c, d0, gx, gy);
    double coarse = grid_torsion(x0, y0, x1, y1, 500, c, d0, gx, gy);
    double fine = grid_torsion(x0, y0, x1, y1, 1000, c, d0, gx, gy);
    double bound = fabs(fine - coarse); /* second order: the finer sum's error is ~ a third of it */
    rd_check_abs("affine pressure: integral of d |r - c| against the grid (m^4)", got, fine, bound,
                 RD_STRICT);
}

/* A square face of side a as 1 quad, 2 and 200 triangles, each against the same reference face:
 * the loads summed, and the twisting lever about the pieces' common centroid. */
static void square_pieces(int pieces, double a, double d0, double gx, double gy, double out[8])
{
    rd_poly2 tri[200];
    int n = 0;
    if (pieces == 1) {
        tri[n++] = rect(-a / 2, -a / 2, a / 2, a / 2);
    } else {
        int cells = pieces == 2 ? 1 : 10;
        double hh = a / cells;
        for (int i = 0; i < cells; i++)
            for (int j = 0; j < cells; j++) {
                double xa = -a / 2 + i * hh, ya = -a / 2 + j * hh, xb = xa + hh, yb = ya + hh;
                tri[n++] = (rd_poly2){ 3, { { xa, ya }, { xb, ya }, { xb, yb } } };
                tri[n++] = (rd_poly2){ 3, { { xa, ya }, { xb, yb }, { xa, yb } } };
            }
    }
    rd_poly2 comp[200];
    double area = 0, sx = 0, sy = 0;
    for (int k = 0; k < 8; k++) out[k] = 0;
    for (int k = 0; k < n; k++) {
        rd_patch_load ld;
        rd_patch_load_of(&tri[k], d0, gx, gy, &ld, &comp[k]);
        out[0] += ld.area;
        out[1] += ld.f;
        out[2] += ld.mx;
        out[3] += ld.my;
        out[4] += ld.e2;
        out[5] += ld.polar + ld.area * (ld.cx * ld.cx + ld.cy * ld.cy); /* about the origin */
        area += ld.area;
        sx += ld.area * ld.cx;
        sy += ld.area * ld.cy;
    }
    const double c[2] = { sx / area, sy / area };
    for (int k = 0; k < n; k++)
        if (comp[k].n) out[6] += rd_patch_torsion(&comp[k], c, d0, gx, gy);
    /* the same over the pieces' union boundary (shared edges cancel) */
    rd_poly2 live[200];
    int nl = 0;
    for (int k = 0; k < n; k++)
        if (comp[k].n) live[nl++] = comp[k];
    rd_patch_scratch sc = { 0, NULL, NULL, NULL };
    out[7] = rd_patch_torsion_set(live, nl, c, d0, gx, gy, &sc);
    free(sc.slot);
    free(sc.count);
    free(sc.ends);
}

static void test_tessellation(void **state)
{
    (void)state;
    const char *what[8] = { "area",           "force",
                            "x-moment",       "y-moment",
                            "energy",         "polar moment",
                            "twisting lever", "twisting lever over the union's boundary" };
    /* a rocking base, compressed over part of it (the zero-gap line crosses the triangles) */
    const double a = 0.5, d0 = 2e-5, gx = -1e-4, gy = 3e-5;
    double one[8], two[8], many[8];
    square_pieces(1, a, d0, gx, gy, one);
    square_pieces(2, a, d0, gx, gy, two);
    square_pieces(200, a, d0, gx, gy, many);
    /* a uniform pressure: the common centroid is a vertex of the triangles, on their edges */
    double one_u[8], many_u[8];
    square_pieces(1, a, 1e-5, 0.0, 0.0, one_u);
    square_pieces(200, a, 1e-5, 0.0, 0.0, many_u);
    rd_check_rel(
        "200 triangles vs the quad, uniform pressure, centre on their vertex: twisting lever",
        many_u[6], one_u[6], ROUNDOFF, RD_STRICT);
    for (int k = 0; k < 8; k++) {
        char msg[96];
        snprintf(msg, sizeof msg, "2 triangles vs the quad: %s", what[k]);
        rd_check_rel(msg, two[k], one[k], ROUNDOFF, RD_STRICT);
        snprintf(msg, sizeof msg, "200 triangles vs the quad: %s", what[k]);
        rd_check_rel(msg, many[k], one[k], ROUNDOFF, RD_STRICT);
    }
}

/* A unit square face S at z = -delta facing down, half of it over the edge x = 0.5 of a large
 * reference face R on z = 0 facing up: the patch is the half over R, depth delta. */
static void test_faces_half_over(void **state)
{
    (void)state;
    const double delta = 1e-4;
    const double o[3] = { 0.5, 0.5, -delta }, e1[3] = { 0, 1, 0 }, e2[3] = { 1, 0, 0 },
                 n[3] = { 0, 0, -1 };
    /* S in its frame (x along e1 = y, y along e2 = x), counter-clockwise about n = e1 x e2 */
    rd_poly2 s = rect(-0.5, -0.5, 0.5, 0.5);
    const double rv[4][3] = {
        { -5, -5, 0 }, { 0.5, -5, 0 }, { 0.5, 5, 0 }, { -5, 5, 0 }
    }; /* x <= 0.5 */
    const double u[3] = { 0, 0, 1 };
    rd_poly2 patch;
    double dep[3];
    assert_true(rd_patch_faces(o, e1, e2, n, &s, rv, 4, u, 0.0, &patch, dep) > 0);
    rd_patch_load ld;
    rd_patch_load_of(&patch, dep[0], dep[1], dep[2], &ld, NULL);
    rd_check_rel("half over the edge: area (m^2)", ld.area, 0.5, ROUNDOFF, RD_STRICT);
    rd_check_rel("half over the edge: force / KN (m^3)", ld.f, 0.5 * delta, ROUNDOFF, RD_STRICT);
    rd_check_rel("half over the edge: centroid along e2 (m)", ld.cy, -0.25, ROUNDOFF, RD_STRICT);
    /* two faces that do not face each other give no patch */
    const double up[3] = { 0, 0, -1 };
    assert_int_equal(rd_patch_faces(o, e1, e2, n, &s, rv, 4, up, 0.0, &patch, dep), 0);
}

/* A square face of side a, tilted by theta about its e1 axis, its lowest edge delta below R:
 * depth delta - x2 sin(theta) ... in S's own coordinates y (along e2, the slope), compressed
 * over y < delta / sin(theta) from the low edge. */
static void test_faces_tilted(void **state)
{
    (void)state;
    const double a = 0.5, th = 0.01, delta = 2e-5, st = sin(th), ct = cos(th);
    /* S: e1 = x, e2 = (0, cos, sin) rising, n = e1 x e2 = (0, -sin, cos)... facing down wants n
       ~ -z: take e1 = -x, e2 = (0, cos, sin): n = (0, sin, -cos) */
    const double e1[3] = { -1, 0, 0 }, e2[3] = { 0, ct, st }, n[3] = { 0, st, -ct };
    const double o[3] = { 0, 0, -delta }; /* the low edge's midpoint */
    rd_poly2 s = rect(-a / 2, 0, a / 2, a);
    const double rv[4][3] = { { -5, -5, 0 }, { 5, -5, 0 }, { 5, 5, 0 }, { -5, 5, 0 } },
                 u[3] = { 0, 0, 1 };
    rd_poly2 patch;
    double dep[3];
    assert_true(rd_patch_faces(o, e1, e2, n, &s, rv, 4, u, 0.0, &patch, dep) > 0);
    rd_patch_load ld;
    rd_patch_load_of(&patch, dep[0], dep[1], dep[2], &ld, NULL);
    const double ys = delta / st; /* where S's material line crosses z = 0 */
    rd_check_rel("tilted face: compressed area (m^2)", ld.area, a * ys, ROUNDOFF, RD_STRICT);
    rd_check_rel("tilted face: force / KN (m^3)", ld.f, a * delta * ys / 2, ROUNDOFF, RD_STRICT);
    rd_check_rel("tilted face: moment along the slope / KN (m^4)", ld.my, a * delta * ys * ys / 6,
                 ROUNDOFF, RD_STRICT);
}

/* The faces of an n x n grid of squares over [0, w] x [0, h], each cut into two triangles
 * counter-clockwise, as rd_patch_cells takes them; keep[k] (or all when NULL) picks squares. */
static int grid_faces(int n, double w, double h, const int *keep, int *f0, int *vid,
                      double (*xy)[2])
{
    int nf = 0, m = 0;
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) {
            if (keep && !keep[i * n + j]) continue;
            const int a = i * (n + 1) + j, b = a + 1, c = a + n + 2, d = a + n + 1;
            const int tri[2][3] = { { a, b, c }, { a, c, d } };
            for (int t = 0; t < 2; t++) {
                f0[nf++] = m;
                for (int k = 0; k < 3; k++, m++) {
                    vid[m] = tri[t][k];
                    xy[m][0] = w * (tri[t][k] % (n + 1)) / n;
                    xy[m][1] = h * (tri[t][k] / (n + 1)) / n;
                }
            }
        }
    f0[nf] = m;
    return nf;
}

/* The cells' moments summed, and whether every cell is convex and counter-clockwise. */
static int cells_moments(int nc, const int *c0, const int *cs, const double (*xy)[2], rd_moments *m)
{
    int convex = 1;
    *m = (rd_moments){ 0, 0, 0, 0, 0, 0 };
    for (int c = 0; c < nc; c++) {
        rd_poly2 p;
        p.n = c0[c + 1] - c0[c];
        for (int k = 0; k < p.n; k++) {
            p.p[k][0] = xy[cs[c0[c] + k]][0];
            p.p[k][1] = xy[cs[c0[c] + k]][1];
        }
        for (int k = 0; k < p.n; k++) {
            const double *a = p.p[k], *b = p.p[(k + 1) % p.n], *q = p.p[(k + 2) % p.n];
            if ((b[0] - a[0]) * (q[1] - b[1]) - (b[1] - a[1]) * (q[0] - b[0]) < 0) convex = 0;
        }
        rd_moments pm;
        rd_patch_moments(&p, &pm);
        rd_moments_add(m, &pm);
    }
    return convex;
}

#define GRID_N 8

/* A 0.5 x 0.3 m rectangle cut into 2 GRID_N^2 triangles (49 interior vertices): convex cells
 * with the rectangle's moments; merging must remove interior vertices (a face-by-face merge
 * that cannot close a vertex's star leaves a cell per few triangles), so at most GRID_N cells
 * (one per row of squares at worst). */
static void test_cells_grid(void **state)
{
    (void)state;
    enum { NF = 2 * GRID_N * GRID_N };
    int f0[NF + 1], vid[3 * NF], c0[NF + 1], cs[3 * NF];
    double xy[3 * NF][2];
    const double w = 0.5, h = 0.3;
    int nf = grid_faces(GRID_N, w, h, NULL, f0, vid, xy);
    int nc = rd_patch_cells(nf, f0, vid, (const double(*)[2])xy, RD_PATCH_CELL_MAX, c0, cs);
    rd_moments m, ex;
    rd_poly2 r = rect(0, 0, w, h);
    rd_patch_moments(&r, &ex);
    int convex = cells_moments(nc, c0, cs, (const double(*)[2])xy, &m);
    printf("grid of %d triangles: %d cells\n", nf, nc);
    rd_check_abs("grid cells: every cell convex", (double)!convex, 0.0, 0.5, RD_STRICT);
    rd_check_abs("grid cells: at most GRID_N cells", (double)(nc > GRID_N), 0.0, 0.5, RD_STRICT);
    rd_check_rel("grid cells: area (m^2)", m.a, ex.a, ROUNDOFF, RD_STRICT);
    rd_check_rel("grid cells: Sx (m^3)", m.sx, ex.sx, ROUNDOFF, RD_STRICT);
    rd_check_rel("grid cells: Syy (m^4)", m.syy, ex.syy, ROUNDOFF, RD_STRICT);
    rd_check_rel("grid cells: Sxy (m^4)", m.sxy, ex.sxy, ROUNDOFF, RD_STRICT);
}

/* The same rectangle with its 49 interior vertices moved off the grid (by up to 0.3 of a cell,
 * a fixed pseudo-random pattern; a scanned rock's sawn base): merging face by face cannot
 * close the irregular stars, the outline (convex, 32 vertices) re-triangulated and merged is
 * one cell, with the rectangle's moments. */
static void test_cells_jittered(void **state)
{
    (void)state;
    enum { NF = 2 * GRID_N * GRID_N };
    int f0[NF + 1], vid[3 * NF], c0[NF + 1], cs[3 * NF];
    double xy[3 * NF][2];
    const double w = 0.5, h = 0.3;
    int nf = grid_faces(GRID_N, w, h, NULL, f0, vid, xy);
    for (int q = 0; q < f0[nf]; q++) {
        const int i = vid[q] / (GRID_N + 1), j = vid[q] % (GRID_N + 1);
        if (i == 0 || j == 0 || i == GRID_N || j == GRID_N) continue;
        xy[q][0] += 0.3 * w / GRID_N * sin(12.9898 * vid[q]);
        xy[q][1] += 0.3 * h / GRID_N * cos(78.233 * vid[q]);
    }
    int nc = rd_patch_cells(nf, f0, vid, (const double(*)[2])xy, RD_PATCH_CELL_MAX, c0, cs);
    rd_moments m, ex;
    rd_poly2 r = rect(0, 0, w, h);
    rd_patch_moments(&r, &ex);
    int convex = cells_moments(nc, c0, cs, (const double(*)[2])xy, &m);
    rd_check_abs("jittered grid cells: every cell convex", (double)!convex, 0.0, 0.5, RD_STRICT);
    rd_check_abs("jittered grid cells: one cell", (double)nc, 1.0, 0.5, RD_STRICT);
    rd_check_rel("jittered grid cells: area (m^2)", m.a, ex.a, ROUNDOFF, RD_STRICT);
    rd_check_rel("jittered grid cells: Sx (m^3)", m.sx, ex.sx, ROUNDOFF, RD_STRICT);
    rd_check_rel("jittered grid cells: Sxy (m^4)", m.sxy, ex.sxy, ROUNDOFF, RD_STRICT);
}

/* An L of three squares (six triangles) is not convex: at least two cells, each convex, with
 * the L's area. */
static void test_cells_l_shape(void **state)
{
    (void)state;
    const int keep[4] = { 1, 1, 1, 0 };
    int f0[7], vid[18], c0[7], cs[18];
    double xy[18][2];
    int nf = grid_faces(2, 1.0, 1.0, keep, f0, vid, xy);
    int nc = rd_patch_cells(nf, f0, vid, (const double(*)[2])xy, RD_PATCH_CELL_MAX, c0, cs);
    rd_moments m;
    int convex = cells_moments(nc, c0, cs, (const double(*)[2])xy, &m);
    rd_check_abs("L cells: every cell convex", (double)!convex, 0.0, 0.5, RD_STRICT);
    rd_check_abs("L cells: two cells", (double)nc, 2.0, 0.5, RD_STRICT);
    rd_check_rel("L cells: area (m^2)", m.a, 0.75, ROUNDOFF, RD_STRICT);
}

/* A regular 12-gon of circumradius r about the origin. */
static rd_poly2 dodecagon(double r)
{
    rd_poly2 gon;
    gon.n = 12;
    for (int k = 0; k < 12; k++) {
        gon.p[k][0] = r * cos(2 * M_PI * k / 12);
        gon.p[k][1] = r * sin(2 * M_PI * k / 12);
    }
    return gon;
}

/* The torsion bound against the exact lever: a uniform pressure on a square about its centre,
 * on a regular 12-gon, and an affine pressure about an off-centre point of a triangle. */
static void test_torsion_bound(void **state)
{
    (void)state;
    rd_poly2 sq = rect(-0.5, -0.5, 0.5, 0.5), tri = { 3, { { 0, 0 }, { 1.2, 0.1 }, { 0.3, 0.9 } } };
    const rd_poly2 gon = dodecagon(0.4);
    const rd_poly2 *poly[3] = { &sq, &gon, &tri };
    const double c[3][2] = { { 0, 0 }, { 0, 0 }, { 0.45, 0.35 } };
    const double dep[3][3] = { { 1, 0, 0 }, { 1, 0, 0 }, { 0.1, 0.3, -0.05 } };
    const char *name[3] = { "square", "12-gon", "triangle, affine pressure" };
    for (int k = 0; k < 3; k++) {
        double ex = rd_patch_torsion(poly[k], c[k], dep[k][0], dep[k][1], dep[k][2]);
        double lo = rd_patch_torsion_bound(poly[k], 1, c[k], dep[k][0], dep[k][1], dep[k][2]);
        char what[96];
        snprintf(what, sizeof what, "torsion bound / lever, %s", name[k]);
        rd_check_abs(what, lo / ex, 0.5, 0.5, RD_STRICT); /* in (0, 1]: a lower bound */
    }
    /* the square's ratio in closed form: (a^4 / 6) / (a / sqrt 2) over a^3 (sqrt 2 + ln(1 +
       sqrt 2)) / 6 */
    double ex = rd_patch_torsion(&sq, c[0], 1, 0, 0);
    double lo = rd_patch_torsion_bound(&sq, 1, c[0], 1, 0, 0);
    rd_check_rel("torsion bound / lever, square, closed form", lo / ex,
                 sqrt(2.0) / (sqrt(2.0) + log(1 + sqrt(2.0))), 1e-8, RD_STRICT);
}

/* The disc bound against the exact lever on the same three patches, and on a wedge of pressure
 * that vanishes along one side of the square; on the uniform square in closed form. */
static void test_torsion_disc(void **state)
{
    (void)state;
    rd_poly2 sq = rect(-0.5, -0.5, 0.5, 0.5), tri = { 3, { { 0, 0 }, { 1.2, 0.1 }, { 0.3, 0.9 } } };
    const rd_poly2 gon = dodecagon(0.4);
    const rd_poly2 *poly[4] = { &sq, &gon, &tri, &sq };
    const double c[4][2] = { { 0, 0 }, { 0, 0 }, { 0.45, 0.35 }, { 0, 0 } };
    const double dep[4][3] = { { 1, 0, 0 }, { 1, 0, 0 }, { 0.1, 0.3, -0.05 }, { 0.5, 1, 0 } };
    const char *name[4] = { "square", "12-gon", "triangle, affine pressure", "square, wedge" };
    for (int k = 0; k < 4; k++) {
        rd_moments m;
        rd_patch_moments(poly[k], &m);
        const double f = dep[k][0] * m.a + dep[k][1] * m.sx + dep[k][2] * m.sy;
        double ex = rd_patch_torsion(poly[k], c[k], dep[k][0], dep[k][1], dep[k][2]);
        double lo = rd_patch_torsion_disc(poly[k], 1, f, dep[k][0], dep[k][1], dep[k][2]);
        char what[96];
        snprintf(what, sizeof what, "disc bound / lever, %s", name[k]);
        rd_check_abs(what, lo / ex, 0.5, 0.5, RD_STRICT); /* in (0, 1]: a lower bound */
    }
    /* the unit square under d = 1: (2/3) sqrt(1 / (3 pi)) over (sqrt 2 + ln(1 + sqrt 2)) / 6 */
    double ex = rd_patch_torsion(&sq, c[0], 1, 0, 0);
    double lo = rd_patch_torsion_disc(&sq, 1, 1.0, 1, 0, 0);
    rd_check_rel("disc bound / lever, square, closed form", lo / ex,
                 4 / (sqrt(3 * M_PI) * (sqrt(2.0) + log(1 + sqrt(2.0)))), 1e-8, RD_STRICT);
}

/* The first-fit scan that rd_plane_group must reproduce: each face against every plane. */
static int plane_scan(int nf, const double (*fn)[3], const double *fd, double ntol, double dtol,
                      int *plane_of)
{
    int np = 0, *first = malloc((size_t)nf * sizeof *first);
    for (int f = 0; f < nf; f++) {
        int k = 0;
        for (; k < np; k++) {
            const double *m = fn[first[k]];
            if (fn[f][0] * m[0] + fn[f][1] * m[1] + fn[f][2] * m[2] > 1 - ntol &&
                fabs(fd[first[k]] - fd[f]) <= dtol)
                break;
        }
        if (k == np) first[np++] = f;
        plane_of[f] = k;
    }
    free(first);
    return np;
}

static void test_plane_group(void **state)
{
    (void)state;
    enum { NF = 4000, NBASE = 12 };
    const double ntol = 1e-9, dtol = 2e-6, amax = 2 * sqrt(2 * ntol);
    double(*fn)[3] = malloc(NF * sizeof *fn), *fd = malloc(NF * sizeof *fd);
    int *pa = malloc(NF * sizeof *pa), *pb = malloc(NF * sizeof *pb),
        *first = malloc(NF * sizeof *first);
    srand(39);
    for (int f = 0; f < NF; f++) {
        const int b = f % NBASE; /* base plane b: its normal on a spiral, offset b / 10 m */
        const double th = 0.4 + 0.2 * b, ph = 2.1 * b;
        const double n[3] = { sin(th) * cos(ph), sin(th) * sin(ph), cos(th) };
        const double e1[3] = { -sin(ph), cos(ph), 0 };
        const double e2[3] = { n[1] * e1[2] - n[2] * e1[1], n[2] * e1[0] - n[0] * e1[2],
                               n[0] * e1[1] - n[1] * e1[0] };
        const double a = amax * rand() / RAND_MAX, w = 2 * M_PI * rand() / RAND_MAX;
        double len = 0;
        for (int c = 0; c < 3; c++) {
            fn[f][c] = cos(a) * n[c] + sin(a) * (cos(w) * e1[c] + sin(w) * e2[c]);
            len += fn[f][c] * fn[f][c];
        }
        for (int c = 0; c < 3; c++) fn[f][c] /= sqrt(len);
        fd[f] = 0.1 * b + 2 * dtol * (2.0 * rand() / RAND_MAX - 1);
    }
    const int na = rd_plane_group(NF, (const double(*)[3])fn, fd, ntol, dtol, pa, first);
    const int nb = plane_scan(NF, (const double(*)[3])fn, fd, ntol, dtol, pb);
    int same = na == nb;
    for (int f = 0; f < NF && same; f++) same = pa[f] == pb[f];
    for (int k = 0; k < na && same; k++) same = pa[first[k]] == k;
    printf("CHECK plane_group: %d faces, %d planes (scan %d), same grouping %d\n", NF, na, nb,
           same);
    assert_true(same);
    assert_true(na > NBASE && na < NF / 4); /* both merges and misses happened */
    free(fn);
    free(fd);
    free(pa);
    free(pb);
    free(first);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_moments_rectangle),
        cmocka_unit_test(test_load_affine_compressed),
        cmocka_unit_test(test_load_rocking_base),
        cmocka_unit_test(test_torsion_square),
        cmocka_unit_test(test_torsion_regular_polygon),
        cmocka_unit_test(test_torsion_affine_grid),
        cmocka_unit_test(test_tessellation),
        cmocka_unit_test(test_faces_half_over),
        cmocka_unit_test(test_faces_tilted),
        cmocka_unit_test(test_cells_grid),
        cmocka_unit_test(test_cells_jittered),
        cmocka_unit_test(test_cells_l_shape),
        cmocka_unit_test(test_torsion_bound),
        cmocka_unit_test(test_torsion_disc),
        cmocka_unit_test(test_plane_group),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
