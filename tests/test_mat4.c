/* test_mat4.c - the vertex stage's matrix maths and its row-major convention. */
#include "test_common.h"

#include <math.h>
#include <string.h>

#include "pipeline/mat4.h"
#include "pipeline/vertex.h"

static void mul_is_row_major_product(void **state) {
    (void)state;
    /* Translation by (1,2,3) in row-major: the offsets sit at m[3], m[7], m[11]. */
    const float t[16] = {1, 0, 0, 1, 0, 1, 0, 2, 0, 0, 1, 3, 0, 0, 0, 1};
    const float s[16] = {2, 0, 0, 0, 0, 3, 0, 0, 0, 0, 4, 0, 0, 0, 0, 1};
    float ts[16], v[4];
    sg_mat4_mul(ts, t, s); /* scale first, then translate */
    const float p[4] = {1, 1, 1, 1};
    sg_mat4_transform(v, ts, p);
    assert_float_equal(v[0], 3.0f, 0.0f);
    assert_float_equal(v[1], 5.0f, 0.0f);
    assert_float_equal(v[2], 7.0f, 0.0f);
    assert_float_equal(v[3], 1.0f, 0.0f);
    float st[16];
    sg_mat4_mul(st, s, t); /* translate first, then scale */
    sg_mat4_transform(v, st, p);
    assert_float_equal(v[0], 4.0f, 0.0f);
    assert_float_equal(v[1], 9.0f, 0.0f);
    assert_float_equal(v[2], 16.0f, 0.0f);
}

static void perspective_gives_w_equal_minus_z(void **state) {
    (void)state;
    /* The OpenGL perspective matrix the scenes use (fovy 45, near 0.1, far 100). */
    const float proj[16] = {2.41421f, 0, 0,       0,        0, 2.41421f, 0,  0,
                            0,        0, -1.002f, -0.2002f, 0, 0,        -1, 0};
    float v[4];
    const float near_pt[4] = {0, 0, -0.1f, 1}, far_pt[4] = {0, 0, -100, 1};
    sg_mat4_transform(v, proj, near_pt);
    assert_float_equal(v[2] / v[3], -1.0f, 1e-4f);
    assert_float_equal(v[3], 0.1f, 1e-7f);
    sg_mat4_transform(v, proj, far_pt);
    assert_float_equal(v[2] / v[3], 1.0f, 1e-4f);
}

static void vertex_stage_transforms_each_vertex_once(void **state) {
    (void)state;
    const float id[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    const float pos[3 * 4] = {0, 0, 0, 1, 2, 0, 0, 1, 0, 0, -2, 1};
    float clip[3][4];
    uint32_t codes[3];
    sg_guard g = sg_guard_for_viewport(64, 64);
    sg_vertex_transform(id, pos, 3, clip, codes, &g);
    assert_int_equal(codes[0], 0);
    assert_int_equal(codes[1], 0); /* x = 2 is outside the viewport but inside the guard band */
    assert_int_equal(codes[2], SG_CLIP_NEAR);
}

/* The outcode as clip.h defines it, one plane at a time in plain C. */
static uint32_t outcode_reference(const float p[4], const sg_guard *g) {
    for (int k = 0; k < 4; k++)
        if (!isfinite(p[k])) return SG_CLIP_NONFINITE | ((1u << SG_CLIP_PLANE_COUNT) - 1);
    float x = p[0], y = p[1], z = p[2], w = p[3];
    const float d[SG_CLIP_PLANE_COUNT] = {z + w,         w - z,         w - SG_CLIP_W_MIN,
                                          x + g->gx * w, g->gx * w - x, y + g->gy * w,
                                          g->gy * w - y};
    uint32_t code = 0;
    for (int k = 0; k < SG_CLIP_PLANE_COUNT; k++)
        if (!(d[k] >= 0.0f)) code |= 1u << k;
    return code;
}

/* The vertex stage works four vertices at a time: its outcodes and attribute checks must be those
 * of the one-vertex functions, for values on every plane, just off it, and non-finite. */
static void vertex_stage_matches_one_vertex_functions(void **state) {
    (void)state;
    const float id[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    const float vals[] = {0.0f,      -0.0f,   1.0f,      -1.0f,     1e-9f,  2e-9f,
                          1e-10f,    1000.0f, -1000.0f,  1e30f,     -1e30f, INFINITY,
                          -INFINITY, NAN,     0.999999f, -1.000001f};
    enum { NV = sizeof vals / sizeof vals[0], N = 4099 }; /* not a multiple of 4: a tail too */
    static float pos[N * 4], clip[N][4], colors[N * 4], tex[N * 2];
    static uint32_t codes[N];
    static uint8_t ok[N];
    unsigned seed = 12345;
    for (int i = 0; i < N * 4; i++) {
        seed = seed * 1103515245u + 12345u;
        pos[i] = vals[(seed >> 16) % NV];
        colors[i] = (seed >> 8) % 97 == 0 ? vals[(seed >> 4) % NV] : 0.5f;
        if (i < N * 2) tex[i] = (seed >> 9) % 89 == 0 ? vals[(seed >> 3) % NV] : 1.5f;
    }
    for (int i = 0; i < N; i++) pos[i * 4 + 3] = i % 3 ? pos[i * 4 + 3] : fabsf(pos[i * 4 + 3]);
    sg_guard g = sg_guard_for_viewport(1024, 768);
    sg_vertex_transform(id, pos, N, clip, codes, &g);
    for (int i = 0; i < N; i++) {
        assert_int_equal(codes[i], sg_clip_outcode(clip[i], &g));
        assert_int_equal(codes[i], outcode_reference(clip[i], &g));
    }
    for (int nattr = 4; nattr <= 6; nattr += 2)
        for (int with_colors = 0; with_colors < 2; with_colors++) {
            const float *c = with_colors ? colors : NULL;
            for (int i = 0; i < N; i++) ok[i] = (uint8_t)(i % 5 != 0);
            sg_vertex_check_attributes(c, tex, nattr, N, ok);
            for (int i = 0; i < N; i++)
                assert_int_equal(ok[i], i % 5 != 0 &&
                                            sg_vertex_attributes_finite(c, tex, nattr, (size_t)i));
        }
}

/* The fused stage of fixed draws gives the outcodes, screen records and flags of
 * sg_vertex_transform then sg_vertex_project, and sg_vertex_clip the clip positions the first
 * stores (assembly works them out again for the primitives it clips), to the bit. */
static void fused_stage_matches_transform_then_project(void **state) {
    (void)state;
    const float proj[16] = {2.41421f, 0, 0,       0,        0, 2.41421f, 0,  0,
                            0,        0, -1.002f, -0.2002f, 0, 0,        -1, 0};
    const float wv[16] = {0.8f, -0.6f, 0,     0.3f, 0.6f, 0.8f, 0.1f, -0.2f,
                          0,    -0.1f, 0.99f, -3,   0,    0,    0,    1};
    float mvp[16];
    sg_mat4_mul(mvp, proj, wv);
    enum { N = 4099 };
    static float pos[N * 4], clip[N][4];
    static uint32_t codes[N], codes2[N];
    static sg_svert screen[N], screen2[N];
    static uint8_t ok[N], ok2[N];
    unsigned seed = 777;
    for (int i = 0; i < N * 4; i++) {
        seed = seed * 1103515245u + 12345u;
        pos[i] = (float)((int)(seed >> 8) % 20001 - 10000) / 1000.0f; /* -10 .. 10 */
        if (i % 4 == 3) pos[i] = (seed >> 20) % 13 == 0 ? 0.5f : 1.0f;
    }
    pos[17] = NAN;
    pos[42] = INFINITY;
    sg_guard g = sg_guard_for_viewport(800, 600);
    sg_setup_params p = {0};
    p.width = 800;
    p.height = 600;
    sg_vertex_transform(mvp, pos, N, clip, codes, &g);
    sg_vertex_project(&p, (const float(*)[4])clip, codes, N, screen, ok);
    memset(screen2, 0, sizeof screen2);
    sg_vertex_transform_project(mvp, pos, N, codes2, &g, &p, screen2, ok2);
    int inside = 0, outside = 0;
    for (int i = 0; i < N; i++) {
        float c[4];
        sg_vertex_clip(mvp, pos + (size_t)i * 4, c);
        assert_memory_equal(c, clip[i], sizeof c);
        assert_int_equal(codes2[i], codes[i]);
        assert_int_equal(ok2[i], ok[i]);
        if (ok[i]) assert_memory_equal(&screen2[i], &screen[i], sizeof screen[i]);
        inside += ok[i];
        outside += codes[i] != 0;
    }
    assert_true(inside > N / 10 && outside > N / 10); /* both kinds are tested */
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(mul_is_row_major_product),
        cmocka_unit_test(perspective_gives_w_equal_minus_z),
        cmocka_unit_test(vertex_stage_transforms_each_vertex_once),
        cmocka_unit_test(vertex_stage_matches_one_vertex_functions),
        cmocka_unit_test(fused_stage_matches_transform_then_project),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
