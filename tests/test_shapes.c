/* Shapes: prisms/frustums, convex hulls and polyhedra from faces against closed forms. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include "geometry/geom.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static int rel_close(double a, double b, double tol) { return fabs(a - b) <= tol * fabs(b); }

/* Regular n-gon of circumradius r: A = n r^2 sin(2 pi/n) / 2 (n triangles with apex angle
 * 2 pi/n at the centre). Polar moment about the centre, summing the triangles (0, a, b) with
 * int |x|^2 dA = A_t (|a|^2 + |b|^2 + a.b) / 6: J = A r^2 (2 + cos(2 pi/n)) / 6; the polygon
 * is isotropic for n >= 3, so int x^2 dA = int y^2 dA = J / 2. For a prism of height h and
 * per unit density: V = A h, I_z = V r^2 (2 + cos(2 pi/n)) / 6,
 * I_x = I_y = V r^2 (2 + cos(2 pi/n)) / 12 + V h^2 / 12. Round-off only: 1e-12 relative. */
static void test_prism_mass(void **state)
{
    (void)state;
    const int ns[] = { 3, 4, 6, 17, 64 };
    double r = 0.4, h = 1.3;
    for (size_t t = 0; t < sizeof ns / sizeof ns[0]; t++) {
        int n = ns[t];
        rd_poly p;
        rd_mass m;
        rd_error err;
        assert_int_equal(rd_poly_prism(&p, n, r, r, h, &err), 0);
        assert_int_equal(p.nv, 2 * n);
        assert_int_equal(p.nf, n + 2);
        assert_int_equal(p.flen[0], n);
        assert_int_equal(p.flen[1], n);
        assert_int_equal(p.flen[2], 4);
        assert_true(fabs(p.fn[0][2] + 1) < 1e-15 && fabs(p.fn[1][2] - 1) < 1e-15);
        assert_true(fabs(p.fd[0] - h / 2) < 1e-15);
        assert_int_equal(rd_poly_check(&p, "prism", 0, &err), 0);
        assert_int_equal(rd_poly_mass(&p, &m, &err), 0);
        double c2 = 2 + cos(2 * M_PI / n);
        double V = n * r * r * sin(2 * M_PI / n) / 2 * h;
        assert_true(rel_close(m.volume, V, 1e-12));
        for (int i = 0; i < 3; i++) assert_true(fabs(m.centroid[i]) < 1e-14);
        double Iz = V * r * r * c2 / 6, Ix = V * r * r * c2 / 12 + V * h * h / 12;
        assert_true(rel_close(m.inertia[8], Iz, 1e-12));
        assert_true(rel_close(m.inertia[0], Ix, 1e-12));
        assert_true(rel_close(m.inertia[4], Ix, 1e-12));
        assert_true(fabs(m.inertia[1]) < 1e-12 * Ix && fabs(m.inertia[2]) < 1e-12 * Ix);
        rd_poly_free(&p);
    }
}

/* Frustum of similar regular n-gons, circumradii R (base) and r (top), height h; with
 * c = n sin(2 pi/n) / 2 and rho(z) the circumradius at height z above the base:
 * V = c h (R^2 + R r + r^2) / 3; centroid at z = h (R^2 + 2 R r + 3 r^2) / (4 (R^2 + R r + r^2))
 * above the base (at -h/2); I_z = c (2 + cos(2 pi/n)) / 6 * int rho^4 dz
 *     = c (2 + cos(2 pi/n)) / 6 * h (R^5 - r^5) / (5 (R - r)). */
static void test_frustum_mass(void **state)
{
    (void)state;
    int n = 12;
    double R = 0.5, r = 0.3, h = 0.8, c = n * sin(2 * M_PI / n) / 2;
    rd_poly p;
    rd_mass m;
    rd_error err;
    assert_int_equal(rd_poly_prism(&p, n, R, r, h, &err), 0);
    assert_int_equal(rd_poly_check(&p, "frustum", 0, &err), 0);
    assert_int_equal(rd_poly_mass(&p, &m, &err), 0);
    double V = c * h * (R * R + R * r + r * r) / 3;
    double zc = -h / 2 + h * (R * R + 2 * R * r + 3 * r * r) / (4 * (R * R + R * r + r * r));
    double Iz = c * (2 + cos(2 * M_PI / n)) / 6 * h * (pow(R, 5) - pow(r, 5)) / (5 * (R - r));
    assert_true(rel_close(m.volume, V, 1e-12));
    assert_true(fabs(m.centroid[2] - zc) < 1e-12 * h);
    assert_true(rel_close(m.inertia[8], Iz, 1e-12));
    rd_poly_free(&p);
}

static void test_prism_errors(void **state)
{
    (void)state;
    rd_poly p;
    rd_error err;
    assert_int_equal(rd_poly_prism(&p, 2, 1, 1, 1, &err), -1);
    assert_non_null(strstr(err.msg, "at least 3 sides"));
    assert_int_equal(rd_poly_prism(&p, 8, 1, 0, 1, &err), -1);
    assert_non_null(strstr(err.msg, "must be positive"));
}

/* Corners, face centres, edge midpoints and interior points of a brick: the hull is the brick
 * with 6 quadrilateral faces (coplanar triangles merged), 8 vertices, volume a b c. */
static void test_hull_brick(void **state)
{
    (void)state;
    double a[3] = { 0.3, 0.64, 0.8 }, pts[125][3];
    int n = 0;
    for (int i = 0; i < 5; i++)
        for (int j = 0; j < 5; j++)
            for (int k = 0; k < 5; k++) {
                pts[n][0] = 7 + a[0] * i / 4;
                pts[n][1] = -3 + a[1] * j / 4;
                pts[n][2] = a[2] * k / 4;
                n++;
            }
    rd_poly p;
    rd_mass m;
    rd_error err;
    assert_int_equal(rd_poly_hull(&p, (const double(*)[3])pts, n, &err), 0);
    assert_int_equal(p.nv, 8);
    assert_int_equal(p.nf, 6);
    for (int f = 0; f < 6; f++) assert_int_equal(p.flen[f], 4);
    assert_int_equal(rd_poly_check(&p, "hull", 0, &err), 0);
    assert_int_equal(rd_poly_mass(&p, &m, &err), 0);
    assert_true(rel_close(m.volume, a[0] * a[1] * a[2], 1e-12));
    assert_true(fabs(m.centroid[0] - 7.15) < 1e-12 && fabs(m.centroid[2] - 0.4) < 1e-12);
    rd_poly_free(&p);
}

static double lcg(uint64_t *s)
{
    *s = *s * 6364136223846793005ULL + 1442695040888963407ULL;
    return (double)(*s >> 11) / 9007199254740992.0;
}

/* 500 random points in a ball: every point lies inside or on every face plane, face vertices
 * lie on their plane (1e-12 m), the centroid is strictly inside (outward normals), hull
 * vertices are input points, Euler V - E + F = 2, and the surface passes rd_poly_check. */
static void test_hull_random(void **state)
{
    (void)state;
    enum { N = 500 };
    double pts[N][3];
    uint64_t s = 42;
    for (int i = 0; i < N; i++) {
        double x[3], r2;
        do {
            for (int k = 0; k < 3; k++) x[k] = 2 * lcg(&s) - 1;
            r2 = x[0] * x[0] + x[1] * x[1] + x[2] * x[2];
        } while (r2 > 1);
        for (int k = 0; k < 3; k++) pts[i][k] = x[k] + (k == 0 ? 100 : 0);
    }
    rd_poly p;
    rd_mass m;
    rd_error err;
    assert_int_equal(rd_poly_hull(&p, (const double(*)[3])pts, N, &err), 0);
    assert_int_equal(rd_poly_check(&p, "hull", 0, &err), 0);
    assert_int_equal(rd_poly_mass(&p, &m, &err), 0);
    assert_true(m.volume > 0 && m.volume < 4.0 / 3.0 * M_PI);
    int edges2 = 0;
    for (int f = 0; f < p.nf; f++) {
        edges2 += p.flen[f];
        for (int i = 0; i < N; i++)
            assert_true(p.fn[f][0] * pts[i][0] + p.fn[f][1] * pts[i][1] + p.fn[f][2] * pts[i][2] <=
                        p.fd[f] + 1e-10);
        for (int k = 0; k < p.flen[f]; k++) {
            const double *v = p.v[p.fidx[p.fstart[f] + k]];
            assert_true(fabs(p.fn[f][0] * v[0] + p.fn[f][1] * v[1] + p.fn[f][2] * v[2] - p.fd[f]) <
                        1e-12 * 100);
        }
        double c =
            p.fn[f][0] * m.centroid[0] + p.fn[f][1] * m.centroid[1] + p.fn[f][2] * m.centroid[2];
        assert_true(c < p.fd[f] - 0.01);
    }
    assert_int_equal(p.nv - edges2 / 2 + p.nf, 2);
    for (int i = 0; i < p.nv; i++) {
        int found = 0;
        for (int j = 0; j < N && !found; j++) found = !memcmp(p.v[i], pts[j], sizeof pts[j]);
        assert_true(found);
    }
    rd_poly_free(&p);
}

static void test_hull_errors(void **state)
{
    (void)state;
    double flat[5][3] = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 1, 1, 0 }, { 0.5, 0.5, 0 } };
    rd_poly p;
    rd_error err;
    assert_int_equal(rd_poly_hull(&p, (const double(*)[3])flat, 3, &err), -1);
    assert_non_null(strstr(err.msg, "at least 4 points"));
    assert_int_equal(rd_poly_hull(&p, (const double(*)[3])flat, 5, &err), -1);
    assert_non_null(strstr(err.msg, "coplanar"));
}

/* L-shaped prism: the L = [0,2]x[0,1] + [0,1]x[1,2] (as one star-shaped hexagon face, fanned
 * from (0,0)), extruded over z in [0, h]. By the two boxes: V = 3 h, centroid (5/6, 5/6, h/2),
 * int x^2 dV = h (8/3 + 1/3) = 3 h, int x y dV = h (1 + 3/4) = 7 h / 4. */
static const double L_xy[6][2] = { { 0, 0 }, { 2, 0 }, { 2, 1 }, { 1, 1 }, { 1, 2 }, { 0, 2 } };

static int l_prism(rd_poly *p, double h, int flip, int top_first, rd_error *err)
{
    double v[12][3];
    int idx[36], start[8], len[8], at = 0;
    for (int k = 0; k < 6; k++) {
        v[k][0] = v[6 + k][0] = L_xy[k][0];
        v[k][1] = v[6 + k][1] = L_xy[k][1];
        v[k][2] = 0;
        v[6 + k][2] = h;
    }
    start[0] = at;
    len[0] = 6;
    for (int k = 0; k < 6; k++) idx[at++] = (6 - k) % 6; /* 0, 5, 4, ...: fanned from (0, 0) */
    start[1] = at;
    len[1] = 6;
    for (int k = 0; k < 6; k++) idx[at++] = 6 + (top_first + k) % 6;
    for (int k = 0; k < 6; k++) {
        start[2 + k] = at;
        len[2 + k] = 4;
        idx[at++] = k;
        idx[at++] = (k + 1) % 6;
        idx[at++] = 6 + (k + 1) % 6;
        idx[at++] = 6 + k;
    }
    if (flip) /* reverse every face, keeping its first vertex */
        for (int f = 0; f < 8; f++)
            for (int a = start[f] + 1, b = start[f] + len[f] - 1; a < b; a++, b--) {
                int t = idx[a];
                idx[a] = idx[b];
                idx[b] = t;
            }
    return rd_poly_from_faces(p, (const double(*)[3])v, 12, start, len, idx, 8, err);
}

static void test_from_faces_l_prism(void **state)
{
    (void)state;
    double h = 0.75;
    rd_poly p;
    rd_mass m;
    rd_error err;
    assert_int_equal(l_prism(&p, h, 0, 0, &err), 0);
    assert_int_equal(rd_poly_mass(&p, &m, &err), 0);
    double V = 3 * h, c[3] = { 5.0 / 6, 5.0 / 6, h / 2 };
    assert_true(rel_close(m.volume, V, 1e-12));
    for (int i = 0; i < 3; i++) assert_true(fabs(m.centroid[i] - c[i]) < 1e-12);
    double Sxx = 3 * h - V * c[0] * c[0], Sxy = 7 * h / 4 - V * c[0] * c[1];
    double Szz = h * h * h / 3 * 3 - V * c[2] * c[2];
    assert_true(rel_close(m.inertia[0], Sxx + Szz, 1e-12)); /* I_xx = S_yy + S_zz, S_yy = S_xx */
    assert_true(rel_close(m.inertia[1], -Sxy, 1e-12));
    assert_true(rel_close(m.inertia[8], 2 * Sxx, 1e-12));
    assert_int_equal(p.flen[0], 6);
    rd_poly_free(&p);
    assert_int_equal(l_prism(&p, h, 1, 0, &err), -1);
    assert_string_equal(err.msg,
                        "faces: inside-out mesh (volume -2.25 m^3); flip the face orientation");
    /* the top hexagon fanned from (2, 1) instead of (0, 0): the fan folds over at (1, 1) */
    assert_int_equal(l_prism(&p, h, 0, 2, &err), -1);
    assert_non_null(strstr(err.msg, "faces: face 1 folds over when fanned from its first vertex"));
}

/* Hull vertices of the L prism: all but the two at its reflex corner (1, 1) (the broad phase
 * boxes a mesh by its hull vertices alone). */
static void test_hull_marks_l_prism(void **state)
{
    (void)state;
    rd_poly p;
    rd_error err;
    char on[12];
    assert_int_equal(l_prism(&p, 0.75, 0, 0, &err), 0);
    assert_int_equal(rd_poly_hull_marks(&p, on, &err), 0);
    for (int v = 0; v < 12; v++) assert_int_equal(on[v], !(p.v[v][0] == 1 && p.v[v][1] == 1));
    rd_poly_free(&p);
}

/* Unit cube faces, outward; edits of them exercise each failure of rd_poly_check. */
static const double cube_v[9][3] = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 },
                                     { 1, 1, 0 }, { 0, 0, 1 }, { 1, 0, 1 },
                                     { 0, 1, 1 }, { 1, 1, 1 }, { 2, 2, 2 } };
static int cube_faces(int *idx, int *start, int *len)
{
    static const int q[6][4] = { { 0, 2, 3, 1 }, { 4, 5, 7, 6 }, { 0, 1, 5, 4 },
                                 { 2, 6, 7, 3 }, { 0, 4, 6, 2 }, { 1, 3, 7, 5 } };
    for (int f = 0; f < 6; f++) {
        start[f] = 4 * f;
        len[f] = 4;
        memcpy(idx + 4 * f, q[f], sizeof q[f]);
    }
    return 6;
}

static void expect_faces_error(int nv, const int *start, const int *len, const int *idx, int nf,
                               const char *want)
{
    rd_poly p;
    rd_error err;
    assert_int_equal(rd_poly_from_faces(&p, cube_v, nv, start, len, idx, nf, &err), -1);
    if (!strstr(err.msg, want)) fail_msg("got '%s', wanted '%s'", err.msg, want);
}

/* ---- convexity (rd_poly_convex) against the definition, every vertex behind every face plane;
 * bodies of more than 1e5 vertex-plane pairs take the edge and hull test ---- */

static int convex_by_definition(const rd_poly *p, double tol)
{
    for (int f = 0; f < p->nf; f++)
        for (int v = 0; v < p->nv; v++)
            if (p->fn[f][0] * p->v[v][0] + p->fn[f][1] * p->v[v][1] + p->fn[f][2] * p->v[v][2] -
                    p->fd[f] >
                tol)
                return 0;
    return 1;
}

/* UV sphere of radius 1 m, nlat x nlon, triangles; vertex `dent` (-1: none) moved by `push` m
 * along its radius (negative: inward). */
static int uv_sphere(rd_poly *p, int nlat, int nlon, int dent, double push, rd_error *err)
{
    int nv = 2 + (nlat - 1) * nlon, nf = 2 * nlon * (nlat - 1), at = 0, f = 0;
    double(*v)[3] = malloc((size_t)nv * sizeof *v);
    int *idx = malloc((size_t)nf * 3 * sizeof *idx), *start = malloc((size_t)nf * sizeof *start);
    int *len = malloc((size_t)nf * sizeof *len);
    v[0][0] = v[0][1] = 0;
    v[0][2] = 1;
    for (int i = 1; i < nlat; i++)
        for (int j = 0; j < nlon; j++) {
            double t = M_PI * i / nlat, ph = 2 * M_PI * j / nlon, *x = v[1 + (i - 1) * nlon + j];
            x[0] = sin(t) * cos(ph);
            x[1] = sin(t) * sin(ph);
            x[2] = cos(t);
        }
    v[nv - 1][0] = v[nv - 1][1] = 0;
    v[nv - 1][2] = -1;
    if (dent >= 0)
        for (int k = 0; k < 3; k++) v[dent][k] *= 1 + push;
#define ID(i, j) (1 + (i)*nlon + ((j) % nlon))
#define TRI(a, b, c)                                                                               \
    (start[f] = at, len[f++] = 3, idx[at++] = (a), idx[at++] = (b), idx[at++] = (c))
    for (int j = 0; j < nlon; j++) TRI(0, ID(0, j), ID(0, j + 1));
    for (int i = 0; i + 2 < nlat; i++)
        for (int j = 0; j < nlon; j++) {
            TRI(ID(i, j), ID(i + 1, j), ID(i + 1, j + 1));
            TRI(ID(i, j), ID(i + 1, j + 1), ID(i, j + 1));
        }
    for (int j = 0; j < nlon; j++) TRI(nv - 1, ID(nlat - 2, j + 1), ID(nlat - 2, j));
#undef TRI
#undef ID
    int rc = rd_poly_from_faces(p, (const double(*)[3])v, nv, start, len, idx, nf, err);
    free(v);
    free(idx);
    free(start);
    free(len);
    return rc;
}

static void expect_convex(rd_poly *p, int want)
{
    rd_error err;
    int c = -1;
    double tol = 1e-9 * (1 + p->radius); /* engine/setup.c RD_CONVEX_TOL */
    assert_int_equal(rd_poly_convex(p, tol, &c, &err), 0);
    assert_int_equal(c, want);
    assert_int_equal(convex_by_definition(p, tol), want);
    rd_poly_free(p);
}

/* Convex: a brick, a 128-sided drum, a 2000-sided frustum, a hull of random points, a 9,800-triangle sphere and the
 * same with a vertex pushed 1e-12 m in or out (round-off, under the 2e-9 m tolerance). Not
 * convex: the L prism (a reflex edge and reflex corners in its caps), the sphere with a vertex
 * pushed 1e-6 m in (a dimple 500 x the tolerance) or out (the sphere's quads are split into two
 * coplanar triangles, so a bump of a corner folds a diagonal: 1.06e-6 m past a face plane). */
static void test_convexity(void **state)
{
    (void)state;
    rd_poly p;
    rd_error err;
    const double size[3] = { 0.4, 0.5, 1.0 };
    assert_int_equal(rd_poly_brick(&p, size, &err), 0);
    expect_convex(&p, 1);
    assert_int_equal(rd_poly_prism(&p, 128, 0.5, 0.5, 1.0, &err), 0);
    expect_convex(&p, 1);
    assert_int_equal(rd_poly_prism(&p, 2000, 0.5, 0.3, 1.0, &err),
                     0); /* 2000-gon caps, the edge test */
    expect_convex(&p, 1);
    double pts[200][3];
    srand(7);
    for (int i = 0; i < 200; i++)
        for (int k = 0; k < 3; k++) pts[i][k] = (double)rand() / RAND_MAX - 0.5;
    assert_int_equal(rd_poly_hull(&p, (const double(*)[3])pts, 200, &err), 0);
    expect_convex(&p, 1);
    assert_int_equal(uv_sphere(&p, 50, 100, -1, 0, &err), 0);
    expect_convex(&p, 1);
    assert_int_equal(uv_sphere(&p, 50, 100, 1234, -1e-12, &err), 0);
    expect_convex(&p, 1);
    assert_int_equal(uv_sphere(&p, 50, 100, 1234, 1e-12, &err), 0);
    expect_convex(&p, 1);
    assert_int_equal(l_prism(&p, 0.75, 0, 0, &err), 0);
    expect_convex(&p, 0);
    assert_int_equal(uv_sphere(&p, 50, 100, 1234, -1e-6, &err), 0);
    expect_convex(&p, 0);
    assert_int_equal(uv_sphere(&p, 50, 100, 1234, 1e-6, &err), 0);
    expect_convex(&p, 0);
}

static void test_from_faces_errors(void **state)
{
    (void)state;
    int idx[32], start[8], len[8];
    rd_poly p;
    rd_error err;
    int nf = cube_faces(idx, start, len);
    assert_int_equal(rd_poly_from_faces(&p, cube_v, 8, start, len, idx, nf, &err), 0);
    rd_poly_free(&p);
    expect_faces_error(8, start, len, idx, 5,
                       "faces: open mesh: edge (1, 3) belongs to 1 face (first: face 0)");
    expect_faces_error(9, start, len, idx, 6, "faces: vertex 8 is used by no face");
    int t = idx[5];
    idx[5] = idx[7];
    idx[7] = t; /* reverse face 1 */
    expect_faces_error(
        8, start, len, idx, 6,
        "faces: inconsistent orientation: faces 1 and 2 both run edge (4, 5) from vertex 5");
    cube_faces(idx, start, len);
    idx[3] = 9;
    expect_faces_error(8, start, len, idx, 6,
                       "faces: face 0 uses vertex 9 but there are 8 vertices");
    cube_faces(idx, start, len);
    idx[2] = 2;
    idx[3] = 0; /* (0, 2, 2, 0): zero area */
    expect_faces_error(8, start, len, idx, 6, "faces: degenerate face 0 (zero area)");
    cube_faces(idx, start, len);
    idx[3] = 8; /* (0, 2, 3, 8): not planar */
    expect_faces_error(9, start, len, idx, 6, "faces: face 0 is not planar (vertex ");
    cube_faces(idx, start, len);
    len[0] = 2;
    expect_faces_error(8, start, len, idx, 6, "faces: face 0 has 2 vertices");
    /* a fourth face on edge (0, 1): the triangle (0, 1, 8) and its reverse */
    cube_faces(idx, start, len);
    int extra[6] = { 0, 1, 8, 8, 1, 0 };
    memcpy(idx + 24, extra, sizeof extra);
    start[6] = 24;
    len[6] = 3;
    start[7] = 27;
    len[7] = 3;
    expect_faces_error(9, start, len, idx, 8,
                       "faces: non-manifold mesh: edge (0, 1) belongs to 4 faces (first: face 0)");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_prism_mass),         cmocka_unit_test(test_frustum_mass),
        cmocka_unit_test(test_prism_errors),       cmocka_unit_test(test_hull_brick),
        cmocka_unit_test(test_hull_random),        cmocka_unit_test(test_hull_errors),
        cmocka_unit_test(test_from_faces_l_prism), cmocka_unit_test(test_hull_marks_l_prism),
        cmocka_unit_test(test_from_faces_errors),  cmocka_unit_test(test_convexity),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
