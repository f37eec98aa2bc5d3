/* test_clip.c - homogeneous clipping: near plane crossings, vertices behind the eye, w = 0. */
#include "test_common.h"

#include <math.h>
#include <string.h>

#include "pipeline/clip.h"

static sg_cvert vert(float x, float y, float z, float w, float a) {
    sg_cvert v;
    memset(&v, 0, sizeof v);
    v.pos[0] = x;
    v.pos[1] = y;
    v.pos[2] = z;
    v.pos[3] = w;
    v.attr[0] = a;
    return v;
}

static uint32_t codes(const sg_cvert *p, int n, const sg_guard *g) {
    uint32_t c = 0;
    for (int i = 0; i < n; i++) c |= sg_clip_outcode(p[i].pos, g);
    return c;
}

static void crossing_near_plane_is_split(void **state) {
    (void)state;
    sg_guard g = sg_guard_for_viewport(100, 100);
    /* One vertex behind the near plane (z < -w): the triangle becomes a quad. */
    sg_cvert p[SG_CLIP_MAX_VERTS] = {vert(0, 0, -2, 1, 0), vert(1, 0, 0, 1, 1),
                                     vert(0, 1, 0, 1, 1)};
    int n = sg_clip_polygon(p, 3, codes(p, 3, &g), 1, &g);
    assert_int_equal(n, 4);
    for (int i = 0; i < n; i++) {
        assert_true(p[i].pos[2] + p[i].pos[3] >= -1e-6f);
        assert_true(p[i].pos[3] > 0);
    }
    /* Cut vertices lie halfway along their edges (z from -2 to 0, plane at z = -1), and the
     * attribute is interpolated with them. */
    int halfway = 0;
    for (int i = 0; i < n; i++)
        if (fabsf(p[i].pos[2] + 1.0f) < 1e-6f) {
            assert_float_equal(p[i].attr[0], 0.5f, 1e-6f);
            halfway++;
        }
    assert_int_equal(halfway, 2);
}

static void vertices_behind_eye_never_reach_divide(void **state) {
    (void)state;
    sg_guard g = sg_guard_for_viewport(100, 100);
    /* Two vertices behind the eye (w < 0), one in front. */
    sg_cvert p[SG_CLIP_MAX_VERTS] = {vert(0, 0, 0, 1, 0), vert(1, 0, 2, -2, 0),
                                     vert(-1, 0.5f, 3, -3, 0)};
    int n = sg_clip_polygon(p, 3, codes(p, 3, &g), 1, &g);
    assert_int_equal(n, 3);
    for (int i = 0; i < n; i++) {
        assert_true(p[i].pos[3] >= SG_CLIP_W_MIN);
        assert_int_equal(sg_clip_outcode(p[i].pos, &g) & (SG_CLIP_NEAR | SG_CLIP_WMIN), 0);
    }
    /* All three behind the eye: outcodes share a plane, nothing is left. */
    sg_cvert q[SG_CLIP_MAX_VERTS] = {vert(0, 0, 2, -1, 0), vert(1, 0, 2, -1, 0),
                                     vert(0, 1, 2, -1, 0)};
    uint32_t c = sg_clip_outcode(q[0].pos, &g) & sg_clip_outcode(q[1].pos, &g) &
                 sg_clip_outcode(q[2].pos, &g);
    assert_true(c != 0);
    assert_int_equal(sg_clip_polygon(q, 3, codes(q, 3, &g), 1, &g), 0);
}

static void w_zero_is_clipped_away(void **state) {
    (void)state;
    sg_guard g = sg_guard_for_viewport(100, 100);
    sg_cvert p[SG_CLIP_MAX_VERTS] = {vert(0, 0, 0, 0, 0), vert(0.5f, 0, 0, 1, 0),
                                     vert(0, 0.5f, 0, 1, 0)};
    assert_true(sg_clip_outcode(p[0].pos, &g) & SG_CLIP_WMIN);
    int n = sg_clip_polygon(p, 3, codes(p, 3, &g), 1, &g);
    assert_true(n >= 3);
    for (int i = 0; i < n; i++) assert_true(p[i].pos[3] >= SG_CLIP_W_MIN);
}

static void nan_vertex_is_outside_every_plane(void **state) {
    (void)state;
    sg_guard g = sg_guard_for_viewport(100, 100);
    const float p[4] = {NAN, 0, 0, 1}, q[4] = {0, 0, INFINITY, 1};
    uint32_t all = SG_CLIP_NONFINITE | ((1u << SG_CLIP_PLANE_COUNT) - 1);
    assert_int_equal(sg_clip_outcode(p, &g), all);
    assert_int_equal(sg_clip_outcode(q, &g), all);
}

static void shared_clipped_edge_is_bit_identical(void **state) {
    (void)state;
    sg_guard g = sg_guard_for_viewport(100, 100);
    /* Two triangles share the edge a-b, which crosses the near plane; each lists it in a
     * different direction. The new vertex on that edge must be the same bits in both. */
    sg_cvert a = vert(0.3f, 0.1f, -3.7f, 1.3f, 0.25f), b = vert(-0.2f, 0.7f, 0.4f, 0.9f, 0.75f);
    sg_cvert t1[SG_CLIP_MAX_VERTS] = {a, b, vert(0.9f, -0.4f, 0.1f, 1.1f, 0)};
    sg_cvert t2[SG_CLIP_MAX_VERTS] = {b, a, vert(-0.8f, -0.6f, 0.2f, 1.0f, 1)};
    int n1 = sg_clip_polygon(t1, 3, codes(t1, 3, &g), 1, &g);
    int n2 = sg_clip_polygon(t2, 3, codes(t2, 3, &g), 1, &g);
    int matches = 0;
    for (int i = 0; i < n1; i++)
        for (int j = 0; j < n2; j++)
            if (memcmp(t1[i].pos, t2[j].pos, sizeof t1[i].pos) == 0 &&
                memcmp(t1[i].attr, t2[j].attr, sizeof t1[i].attr) == 0)
                matches++;
    assert_int_equal(matches, 2); /* b and the cut point on a-b */
}

static void guard_band_only_cuts_far_outside(void **state) {
    (void)state;
    sg_guard g = sg_guard_for_viewport(1024, 1024);
    const float inside[4] = {50, -50, 0, 1}; /* far off screen, inside the guard band */
    const float outside[4] = {1e6f, 0, 0, 1};
    assert_int_equal(sg_clip_outcode(inside, &g), 0);
    assert_int_equal(sg_clip_outcode(outside, &g), SG_CLIP_RIGHT);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(crossing_near_plane_is_split),
        cmocka_unit_test(vertices_behind_eye_never_reach_divide),
        cmocka_unit_test(w_zero_is_clipped_away),
        cmocka_unit_test(nan_vertex_is_outside_every_plane),
        cmocka_unit_test(shared_clipped_edge_is_bit_identical),
        cmocka_unit_test(guard_band_only_cuts_far_outside),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
