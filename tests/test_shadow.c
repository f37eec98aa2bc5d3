/* test_shadow.c - depth-only passes, depth bias and shadow maps through the public API: a
 * depth-only pass writes the depth an ordinary pass writes, bit for bit (blended draws included,
 * at 1 and 2 threads); bias moves depth by its constant and slope terms, clamped to [0, 1];
 * shadowed unlit pixels are half their colour, exactly, with PCF's quarter steps on an edge; a
 * hidden light removes exactly that light's share of Phong, flat and Gouraud lighting (flat and
 * Gouraud seen: the unshadowed image, within a step); points behind the light or
 * off the map are lit; and every bad input is refused with its code, nothing drawn.
 */
#include "test_common.h"
#include "test_objects.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "raster/shadow.h"
#include "sgapi/sgapi.h"

enum { S = 32 };
static const float IDENTITY[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
/* Orthographic: x, y as they are; view z -2 to NDC -0.25 (window depth 0.375). */
static const float ORTHO[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -0.25f, -0.75f, 0, 0, 0, 1};

typedef struct api {
    sgDevice *dev;
    sgImage2D color, depth, map;
} api;

static void api_open(api *a, int threads) {
    assert_int_equal(sgCreateDevice(&(sgDeviceDesc){.thread_count = threads}, &a->dev), SG_OK);
    a->color = test_image(a->dev, S, S, SG_FORMAT_RGBA8_UNORM);
    a->depth = test_image(a->dev, S, S, SG_FORMAT_D32_FLOAT);
    a->map = test_image(a->dev, S, S, SG_FORMAT_D32_FLOAT);
}

static sgDrawParams params_of(const float proj[16]) {
    sgDrawParams p;
    memset(&p, 0, sizeof p);
    memcpy(p.world_view, IDENTITY, sizeof IDENTITY);
    memcpy(p.proj, proj, 16 * sizeof(float));
    return p;
}

/* ---- depth-only passes ---- */

/* Overlapping triangles at several depths under a perspective projection, some crossing the near
 * plane, with vertex colours (which a depth-only pass never reads). */
static sgGeom scene_geom(sgDevice *dev) {
    enum { N = 40 };
    float pos[N * 3 * 4], col[N * 3 * 4];
    uint32_t idx[N * 3];
    unsigned x = 12345;
    for (int i = 0; i < N * 3; i++) {
        for (int k = 0; k < 4; k++) {
            x = x * 1664525u + 1013904223u;
            float r = (float)(x >> 8) / 16777216.0f;
            pos[i * 4 + k] = k == 3 ? 1.0f : k == 2 ? -0.2f - 6.0f * r : -3.0f + 6.0f * r;
            col[i * 4 + k] = r;
        }
        idx[i] = (uint32_t)i;
    }
    sgGeom g;
    assert_int_equal(sgCreateGeom(dev,
                                  &(sgGeomDesc){.vertex_count = N * 3,
                                                .positions = pos,
                                                .colors = col,
                                                .index_count = N * 3,
                                                .indices = idx},
                                  &g),
                     SG_OK);
    return g;
}

static const float PERSP[16] = {1.5f, 0, 0, 0, 0, 1.5f, 0, 0, 0, 0, -1.02f, -0.202f, 0, 0, -1, 0};

/* The scene's depth, rendered with or without a colour target. */
static void render_depth(api *a, bool with_color, sgPipelineDesc d, float *out) {
    sgGeom g = scene_geom(a->dev);
    sgPipelineStateObject p = test_pso(a->dev, d);
    sgDrawParams dp = params_of(PERSP);
    sgPassDesc pass = {.depth = a->depth,
                       .depth_load = SG_LOAD_CLEAR,
                       .clear_depth = d.depth.compare == SG_COMPARE_GREATER ? 0.0f : 1.0f};
    if (with_color) pass.color = a->color;
    assert_int_equal(sgBeginRenderPass(a->dev, &pass), SG_OK);
    assert_int_equal(sgDraw(a->dev, p, g, &dp), SG_OK);
    assert_int_equal(sgEndRenderPass(a->dev, &pass), SG_OK);
    assert_int_equal(sgReadImage2D(a->dev, a->depth, out, 0), SG_OK);
    sgDestroyGeom(a->dev, g);
    sgDestroyPipelineStateObject(a->dev, p);
}

static void depth_only_pass_writes_the_same_depth(void **state) {
    (void)state;
    const sgPipelineDesc descs[] = {
        {.depth = {.compare = SG_COMPARE_LESS, .write = true}},
        {.depth = {.compare = SG_COMPARE_LESS_EQUAL, .write = true}, .blend = SG_BLEND_ALPHA},
        {.depth = {.compare = SG_COMPARE_GREATER, .write = true}},
        {.depth = {.compare = SG_COMPARE_LESS, .write = true}, .cull = SG_CULL_BACK},
        {.depth = {.compare = SG_COMPARE_LESS,
                   .write = true,
                   .bias_constant = 0.001f,
                   .bias_slope = 1.5f}},
    };
    for (int threads = 1; threads <= 2; threads++) {
        api a;
        api_open(&a, threads);
        for (size_t i = 0; i < sizeof descs / sizeof *descs; i++) {
            float full[S * S], only[S * S];
            render_depth(&a, true, descs[i], full);
            render_depth(&a, false, descs[i], only);
            assert_memory_equal(full, only, sizeof full);
            int written = 0;
            for (int k = 0; k < S * S; k++) written += full[k] != 1.0f && full[k] != 0.0f;
            assert_true(written > S * S / 4); /* the scene covers the view */
        }
        sgDestroyDevice(a.dev);
    }
}

/* A depth-only pass needs no colour but must have a target; its draws still check their input. */
static void depth_only_pass_input(void **state) {
    (void)state;
    api a;
    api_open(&a, 1);
    sgPassDesc none = {0};
    assert_int_equal(sgBeginRenderPass(a.dev, &none), SG_ERROR_INVALID_HANDLE);
    sgPassDesc bad = {.depth = a.color};
    assert_int_equal(sgBeginRenderPass(a.dev, &bad), SG_ERROR_FORMAT_MISMATCH);
    sgPassDesc pass = {.depth = a.map, .clear_depth = 1.0f};
    assert_int_equal(sgBeginRenderPass(a.dev, &pass), SG_OK);
    sgGeom g = scene_geom(a.dev);
    sgPipelineStateObject p =
        test_pso(a.dev, (sgPipelineDesc){.shade = SG_SHADE_TEXTURE_MODULATE,
                                         .depth = {.compare = SG_COMPARE_LESS, .write = true}});
    sgDrawParams dp = params_of(PERSP);
    assert_int_equal(sgDraw(a.dev, p, g, &dp), SG_ERROR_MISSING_TEXTURE);
    assert_int_equal(sgEndRenderPass(a.dev, &pass), SG_OK);
    float d[S * S];
    assert_int_equal(sgReadImage2D(a.dev, a.map, d, 0), SG_OK);
    for (int i = 0; i < S * S; i++) assert_true(d[i] == 1.0f);
    sgDestroyDevice(a.dev);
}

/* ---- depth bias ---- */

/* A quad covering the view at view depth z0 (left edge) to z1 (right edge), orthographic. */
static sgGeom quad(sgDevice *dev, float z0, float z1, const float *normals) {
    const float pos[16] = {-1, -1, z0, 1, 1, -1, z1, 1, 1, 1, z1, 1, -1, 1, z0, 1};
    const uint32_t idx[6] = {0, 1, 2, 0, 2, 3};
    sgGeom g;
    assert_int_equal(sgCreateGeom(dev,
                                  &(sgGeomDesc){.vertex_count = 4,
                                                .positions = pos,
                                                .normals = normals,
                                                .index_count = 6,
                                                .indices = idx},
                                  &g),
                     SG_OK);
    return g;
}

static void quad_depth(api *a, float z0, float z1, float bc, float bs, float *out) {
    sgGeom g = quad(a->dev, z0, z1, NULL);
    sgPipelineStateObject p =
        test_pso(a->dev, (sgPipelineDesc){.depth = {.compare = SG_COMPARE_ALWAYS,
                                                    .write = true,
                                                    .bias_constant = bc,
                                                    .bias_slope = bs}});
    sgDrawParams dp = params_of(ORTHO);
    sgPassDesc pass = {.depth = a->map, .clear_depth = 1.0f};
    assert_int_equal(sgBeginRenderPass(a->dev, &pass), SG_OK);
    assert_int_equal(sgDraw(a->dev, p, g, &dp), SG_OK);
    assert_int_equal(sgEndRenderPass(a->dev, &pass), SG_OK);
    assert_int_equal(sgReadImage2D(a->dev, a->map, out, 0), SG_OK);
    sgDestroyGeom(a->dev, g);
    sgDestroyPipelineStateObject(a->dev, p);
}

static void depth_bias_moves_depth(void **state) {
    (void)state;
    api a;
    api_open(&a, 1);
    float base[S * S], biased[S * S];
    /* Constant: a flat quad's depth moves by exactly the constant (one float addition). */
    quad_depth(&a, -2, -2, 0, 0, base);
    quad_depth(&a, -2, -2, 0.01f, 7.0f, biased); /* no slope: the slope term adds nothing */
    for (int i = 0; i < S * S; i++) assert_true(biased[i] == base[i] + 0.01f);
    /* Slope: a quad sloping in x by 0.25 * 2 / S window depth a pixel gains slope x that. */
    quad_depth(&a, -1, -3, 0, 0, base);
    quad_depth(&a, -1, -3, 0, 2.0f, biased);
    const double grad = 0.25 * 2.0 / S * 0.5;
    for (int i = 0; i < S * S; i++) assert_true(fabs((biased[i] - base[i]) - 2.0 * grad) < 1e-6);
    /* Clamped to the depth range. */
    quad_depth(&a, -2, -2, 5.0f, 0, biased);
    for (int i = 0; i < S * S; i++) assert_true(biased[i] == 1.0f);
    quad_depth(&a, -2, -2, -5.0f, 0, biased);
    for (int i = 0; i < S * S; i++) assert_true(biased[i] == 0.0f);
    /* Not finite: refused. */
    sgPipelineStateObject p;
    assert_int_equal(
        sgCreatePipelineStateObject(
            a.dev, &(sgPipelineDesc){.depth = {.write = true, .bias_constant = NAN}}, &p),
        SG_ERROR_INVALID_VALUE);
    assert_non_null(strstr(sgGetLastError(a.dev), "bias"));
    assert_int_equal(
        sgCreatePipelineStateObject(
            a.dev, &(sgPipelineDesc){.depth = {.write = true, .bias_slope = -INFINITY}}, &p),
        SG_ERROR_INVALID_VALUE);
    sgDestroyDevice(a.dev);
}

/* ---- receiving shadows ---- */

/* The map: texels of columns < edge at depth 0 (a caster in front of everything), the others 1
 * (nothing). */
static void upload_map(api *a, int edge) {
    float m[S * S];
    for (int y = 0; y < S; y++)
        for (int x = 0; x < S; x++) m[y * S + x] = x < edge ? 0.0f : 1.0f;
    assert_int_equal(sgUploadImage2D(a->dev, a->map, m, 0), SG_OK);
}

static uint8_t unorm(float v) {
    return (uint8_t)(v <= 0 ? 0 : v >= 1 ? 255 : (int)(v * 255.0f + 0.5f));
}

/* Draws the flat quad at depth -2 in `color` (unlit, or lit by `l` with normals +z), receiving
 * `sh` (NULL: none), and reads the image. */
static sgResult draw_receiver(api *a, sgLightingMode mode, const sgLighting *l, const sgShadow *sh,
                              uint8_t *out) {
    const float up[12] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
    sgGeom g = quad(a->dev, -2, -2, up);
    sgPipelineStateObject p = test_pso(a->dev, (sgPipelineDesc){.lighting = mode});
    sgDrawParams dp = params_of(ORTHO);
    const sgColor color = {0.8f, 0.6f, 0.3f, 1.0f};
    dp.color = &color;
    dp.lighting = l;
    dp.specular[0] = dp.specular[1] = dp.specular[2] = 0.5f;
    dp.shininess = 16.0f;
    dp.shadow = sh;
    sgPassDesc pass = {.color = a->color};
    assert_int_equal(sgBeginRenderPass(a->dev, &pass), SG_OK);
    sgResult r = sgDraw(a->dev, p, g, &dp);
    assert_int_equal(sgEndRenderPass(a->dev, &pass), SG_OK);
    assert_int_equal(sgReadImage2D(a->dev, a->color, out, 0), SG_OK);
    sgDestroyGeom(a->dev, g);
    sgDestroyPipelineStateObject(a->dev, p);
    return r;
}

/* The light sees the view as the camera does, a quarter texel right and down (so no pixel centre
 * falls on a texel's edge or, with PCF, on a texel's centre). */
static sgShadow shadow_of(const api *a, bool pcf) {
    sgShadow sh;
    memset(&sh, 0, sizeof sh);
    sh.map = a->map;
    memcpy(sh.matrix, ORTHO, sizeof ORTHO);
    sh.matrix[3] = 0.5f / S;
    sh.matrix[7] = -0.5f / S;
    sh.pcf = pcf;
    return sh;
}

static void unlit_shadow_halves_the_colour(void **state) {
    (void)state;
    api a;
    api_open(&a, 1);
    upload_map(&a, 16);
    uint8_t img[S * S * 4];
    const float c[3] = {0.8f, 0.6f, 0.3f};
    for (int pcf = 0; pcf < 2; pcf++) {
        sgShadow sh = shadow_of(&a, pcf);
        assert_int_equal(draw_receiver(&a, SG_LIGHTING_NONE, NULL, &sh, img), SG_OK);
        for (int y = 0; y < S; y++)
            for (int x = 0; x < S; x++) {
                /* Without PCF texel (x, y) decides; with it texels x, x + 1 of rows y, y + 1
                 * (row S is off the map: lit). */
                float vis = (float)(x >= 16);
                if (pcf)
                    vis = ((float)(x >= 16) + (float)(x + 1 >= 16) +
                           (y + 1 < S ? (float)(x >= 16) + (float)(x + 1 >= 16) : 2.0f)) /
                          4.0f;
                const uint8_t *px = img + (y * S + x) * 4;
                for (int k = 0; k < 3; k++)
                    if (px[k] != unorm(c[k] * (0.5f + 0.5f * vis)))
                        fail_msg("pcf %d pixel (%d, %d) channel %d: %d, expected %d", pcf, x, y, k,
                                 px[k], unorm(c[k] * (0.5f + 0.5f * vis)));
                assert_int_equal(px[3], 255);
            }
    }
    /* Behind the light (w <= 0) or off the map: lit. */
    uint8_t plain[S * S * 4];
    assert_int_equal(draw_receiver(&a, SG_LIGHTING_NONE, NULL, NULL, plain), SG_OK);
    sgShadow behind = shadow_of(&a, false);
    behind.matrix[15] = -1.0f;
    assert_int_equal(draw_receiver(&a, SG_LIGHTING_NONE, NULL, &behind, img), SG_OK);
    assert_memory_equal(img, plain, sizeof img);
    sgShadow off = shadow_of(&a, true);
    off.matrix[3] = 3.0f; /* every point lands right of the map */
    assert_int_equal(draw_receiver(&a, SG_LIGHTING_NONE, NULL, &off, img), SG_OK);
    assert_memory_equal(img, plain, sizeof img);
    sgDestroyDevice(a.dev);
}

/* An ambient light, a sun and a point light: the lighting of the hidden-light tests. */
static sgLighting two_lights(void) {
    sgLighting two;
    memset(&two, 0, sizeof two);
    two.ambient[0] = two.ambient[1] = two.ambient[2] = 0.15f;
    two.light_count = 2;
    two.lights[0] = (sgLight){
        .type = SG_LIGHT_DIRECTIONAL, .direction = {0.3f, -0.2f, -1}, .color = {0.4f, 0.4f, 0.4f}};
    two.lights[1] = (sgLight){
        .type = SG_LIGHT_POINT, .position = {0.2f, 0.4f, -1.0f}, .color = {0.6f, 0.5f, 0.3f}};
    return two;
}

static void hidden_light_is_removed_from_phong(void **state) {
    (void)state;
    api a;
    api_open(&a, 1);
    sgLighting two = two_lights();
    sgLighting first = two;
    first.light_count = 1;
    uint8_t img[S * S * 4], lit[S * S * 4], without[S * S * 4];
    assert_int_equal(draw_receiver(&a, SG_LIGHTING_PHONG, &two, NULL, lit), SG_OK);
    assert_int_equal(draw_receiver(&a, SG_LIGHTING_PHONG, &first, NULL, without), SG_OK);
    assert_memory_not_equal(lit, without, sizeof lit);
    sgShadow sh = shadow_of(&a, false);
    sh.light = 1;
    upload_map(&a, S); /* all hidden: exactly the image without light 1 */
    assert_int_equal(draw_receiver(&a, SG_LIGHTING_PHONG, &two, &sh, img), SG_OK);
    assert_memory_equal(img, without, sizeof img);
    upload_map(&a, 0); /* nothing hidden: exactly the unshadowed image */
    assert_int_equal(draw_receiver(&a, SG_LIGHTING_PHONG, &two, &sh, img), SG_OK);
    assert_memory_equal(img, lit, sizeof img);
    upload_map(&a, 16); /* half: each side as its whole image */
    assert_int_equal(draw_receiver(&a, SG_LIGHTING_PHONG, &two, &sh, img), SG_OK);
    for (int y = 0; y < S; y++)
        for (int x = 0; x < S; x++) {
            size_t o = (size_t)(y * S + x) * 4;
            assert_memory_equal(img + o, x < 16 ? without + o : lit + o, 4);
        }
    sgDestroyDevice(a.dev);
}

/* Whether two images differ by at most one step in every channel. */
static bool within_one(const uint8_t *a, const uint8_t *b, size_t n) {
    for (size_t i = 0; i < n; i++)
        if (a[i] > b[i] + 1 || b[i] > a[i] + 1) return false;
    return true;
}

/* Flat and Gouraud draws keep the hidden light's part of their colours apart (light.h, split):
 * where it is hidden, exactly the image without that light (no vertex saturates here, so clamping
 * after interpolation is clamping before); where it is seen, the unshadowed image, exactly when
 * it is the only light, within one step with another light (the sums are grouped otherwise). */
static void hidden_light_is_removed_from_flat_and_gouraud(void **state) {
    (void)state;
    api a;
    api_open(&a, 1);
    sgLighting two = two_lights();
    sgLighting first = two, second = two;
    first.light_count = 1;
    second.light_count = 1;
    second.lights[0] = two.lights[1];
    const sgLightingMode modes[2] = {SG_LIGHTING_GOURAUD, SG_LIGHTING_FLAT};
    for (int m = 0; m < 2; m++) {
        uint8_t img[S * S * 4], lit[S * S * 4], without[S * S * 4], alone[S * S * 4];
        assert_int_equal(draw_receiver(&a, modes[m], &two, NULL, lit), SG_OK);
        assert_int_equal(draw_receiver(&a, modes[m], &first, NULL, without), SG_OK);
        assert_int_equal(draw_receiver(&a, modes[m], &second, NULL, alone), SG_OK);
        assert_memory_not_equal(lit, without, sizeof lit);
        sgShadow sh = shadow_of(&a, false);
        sh.light = 1;
        upload_map(&a, S); /* all hidden: exactly the image without light 1 */
        assert_int_equal(draw_receiver(&a, modes[m], &two, &sh, img), SG_OK);
        assert_memory_equal(img, without, sizeof img);
        upload_map(&a, 0); /* nothing hidden: the unshadowed image */
        assert_int_equal(draw_receiver(&a, modes[m], &two, &sh, img), SG_OK);
        assert_true(within_one(img, lit, sizeof img));
        upload_map(&a, 16); /* half: each side as its whole image */
        assert_int_equal(draw_receiver(&a, modes[m], &two, &sh, img), SG_OK);
        for (int y = 0; y < S; y++)
            for (int x = 0; x < S; x++) {
                size_t o = (size_t)(y * S + x) * 4;
                if (x < 16)
                    assert_memory_equal(img + o, without + o, 4);
                else
                    assert_true(within_one(img + o, lit + o, 4));
            }
        /* The shadowed light alone (and ambient): seen, exactly the unshadowed image. */
        sh.light = 0;
        upload_map(&a, 0);
        assert_int_equal(draw_receiver(&a, modes[m], &second, &sh, img), SG_OK);
        assert_memory_equal(img, alone, sizeof img);
    }
    sgDestroyDevice(a.dev);
}

/* Every bad shadow input: its code, a message naming the field, and nothing drawn. */
static void bad_shadow_input_is_refused(void **state) {
    (void)state;
    api a;
    api_open(&a, 1);
    sgLighting one;
    memset(&one, 0, sizeof one);
    one.light_count = 1;
    one.lights[0] =
        (sgLight){.type = SG_LIGHT_DIRECTIONAL, .direction = {0, 0, -1}, .color = {1, 1, 1}};
    uint8_t img[S * S * 4];
    sgShadow sh = shadow_of(&a, false);
    sh.map.id = 0;
    assert_int_equal(draw_receiver(&a, SG_LIGHTING_NONE, NULL, &sh, img), SG_ERROR_INVALID_HANDLE);
    assert_non_null(strstr(sgGetLastError(a.dev), "shadow->map"));
    sh.map = a.color;
    assert_int_equal(draw_receiver(&a, SG_LIGHTING_NONE, NULL, &sh, img), SG_ERROR_FORMAT_MISMATCH);
    sh = shadow_of(&a, false);
    sh.matrix[6] = NAN;
    assert_int_equal(draw_receiver(&a, SG_LIGHTING_NONE, NULL, &sh, img), SG_ERROR_INVALID_VALUE);
    assert_non_null(strstr(sgGetLastError(a.dev), "matrix[6]"));
    sh = shadow_of(&a, false);
    sh.light = 1;
    assert_int_equal(draw_receiver(&a, SG_LIGHTING_PHONG, &one, &sh, img), SG_ERROR_INVALID_VALUE);
    assert_non_null(strstr(sgGetLastError(a.dev), "shadow->light"));
    sh.light = -1;
    assert_int_equal(draw_receiver(&a, SG_LIGHTING_PHONG, &one, &sh, img), SG_ERROR_INVALID_VALUE);
    /* The light must be one of the draw's in every lit mode. */
    for (int mode = SG_LIGHTING_FLAT; mode <= SG_LIGHTING_GOURAUD; mode++) {
        sh.light = 1;
        assert_int_equal(draw_receiver(&a, (sgLightingMode)mode, &one, &sh, img),
                         SG_ERROR_INVALID_VALUE);
        assert_non_null(strstr(sgGetLastError(a.dev), "shadow->light"));
    }
    /* Every failed draw left the clear colour. */
    for (int i = 0; i < S * S * 4; i++) assert_int_equal(img[i], 0);

    /* The map is the depth target of the open pass: in use. While a pass samples it, it cannot
     * be replaced or destroyed. */
    sgGeom g = quad(a.dev, -2, -2, NULL);
    sgPipelineStateObject p = test_pso(a.dev, (sgPipelineDesc){.depth = {.write = true}});
    sgDrawParams dp = params_of(ORTHO);
    sh = shadow_of(&a, false);
    dp.shadow = &sh;
    sgPassDesc own = {.depth = a.map};
    assert_int_equal(sgBeginRenderPass(a.dev, &own), SG_OK);
    assert_int_equal(sgDraw(a.dev, p, g, &dp), SG_ERROR_IN_USE);
    assert_int_equal(sgEndRenderPass(a.dev, &own), SG_OK);
    sgPassDesc main = {.color = a.color, .depth = a.depth};
    assert_int_equal(sgBeginRenderPass(a.dev, &main), SG_OK);
    assert_int_equal(sgDraw(a.dev, p, g, &dp), SG_OK);
    float m[S * S] = {0};
    assert_int_equal(sgUploadImage2D(a.dev, a.map, m, 0), SG_ERROR_IN_USE);
    assert_int_equal(sgDestroyImage2D(a.dev, a.map), SG_ERROR_IN_USE);
    assert_int_equal(sgEndRenderPass(a.dev, &main), SG_OK);
    assert_int_equal(sgUploadImage2D(a.dev, a.map, m, 0), SG_OK);
    sgDestroyDevice(a.dev);
}

/* The scalar visibility at a few hand-placed points (the SIMD variants are held to it by
 * test_shade_simd). */
static void visibility_by_hand(void **state) {
    (void)state;
    const float map[4] = {0.5f, 1.0f, 0.25f, 0.75f}; /* 2 x 2 */
    sg_shadow_view s = {map, 2, 2, {0}, 0, false};
    memcpy(s.m, IDENTITY, sizeof IDENTITY); /* P is already the light's clip position */
    /* texel (0, 0) is x in [-1, 0), y in (0, 1]; depth 0.5 is NDC z 0 */
    assert_true(sg_shadow_visibility(&s, (const float[3]){-0.5f, 0.5f, 0.0f}) == 1.0f);
    assert_true(sg_shadow_visibility(&s, (const float[3]){-0.5f, 0.5f, 0.01f}) == 0.0f);
    assert_true(sg_shadow_visibility(&s, (const float[3]){0.5f, -0.5f, 0.6f}) == 0.0f);
    assert_true(sg_shadow_visibility(&s, (const float[3]){0.5f, -0.5f, 0.4f}) == 1.0f);
    assert_true(sg_shadow_visibility(&s, (const float[3]){1.5f, 0.0f, 0.99f}) == 1.0f); /* off */
    assert_true(sg_shadow_visibility(&s, (const float[3]){0.0f, 0.0f, 5.0f}) == 0.0f);  /* far */
    s.pcf = true; /* the centre of the map: the mean of all four */
    assert_true(sg_shadow_visibility(&s, (const float[3]){0.0f, 0.0f, 0.2f}) == 0.5f);
    assert_true(sg_shadow_visibility(&s, (const float[3]){0.0f, 0.0f, -0.4f}) == 0.75f);
    assert_true(sg_shadow_visibility(&s, (const float[3]){0.0f, 0.0f, -0.8f}) == 1.0f);
    /* a corner: one texel in the map, three outside (lit) */
    assert_true(sg_shadow_visibility(&s, (const float[3]){-1.0f, 1.0f, 0.9f}) == 0.75f);
    assert_true(sg_shadow_visibility(&s, (const float[3]){NAN, 0.0f, 0.0f}) == 1.0f);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(depth_only_pass_writes_the_same_depth),
        cmocka_unit_test(depth_only_pass_input),
        cmocka_unit_test(depth_bias_moves_depth),
        cmocka_unit_test(unlit_shadow_halves_the_colour),
        cmocka_unit_test(hidden_light_is_removed_from_phong),
        cmocka_unit_test(hidden_light_is_removed_from_flat_and_gouraud),
        cmocka_unit_test(bad_shadow_input_is_refused),
        cmocka_unit_test(visibility_by_hand),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
