/* test_blend.c - alpha blending and back-to-front sorting.
 *
 * - The 8-bit blend of one channel against the documented formula (lavapipe's, found by rendering
 *   all 2^24 (src, dst, alpha) there), for every input, and the packed RGBA8 blend channel by
 *   channel against it.
 * - Order: a pass of many overlapping blended and opaque triangles, in draws of several
 *   triangles, is byte-identical to drawing each triangle in a pass of its own that loads the
 *   previous result, for 1, 2 and 3 threads and every instruction set this CPU runs.
 * - Every unlit shading variant (vertex colour; texture nearest / bilinear, repeat / clamp;
 *   without mipmaps, nearest and linear), flat and varying colours, with and without a depth
 *   test, blended by every instruction set this CPU runs: the scalar reference's bytes.
 * - The constant draw colour multiplies the vertex colour; alpha from the vertex colour and from
 *   the texel.
 * - With 4 samples, a blend in front of the bin's depth at every pixel centre but not at every
 *   sample: every instruction set this CPU runs gives the scalar reference's bytes.
 * - The back-to-front order against a plain stable sort of the same keys, ties, NaN keys and
 *   quads included.
 */
#include "test_common.h"
#include "test_objects.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "pipeline/sort.h"
#include "raster/blend.h"
#include "sgapi/sgapi.h"

static const float IDENTITY[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

/* The documented blend of one channel: each product x y / 255 rounded the way lavapipe rounds it,
 * floor((t + floor(t / 256) + 128) / 256) with t = x y, then the two terms added; written with
 * divisions, independently of the library's shifts. */
static uint32_t product(uint32_t x, uint32_t y) {
    uint32_t t = x * y;
    return (t + t / 256 + 128) / 256;
}

static uint32_t reference_channel(uint32_t s, uint32_t d, uint32_t a) {
    return product(s, a) + product(d, 255 - a);
}

/* The product rounding is exact but for 24 of the 65536 products, e.g. 191 * 253 / 255 =
 * 189.5 - 1/255 rounds to 190, and the blend gives 189. */
static void product_rounding(void **state) {
    (void)state;
    int inexact = 0;
    for (uint32_t x = 0; x < 256; x++)
        for (uint32_t y = 0; y < 256; y++) {
            uint32_t exact = (2 * x * y + 255) / 510;
            assert_int_equal(sg_mul_unorm8(x, y), product(x, y));
            inexact += sg_mul_unorm8(x, y) != exact;
        }
    assert_int_equal(inexact, 24);
    assert_int_equal(sg_mul_unorm8(191, 253), 189);
}

static void blend_channel_exhaustive(void **state) {
    (void)state;
    for (uint32_t a = 0; a < 256; a++)
        for (uint32_t s = 0; s < 256; s++)
            for (uint32_t d = 0; d < 256; d++)
                if (sg_blend_channel(s, d, a) != reference_channel(s, d, a))
                    fail_msg("s %u d %u a %u: %u, want %u", s, d, a, sg_blend_channel(s, d, a),
                             reference_channel(s, d, a));
}

static void blend_rgba8_channel_by_channel(void **state) {
    (void)state;
    uint32_t x = 12345;
    for (int i = 0; i < 1000000; i++) {
        x = x * 1664525u + 1013904223u;
        uint32_t src = x;
        x = x * 1664525u + 1013904223u;
        uint32_t dst = x, out = sg_blend_rgba8(src, dst), a = src >> 24;
        for (int k = 0; k < 32; k += 8)
            assert_int_equal((out >> k) & 255u,
                             reference_channel((src >> k) & 255u, (dst >> k) & 255u, a));
    }
}

/* The 16-pixel blend of multisampled passes: sg_blend_rgba8 in every lane, alpha 0 and 255
 * and every channel's extremes among random values. */
static void blend16_matches_the_pixel_blend(void **state) {
    (void)state;
    uint32_t x = 4242;
    for (int i = 0; i < 100000; i++) {
        uint32_t src[16], dst[16], out[16];
        for (int l = 0; l < 16; l++) {
            x = x * 1664525u + 1013904223u;
            src[l] = x;
            x = x * 1664525u + 1013904223u;
            dst[l] = x;
            if ((x >> 4 & 7) == 0) src[l] |= 0xff000000u;
            if ((x >> 4 & 7) == 1) src[l] &= 0x00ffffffu;
            if ((x >> 4 & 7) == 2) dst[l] = 0xffffffffu;
        }
        sg_blend16_rgba8(src, dst, out);
        for (int l = 0; l < 16; l++) assert_int_equal(out[l], sg_blend_rgba8(src[l], dst[l]));
    }
}

/* ---- order ---- */

enum { S = 150, NTRI = 120, PER_DRAW = 8 };

typedef struct tri_scene {
    float pos[NTRI * 3 * 4], col[NTRI * 3 * 4];
    uint32_t idx[NTRI * 3];
    int blend[NTRI / PER_DRAW], write[NTRI / PER_DRAW];
} tri_scene;

static float rnd(uint32_t *x) {
    *x = *x * 1664525u + 1013904223u;
    return (float)(*x >> 8) / 16777216.0f;
}

static void make_scene(tri_scene *s) {
    uint32_t x = 777;
    for (int t = 0; t < NTRI; t++) {
        float cx = rnd(&x) * 2.2f - 1.1f, cy = rnd(&x) * 2.2f - 1.1f, z = rnd(&x) * 1.8f - 0.9f;
        float col[4] = {rnd(&x), rnd(&x), rnd(&x), rnd(&x)};
        for (int v = 0; v < 3; v++) {
            float *p = s->pos + (t * 3 + v) * 4;
            p[0] = cx + rnd(&x) * 1.2f - 0.6f;
            p[1] = cy + rnd(&x) * 1.2f - 0.6f;
            p[2] = z + rnd(&x) * 0.2f - 0.1f;
            p[3] = 1.0f;
            for (int k = 0; k < 4; k++) s->col[(t * 3 + v) * 4 + k] = v == 2 ? rnd(&x) : col[k];
            s->idx[t * 3 + v] = (uint32_t)(t * 3 + v);
        }
    }
    for (int d = 0; d < NTRI / PER_DRAW; d++) {
        s->blend[d] = d % 3 != 1;
        s->write[d] = d % 4 == 0;
    }
}

/* Renders the scene; per_triangle: every triangle in a pass of its own that loads the previous
 * colour and depth, the plain order no binning can reorder. */
static void render(const void *scene, int threads, sgSimd simd, bool per_triangle, uint8_t *out) {
    const tri_scene *s = scene;
    sgDevice *dev;
    sgDeviceDesc dd = {.thread_count = threads, .simd = simd};
    assert_int_equal(sgCreateDevice(&dd, &dev), SG_OK);
    sgImage2D color, depth;
    assert_int_equal(
        sgCreateImage2D(dev,
                        &(sgImage2DDesc){.width = S, .height = S, .format = SG_FORMAT_RGBA8_UNORM},
                        &color),
        SG_OK);
    assert_int_equal(
        sgCreateImage2D(
            dev, &(sgImage2DDesc){.width = S, .height = S, .format = SG_FORMAT_D32_FLOAT}, &depth),
        SG_OK);
    sgPipelineStateObject pso[2][2];
    for (int b = 0; b < 2; b++)
        for (int w = 0; w < 2; w++)
            assert_int_equal(
                sgCreatePipelineStateObject(
                    dev,
                    &(sgPipelineDesc){.depth = {.compare = SG_COMPARE_LESS_EQUAL, .write = w},
                                      .blend = b ? SG_BLEND_ALPHA : SG_BLEND_OPAQUE},
                    &pso[b][w]),
                SG_OK);
    sgDrawParams params = {0};
    memcpy(params.world_view, IDENTITY, sizeof IDENTITY);
    memcpy(params.proj, IDENTITY, sizeof IDENTITY);
    sgPassDesc pass = {.color = color, .depth = depth, .clear_color = {0.2f, 0.3f, 0.4f, 0.5f}};
    int per = per_triangle ? 1 : PER_DRAW;
    sgGeom *geoms = calloc(NTRI / per, sizeof *geoms);
    for (int g = 0; g < NTRI / per; g++) {
        sgGeomDesc gd = {.vertex_count = NTRI * 3,
                         .positions = s->pos,
                         .colors = s->col,
                         .index_count = 3 * per,
                         .indices = s->idx + g * 3 * per,
                         .storage = SG_STORAGE_REFERENCE};
        assert_int_equal(sgCreateGeom(dev, &gd, &geoms[g]), SG_OK);
    }
    if (!per_triangle) assert_int_equal(sgBeginRenderPass(dev, &pass), SG_OK);
    for (int g = 0; g < NTRI / per; g++) {
        int d = g * per / PER_DRAW;
        if (per_triangle) assert_int_equal(sgBeginRenderPass(dev, &pass), SG_OK);
        assert_int_equal(sgDraw(dev, pso[s->blend[d]][s->write[d]], geoms[g], &params), SG_OK);
        if (per_triangle) {
            assert_int_equal(sgEndRenderPass(dev, &pass), SG_OK);
            pass.color_load = pass.depth_load = SG_LOAD_LOAD;
        }
    }
    if (!per_triangle) assert_int_equal(sgEndRenderPass(dev, &pass), SG_OK);
    assert_int_equal(sgReadImage2D(dev, color, out, 0), SG_OK);
    free(geoms);
    sgDestroyDevice(dev);
}

static void blending_follows_submission_order(void **state) {
    (void)state;
    tri_scene *s = calloc(1, sizeof *s);
    make_scene(s);
    uint8_t *want = malloc(S * S * 4), *got = malloc(S * S * 4);
    render(s, 1, SG_SIMD_SCALAR, true, want);
    /* The image is neither the clear colour nor one opaque colour everywhere. */
    int blended = 0;
    for (int i = 0; i < S * S; i++) blended += want[i * 4 + 3] != 255 && want[i * 4 + 3] != 128;
    assert_true(blended > S * S / 4);
    test_same_in_one_pass(render, s, want, got, S * S * 4);
    free(want);
    free(got);
    free(s);
}

/* ---- where alpha comes from ---- */

/* One full-screen quad of vertex colour `vc` (optionally tinted, optionally textured with a
 * single texel) blended over the clear colour; returns the pixel. */
static uint32_t blend_one(const float vc[4], const sgColor *tint, const uint8_t *texel,
                          const float clear[4]) {
    sgDevice *dev;
    assert_int_equal(sgCreateDevice(NULL, &dev), SG_OK);
    sgImage2D color, tex = {0};
    assert_int_equal(
        sgCreateImage2D(dev,
                        &(sgImage2DDesc){.width = 8, .height = 8, .format = SG_FORMAT_RGBA8_UNORM},
                        &color),
        SG_OK);
    if (texel)
        assert_int_equal(sgCreateImage2D(dev,
                                         &(sgImage2DDesc){.width = 1,
                                                          .height = 1,
                                                          .format = SG_FORMAT_RGBA8_UNORM,
                                                          .data = texel},
                                         &tex),
                         SG_OK);
    float pos[16] = {-1, -1, 0, 1, 1, -1, 0, 1, 1, 1, 0, 1, -1, 1, 0, 1}, col[16], uv[8] = {0};
    for (int i = 0; i < 16; i++) col[i] = vc[i % 4];
    const uint32_t idx[4] = {0, 1, 2, 3};
    sgGeom g;
    assert_int_equal(sgCreateGeom(dev,
                                  &(sgGeomDesc){.vertex_count = 4,
                                                .positions = pos,
                                                .colors = col,
                                                .texcoords = uv,
                                                .index_count = 4,
                                                .indices = idx,
                                                .primitive = SG_PRIMITIVE_QUADS},
                                  &g),
                     SG_OK);
    sgPipelineStateObject pso;
    sgPipelineDesc pd = {.blend = SG_BLEND_ALPHA};
    if (texel) pd.shade = SG_SHADE_TEXTURE_MODULATE;
    assert_int_equal(sgCreatePipelineStateObject(dev, &pd, &pso), SG_OK);
    sgDrawParams params = {.texture = tex, .color = tint};
    memcpy(params.world_view, IDENTITY, sizeof IDENTITY);
    memcpy(params.proj, IDENTITY, sizeof IDENTITY);
    sgPassDesc pass = {.color = color};
    memcpy(pass.clear_color, clear, sizeof pass.clear_color);
    assert_int_equal(sgBeginRenderPass(dev, &pass), SG_OK);
    assert_int_equal(sgDraw(dev, pso, g, &params), SG_OK);
    assert_int_equal(sgEndRenderPass(dev, &pass), SG_OK);
    uint8_t px[8 * 8 * 4];
    assert_int_equal(sgReadImage2D(dev, color, px, 0), SG_OK);
    sgDestroyDevice(dev);
    for (int i = 1; i < 64; i++) assert_memory_equal(px, px + 4 * i, 4);
    return (uint32_t)px[0] | (uint32_t)px[1] << 8 | (uint32_t)px[2] << 16 | (uint32_t)px[3] << 24;
}

static uint32_t unorm(float v) {
    return (uint32_t)(v * 255.0f + 0.5f);
}

static uint32_t expect(const float src[4], const float dst[4]) {
    uint32_t s = 0, d = 0;
    for (int k = 0; k < 4; k++) {
        s |= unorm(src[k]) << (8 * k);
        d |= unorm(dst[k]) << (8 * k);
    }
    return sg_blend_rgba8(s, d);
}

static void alpha_sources(void **state) {
    (void)state;
    const float clear[4] = {0.0f, 0.5f, 1.0f, 1.0f};
    /* Vertex alpha. */
    const float vc[4] = {1.0f, 0.2f, 0.6f, 0.25f};
    assert_int_equal(blend_one(vc, NULL, NULL, clear), expect(vc, clear));
    /* The constant colour multiplies the vertex colour, alpha included. */
    const sgColor tint = {0.5f, 1.0f, 0.5f, 0.5f};
    const float tinted[4] = {1.0f * 0.5f, 0.2f, 0.6f * 0.5f, 0.25f * 0.5f};
    assert_int_equal(blend_one(vc, &tint, NULL, clear), expect(tinted, clear));
    /* Zero-initialised params (no colour) are opaque white: the vertex colour as is; alpha 1
     * replaces the pixel. */
    const float opaque[4] = {0.1f, 0.2f, 0.3f, 1.0f};
    assert_int_equal(blend_one(opaque, NULL, NULL, clear), expect(opaque, clear));
    /* Texel alpha, with a white vertex colour: the texel blends as it is. */
    const float white[4] = {1, 1, 1, 1};
    const uint8_t texel[4] = {200, 100, 50, 64};
    const float tf[4] = {200 / 255.0f, 100 / 255.0f, 50 / 255.0f, 64 / 255.0f};
    assert_int_equal(blend_one(white, NULL, texel, clear), expect(tf, clear));
    /* Alpha 0 leaves the pixel alone. */
    const float none[4] = {1, 1, 1, 0};
    assert_int_equal(blend_one(none, NULL, NULL, clear), expect(clear, clear));
}

/* ---- every shading variant blended ---- */

enum { TS = 96, TTRI = 240, TPER = 24 };

/* Renders TTRI small triangles (vertex colours with alpha, some all white, some one colour;
 * texture coordinates past [0, 1], minified to every level of the chain) in draws of TPER, each
 * draw cycling through the unlit shading variants and depth states, blended over an opaque
 * background; the textured draws with `mip`. */
static void render_variants(sgSimd simd, sgMipmap mip, uint8_t *out) {
    sgDevice *dev;
    assert_int_equal(sgCreateDevice(&(sgDeviceDesc){.simd = simd}, &dev), SG_OK);
    uint8_t texels[13 * 7 * 4];
    uint32_t x = 4242;
    for (int i = 0; i < 13 * 7 * 4; i++) texels[i] = (uint8_t)(rnd(&x) * 256.0f);
    sgImage2D color, depth, tex;
    assert_int_equal(
        sgCreateImage2D(
            dev, &(sgImage2DDesc){.width = TS, .height = TS, .format = SG_FORMAT_RGBA8_UNORM},
            &color),
        SG_OK);
    assert_int_equal(
        sgCreateImage2D(dev,
                        &(sgImage2DDesc){.width = TS, .height = TS, .format = SG_FORMAT_D32_FLOAT},
                        &depth),
        SG_OK);
    assert_int_equal(sgCreateImage2D(dev,
                                     &(sgImage2DDesc){.width = 13,
                                                      .height = 7,
                                                      .format = SG_FORMAT_RGBA8_UNORM,
                                                      .mip_levels = SG_MIP_LEVELS_ALL,
                                                      .data = texels},
                                     &tex),
                     SG_OK);
    float *pos = malloc(TTRI * 3 * 4 * sizeof *pos), *col = malloc(TTRI * 3 * 4 * sizeof *col);
    float *uv = malloc(TTRI * 3 * 2 * sizeof *uv);
    uint32_t *idx = malloc(TTRI * 3 * sizeof *idx);
    for (int t = 0; t < TTRI; t++) {
        float cx = rnd(&x) * 2.0f - 1.0f, cy = rnd(&x) * 2.0f - 1.0f, z = rnd(&x) * 1.6f - 0.8f;
        float size = t % 5 == 0 ? 0.5f : 0.12f; /* mostly a few tiles, partly covered */
        float one[4] = {rnd(&x), rnd(&x), rnd(&x), rnd(&x)};
        for (int v = 0; v < 3; v++) {
            int i = t * 3 + v;
            pos[i * 4 + 0] = cx + (rnd(&x) - 0.5f) * size;
            pos[i * 4 + 1] = cy + (rnd(&x) - 0.5f) * size;
            pos[i * 4 + 2] = z + rnd(&x) * 0.2f - 0.1f;
            pos[i * 4 + 3] = 0.5f + rnd(&x); /* perspective: 1/q varies */
            for (int k = 0; k < 4; k++)
                col[i * 4 + k] = t % 3 == 0 ? 1.0f : (t % 3 == 1 ? one[k] : rnd(&x));
            uv[i * 2 + 0] = rnd(&x) * 4.0f - 1.5f;
            uv[i * 2 + 1] = rnd(&x) * 4.0f - 1.5f;
            idx[i] = (uint32_t)i;
        }
    }
    static const sgFilter filters[2] = {SG_FILTER_NEAREST, SG_FILTER_BILINEAR};
    static const sgWrap wraps[2] = {SG_WRAP_REPEAT, SG_WRAP_CLAMP_TO_EDGE};
    static const sgCompare compares[2] = {SG_COMPARE_ALWAYS, SG_COMPARE_LESS};
    sgPassDesc pass = {.color = color, .depth = depth, .clear_color = {0.2f, 0.6f, 0.4f, 1.0f}};
    assert_int_equal(sgBeginRenderPass(dev, &pass), SG_OK);
    for (int d = 0; d < TTRI / TPER; d++) {
        int variant = d % 5; /* vertex colour, then filter x wrap */
        sgPipelineDesc pd = {.blend = SG_BLEND_ALPHA,
                             .depth = {.compare = compares[(d / 5) % 2], .write = d % 3 != 0}};
        if (variant > 0) {
            pd.shade = SG_SHADE_TEXTURE_MODULATE;
            pd.filter = filters[(variant - 1) / 2];
            pd.wrap = wraps[(variant - 1) % 2];
            pd.mipmap = mip;
        }
        sgPipelineStateObject pso;
        assert_int_equal(sgCreatePipelineStateObject(dev, &pd, &pso), SG_OK);
        sgGeom g;
        assert_int_equal(sgCreateGeom(dev,
                                      &(sgGeomDesc){.vertex_count = TTRI * 3,
                                                    .positions = pos,
                                                    .colors = col,
                                                    .texcoords = uv,
                                                    .index_count = TPER * 3,
                                                    .indices = idx + d * TPER * 3,
                                                    .storage = SG_STORAGE_REFERENCE},
                                      &g),
                         SG_OK);
        sgDrawParams params = {.texture = tex};
        memcpy(params.world_view, IDENTITY, sizeof IDENTITY);
        memcpy(params.proj, IDENTITY, sizeof IDENTITY);
        assert_int_equal(sgDraw(dev, pso, g, &params), SG_OK);
    }
    assert_int_equal(sgEndRenderPass(dev, &pass), SG_OK);
    assert_int_equal(sgReadImage2D(dev, color, out, 0), SG_OK);
    sgDestroyDevice(dev);
    free(pos);
    free(col);
    free(uv);
    free(idx);
}

/* Every instruction set this CPU runs blends every variant to the scalar reference's bytes (the
 * SIMD ones inline the shading and shade pixels, or mipmapped quads, of several tiles together),
 * without mipmaps and with each kind. */
static void blended_variants_identical(void **state) {
    (void)state;
    uint8_t *want = malloc(TS * TS * 4), *got = malloc(TS * TS * 4);
    static const sgMipmap mips[3] = {SG_MIPMAP_NONE, SG_MIPMAP_NEAREST, SG_MIPMAP_LINEAR};
    for (int m = 0; m < 3; m++) {
        render_variants(SG_SIMD_SCALAR, mips[m], want);
        int changed = 0; /* most of the image is drawn over */
        for (int i = 0; i < TS * TS; i++) changed += want[i * 4 + 1] != 153;
        assert_true(changed > TS * TS / 2);
        for (int simd = SG_SIMD_SCALAR + 1; simd <= SG_SIMD_NEON; simd++) {
            if (!test_simd_runs((sgSimd)simd)) continue;
            render_variants((sgSimd)simd, mips[m], got);
            for (int i = 0; i < TS * TS * 4; i++)
                if (want[i] != got[i])
                    fail_msg("simd %d, mipmap %d: byte %d (pixel %d, %d) is %d, the reference's %d",
                             simd, (int)mips[m], i, i / 4 % TS, i / 4 / TS, got[i], want[i]);
        }
    }
    free(want);
    free(got);
}

/* ---- a blend in front of the bin's depth at its pixel centres, not at all its samples ---- */

enum { PS = 64 }; /* one bin */

/* An opaque quad at window depth 0.5 over the whole image, then a blended triangle over it (a
 * depth test, no depth write) whose depth grows by 0.01 a pixel to the right, 0.498 at the last
 * column's centres: every pixel centre passes, but sample 1 of the last column, 0.375 pixel to
 * the right of its centre, lies at 0.50175, behind the quad. 4 samples. */
static void render_near_miss(sgSimd simd, uint8_t *out) {
    sgDevice *dev;
    assert_int_equal(sgCreateDevice(&(sgDeviceDesc){.thread_count = 1, .simd = simd}, &dev), SG_OK);
    sgImage2D color = test_image(dev, PS, PS, SG_FORMAT_RGBA8_UNORM);
    sgImage2D depth = test_image(dev, PS, PS, SG_FORMAT_D32_FLOAT);
    /* window depth 0.498 + 0.01 (x - 63.5) at window x; x = 32 (ndc + 1), depth = (z + 1) / 2 */
    float pos[7 * 4], col[7 * 4];
    const float ndc[7][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}, {-1, -1}, {3, -1}, {-1, 3}};
    for (int v = 0; v < 7; v++) {
        const float win = 0.498f + 0.01f * (32.0f * (ndc[v][0] + 1.0f) - 63.5f);
        pos[4 * v] = ndc[v][0];
        pos[4 * v + 1] = ndc[v][1];
        pos[4 * v + 2] = v < 4 ? 0.0f : 2.0f * win - 1.0f;
        pos[4 * v + 3] = 1.0f;
        const float rgba[2][4] = {{0.9f, 0.1f, 0.1f, 1.0f}, {0.1f, 0.2f, 0.9f, 0.5f}};
        memcpy(col + 4 * v, rgba[v < 4 ? 0 : 1], sizeof rgba[0]);
    }
    const uint32_t quad[6] = {0, 1, 2, 0, 2, 3}, tri[3] = {4, 5, 6};
    sgGeom g[2];
    for (int k = 0; k < 2; k++)
        assert_int_equal(sgCreateGeom(dev,
                                      &(sgGeomDesc){.vertex_count = 7,
                                                    .positions = pos,
                                                    .colors = col,
                                                    .index_count = k ? 3 : 6,
                                                    .indices = k ? tri : quad},
                                      &g[k]),
                         SG_OK);
    sgPipelineStateObject opaque =
        test_pso(dev, (sgPipelineDesc){.depth = {.compare = SG_COMPARE_LESS, .write = true}});
    sgPipelineStateObject blend = test_pso(
        dev, (sgPipelineDesc){.blend = SG_BLEND_ALPHA, .depth = {.compare = SG_COMPARE_LESS}});
    sgDrawParams params = {0};
    memcpy(params.world_view, IDENTITY, sizeof IDENTITY);
    memcpy(params.proj, IDENTITY, sizeof IDENTITY);
    sgPassDesc pass = {.color = color, .depth = depth, .clear_depth = 1.0f, .samples = 4};
    assert_int_equal(sgBeginRenderPass(dev, &pass), SG_OK);
    assert_int_equal(sgDraw(dev, opaque, g[0], &params), SG_OK);
    assert_int_equal(sgDraw(dev, blend, g[1], &params), SG_OK);
    assert_int_equal(sgEndRenderPass(dev, &pass), SG_OK);
    assert_int_equal(sgReadImage2D(dev, color, out, 0), SG_OK);
    sgDestroyDevice(dev);
}

/* A blend whose depth passes at every pixel centre of a bin may still fail at a sample: the sets
 * whose 4-sample walk leaves out a test that every sample passes (rast_msaa.c, passes_bin) keep
 * it here, and give the scalar reference's bytes. */
static void blend_passes_centres_not_samples(void **state) {
    (void)state;
    uint8_t *want = malloc(PS * PS * 4), *got = malloc(PS * PS * 4);
    render_near_miss(SG_SIMD_SCALAR, want);
    /* the last column keeps a sample of the quad, so it resolves unlike the one before it */
    for (int y = 0; y < PS; y++) {
        const uint8_t *row = want + (size_t)y * PS * 4;
        assert_memory_not_equal(row + 4 * (PS - 1), row + 4 * (PS - 3), 4);
        assert_memory_equal(row + 4 * (PS - 3), row + 4 * (PS - 2), 4);
    }
    for (int simd = SG_SIMD_SCALAR + 1; simd <= SG_SIMD_NEON; simd++) {
        if (!test_simd_runs((sgSimd)simd)) continue;
        render_near_miss((sgSimd)simd, got);
        for (int i = 0; i < PS * PS * 4; i++)
            if (want[i] != got[i])
                fail_msg("simd %d: byte %d (pixel %d, %d) is %d, the reference's %d", simd, i,
                         i / 4 % PS, i / 4 / PS, got[i], want[i]);
    }
    free(want);
    free(got);
}

/* ---- back-to-front order ---- */

typedef struct keyed {
    float key;
    uint32_t tri;
} keyed;

static int cmp_keyed(const void *pa, const void *pb) {
    const keyed *a = pa, *b = pb;
    if (isnan(a->key) != isnan(b->key)) return isnan(a->key) ? 1 : -1; /* NaN keys last */
    if (a->key < b->key) return -1;
    if (a->key > b->key) return 1;
    return (a->tri > b->tri) - (a->tri < b->tri); /* stable: equal keys keep their order */
}

static float view_z(const float m[16], const float *p) {
    float z = ((m[8] * p[0] + m[9] * p[1]) + m[10] * p[2]) + m[11] * p[3];
    float w = ((m[12] * p[0] + m[13] * p[1]) + m[14] * p[2]) + m[15] * p[3];
    return w != 1.0f ? z / w : z;
}

static void check_sort(const float m[16], const float *pos, int nv, const uint32_t *idx, int ni,
                       int quads) {
    int per = quads ? 4 : 3, ntri = ni / per * (quads ? 2 : 1);
    uint32_t *tris = malloc((size_t)ntri * 3 * sizeof *tris);
    keyed *k = malloc((size_t)ntri * sizeof *k);
    for (int i = 0, t = 0; i < ni; i += per) {
        const uint32_t *q = idx + i;
        uint32_t sets[2][3] = {{q[0], q[1], q[2]}, {q[0], q[quads ? 2 : 1], q[quads ? 3 : 2]}};
        for (int h = 0; h < (quads ? 2 : 1); h++, t++) {
            memcpy(tris + 3 * t, sets[h], sizeof sets[h]);
            float z0 = view_z(m, pos + 4 * sets[h][0]), z1 = view_z(m, pos + 4 * sets[h][1]);
            float z2 = view_z(m, pos + 4 * sets[h][2]);
            k[t].key = ((z0 + z1) + z2) / 3.0f;
            k[t].tri = (uint32_t)t;
        }
    }
    qsort(k, (size_t)ntri, sizeof *k, cmp_keyed);
    void *scratch = malloc(sg_sort_scratch_size(nv, (size_t)ntri));
    uint32_t *out = malloc((size_t)ntri * 3 * sizeof *out);
    sg_sort_back_to_front(m, pos, nv, idx, ni, quads ? 4 : 3, scratch, out);
    for (int t = 0; t < ntri; t++)
        if (memcmp(out + 3 * t, tris + 3 * k[t].tri, 3 * sizeof *out) != 0)
            fail_msg("triangle %d of the order differs", t);
    free(tris);
    free(k);
    free(scratch);
    free(out);
}

static void sort_is_stable_back_to_front(void **state) {
    (void)state;
    enum { NV = 3000, NI = 6000 };
    float *pos = malloc(NV * 4 * sizeof *pos);
    uint32_t *idx = malloc(NI * sizeof *idx);
    uint32_t x = 99;
    for (int i = 0; i < NV; i++) {
        /* Coarse z values so that many keys tie exactly; some negative zero. */
        pos[i * 4 + 0] = rnd(&x) * 10 - 5;
        pos[i * 4 + 1] = rnd(&x) * 10 - 5;
        pos[i * 4 + 2] = i % 7 == 0 ? -0.0f : (float)(int)(rnd(&x) * 8) - 4;
        pos[i * 4 + 3] = i % 5 == 0 ? 2.0f : 1.0f;
        if (i % 11 == 0) pos[i * 4 + 2] = pos[i * 4 + 3] = 0.0f; /* view z = 0 / 0: NaN key */
    }
    for (int i = 0; i < NI; i++) {
        x = x * 1664525u + 1013904223u;
        idx[i] = (x >> 8) % NV;
    }
    const float rot[16] = {0.8f, 0, 0.6f, 0.1f, 0, 1, 0, -0.2f, -0.6f, 0, 0.8f, -3, 0, 0, 0, 1};
    const float persp_w[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0.01f, 0, 1};
    check_sort(IDENTITY, pos, NV, idx, NI, 0);
    check_sort(rot, pos, NV, idx, NI, 0);
    check_sort(persp_w, pos, NV, idx, NI, 0);
    check_sort(rot, pos, NV, idx, NI, 1);
    check_sort(rot, pos, NV, idx, 0, 0); /* nothing to sort */
    free(pos);
    free(idx);
}

/* Through the API: two overlapping coplanar-in-order quads of one geom, submitted near first;
 * sorted, the far one is blended first and the near one over it. */
static void sorted_draw_blends_far_first(void **state) {
    (void)state;
    sgDevice *dev;
    assert_int_equal(sgCreateDevice(NULL, &dev), SG_OK);
    sgImage2D color;
    assert_int_equal(
        sgCreateImage2D(dev,
                        &(sgImage2DDesc){.width = 4, .height = 4, .format = SG_FORMAT_RGBA8_UNORM},
                        &color),
        SG_OK);
    const float q[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    float pos[32], col[32];
    for (int i = 0; i < 8; i++) {
        pos[i * 4 + 0] = q[i % 4][0];
        pos[i * 4 + 1] = q[i % 4][1];
        pos[i * 4 + 2] = i < 4 ? -1.0f : -2.0f; /* the first quad is nearer (view looks down -z) */
        pos[i * 4 + 3] = 1;
        const float c[4] = {i < 4 ? 1.0f : 0.0f, i < 4 ? 0.0f : 1.0f, 0.0f, 0.5f};
        memcpy(col + i * 4, c, sizeof c);
    }
    const uint32_t idx[8] = {0, 1, 2, 3, 4, 5, 6, 7};
    sgGeom g;
    assert_int_equal(sgCreateGeom(dev,
                                  &(sgGeomDesc){.vertex_count = 8,
                                                .positions = pos,
                                                .colors = col,
                                                .index_count = 8,
                                                .indices = idx,
                                                .primitive = SG_PRIMITIVE_QUADS},
                                  &g),
                     SG_OK);
    sgPipelineStateObject pso;
    assert_int_equal(
        sgCreatePipelineStateObject(dev, &(sgPipelineDesc){.blend = SG_BLEND_ALPHA}, &pso), SG_OK);
    /* An orthographic projection that keeps z in range: z' = z / 4 + ... */
    const float proj[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -0.25f, 0, 0, 0, 0, 1};
    uint32_t px[2];
    for (int sorted = 0; sorted < 2; sorted++) {
        sgDrawParams params = {.sort = sorted ? SG_SORT_BACK_TO_FRONT : SG_SORT_NONE};
        memcpy(params.world_view, IDENTITY, sizeof IDENTITY);
        memcpy(params.proj, proj, sizeof proj);
        sgPassDesc pass = {.color = color, .clear_color = {0, 0, 0, 1}};
        assert_int_equal(sgBeginRenderPass(dev, &pass), SG_OK);
        assert_int_equal(sgDraw(dev, pso, g, &params), SG_OK);
        assert_int_equal(sgEndRenderPass(dev, &pass), SG_OK);
        uint8_t img[4 * 4 * 4];
        assert_int_equal(sgReadImage2D(dev, color, img, 0), SG_OK);
        memcpy(&px[sorted], img, 4);
    }
    sgDestroyDevice(dev);
    const uint32_t black = 0xff000000u, red = 0x800000ffu, green = 0x8000ff00u;
    assert_int_equal(px[0], sg_blend_rgba8(green, sg_blend_rgba8(red, black)));
    assert_int_equal(px[1], sg_blend_rgba8(red, sg_blend_rgba8(green, black)));
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(product_rounding),
        cmocka_unit_test(blend_channel_exhaustive),
        cmocka_unit_test(blend_rgba8_channel_by_channel),
        cmocka_unit_test(blend16_matches_the_pixel_blend),
        cmocka_unit_test(blending_follows_submission_order),
        cmocka_unit_test(alpha_sources),
        cmocka_unit_test(blended_variants_identical),
        cmocka_unit_test(blend_passes_centres_not_samples),
        cmocka_unit_test(sort_is_stable_back_to_front),
        cmocka_unit_test(sorted_draw_blends_far_first),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
