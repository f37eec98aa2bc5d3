/* test_shaders.c - the built-in shaders' C stages called directly on hand-made batches: their
 * lane maths against libm and a double-precision statement of each equation, each shader's own
 * promise (bands, discards, grid placement, flat normal maps), finite output for any input; and,
 * given glslangValidator, every GLSL twin compiles to SPIR-V.
 *
 *   test_shaders [glslangValidator scratch-dir]
 *
 * sgSample is this file's: it returns, per slot, the constant colour the test puts behind
 * sgFragmentBatch.internal (the shaders link against no renderer here).
 */
#include "test_common.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "builtin.h"
#include "shader_math.h"

static const sgShaderInfo *const SHADERS[] = {
    &sg_shader_phong, &sg_shader_toon,     &sg_shader_normal_map, &sg_shader_marble,
    &sg_shader_waves, &sg_shader_dissolve, &sg_shader_instanced,  &sg_shader_phong_lights,
};
#define SHADER_COUNT ((int)(sizeof SHADERS / sizeof SHADERS[0]))

/* What sgSample gives in this test: a constant rgba per slot. */
typedef struct fake_textures {
    float rgba[SG_MAX_DRAW_TEXTURES][4];
} fake_textures;

void sgSample(const sgFragmentBatch *b, int slot, const float u[SG_SHADER_LANES],
              const float v[SG_SHADER_LANES], float rgba[4][SG_SHADER_LANES]) {
    (void)u, (void)v;
    const fake_textures *t = b->internal;
    for (int k = 0; k < 4; k++)
        for (int i = 0; i < SG_SHADER_LANES; i++) rgba[k][i] = t ? t->rgba[slot][k] : 0.0f;
}

static const float IDENTITY[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

/* A small deterministic generator for inputs. */
static float rnd(uint32_t *s, float lo, float hi) {
    *s = *s * 1664525u + 1013904223u;
    return lo + (hi - lo) * (float)(*s >> 8) * (1.0f / 16777216.0f);
}

/* ---- lane maths ---- */

static void test_floor(void **state) {
    (void)state;
    const float xs[] = {0.0f,       -0.0f,       0.5f,        -0.5f,  1.0f,
                        -1.0f,      2.9999998f,  -2.9999998f, 1e6f,   -1e6f + 0.5f,
                        8388607.5f, -8388607.5f, 1e-30f,      -1e-30f};
    for (size_t i = 0; i < sizeof xs / sizeof xs[0]; i++)
        assert_true(sgs_floor(xs[i]) == floorf(xs[i]));
    /* past 2^31 too, where a conversion to int is undefined: the value itself */
    const float big[] = {8388608.0f, -8388608.0f, 3e9f, -3e9f, 1e30f, -1e30f, INFINITY, -INFINITY};
    for (size_t i = 0; i < sizeof big / sizeof big[0]; i++)
        assert_true(sgs_floor(big[i]) == big[i]);
    assert_true(isnan(sgs_floor(NAN)));
    uint32_t s = 1;
    for (int i = 0; i < 100000; i++) {
        float x = rnd(&s, -1000.0f, 1000.0f);
        assert_true(sgs_floor(x) == floorf(x));
    }
}

/* The vector floors give sgs_floor's bits lane by lane: sgs_vfloor for every value, NaN included,
 * sgs_vfloor_small within +-2^23. */
static void expect_vfloor(float x, bool small_too) {
    const float want = sgs_floor(x);
    const sgs_vf v = sgs_vsplat(x);
    const float got = sgs_vfloor(v)[SGS_W - 1];
    if (isnan(want)) {
        assert_true(isnan(got));
        return;
    }
    assert_memory_equal(&got, &want, sizeof want);
    if (!small_too) return; /* past 2^31 its conversion is the set's own */
    const float got_small = sgs_vfloor_small(v)[0];
    assert_memory_equal(&got_small, &want, sizeof want);
}

static void test_vfloor(void **state) {
    (void)state;
    const float xs[] = {0.0f,       -0.0f,       0.5f,       -0.5f,       1.0f,   -1.0f,
                        2.9999998f, -2.9999998f, 8388607.5f, -8388607.5f, 1e-30f, -1e-30f};
    for (size_t i = 0; i < sizeof xs / sizeof xs[0]; i++) expect_vfloor(xs[i], true);
    const float big[] = {8388608.0f, -8388608.0f, 3e9f,      -3e9f, 1e30f,
                         -1e30f,     INFINITY,    -INFINITY, NAN};
    for (size_t i = 0; i < sizeof big / sizeof big[0]; i++) expect_vfloor(big[i], false);
    uint32_t s = 7;
    for (int i = 0; i < 100000; i++) expect_vfloor(rnd(&s, -1e7f, 1e7f), false);
    for (int i = 0; i < 100000; i++) expect_vfloor(rnd(&s, -1000.0f, 1000.0f), true);
}

static void test_sin(void **state) {
    (void)state;
    double worst = 0.0;
    for (int i = -200000; i <= 200000; i++) {
        float x = (float)i * 0.001f; /* -200 .. 200 */
        double e = fabs((double)sgs_sin(x) - sin((double)x));
        double ec = fabs((double)sgs_cos(x) - cos((double)x));
        worst = fmax(worst, fmax(e, ec));
    }
    /* the reduction is exact to float; cos adds the rounding of x + pi/2 (|x| <= 200) */
    assert_true(worst < 2e-5);
    for (int i = -10000; i <= 10000; i++) {
        float x = (float)i * 0.001f; /* small arguments: close to libm */
        assert_true(fabs((double)sgs_sin(x) - sin((double)x)) < 3e-7);
    }
}

static void test_pow_unit(void **state) {
    (void)state;
    const float ss[] = {0.5f, 1.0f, 8.0f, 32.0f, 100.0f, 128.0f};
    for (size_t k = 0; k < sizeof ss / sizeof ss[0]; k++)
        for (int i = 1; i <= 1000; i++) {
            float x = (float)i / 1000.0f;
            double want = pow((double)x, (double)ss[k]);
            double got = sgs_pow_unit(x, ss[k]);
            assert_true(fabs(got - want) <= 1e-5 * want + 1e-30);
        }
    /* OpenGL's 0^0 = 1: the lighting raises the base to FLT_MIN when s = 0 (sgs_light.min_x) */
    assert_true(sgs_pow_unit(FLT_MIN, 0.0f) == 1.0f);
    assert_true(sgs_pow_unit(0.3f, 0.0f) == 1.0f);
    assert_true(sgs_pow_unit(0.0f, 5.0f) == 0.0f);
    assert_true(sgs_pow_unit(1e-39f, 5.0f) == 0.0f);  /* subnormal */
    assert_true(sgs_pow_unit(0.01f, 128.0f) == 0.0f); /* below 2^-126 */
    assert_true(sgs_pow_unit(1.0f, 128.0f) == 1.0f);
}

/* A light without specular skips that term: the same bits as computing it. */
static void test_light_without_specular(void **state) {
    (void)state;
    uint32_t seed = 7;
    for (int round = 0; round < 200; round++) {
        float u[17];
        for (int k = 0; k < 17; k++) u[k] = rnd(&seed, -1.5f, 1.5f);
        for (int k = 11; k < 14; k++) u[k] = round % 3 == 0 ? -0.0f : 0.0f; /* specular */
        u[16] = round % 5 == 0 ? 0.0f : rnd(&seed, 0.0f, 128.0f);           /* shininess */
        sgs_light skip = sgs_light_read(u, 0, 3, 6, 11, 16), full = skip;
        assert_int_equal(skip.specular_on, 0);
        full.specular_on = 1;
        float pf[3][SGS_W], nf[3][SGS_W], bf[3][SGS_W];
        for (int k = 0; k < 3; k++)
            for (int i = 0; i < SGS_W; i++) {
                pf[k][i] = rnd(&seed, -3.0f, 3.0f);
                nf[k][i] = i == 1 ? 0.0f : rnd(&seed, -1.0f, 1.0f); /* a zero normal too */
                bf[k][i] = rnd(&seed, 0.0f, 1.2f);
            }
        sgs_vf p[3], n[3], base[3], a[3], b[3];
        for (int k = 0; k < 3; k++)
            p[k] = sgs_vload(pf[k]), n[k] = sgs_vload(nf[k]), base[k] = sgs_vload(bf[k]);
        sgs_vlight_eval(&skip, p[0], p[1], p[2], n[0], n[1], n[2], base, a);
        sgs_vlight_eval(&full, p[0], p[1], p[2], n[0], n[1], n[2], base, b);
        assert_memory_equal(a, b, sizeof a);
    }
    /* a light colour that is not finite keeps the term: 0 times it is NaN */
    float u[17] = {0.2f, 0.2f, 0.2f, 0, 0, -1, INFINITY, 1, 1, 0, 0, 0, 0, 0, 0, 0, 8};
    assert_int_equal(sgs_light_read(u, 0, 3, 6, 11, 16).specular_on, 1);
    u[6] = 1.0f, u[13] = 0.5f;
    assert_int_equal(sgs_light_read(u, 0, 3, 6, 11, 16).specular_on, 1);
}

static void test_noise(void **state) {
    (void)state;
    /* At lattice points the noise is the hash; values in [0, 1); the same twice. */
    for (int x = -3; x <= 3; x++)
        for (int y = -3; y <= 3; y++)
            for (int z = -3; z <= 3; z++) {
                float h = sgs_hash3(x, y, z);
                assert_true(h >= 0.0f && h < 1.0f);
                assert_true(sgs_noise3((float)x, (float)y, (float)z) == h);
            }
    /* Not constant, spread over the range, continuous. */
    uint32_t s = 7;
    float lo = 1.0f, hi = 0.0f, tlo = 1.0f, thi = 0.0f;
    double mean = 0.0;
    for (int i = 0; i < 20000; i++) {
        float x = rnd(&s, -50, 50), y = rnd(&s, -50, 50), z = rnd(&s, -50, 50);
        float n = sgs_noise3(x, y, z), t = sgs_turbulence(x, y, z), f = sgs_fbm(x, y, z);
        assert_true(n >= 0.0f && n < 1.0f);
        assert_true(t >= 0.0f && t <= 1.0f);
        assert_true(f >= 0.0f && f < 1.0f);
        lo = fminf(lo, n), hi = fmaxf(hi, n), tlo = fminf(tlo, t), thi = fmaxf(thi, t);
        mean += f;
        assert_true(fabsf(sgs_noise3(x + 1e-3f, y, z) - n) < 0.01f);
        assert_true(sgs_noise3(x, y, z) == n);
    }
    assert_true(lo < 0.1f && hi > 0.9f);
    assert_true(tlo < 0.2f && thi > 0.6f);
    mean /= 20000.0;
    assert_true(mean > 0.4 && mean < 0.6);
    /* Distinct neighbours of the lattice: the hash is not degenerate along an axis. */
    int same = 0;
    for (int i = 0; i < 1000; i++) same += sgs_hash3(i, 0, 0) == sgs_hash3(i + 1, 0, 0);
    assert_true(same == 0);
}

/* ---- batches ---- */

static void vertex_batch(sgVertexBatch *b, uint32_t seed, const float *wv, const float *proj) {
    memset(b, 0, sizeof *b);
    b->count = SG_SHADER_LANES;
    b->world_view = wv;
    b->proj = proj;
    for (int i = 0; i < SG_SHADER_LANES; i++) {
        b->index[i] = (uint32_t)i;
        for (int k = 0; k < 3; k++) b->position[k][i] = rnd(&seed, -1, 1);
        b->position[3][i] = 1.0f;
        for (int k = 0; k < 4; k++) b->color[k][i] = rnd(&seed, 0, 1);
        for (int k = 0; k < 3; k++) b->normal[k][i] = rnd(&seed, -1, 1);
        for (int k = 0; k < 2; k++) b->texcoord[k][i] = rnd(&seed, 0, 1);
        for (int k = 0; k < 3; k++) b->attribute[0][k][i] = rnd(&seed, -1, 1);
        b->attribute[0][3][i] = i % 2 ? 1.0f : -1.0f;
    }
}

/* A fragment batch whose varyings are the vertex batch's lanes (as if each pixel sat on a
 * vertex). */
static void fragment_from(sgFragmentBatch *f, const sgVertexBatch *v, const fake_textures *t) {
    memset(f, 0, sizeof *f);
    f->mask = 0xffffu;
    f->front_facing = true;
    f->internal = t;
    memcpy(f->varying, v->varying, sizeof f->varying);
}

static const float WV[16] = {0.8f, 0, 0.6f, 0.1f, 0, 1, 0, -0.2f, -0.6f, 0, 0.8f, -4, 0, 0, 0, 1};
static const float PROJ[16] = {2, 0, 0, 0, 0, 2, 0, 0, 0, 0, -1.02f, -0.2f, 0, 0, -1, 0};

/* The lighting equation of phong.c in double, from its statement. */
static void light_d(const float P[3], const float n[3], const float base[3], const float *amb,
                    const float *dir, const float *col, const float *spec, float shin,
                    double out[3]) {
    double ln = sqrt((double)dir[0] * dir[0] + (double)dir[1] * dir[1] + (double)dir[2] * dir[2]);
    double L[3] = {-dir[0] / ln, -dir[1] / ln, -dir[2] / ln};
    double nl = sqrt((double)n[0] * n[0] + (double)n[1] * n[1] + (double)n[2] * n[2]);
    double pl = sqrt((double)P[0] * P[0] + (double)P[1] * P[1] + (double)P[2] * P[2]);
    double N[3], V[3], H[3];
    for (int k = 0; k < 3; k++) N[k] = n[k] / nl, V[k] = -P[k] / pl, H[k] = L[k] + V[k];
    double hl = sqrt(H[0] * H[0] + H[1] * H[1] + H[2] * H[2]);
    double ndotl = N[0] * L[0] + N[1] * L[1] + N[2] * L[2];
    double ndoth = (N[0] * H[0] + N[1] * H[1] + N[2] * H[2]) / hl;
    for (int k = 0; k < 3; k++) {
        double prim = base[k] * amb[k] + base[k] * fmax(ndotl, 0.0) * col[k];
        prim = fmin(fmax(prim, 0.0), 1.0);
        double s = ndotl > 0.0 ? pow(fmax(ndoth, 0.0), shin) * col[k] * spec[k] : 0.0;
        out[k] = prim + s;
    }
}

static void test_phong(void **state) {
    (void)state;
    const float u[17] = {0.9f,  0.8f, 0.7f,  0.5f, 0.2f, 0.25f, 0.3f, -0.4f, -0.6f,
                         -1.0f, 0.9f, 0.85f, 0.8f, 0.5f, 0.4f,  0.3f, 24.0f};
    sgVertexBatch v;
    vertex_batch(&v, 42, WV, PROJ);
    sg_shader_phong.desc.vertex(&v, u);
    for (int i = 0; i < SG_SHADER_LANES; i++) {
        double view[4], p[4] = {v.position[0][i], v.position[1][i], v.position[2][i], 1.0};
        for (int r = 0; r < 4; r++)
            view[r] = WV[4 * r] * p[0] + WV[4 * r + 1] * p[1] + WV[4 * r + 2] * p[2] +
                      WV[4 * r + 3] * p[3];
        for (int r = 0; r < 4; r++) {
            double c = PROJ[4 * r] * view[0] + PROJ[4 * r + 1] * view[1] +
                       PROJ[4 * r + 2] * view[2] + PROJ[4 * r + 3] * view[3];
            assert_true(fabs(v.clip[r][i] - c) < 1e-5);
        }
        for (int r = 0; r < 3; r++) assert_true(fabs(v.varying[r][i] - view[r]) < 1e-5);
        /* WV's 3 x 3 is a rotation: its normal matrix is itself */
        for (int r = 0; r < 3; r++) {
            double n = WV[4 * r] * v.normal[0][i] + WV[4 * r + 1] * v.normal[1][i] +
                       WV[4 * r + 2] * v.normal[2][i];
            assert_true(fabs(v.varying[3 + r][i] - n) < 1e-5);
        }
        for (int k = 0; k < 4; k++) assert_true(v.varying[6 + k][i] == v.color[k][i] * u[k]);
    }
    sgFragmentBatch f;
    fragment_from(&f, &v, NULL);
    sg_shader_phong.desc.fragment(&f, u);
    int lit = 0;
    for (int i = 0; i < SG_SHADER_LANES; i++) {
        const float P[3] = {f.varying[0][i], f.varying[1][i], f.varying[2][i]};
        const float n[3] = {f.varying[3][i], f.varying[4][i], f.varying[5][i]};
        const float base[3] = {f.varying[6][i], f.varying[7][i], f.varying[8][i]};
        double want[3];
        light_d(P, n, base, u + 4, u + 7, u + 10, u + 13, u[16], want);
        for (int k = 0; k < 3; k++) assert_true(fabs(f.color[k][i] - want[k]) < 2e-5);
        assert_true(f.color[3][i] == f.varying[9][i]);
        lit += want[0] > base[0] * u[4] + 1e-3;
    }
    assert_true(lit > 0 && lit < SG_SHADER_LANES); /* the batch has both sides of the light */
    assert_true(f.discard == 0);
}

/* The equation of phong_lights.c in double, from its statement: lights of 10 floats each. */
static void lights_d(const float P[3], const float n[3], const float base[4], const float *u,
                     const float texel[4], double out[4]) {
    double nl = sqrt((double)n[0] * n[0] + (double)n[1] * n[1] + (double)n[2] * n[2]);
    double pl = sqrt((double)P[0] * P[0] + (double)P[1] * P[1] + (double)P[2] * P[2]);
    double N[3], V[3], diff[3] = {0, 0, 0}, spec[3] = {0, 0, 0};
    for (int k = 0; k < 3; k++) N[k] = n[k] / nl, V[k] = -P[k] / pl;
    for (int j = 0; j < (int)u[12]; j++) {
        const float *s = u + 13 + 10 * j;
        double L[3], att = 1.0;
        if (s[0] == 0.0f) {
            double len = sqrt((double)s[1] * s[1] + (double)s[2] * s[2] + (double)s[3] * s[3]);
            for (int k = 0; k < 3; k++) L[k] = -s[1 + k] / len;
        } else {
            double v[3] = {s[1] - P[0], s[2] - P[1], s[3] - P[2]};
            double d = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
            for (int k = 0; k < 3; k++) L[k] = v[k] / d;
            att = 1.0 / (s[7] + s[8] * d + s[9] * d * d);
        }
        double ndotl = N[0] * L[0] + N[1] * L[1] + N[2] * L[2];
        if (!(ndotl > 0.0)) continue;
        double H[3] = {L[0] + V[0], L[1] + V[1], L[2] + V[2]};
        double hl = sqrt(H[0] * H[0] + H[1] * H[1] + H[2] * H[2]);
        double ndoth = (N[0] * H[0] + N[1] * H[1] + N[2] * H[2]) / hl;
        for (int k = 0; k < 3; k++) {
            diff[k] += att * ndotl * s[4 + k];
            spec[k] += att * pow(fmax(ndoth, 0.0), u[11]) * s[4 + k];
        }
    }
    for (int k = 0; k < 3; k++) {
        double prim = fmin(fmax(base[k] * u[5 + k] + base[k] * diff[k], 0.0), 1.0) * texel[k];
        out[k] = fmin(fmax(prim + spec[k] * u[8 + k], 0.0), 1.0);
    }
    out[3] = (double)base[3] * texel[3];
}

static void test_phong_lights(void **state) {
    (void)state;
    /* One directional light and no texture: phong's uniforms in phong_lights' places give
     * phong's colours, bit for bit (its output clamped, as the pipeline clamps it). */
    const float p[17] = {0.9f,  0.8f, 0.7f,  0.5f, 0.2f, 0.25f, 0.3f, -0.4f, -0.6f,
                         -1.0f, 0.9f, 0.85f, 0.8f, 0.5f, 0.4f,  0.3f, 24.0f};
    float u[53] = {p[0], p[1], p[2], p[3], 0,    p[4],  p[5],  p[6],  p[13], p[14], p[15], p[16],
                   1,    0,    p[7], p[8], p[9], p[10], p[11], p[12], 1,     0,     0};
    sgVertexBatch v, w;
    vertex_batch(&v, 42, WV, PROJ);
    vertex_batch(&w, 42, WV, PROJ);
    sg_shader_phong.desc.vertex(&v, p);
    sg_shader_phong_lights.desc.vertex(&w, u);
    sgFragmentBatch f, g;
    fragment_from(&f, &v, NULL);
    fragment_from(&g, &w, NULL);
    sg_shader_phong.desc.fragment(&f, p);
    sg_shader_phong_lights.desc.fragment(&g, u);
    for (int i = 0; i < SG_SHADER_LANES; i++) {
        for (int k = 0; k < 3; k++) assert_true(g.color[k][i] == sgs_clamp01(f.color[k][i]));
        assert_true(g.color[3][i] == f.color[3][i]);
    }
    /* A directional light, a point light with attenuation, a texture: the double equation. */
    const float more[20] = {0, 0.3f, -0.5f, -0.8f, 0.5f, 0.45f, 0.4f, 1, 0,    0,
                            1, 1.5f, 0.7f,  -2.5f, 0.8f, 0.6f,  0.4f, 1, 0.1f, 0.05f};
    memcpy(u + 13, more, sizeof more);
    u[12] = 2, u[4] = 1;
    const fake_textures t = {{{0.6f, 0.9f, 0.3f, 0.75f}}};
    vertex_batch(&w, 7, WV, PROJ);
    sg_shader_phong_lights.desc.vertex(&w, u);
    fragment_from(&g, &w, &t);
    sg_shader_phong_lights.desc.fragment(&g, u);
    int spots = 0;
    for (int i = 0; i < SG_SHADER_LANES; i++) {
        for (int k = 0; k < 2; k++) assert_true(g.varying[10 + k][i] == w.texcoord[k][i]);
        const float P[3] = {g.varying[0][i], g.varying[1][i], g.varying[2][i]};
        const float n[3] = {g.varying[3][i], g.varying[4][i], g.varying[5][i]};
        const float base[4] = {g.varying[6][i], g.varying[7][i], g.varying[8][i], g.varying[9][i]};
        double want[4];
        lights_d(P, n, base, u, t.rgba[0], want);
        for (int k = 0; k < 4; k++) assert_true(fabs(g.color[k][i] - want[k]) < 2e-5);
        spots += want[0] > 0.05;
    }
    assert_true(spots > 0);
    assert_true(g.discard == 0);
}

static void test_toon_bands(void **state) {
    (void)state;
    /* no rim (width -2), white light, 3 bands: every colour is base x (0.2 + 0.8 k / 2) */
    const float u[15] = {1, 1, 1, 0, 0, -1, 1, 1, 1, 0.2f, 3, -2.0f, 0, 0, 0};
    for (uint32_t seed = 1; seed < 40; seed++) {
        sgVertexBatch v;
        vertex_batch(&v, seed, IDENTITY, IDENTITY);
        sg_shader_toon.desc.vertex(&v, u);
        sgFragmentBatch f;
        fragment_from(&f, &v, NULL);
        sg_shader_toon.desc.fragment(&f, u);
        for (int i = 0; i < SG_SHADER_LANES; i++) {
            float shade = f.color[0][i] / f.varying[6][i];
            if (f.varying[6][i] < 0.05f) continue;
            float k = (shade - 0.2f) / 0.4f;
            assert_true(fabsf(k - roundf(k)) < 1e-3f && k > -0.5f && k < 2.5f);
            assert_true(f.color[3][i] == 1.0f);
        }
    }
    /* a rim: a normal seen edge-on (N.V = 0) takes the rim colour */
    const float r[15] = {1, 1, 1, 0, 0, -1, 1, 1, 1, 0.2f, 3, 0.3f, 0.05f, 0.1f, 0.15f};
    sgFragmentBatch f;
    memset(&f, 0, sizeof f);
    f.mask = 0xffffu;
    for (int i = 0; i < SG_SHADER_LANES; i++) {
        f.varying[2][i] = -3.0f;                     /* P = (0, 0, -3): V = +z */
        f.varying[3][i] = 1.0f, f.varying[5][i] = 0; /* N = +x */
        f.varying[6][i] = f.varying[7][i] = f.varying[8][i] = 1.0f;
    }
    sg_shader_toon.desc.fragment(&f, r);
    for (int i = 0; i < SG_SHADER_LANES; i++)
        for (int k = 0; k < 3; k++) assert_true(fabsf(f.color[k][i] - r[12 + k]) < 1e-6f);
}

static void test_normal_map_flat(void **state) {
    (void)state;
    /* A map of the unperturbed normal (0.5, 0.5, 1) and a white colour texture: the phong
     * equation with the geometric normal and the vertex colour. */
    const float u[15] = {1,    1,     0.2f, 0.25f, 0.3f, -0.4f, -0.6f, -1.0f,
                         0.9f, 0.85f, 0.8f, 0.5f,  0.4f, 0.3f,  24.0f};
    fake_textures t = {{{0.5f, 0.5f, 1.0f, 1.0f}, {1, 1, 1, 1}}};
    sgVertexBatch v;
    vertex_batch(&v, 9, WV, PROJ);
    sg_shader_normal_map.desc.vertex(&v, u);
    sgFragmentBatch f;
    fragment_from(&f, &v, &t);
    sg_shader_normal_map.desc.fragment(&f, u);
    for (int i = 0; i < SG_SHADER_LANES; i++) {
        const float P[3] = {f.varying[0][i], f.varying[1][i], f.varying[2][i]};
        const float n[3] = {f.varying[3][i], f.varying[4][i], f.varying[5][i]};
        const float base[3] = {v.color[0][i], v.color[1][i], v.color[2][i]};
        double want[3];
        light_d(P, n, base, u + 2, u + 5, u + 8, u + 11, u[14], want);
        for (int k = 0; k < 3; k++) assert_true(fabs(f.color[k][i] - want[k]) < 5e-5);
        assert_true(f.color[3][i] == v.color[3][i]);
    }
    /* A map tilted along the tangent: the normal turns towards T, so a light from T's side
     * brightens every lane. */
    const float side[15] = {0, 1, 0, 0, 0, 0, 0, 0, 1, 1, 1, 0, 0, 0, 0};
    fake_textures tilt = {{{0.85f, 0.5f, 0.8f, 1.0f}, {1, 1, 1, 1}}};
    sgFragmentBatch g;
    memset(&g, 0, sizeof g);
    g.mask = 0xffffu;
    for (int i = 0; i < SG_SHADER_LANES; i++) {
        g.varying[2][i] = -3.0f; /* P */
        g.varying[5][i] = 1.0f;  /* N = +z */
        g.varying[6][i] = 1.0f;  /* T = +x */
        g.varying[9][i] = 1.0f;  /* handedness */
        for (int k = 0; k < 4; k++) g.varying[12 + k][i] = 1.0f;
    }
    float lit[2];
    float dir[2][3] = {{-1, 0, -0.2f}, {1, 0, -0.2f}}; /* light travelling -x: it comes from +x */
    for (int j = 0; j < 2; j++) {
        float uu[15];
        memcpy(uu, side, sizeof uu);
        memcpy(uu + 5, dir[j], sizeof dir[j]);
        g.internal = &tilt;
        sg_shader_normal_map.desc.fragment(&g, uu);
        lit[j] = g.color[0][0];
    }
    assert_true(lit[0] > lit[1] + 0.2f);
}

static void test_waves(void **state) {
    (void)state;
    float u[29] = {0};
    u[13] = u[14] = u[15] = 1.0f;
    u[19] = 0, u[20] = -1, u[21] = 0;
    sgVertexBatch v;
    vertex_batch(&v, 5, IDENTITY, IDENTITY);
    /* still water: the grid as it is, normals up */
    sg_shader_waves.desc.vertex(&v, u);
    for (int i = 0; i < SG_SHADER_LANES; i++) {
        for (int k = 0; k < 3; k++) assert_true(v.clip[k][i] == v.position[k][i]);
        assert_true(v.varying[3][i] == 0.0f && v.varying[4][i] == 1.0f && v.varying[5][i] == 0.0f);
    }
    /* three waves: the height is their sum, the normal perpendicular to the surface's slopes
     * (by finite differences of the height) */
    const float waves[12] = {0.1f, 2.0f, 0.5f,  1.0f, 0.05f, -1.0f,
                             3.0f, 2.0f, 0.03f, 4.0f, 4.0f,  0.5f};
    memcpy(u + 1, waves, sizeof waves);
    u[0] = 1.7f;
    sg_shader_waves.desc.vertex(&v, u);
    for (int i = 0; i < SG_SHADER_LANES; i++) {
        double x = v.position[0][i], z = v.position[2][i], y = v.position[1][i];
        double h = 1e-3, dydx = 0, dydz = 0;
        for (int w = 0; w < 3; w++) {
            const float *q = waves + 4 * w;
            double ph = q[1] * x + q[2] * z + q[3] * u[0];
            y += q[0] * sin(ph);
            dydx += q[0] * (sin(ph + q[1] * h) - sin(ph - q[1] * h)) / (2 * h);
            dydz += q[0] * (sin(ph + q[2] * h) - sin(ph - q[2] * h)) / (2 * h);
        }
        assert_true(fabs(v.clip[1][i] - y) < 1e-5);
        double n[3] = {v.varying[3][i], v.varying[4][i], v.varying[5][i]};
        /* n . (1, dydx, 0) = 0 and n . (0, dydz, 1) = 0 */
        assert_true(fabs(n[0] + n[1] * dydx) < 1e-4);
        assert_true(fabs(n[2] + n[1] * dydz) < 1e-4);
    }
}

static void test_dissolve(void **state) {
    (void)state;
    float u[18] = {0.0f, 0.05f, 4.0f, 1, 0.5f, 0.1f, 1,    1,    1,
                   0.2f, 0.2f,  0.2f, 0, 0,    -1,   0.8f, 0.8f, 0.8f};
    int gone = 0, kept = 0, glowing = 0;
    for (uint32_t seed = 1; seed < 200; seed++) {
        sgVertexBatch v;
        vertex_batch(&v, seed, WV, PROJ);
        u[0] = 0.0f; /* nothing is gone, nothing glows */
        sg_shader_dissolve.desc.vertex(&v, u);
        sgFragmentBatch f;
        fragment_from(&f, &v, NULL);
        sg_shader_dissolve.desc.fragment(&f, u);
        assert_true(f.discard == 0);
        u[0] = 1.0f; /* everything is gone */
        fragment_from(&f, &v, NULL);
        sg_shader_dissolve.desc.fragment(&f, u);
        assert_true(f.discard == 0xffffu);
        u[0] = 0.5f;
        fragment_from(&f, &v, NULL);
        sg_shader_dissolve.desc.fragment(&f, u);
        for (int i = 0; i < SG_SHADER_LANES; i++) {
            float n = sgs_fbm(f.varying[0][i], f.varying[1][i], f.varying[2][i]);
            assert_true(((f.discard >> i) & 1u) == (n < 0.5f));
            gone += n < 0.5f;
            kept += n >= 0.55f;
            if (n >= 0.5f && n < 0.5025f) { /* the first twentieth of the band: near glow */
                glowing++;
                assert_true(fabsf(f.color[0][i] - 1.0f) < 0.1f && f.color[2][i] < 0.2f);
            }
        }
    }
    assert_true(gone > 200 && kept > 200 && glowing > 0);
}

static void test_instanced_grid(void **state) {
    (void)state;
    /* 5 columns, spacing 2, copies of size 0 (each a point at its place), no turn, bob 0.25 */
    const float u[14] = {5, 2, 0, 0, 0.25f, 0.3f, 0.3f, 0.3f, 0, 0, -1, 0.7f, 0.7f, 0.7f};
    for (int inst = 0; inst < 25; inst++) {
        sgVertexBatch v;
        vertex_batch(&v, (uint32_t)inst + 1, IDENTITY, IDENTITY);
        v.instance = inst;
        sg_shader_instanced.desc.vertex(&v, u);
        float x = (float)(inst % 5 - 2) * 2.0f, z = (float)(inst / 5 - 2) * 2.0f;
        float y = (sgs_hash3(inst, 5, 0) - 0.5f) * (2.0f * 0.25f * 2.0f);
        for (int i = 0; i < SG_SHADER_LANES; i++) {
            assert_true(fabsf(v.clip[0][i] - x) < 1e-5f);
            assert_true(fabsf(v.clip[1][i] - y) < 1e-5f);
            assert_true(fabsf(v.clip[2][i] - z) < 1e-5f);
            assert_true(v.clip[3][i] == 1.0f);
            /* colour: lit hash colour, the same for every vertex of a face's normal */
            for (int k = 0; k < 3; k++)
                assert_true(v.varying[k][i] >= 0.0f && v.varying[k][i] <= 1.0f);
        }
    }
    /* neighbours differ in colour */
    sgVertexBatch a, b;
    vertex_batch(&a, 1, IDENTITY, IDENTITY);
    b = a;
    a.instance = 3, b.instance = 4;
    sg_shader_instanced.desc.vertex(&a, u);
    sg_shader_instanced.desc.vertex(&b, u);
    assert_true(a.varying[0][0] != b.varying[0][0] || a.varying[1][0] != b.varying[1][0]);
    /* a spin turns the copy: with size 1 and time 1 the vertices move */
    const float spin[14] = {5, 2, 1, 1, 1, 0.3f, 0.3f, 0.3f, 0, 0, -1, 0.7f, 0.7f, 0.7f};
    const float still[14] = {5, 2, 1, 0, 0, 0.3f, 0.3f, 0.3f, 0, 0, -1, 0.7f, 0.7f, 0.7f};
    b.instance = a.instance;
    sg_shader_instanced.desc.vertex(&a, spin);
    sg_shader_instanced.desc.vertex(&b, still);
    assert_true(fabsf(a.clip[0][0] - b.clip[0][0]) + fabsf(a.clip[2][0] - b.clip[2][0]) > 1e-3f);
}

/* Every shader on random batches, with uniforms of either sign: every output lane finite
 * (colours are clamped later; NaN would be written as 0, but a shader should not make it). */
static void test_all_finite(void **state) {
    (void)state;
    fake_textures t = {{{0.2f, 0.7f, 0.9f, 1}, {0.5f, 0.5f, 0.5f, 1}}};
    for (int s = 0; s < SHADER_COUNT; s++) {
        const sgShaderInfo *sh = SHADERS[s];
        assert_true(sh->uniform_count > 0 && sh->uniform_count <= 64);
        assert_true(sh->desc.varying_count >= 0 && sh->desc.varying_count <= SG_MAX_VARYINGS);
        assert_true(sh->desc.vertex && sh->desc.fragment && sh->glsl_vertex && sh->glsl_fragment);
        for (uint32_t seed = 1; seed < 300; seed++) {
            uint32_t r = seed * 77u;
            float u[64];
            for (int k = 0; k < 64; k++) u[k] = rnd(&r, -2.0f, 2.0f);
            if (seed % 3 == 0) memset(u, 0, sizeof u); /* zero lights, zero directions */
            sgVertexBatch v;
            vertex_batch(&v, seed, seed % 2 ? WV : IDENTITY, PROJ);
            v.instance = (int)(seed % 50);
            sh->desc.vertex(&v, u);
            for (int i = 0; i < SG_SHADER_LANES; i++) {
                for (int k = 0; k < 4; k++) assert_true(isfinite(v.clip[k][i]));
                for (int k = 0; k < sh->desc.varying_count; k++)
                    assert_true(isfinite(v.varying[k][i]));
            }
            sgFragmentBatch f;
            fragment_from(&f, &v, &t);
            f.front_facing = seed % 4 != 0;
            sh->desc.fragment(&f, u);
            for (int i = 0; i < SG_SHADER_LANES; i++)
                for (int k = 0; k < 4; k++) assert_true(isfinite(f.color[k][i]));
        }
    }
}

/* ---- the GLSL twins ---- */

static const char *validator, *scratch;

static void compile_twin(const char *name, const char *ext, const char *src) {
    char path[1024], cmd[4096];
    snprintf(path, sizeof path, "%s/%s.%s", scratch, name, ext);
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    assert_true(fputs(src, f) >= 0);
    assert_int_equal(fclose(f), 0);
    snprintf(cmd, sizeof cmd, "'%s' -V --quiet -o '%s.spv' '%s' >'%s.log' 2>&1", validator, path,
             path, path);
    int rc = system(cmd);
    if (rc != 0) {
        char log[8192] = "";
        snprintf(cmd, sizeof cmd, "%s.log", path);
        FILE *lf = fopen(cmd, "r");
        if (lf) {
            size_t n = fread(log, 1, sizeof log - 1, lf);
            log[n] = 0;
            fclose(lf);
        }
        fail_msg("%s.%s does not compile:\n%s", name, ext, log);
    }
}

static void test_twins_compile(void **state) {
    (void)state;
    if (!validator) skip();
    for (int s = 0; s < SHADER_COUNT; s++) {
        assert_non_null(strstr(SHADERS[s]->glsl_vertex, "#version 450"));
        assert_non_null(strstr(SHADERS[s]->glsl_fragment, "#version 450"));
        compile_twin(SHADERS[s]->name, "vert", SHADERS[s]->glsl_vertex);
        compile_twin(SHADERS[s]->name, "frag", SHADERS[s]->glsl_fragment);
    }
}

int main(int argc, char **argv) {
    if (argc == 3) validator = argv[1], scratch = argv[2];
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_floor),
        cmocka_unit_test(test_vfloor),
        cmocka_unit_test(test_sin),
        cmocka_unit_test(test_pow_unit),
        cmocka_unit_test(test_light_without_specular),
        cmocka_unit_test(test_noise),
        cmocka_unit_test(test_phong),
        cmocka_unit_test(test_phong_lights),
        cmocka_unit_test(test_toon_bands),
        cmocka_unit_test(test_normal_map_flat),
        cmocka_unit_test(test_waves),
        cmocka_unit_test(test_dissolve),
        cmocka_unit_test(test_instanced_grid),
        cmocka_unit_test(test_all_finite),
        cmocka_unit_test(test_twins_compile),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
