/* The surface contact model between two meshes (`contact model surface`, src/engine/surface.c
 * pair_mesh: neither body convex, the face pairs from the two bodies' trees, src/contact/bvh.c;
 * docs/CONTACT.md section 8.5). Issue 39, item 2: mesh against mesh, every face of every body.
 * On main such pairs were refused ("are both non-convex") or, in the vertex model, never met. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "rockdem/rockdem.h"

/* Mesh against mesh (src/engine/surface.c pair_mesh: neither body convex; main refused the pair,
 * "are both non-convex"): an L-shaped prism (tests/data/mesh/L_block.obj, 0.2 m^2, 0.4 m tall,
 * rho 2700) settled on an L-shaped fixed prism twice its size (L_base.obj) bears on the whole of
 * its footprint, every point once: its closure is the Winkler closed form m g / (KN A), A = 0.2
 * m^2. Tolerance 1e-3 relative, as the convex stack's (a point counted twice, or a face pair
 * missed, is a whole triangle's share: 25 % or more). Also the free pair: the L block on a free
 * L base on the fixed one (both joints mesh against mesh). */
static void test_mesh_closure(void **state)
{
    (void)state;
    for (int k = 0; k < 2; k++) {
        const char *fixed_base =
            "block import mesh 'L_base.obj' position 0.44 0.44 -0.25 density 2700 fixed name base\n"
            "block import mesh 'L_block.obj' position 0.27 0.27 0.2 density 2700 name block\n";
        const char *free_base =
            "block import mesh 'L_base.obj' position 0.44 0.44 -0.75 density 2700 fixed name floor\n"
            "block import mesh 'L_base.obj' position 0.44 0.44 -0.25 density 2700 name base\n"
            "block import mesh 'L_block.obj' position 0.27 0.27 0.2 density 2700 name block\n";
        char text[1024];
        snprintf(text, sizeof text,
                 "%scontact model surface\n"
                 "contact property stiffness-normal 1e10 stiffness-shear 1e11 friction 40 "
                 "restitution 1\nmodel damping viscous 0.5\nmodel solve time 0.2\n",
                 k ? free_base : fixed_base);
        rd_scenario sc;
        rd_error err;
        if (rd_scenario_parse(&sc, "tests/data/mesh/closure.dat", text, &err))
            fail_msg("%s", err.msg);
        rd_sim *sim = rd_sim_create(&sc, &err);
        if (!sim) fail_msg("%s", err.msg);
        assert_false(rd_status_failed(rd_sim_run(sim)));
        double xb[3] = { 0, 0, -0.25 }, qb[4] = { 1, 0, 0, 0 }, x[3], q[4], v[3], w[3];
        if (k) rd_sim_body_state(sim, 0, xb, qb, v, w);
        rd_sim_body_state(sim, k, x, q, v, w);
        /* the base's top normal (it tilts under the block's offset load): the closure is the
           block's height above the top plane less its 0.2 m, along that normal */
        const double n[3] = { 2 * (qb[1] * qb[3] + qb[0] * qb[2]),
                              2 * (qb[2] * qb[3] - qb[0] * qb[1]),
                              1 - 2 * (qb[1] * qb[1] + qb[2] * qb[2]) };
        const double h = n[0] * (x[0] - xb[0]) + n[1] * (x[1] - xb[1]) + n[2] * (x[2] - xb[2]);
        rd_sim_free(sim);
        rd_scenario_free(&sc);
        const double g = 9.81, KN = 1e10, m = 2700 * 0.2 * 0.4, A = 0.2;
        rd_check_rel(k ? "L block's closure on a free L base (m)"
                       : "L block's closure on a fixed L base (m)",
                     0.25 + 0.2 - h, m * g / (KN * A), 1e-3, RD_STRICT);
    }
}

/* Nothing passes silently (issue 39, item 3): at KN 1e5 Pa/m the L block's static closure would
 * be m g / (KN A) = 0.106 m, far past the contact band (1e-3 of the smaller radius, 0.39 mm):
 * the run must end `penetrated`, naming the pair, not go on with the block inside its base. */
static void test_mesh_penetrated(void **state)
{
    (void)state;
    const char *text =
        "block import mesh 'L_base.obj' position 0.44 0.44 -0.25 density 2700 fixed name base\n"
        "block import mesh 'L_block.obj' position 0.27 0.27 0.2 density 2700 name block\n"
        "contact model surface\n"
        "contact property stiffness-normal 1e5 stiffness-shear 1e6 friction 40 restitution 1\n"
        "model settle off\nmodel solve time 1\n";
    rd_scenario sc;
    rd_error err;
    if (rd_scenario_parse(&sc, "tests/data/mesh/sink.dat", text, &err)) fail_msg("%s", err.msg);
    rd_sim *sim = rd_sim_create(&sc, &err);
    if (!sim) fail_msg("%s", err.msg);
    rd_status st = rd_sim_run(sim);
    const char *msg = rd_sim_error(sim);
    print_message("status %d: %s\n", (int)st, msg ? msg : "");
    assert_int_equal(st, RD_STATUS_PENETRATED);
    assert_non_null(strstr(msg, "body 'block' passed into body 'base'"));
    rd_sim_free(sim);
    rd_scenario_free(&sc);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_mesh_closure),
        cmocka_unit_test(test_mesh_penetrated),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
