/* Geometry: polyhedron mass properties and subcontact points against closed forms. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include "geometry/geom.h"

#include <math.h>
#include <stdlib.h>

/* Brick a x b x c: V = abc, I_x = V (b^2 + c^2) / 12 per unit density. Exact arithmetic up to
 * round-off, so 1e-12 relative. */
static void test_brick_mass(void **state)
{
    (void)state;
    rd_poly p;
    rd_mass m;
    rd_error err;
    double size[3] = { 0.4, 0.7, 1.6 };
    assert_int_equal(rd_poly_brick(&p, size, &err), 0);
    assert_int_equal(rd_poly_mass(&p, &m, &err), 0);
    double V = 0.4 * 0.7 * 1.6;
    assert_true(fabs(m.volume - V) < 1e-12 * V);
    for (int i = 0; i < 3; i++) assert_true(fabs(m.centroid[i]) < 1e-14);
    double I[3] = { V * (0.49 + 2.56) / 12, V * (0.16 + 2.56) / 12, V * (0.16 + 0.49) / 12 };
    /* principal moments come sorted ascending: z, y, x */
    assert_true(fabs(m.principal[0] - I[2]) < 1e-12 * I[2]);
    assert_true(fabs(m.principal[1] - I[1]) < 1e-12 * I[1]);
    assert_true(fabs(m.principal[2] - I[0]) < 1e-12 * I[0]);
    rd_poly_free(&p);
}

/* A brick moved off the origin and rotated: the divergence-theorem integrals must give the same
 * volume and principal moments, the centroid at the offset, and an axis along the long edge. */
static void test_offset_rotated_brick(void **state)
{
    (void)state;
    rd_poly p;
    rd_mass m;
    rd_error err;
    double size[3] = { 1, 2, 3 };
    assert_int_equal(rd_poly_brick(&p, size, &err), 0);
    double c = cos(0.3), s = sin(0.3), off[3] = { 10, -5, 2 };
    for (int i = 0; i < p.nv; i++) {
        double x = p.v[i][0], y = p.v[i][1];
        p.v[i][0] = c * x - s * y + off[0];
        p.v[i][1] = s * x + c * y + off[1];
        p.v[i][2] += off[2];
    }
    rd_poly_update(&p);
    assert_int_equal(rd_poly_mass(&p, &m, &err), 0);
    assert_true(fabs(m.volume - 6) < 1e-11);
    for (int i = 0; i < 3; i++) assert_true(fabs(m.centroid[i] - off[i]) < 1e-11);
    assert_true(fabs(m.principal[0] - 6 * (1 + 4) / 12.0) < 1e-10); /* about the 3 m axis */
    assert_true(fabs(m.principal[2] - 6 * (4 + 9) / 12.0) < 1e-10); /* about the 1 m axis */
    assert_true(fabs(fabs(m.axes[6]) - 1) < 1e-10); /* first principal axis (smallest) along z */
    rd_poly_to_frame(&p, &m);
    double r = sqrt(0.25 + 1 + 2.25);
    assert_true(fabs(p.radius - r) < 1e-10);
    rd_poly_free(&p);
}

/* Subcontact areas sum to the face area; corner mode gives the 4 vertices with A/4 each;
 * spacing L/10 on a square gives an 11 x 11 grid whose interior points carry one cell each. */
static void test_face_points(void **state)
{
    (void)state;
    rd_poly p;
    rd_error err;
    double size[3] = { 0.5, 0.5, 1.0 };
    assert_int_equal(rd_poly_brick(&p, size, &err), 0);
    double(*x)[3] = malloc(400 * sizeof *x), *a = malloc(400 * sizeof *a);
    int n = rd_poly_face_points(&p, 0, 0.0, x, a, 400);
    assert_int_equal(n, 4);
    double sum = 0;
    for (int i = 0; i < n; i++) {
        sum += a[i];
        assert_true(fabs(a[i] - 0.0625) < 1e-15);
    }
    assert_true(fabs(sum - 0.25) < 1e-14);
    n = rd_poly_face_points(&p, 0, 0.05, x, a, 400);
    assert_int_equal(n, 121);
    sum = 0;
    double amax = 0;
    for (int i = 0; i < n; i++) {
        sum += a[i];
        amax = fmax(amax, a[i]);
        assert_true(fabs(x[i][2] + 0.5) < 1e-15);
    }
    assert_true(fabs(sum - 0.25) < 1e-13);
    assert_true(fabs(amax - 0.0025) < 1e-15);
    assert_int_equal(rd_poly_face_points(&p, 0, 0.05, x, a, 10), -1); /* too small a buffer */
    assert_true(fabs(rd_poly_face_area(&p, 2) - 0.5) < 1e-14);
    free(x);
    free(a);
    rd_poly_free(&p);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_brick_mass),
        cmocka_unit_test(test_offset_rotated_brick),
        cmocka_unit_test(test_face_points),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
