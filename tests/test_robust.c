/* test_robust.c - behaviour on hard input, through the public API: texcoords far from the origin
 * sample exactly like their twins near it under repeat wrapping (no drift), and a triangle with a
 * NaN or infinite position, colour or texcoord is dropped without touching anything else. */
#include "test_common.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <sgapi/sgapi.h>

#define S 64

typedef struct fixture {
    sgDevice *dev;
    sgImage2D color, tex;
    sgPipelineStateObject pso;
} fixture;

static int setup(void **state) {
    fixture *f = calloc(1, sizeof *f);
    assert_int_equal(sgCreateDevice(NULL, &f->dev), SG_OK);
    sgImage2DDesc cd = {.width = S, .height = S, .format = SG_FORMAT_RGBA8_UNORM};
    assert_int_equal(sgCreateImage2D(f->dev, &cd, &f->color), SG_OK);
    /* 7 x 5 texture with a different value in every texel, so any drift shows. */
    uint8_t texels[7 * 5 * 4];
    for (int i = 0; i < 7 * 5; i++) {
        texels[i * 4 + 0] = (uint8_t)(i * 37);
        texels[i * 4 + 1] = (uint8_t)(255 - i * 11);
        texels[i * 4 + 2] = (uint8_t)(i * 91);
        texels[i * 4 + 3] = 255;
    }
    sgImage2DDesc td = {.width = 7, .height = 5, .format = SG_FORMAT_RGBA8_UNORM, .data = texels};
    assert_int_equal(sgCreateImage2D(f->dev, &td, &f->tex), SG_OK);
    sgPipelineDesc pd = {
        .shade = SG_SHADE_TEXTURE_MODULATE, .filter = SG_FILTER_BILINEAR, .wrap = SG_WRAP_REPEAT};
    assert_int_equal(sgCreatePipelineStateObject(f->dev, &pd, &f->pso), SG_OK);
    *state = f;
    return 0;
}

static int teardown(void **state) {
    fixture *f = *state;
    sgDestroyDevice(f->dev);
    free(f);
    return 0;
}

/* Draws a full-screen quad with texcoords from (s0, t0) into out; with `shift`, every texcoord is
 * then moved back by (s0, t0) in float, which is exact: the near-origin twin of the same floats. */
static void draw_quad(fixture *f, float s0, float t0, int shift, const float *bad_pos,
                      const float *bad_uv, uint8_t *out) {
    float pos[5 * 4] = {-1, -1, 0, 1, 1, -1, 0, 1, 1, 1, 0, 1, -1, 1, 0, 1, 0, 0, 0, 1};
    /* Spans that are not dyadic, so interpolation rounds (at 1e4 to about 1e-3). */
    const float ds = 1.37f, dt = 0.91f;
    float uv[5 * 2] = {s0, t0, s0 + ds, t0, s0 + ds, t0 + dt, s0, t0 + dt, s0, t0};
    for (int i = 0; shift && i < 5; i++) {
        uv[i * 2] -= s0;
        uv[i * 2 + 1] -= t0;
    }
    if (bad_pos) memcpy(&pos[16], bad_pos, 4 * sizeof(float));
    if (bad_uv) memcpy(&uv[8], bad_uv, 2 * sizeof(float));
    /* Two triangles of the quad, plus one using vertex 4 (the bad one, when set). */
    const uint32_t idx[9] = {0, 1, 2, 0, 2, 3, 0, 4, 2};
    sgGeomDesc gd = {.vertex_count = 5,
                     .positions = pos,
                     .texcoords = uv,
                     .index_count = bad_pos || bad_uv ? 9 : 6,
                     .indices = idx};
    sgGeom g;
    assert_int_equal(sgCreateGeom(f->dev, &gd, &g), SG_OK);
    sgPassDesc pass = {.color = f->color};
    sgDrawParams dp = {.world_view = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1},
                       .proj = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1},
                       .texture = f->tex};
    assert_int_equal(sgBeginRenderPass(f->dev, &pass), SG_OK);
    assert_int_equal(sgDraw(f->dev, f->pso, g, &dp), SG_OK);
    assert_int_equal(sgEndRenderPass(f->dev, &pass), SG_OK);
    assert_int_equal(sgReadImage2D(f->dev, f->color, out, 0), SG_OK);
    assert_int_equal(sgDestroyGeom(f->dev, g), SG_OK);
}

static void far_texcoords_do_not_drift(void **state) {
    fixture *f = *state;
    static uint8_t near[S * S * 4], far[S * S * 4];
    /* Interpolated naively, texcoords near 1e4 have a resolution of 1e-3 (a few bilinear-weight
     * steps on this texture); rebased per triangle they sample exactly as near the origin. */
    const float offsets[][2] = {{10000, 0}, {0, -10000}, {-9999, 12345}, {65536, 65536}};
    for (int k = 0; k < 4; k++) {
        draw_quad(f, offsets[k][0], offsets[k][1], 1, NULL, NULL, near);
        draw_quad(f, offsets[k][0], offsets[k][1], 0, NULL, NULL, far);
        assert_memory_equal(near, far, sizeof near);
    }
}

static void nonfinite_triangles_are_dropped(void **state) {
    fixture *f = *state;
    static uint8_t clean[S * S * 4], dirty[S * S * 4];
    draw_quad(f, 0.25f, 0.5f, 0, NULL, NULL, clean);
    const float bad_pos[][4] = {
        {NAN, 0, 0, 1}, {0, INFINITY, 0, 1}, {0, 0, -INFINITY, 1}, {0, 0, 0, NAN}};
    for (int k = 0; k < 4; k++) {
        draw_quad(f, 0.25f, 0.5f, 0, bad_pos[k], NULL, dirty);
        assert_memory_equal(clean, dirty, sizeof clean);
    }
    const float bad_uv[][2] = {{NAN, 0}, {0, INFINITY}, {-INFINITY, NAN}};
    /* The extra triangle would cover the left half again; with a bad texcoord it is dropped. */
    const float inside[4] = {-1, 1, 0, 1};
    for (int k = 0; k < 3; k++) {
        draw_quad(f, 0.25f, 0.5f, 0, inside, bad_uv[k], dirty);
        assert_memory_equal(clean, dirty, sizeof clean);
    }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(far_texcoords_do_not_drift),
        cmocka_unit_test(nonfinite_triangles_are_dropped),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
