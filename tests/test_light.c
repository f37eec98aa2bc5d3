/* test_light.c - lighting: the equation against an independent double-precision evaluation of
 * its statement (OpenGL 1.x fixed-function lighting, docs/api.md), the float pow against libm,
 * numerical stability (degenerate triangles, zero normals, shininess 0 and 128, a light at the
 * surface, saturating colours, normals under non-uniform scale), the three modes through the
 * public API, and the checks of bad input.
 */
#include "test_common.h"
#include "test_objects.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pipeline/light.h"
#include "sgapi/sgapi.h"

/* ---- the equation in double, written from its statement ---- */

static void norm_d(const double v[3], double out[3]) {
    double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int k = 0; k < 3; k++) out[k] = l > 0 ? v[k] / l : 0.0;
}

static double dot_d(const double a[3], const double b[3]) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void eval_d(const sgLighting *l, const float spec[3], float shine, const float P[3],
                   const float n[3], const float base[4], double prim[4], double sec[3]) {
    double N[3], V[3], nn[3] = {n[0], n[1], n[2]}, mp[3] = {-P[0], -P[1], -P[2]};
    norm_d(nn, N);
    norm_d(mp, V);
    double diff[3] = {0}, sp[3] = {0};
    for (int i = 0; i < l->light_count; i++) {
        const sgLight *li = &l->lights[i];
        double L[3], att = 1.0;
        if (li->type == SG_LIGHT_DIRECTIONAL) {
            double d[3] = {-li->direction[0], -li->direction[1], -li->direction[2]};
            norm_d(d, L);
        } else {
            double v[3] = {li->position[0] - P[0], li->position[1] - P[1], li->position[2] - P[2]};
            double dist = sqrt(dot_d(v, v));
            norm_d(v, L);
            double c = li->attenuation[0], lin = li->attenuation[1], q = li->attenuation[2];
            if (c == 0 && lin == 0 && q == 0) c = 1;
            att = 1.0 / (c + lin * dist + q * dist * dist);
        }
        double ndotl = dot_d(N, L);
        if (ndotl <= 0) continue;
        double h[3] = {L[0] + V[0], L[1] + V[1], L[2] + V[2]}, H[3];
        norm_d(h, H);
        double ndoth = dot_d(N, H);
        double s = shine == 0 ? 1.0 : pow(ndoth > 0 ? ndoth : 0.0, shine);
        for (int k = 0; k < 3; k++) {
            diff[k] += att * ndotl * li->color[k];
            sp[k] += att * s * li->color[k];
        }
    }
    for (int k = 0; k < 3; k++) {
        double v = base[k] * l->ambient[k] + base[k] * diff[k];
        prim[k] = v < 0 ? 0 : v > 1 ? 1 : v;
        sec[k] = sp[k] * spec[k];
    }
    prim[3] = base[3];
}

static float frand(unsigned *x, float lo, float hi) {
    *x = *x * 1664525u + 1013904223u;
    return lo + (hi - lo) * (float)(*x >> 8) / 16777216.0f;
}

static void random_lighting(unsigned *x, sgLighting *l) {
    memset(l, 0, sizeof *l);
    l->light_count = 1 + (int)(*x % SG_MAX_LIGHTS);
    for (int k = 0; k < 3; k++) l->ambient[k] = frand(x, 0, 0.3f);
    for (int i = 0; i < l->light_count; i++) {
        sgLight *li = &l->lights[i];
        li->type = i % 2 ? SG_LIGHT_POINT : SG_LIGHT_DIRECTIONAL;
        for (int k = 0; k < 3; k++) {
            li->direction[k] = frand(x, -1, 1);
            li->position[k] = frand(x, -4, 4);
            li->color[k] = frand(x, 0, 1);
            li->attenuation[k] = frand(x, 0, 0.3f);
        }
        li->attenuation[0] += 0.5f;
    }
}

static void equation_matches_its_statement(void **state) {
    (void)state;
    unsigned x = 2024;
    double worst_prim = 0, worst_sec = 0;
    for (int n = 0; n < 200000; n++) {
        sgLighting l;
        random_lighting(&x, &l);
        float spec[3] = {frand(&x, 0, 1), frand(&x, 0, 1), frand(&x, 0, 1)};
        float shine = n % 7 == 0 ? 0.0f : n % 11 == 0 ? 128.0f : frand(&x, 0, 128);
        sg_lights ls;
        assert_true(sg_light_prepare(&l, spec, shine, &ls, NULL, NULL));
        float P[3] = {frand(&x, -2, 2), frand(&x, -2, 2), frand(&x, -8, -0.5f)};
        float nrm[3] = {frand(&x, -1, 1), frand(&x, -1, 1), frand(&x, -1, 1)};
        float base[4] = {frand(&x, 0, 1), frand(&x, 0, 1), frand(&x, 0, 1), frand(&x, 0, 1)};
        float prim[4], sec[3];
        double pd[4], sd[3];
        sg_light_eval(&ls, P, nrm, base, prim, sec);
        eval_d(&l, spec, shine, P, nrm, base, pd, sd);
        for (int k = 0; k < 4; k++) {
            double e = fabs(prim[k] - pd[k]);
            if (e > worst_prim) worst_prim = e;
        }
        for (int k = 0; k < 3; k++) {
            double e = fabs(sec[k] - sd[k]) / (1.0 + fabs(sd[k]));
            if (e > worst_sec) worst_sec = e;
        }
    }
    /* A 1/255 step is 3.9e-3: the float evaluation is a thousand times closer than that. */
    if (worst_prim > 4e-6 || worst_sec > 4e-5)
        fail_msg("largest error: primary %g, secondary %g", worst_prim, worst_sec);
}

static void pow_is_accurate_and_exact_at_the_ends(void **state) {
    (void)state;
    double worst = 0;
    unsigned x = 7;
    for (int n = 0; n < 1000000; n++) {
        float b = frand(&x, 0, 1), s = frand(&x, 0, 128);
        if (n % 3 == 0) b = 1.0f - frand(&x, 0, 1e-3f); /* near 1, where highlights are */
        double want = pow((double)b, (double)s), got = sg_pow_unit(b, s);
        double e = fabs(got - want) / (want > 1e-30 ? want : 1e-30);
        if (want > 1e-30 && e > worst) worst = e;
    }
    if (worst > 2e-5) fail_msg("largest relative error of pow: %g", worst);
    assert_true(sg_pow_unit(0.0f, 0.0f) == 1.0f); /* OpenGL's 0^0 = 1 */
    assert_true(sg_pow_unit(0.5f, 0.0f) == 1.0f);
    assert_true(sg_pow_unit(0.0f, 1.0f) == 0.0f);
    assert_true(sg_pow_unit(1.0f, 128.0f) == 1.0f);
    assert_true(sg_pow_unit(0.5f, 128.0f) >= 0.0f && sg_pow_unit(0.5f, 128.0f) < 1e-38f);
}

/* Degenerate input gives finite colours. */
static void degenerate_input_is_finite(void **state) {
    (void)state;
    sgLighting l;
    memset(&l, 0, sizeof l);
    l.light_count = 2;
    l.lights[0] = (sgLight){.type = SG_LIGHT_POINT,
                            .position = {0, 0, -2},
                            .color = {1, 1, 1},
                            .attenuation = {0, 0, 1}}; /* 1 / d^2: infinite at the surface */
    l.lights[1] = (sgLight){
        .type = SG_LIGHT_DIRECTIONAL, .direction = {0, 0, -1}, .color = {5, 5, 5}}; /* saturates */
    l.lights[0].color[1] = 3e38f; /* near the light, its attenuation overflows this */
    const float spec[3] = {1, 0, 1}, base[4] = {1, 0, 1, 1}; /* zero channels: inf x 0 */
    const float shines[] = {0.0f, 1.0f, 128.0f};
    const float normals[][3] = {{0, 0, 0}, {0, 0, 1}, {1e-30f, 0, 0}, {3e38f, 3e38f, 3e38f}};
    const float positions[][3] = {{0, 0, -2}, {0, 0, 0}, {1, 1, -3}, {0, 0, -2.000001f}};
    for (size_t s = 0; s < 3; s++) {
        sg_lights ls;
        assert_true(sg_light_prepare(&l, spec, shines[s], &ls, NULL, NULL));
        for (size_t i = 0; i < 4; i++)
            for (size_t p = 0; p < 4; p++) {
                float prim[4], sec[3];
                sg_light_eval(&ls, positions[p], normals[i], base, prim, sec);
                for (int k = 0; k < 4; k++) assert_true(prim[k] >= 0.0f && prim[k] <= 1.0f);
                for (int k = 0; k < 3; k++) assert_true(isfinite(sec[k]) && sec[k] >= 0.0f);
            }
    }
}

/* The normal matrix is the inverse transpose: a normal of a plane stays perpendicular to it
 * under non-uniform scale. */
static void normal_matrix_keeps_normals_perpendicular(void **state) {
    (void)state;
    const float wv[16] = {3, 0, 0, 1, 0, 0.5f, 0, 2, 0, 0, 1, -5, 0, 0, 0, 1};
    float nm[9];
    sg_normal_matrix(wv, nm);
    /* The plane x + y = 0 has normal (1, 1, 0); scaled, its points go to (3t, -0.5t, z). */
    float n[3] = {nm[0] + nm[1], nm[3] + nm[4], nm[6] + nm[7]};
    float along[3] = {3.0f, -0.5f, 0.0f};
    assert_true(fabsf(n[0] * along[0] + n[1] * along[1] + n[2] * along[2]) < 1e-6f);
    const float singular[16] = {1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    sg_normal_matrix(singular, nm);
    for (int k = 0; k < 9; k++) assert_true(nm[k] == 0.0f);
}

/* ---- through the API ---- */

enum { S = 32 };
static const float IDENTITY[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

typedef struct api {
    sgDevice *dev;
    sgImage2D color, depth;
} api;

static void api_open(api *a) {
    assert_int_equal(sgCreateDevice(NULL, &a->dev), SG_OK);
    a->color = test_image(a->dev, S, S, SG_FORMAT_RGBA8_UNORM);
    a->depth = test_image(a->dev, S, S, SG_FORMAT_D32_FLOAT);
}

/* A quad at view depth -2 spanning the view (orthographic), with the given normals (NULL: none)
 * at its corners; draws it with `mode` and returns the image. */
static sgResult draw_quad(api *a, sgLightingMode mode, const float *normals, const sgLighting *l,
                          float shininess, uint8_t *out) {
    const float pos[16] = {-1, -1, -2, 1, 1, -1, -2, 1, 1, 1, -2, 1, -1, 1, -2, 1};
    const uint32_t idx[6] = {0, 1, 2, 0, 2, 3};
    sgGeom g;
    assert_int_equal(sgCreateGeom(a->dev,
                                  &(sgGeomDesc){.vertex_count = 4,
                                                .positions = pos,
                                                .normals = normals,
                                                .index_count = 6,
                                                .indices = idx},
                                  &g),
                     SG_OK);
    sgPipelineStateObject pso;
    assert_int_equal(sgCreatePipelineStateObject(a->dev, &(sgPipelineDesc){.lighting = mode}, &pso),
                     SG_OK);
    /* z' = -(z + 3) / 2: depth -2 lands at NDC -0.5, inside the clip volume. */
    const float proj[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0.5f, 0, 0, 0, 0, 1};
    sgDrawParams p = {.lighting = l, .specular = {0.5f, 0.5f, 0.5f}, .shininess = shininess};
    memcpy(p.world_view, IDENTITY, sizeof IDENTITY);
    memcpy(p.proj, proj, sizeof proj);
    sgPassDesc pass = {.color = a->color};
    assert_int_equal(sgBeginRenderPass(a->dev, &pass), SG_OK);
    sgResult r = sgDraw(a->dev, pso, g, &p);
    assert_int_equal(sgEndRenderPass(a->dev, &pass), SG_OK);
    if (out) assert_int_equal(sgReadImage2D(a->dev, a->color, out, 0), SG_OK);
    sgDestroyGeom(a->dev, g);
    sgDestroyPipelineStateObject(a->dev, pso);
    return r;
}

static uint8_t unorm(float v) {
    return (uint8_t)(v <= 0 ? 0 : v >= 1 ? 255 : (int)(v * 255.0f + 0.5f));
}

static void modes_through_the_api(void **state) {
    (void)state;
    api a;
    api_open(&a);
    sgLighting l;
    memset(&l, 0, sizeof l);
    l.ambient[0] = l.ambient[1] = l.ambient[2] = 0.1f;
    l.light_count = 1;
    l.lights[0] = (sgLight){
        .type = SG_LIGHT_POINT, .position = {0.5f, 0.3f, 0.0f}, .color = {0.5f, 0.4f, 0.3f}};
    const float up[12] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
    uint8_t img[S * S * 4];
    sg_lights ls;
    const float spec[3] = {0.5f, 0.5f, 0.5f}, white[4] = {1, 1, 1, 1};
    assert_true(sg_light_prepare(&l, spec, 20.0f, &ls, NULL, NULL));

    /* Flat: one colour, the equation at a triangle's centroid with its face normal (+z). */
    assert_int_equal(draw_quad(&a, SG_LIGHTING_FLAT, NULL, &l, 20.0f, img), SG_OK);
    const float c0[3] = {1.0f / 3.0f, -1.0f / 3.0f, -2.0f}; /* triangle 0 1 2 */
    const float nz[3] = {0, 0, 4};
    float prim[4], sec[3];
    sg_light_eval(&ls, c0, nz, white, prim, sec);
    /* pixel (28, 28) is in triangle 0 1 2 (below the diagonal, right) */
    const uint8_t *px = img + (28 * S + 28) * 4;
    for (int k = 0; k < 3; k++) assert_int_equal(px[k], unorm(prim[k] + sec[k]));

    /* Gouraud and Phong: smooth, and brightest where the light is nearest (x = 0.5, y = 0.3). */
    const sgLightingMode smooth[2] = {SG_LIGHTING_GOURAUD, SG_LIGHTING_PHONG};
    for (int m = 0; m < 2; m++) {
        assert_int_equal(draw_quad(&a, smooth[m], up, &l, 20.0f, img), SG_OK);
        int bx = 0, by = 0, best = -1;
        for (int y = 0; y < S; y++)
            for (int x = 0; x < S; x++) {
                int v = img[(y * S + x) * 4];
                if (v > best) best = v, bx = x, by = y;
            }
        /* Gouraud lights the corners: the brightest pixel is at the corner nearest the light
         * (top right). Phong lights every pixel: the light's foot is pixel (24, 11), the mirror
         * point of its reflection (20, 13.6), and the brightest pixel lies between them. */
        if (m == 0 ? !(bx >= S - 3 && by <= 2) : !(bx >= 19 && bx <= 25 && by >= 10 && by <= 15))
            fail_msg("mode %d: brightest pixel (%d, %d)", (int)smooth[m], bx, by);
        if (m == 1) { /* Phong: every pixel centre is the equation at its position */
            for (int y = 0; y < S; y += 5)
                for (int x = 0; x < S; x += 3) {
                    float P[3] = {(2 * x + 1) / (float)S - 1, 1 - (2 * y + 1) / (float)S, -2};
                    sg_light_eval(&ls, P, up, white, prim, sec);
                    const uint8_t *q = img + (y * S + x) * 4;
                    for (int k = 0; k < 3; k++)
                        if (abs(q[k] - unorm(prim[k] + sec[k])) > 1)
                            fail_msg("pixel (%d, %d) channel %d: %d, the equation %d", x, y, k,
                                     q[k], unorm(prim[k] + sec[k]));
                }
        }
    }
    /* Gouraud and Phong need normals; flat does not. */
    assert_int_equal(draw_quad(&a, SG_LIGHTING_GOURAUD, NULL, &l, 1, NULL),
                     SG_ERROR_MISSING_ATTRIBUTE);
    assert_int_equal(draw_quad(&a, SG_LIGHTING_PHONG, NULL, &l, 1, NULL),
                     SG_ERROR_MISSING_ATTRIBUTE);
    /* No lights: ambient 0, black; zero normals: ambient only. */
    assert_int_equal(draw_quad(&a, SG_LIGHTING_PHONG, up, NULL, 0, img), SG_OK);
    for (int i = 0; i < S * S; i++) assert_int_equal(img[i * 4], 0);
    const float zero[12] = {0};
    assert_int_equal(draw_quad(&a, SG_LIGHTING_PHONG, zero, &l, 0, img), SG_OK);
    for (int i = 0; i < S * S; i++) assert_int_equal(img[i * 4], unorm(0.1f));
    sgDestroyDevice(a.dev);
}

static void bad_input_is_refused(void **state) {
    (void)state;
    api a;
    api_open(&a);
    const float up[12] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
    sgLighting l;
    memset(&l, 0, sizeof l);
    l.light_count = 1;
    l.lights[0] =
        (sgLight){.type = SG_LIGHT_DIRECTIONAL, .direction = {0, 0, -1}, .color = {1, 1, 1}};
    uint8_t img[S * S * 4];
    assert_int_equal(draw_quad(&a, SG_LIGHTING_PHONG, up, &l, 129.0f, NULL),
                     SG_ERROR_INVALID_VALUE);
    assert_int_equal(draw_quad(&a, SG_LIGHTING_PHONG, up, &l, -1.0f, NULL), SG_ERROR_INVALID_VALUE);
    assert_int_equal(draw_quad(&a, SG_LIGHTING_PHONG, up, &l, NAN, NULL), SG_ERROR_INVALID_VALUE);
    sgLighting bad = l;
    bad.light_count = SG_MAX_LIGHTS + 1;
    assert_int_equal(draw_quad(&a, SG_LIGHTING_FLAT, up, &bad, 1, NULL), SG_ERROR_INVALID_COUNT);
    bad = l;
    bad.lights[0].color[1] = NAN;
    assert_int_equal(draw_quad(&a, SG_LIGHTING_FLAT, up, &bad, 1, NULL), SG_ERROR_INVALID_VALUE);
    bad = l;
    bad.lights[0].direction[0] = bad.lights[0].direction[2] = 0;
    assert_int_equal(draw_quad(&a, SG_LIGHTING_FLAT, up, &bad, 1, NULL), SG_ERROR_INVALID_VALUE);
    bad = l;
    bad.lights[0].type = (sgLightType)7;
    assert_int_equal(draw_quad(&a, SG_LIGHTING_FLAT, up, &bad, 1, NULL), SG_ERROR_INVALID_ENUM);
    bad = l;
    bad.ambient[2] = INFINITY;
    assert_int_equal(draw_quad(&a, SG_LIGHTING_FLAT, up, &bad, 1, NULL), SG_ERROR_INVALID_VALUE);
    bad = l;
    bad.lights[0].type = SG_LIGHT_POINT;
    bad.lights[0].attenuation[1] = -1;
    assert_int_equal(draw_quad(&a, SG_LIGHTING_FLAT, up, &bad, 1, NULL), SG_ERROR_INVALID_VALUE);
    sgPipelineStateObject pso;
    assert_int_equal(
        sgCreatePipelineStateObject(a.dev, &(sgPipelineDesc){.lighting = (sgLightingMode)9}, &pso),
        SG_ERROR_INVALID_ENUM);
    assert_non_null(strstr(sgGetLastError(a.dev), "lighting"));
    /* A failed draw drew nothing: the image is the clear colour. */
    assert_int_equal(sgReadImage2D(a.dev, a.color, img, 0), SG_OK);
    for (int i = 0; i < S * S * 4; i++) assert_int_equal(img[i], 0);
    sgDestroyDevice(a.dev);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(equation_matches_its_statement),
        cmocka_unit_test(pow_is_accurate_and_exact_at_the_ends),
        cmocka_unit_test(degenerate_input_is_finite),
        cmocka_unit_test(normal_matrix_keeps_normals_perpendicular),
        cmocka_unit_test(modes_through_the_api),
        cmocka_unit_test(bad_input_is_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
