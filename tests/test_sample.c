/* test_sample.c - texture sampling: bilinear weights, repeat and clamp at the edges, orientation.
 */
#include "test_common.h"

#include "tex/sample.h"

/* 2x2 texture, uploaded top row first: top row (10, 20), bottom row (30, 40) in red. */
static const uint8_t texels[16] = {10, 0, 0, 255, 20, 0, 0, 255, 30, 0, 0, 255, 40, 0, 0, 255};
static const sg_texview tv = {texels, 2, 2};

static void t_zero_is_the_bottom_row(void **state) {
    (void)state;
    assert_int_equal(sg_sample(&tv, 0.25f, 0.25f, 0, 1).c[0], 30);
    assert_int_equal(sg_sample(&tv, 0.75f, 0.25f, 0, 1).c[0], 40);
    assert_int_equal(sg_sample(&tv, 0.25f, 0.75f, 0, 1).c[0], 10);
    assert_int_equal(sg_sample(&tv, 0.75f, 0.75f, 0, 1).c[3], 255);
}

static void bilinear_weights(void **state) {
    (void)state;
    /* Texel centres give texels exactly; the middle gives the mean of all four. */
    assert_int_equal(sg_sample(&tv, 0.25f, 0.25f, 1, 1).c[0], 30);
    assert_int_equal(sg_sample(&tv, 0.75f, 0.75f, 1, 0).c[0], 20);
    assert_int_equal(sg_sample(&tv, 0.5f, 0.5f, 1, 0).c[0], 25);
    /* A quarter of the way from the bottom-left centre to the right: 30 + (40 - 30) / 4. */
    assert_int_equal(sg_sample(&tv, 0.375f, 0.25f, 1, 0).c[0], 33); /* 32.5 rounds up */
}

static void repeat_wraps_across_the_edge(void **state) {
    (void)state;
    /* s = 0 sits between the last and the first column: half of each with repeat. */
    assert_int_equal(sg_sample(&tv, 0.0f, 0.25f, 1, 1).c[0], 35);
    assert_int_equal(sg_sample(&tv, 1.0f, 0.25f, 1, 1).c[0], 35);
    /* Clamp keeps the edge texel instead. */
    assert_int_equal(sg_sample(&tv, 0.0f, 0.25f, 1, 0).c[0], 30);
    assert_int_equal(sg_sample(&tv, -5.0f, 0.25f, 1, 0).c[0], 30);
    assert_int_equal(sg_sample(&tv, 7.0f, 0.25f, 0, 0).c[0], 40);
    /* Far from the origin, repeat gives the same texel as near it. */
    assert_int_equal(sg_sample(&tv, 1000.25f, 0.25f, 0, 1).c[0], 30);
    assert_int_equal(sg_sample(&tv, -999.25f, 0.25f, 0, 1).c[0], 40);
    assert_int_equal(sg_sample(&tv, 1000.375f, 0.25f, 1, 1).c[0],
                     sg_sample(&tv, 0.375f, 0.25f, 1, 1).c[0]);
}

static void nonfinite_coordinates_stay_in_bounds(void **state) {
    (void)state;
    const float bad[] = {NAN, INFINITY, -INFINITY, 1e30f, -1e30f};
    for (int i = 0; i < 5; i++)
        for (int f = 0; f < 2; f++)
            for (int r = 0; r < 2; r++) {
                sg_texel t = sg_sample(&tv, bad[i], bad[4 - i], f, r);
                assert_true(t.c[0] >= 10 && t.c[0] <= 40);
            }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(t_zero_is_the_bottom_row),
        cmocka_unit_test(bilinear_weights),
        cmocka_unit_test(repeat_wraps_across_the_edge),
        cmocka_unit_test(nonfinite_coordinates_stay_in_bounds),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
