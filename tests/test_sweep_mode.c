/* Response modes of a sweep case (src/ensembles/sweep_mode.c, docs/FRAGILITY.md): each of the
 * six modes from a body summary and its joint slip, on both sides of each threshold. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include "rockdem/sweep.h"

#include <string.h>

static rd_body_summary body(int overturned, int uplifted, double tilt_ratio, double twist)
{
    rd_body_summary b;
    memset(&b, 0, sizeof b);
    b.overturned = overturned;
    b.uplifted = uplifted;
    b.max_tilt_ratio = tilt_ratio;
    b.max_twist = twist;
    return b;
}

static void each_mode(void **state)
{
    (void)state;
    const double slip = 2 * RD_MODE_SLIP_MIN, tilt = 2 * RD_MODE_TILT_MIN,
                 twist = 2 * RD_MODE_TWIST_MIN;
    rd_body_summary b;
    b = body(0, 0, 0.0, 0.0);
    assert_int_equal(rd_sweep_mode_of(&b, 0.0), RD_MODE_REST);
    assert_int_equal(rd_sweep_mode_of(&b, slip), RD_MODE_SLIDE);
    b = body(0, 0, 0.0, twist); /* spinning on its base without rocking: a slide */
    assert_int_equal(rd_sweep_mode_of(&b, slip), RD_MODE_SLIDE);
    b = body(0, 1, tilt, 0.0);
    assert_int_equal(rd_sweep_mode_of(&b, 0.0), RD_MODE_ROCK);
    assert_int_equal(rd_sweep_mode_of(&b, slip), RD_MODE_ROCK_SLIDE);
    b = body(0, 1, tilt, -twist); /* the sign of the twist does not matter */
    assert_int_equal(rd_sweep_mode_of(&b, 0.0), RD_MODE_ROCK_TWIST);
    assert_int_equal(rd_sweep_mode_of(&b, slip), RD_MODE_ROCK_TWIST);
    b = body(1, 1, 5.0, twist);
    assert_int_equal(rd_sweep_mode_of(&b, slip), RD_MODE_OVERTURN);
}

static void thresholds(void **state)
{
    (void)state;
    rd_body_summary b = body(0, 1, 0.5 * RD_MODE_TILT_MIN, 0.0); /* lifted, tilt below: rest */
    assert_int_equal(rd_sweep_mode_of(&b, 0.0), RD_MODE_REST);
    b = body(0, 0, 10 * RD_MODE_TILT_MIN, 0.0); /* tilt without uplift (the bed's): rest */
    assert_int_equal(rd_sweep_mode_of(&b, 0.0), RD_MODE_REST);
    assert_int_equal(rd_sweep_mode_of(&b, 0.5 * RD_MODE_SLIP_MIN), RD_MODE_REST);
    b = body(0, 1, 2 * RD_MODE_TILT_MIN, 0.5 * RD_MODE_TWIST_MIN);
    assert_int_equal(rd_sweep_mode_of(&b, 0.0), RD_MODE_ROCK);
}

static void names(void **state)
{
    (void)state;
    static const char *const want[RD_MODE_COUNT] = { "rest",       "slide",      "rock",
                                                     "rock-slide", "rock-twist", "overturn" };
    for (int m = 0; m < RD_MODE_COUNT; m++)
        assert_string_equal(rd_sweep_mode_name((rd_sweep_mode)m), want[m]);
    assert_string_equal(rd_sweep_mode_name(RD_MODE_COUNT), "unknown");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(each_mode),
        cmocka_unit_test(thresholds),
        cmocka_unit_test(names),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
