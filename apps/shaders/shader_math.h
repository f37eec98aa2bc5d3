/* shader_math.h - what the built-in shaders share: per-lane maths written so that a loop over the
 * 16 lanes vectorises (no calls, no branches a select cannot replace), and the GLSL text of the
 * same functions and declarations for their twins (docs/api.md, "Shaders").
 *
 * Only static inline functions and macros: a shader file owns no state but its sgShaderInfo.
 */
#ifndef SG_SHADER_MATH_H
#define SG_SHADER_MATH_H

#include <float.h>
#include <stdint.h>
#include <string.h>

#include "sgapi/sgapi_shaders.h"

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#elif defined(__aarch64__)
#include <arm_neon.h>
#endif

#define SGS_LANES SG_SHADER_LANES

/* Before a loop over the lanes: vectorise it whatever the compiler's cost model says of its
 * selects (-fopenmp-simd; the lanes are independent). */
#define SGS_SIMD _Pragma("omp simd")

/* A stage function compiled for the baseline and for AVX2 and AVX-512, the copy this CPU runs
 * chosen when the program starts: 16 lanes fill one AVX-512 register. Lane-wise IEEE operations
 * without fused multiply-add give the same bits in every copy. (Not under the sanitizers, whose
 * builds need no speed.) */
/* A sanitizer's runtime is not up yet when the program's start runs the copies' resolvers (gcc
 * says so with __SANITIZE_*, clang with __has_feature). */
#if defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) ||                         \
    __has_feature(memory_sanitizer)
#define SG_UNDER_SANITIZER 1
#endif
#endif
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__SANITIZE_ADDRESS__) &&                  \
    !defined(__SANITIZE_THREAD__) && !defined(SG_UNDER_SANITIZER) && !defined(SGS_AVX512) &&       \
    !defined(SGS_AVX2)
#define SGS_STAGE __attribute__((target_clones("default", "arch=x86-64-v3", "arch=x86-64-v4")))
#else
#define SGS_STAGE
#endif
/* GCC lowers vector code for the file's own target before it makes the copies above, so a clone
 * for a wider set keeps the baseline's vectors: on a CPU with AVX-512 or AVX2 the built-in shaders
 * run from a compilation of their files for that set (SGS_AVX512, SGS_AVX2, its shaders named
 * <name>_avx512 or <name>_avx2, library.c chooses), whose vectors are that set's registers. */
#ifdef SGS_AVX512
#define SGS_NAME(name) name##_avx512
#elif defined(SGS_AVX2)
#define SGS_NAME(name) name##_avx2
#else
#define SGS_NAME(name) name
#endif

/* ---- a register of lanes as one value ----------------------------------------------------------
 *
 * The lane loops with conditions (lighting, pow, noise) are written on GCC vector types, not as
 * loops over lanes: the compiler turns a loop's selects into branches where it duplicates code
 * (jump threading), and the loop then stays scalar. An operation on a vector is the same IEEE
 * operation in every lane, in the order written, so these give the bits of the scalar code.
 *
 * A vector is one register of the compilation's set, SGS_W lanes: 16 with AVX-512, 8 with AVX2, 4
 * otherwise, and a stage goes over its 16 lanes a vector at a time (SGS_EACH_VECTOR). Vectors wider
 * than the registers would cost more than the extra loop: GCC 12 compares them one lane at a time,
 * with a branch each, and a long chain of them (the lights of phong_lights) spills. */
#if defined(__AVX512F__)
#define SGS_W 16
#elif defined(__AVX__)
#define SGS_W 8
#else
#define SGS_W 4
#endif
#define SGS_EACH_VECTOR(h) for (int h = 0; h < SGS_LANES; h += SGS_W)

/* Vectors are passed only to inline functions, here and in the files that include this header:
 * the note that their calling convention depends on the set does not apply. */
#pragma GCC diagnostic ignored "-Wpragmas"
#pragma GCC diagnostic ignored "-Wunknown-warning-option"
#pragma GCC diagnostic ignored "-Wpsabi"

typedef float sgs_vf __attribute__((vector_size(4 * SGS_W)));
typedef int32_t sgs_vi __attribute__((vector_size(4 * SGS_W)));
typedef uint32_t sgs_vu __attribute__((vector_size(4 * SGS_W)));

/* SGS_W lanes from p, into p. */
static inline sgs_vf sgs_vload(const float *p) {
    sgs_vf v;
    memcpy(&v, p, sizeof v);
    return v;
}
static inline void sgs_vstore(float *p, sgs_vf v) {
    memcpy(p, &v, sizeof v);
}
static inline sgs_vf sgs_vsplat(float s) {
    sgs_vf v;
    for (int i = 0; i < SGS_W; i++) v[i] = s;
    return v;
}
/* m ? a : b lane by lane, m from a comparison (a < b on vectors: all bits set or none). */
static inline sgs_vf sgs_vsel(sgs_vi m, sgs_vf a, sgs_vf b) {
    return (sgs_vf)((m & (sgs_vi)a) | (~m & (sgs_vi)b));
}
static inline sgs_vi sgs_vseli(sgs_vi m, sgs_vi a, sgs_vi b) {
    return (m & a) | (~m & b);
}
/* Square root lane by lane, correctly rounded: the set's instruction (a loop over the lanes calls
 * the library for errno where the compiler may not assume it away). */
static inline sgs_vf sgs_vsqrt(sgs_vf v) {
#if defined(__AVX512F__)
    return (sgs_vf)_mm512_sqrt_ps((__m512)v);
#elif defined(__AVX__)
    return (sgs_vf)_mm256_sqrt_ps((__m256)v);
#elif defined(__SSE2__)
    return (sgs_vf)_mm_sqrt_ps((__m128)v);
#elif defined(__aarch64__)
    return (sgs_vf)vsqrtq_f32((float32x4_t)v);
#else
    for (int i = 0; i < SGS_W; i++) v[i] = __builtin_sqrtf(v[i]);
    return v;
#endif
}

/* ---- the twins' declarations ------------------------------------------------------------------
 */

/* The contract of every twin: version and the uniforms; a vertex stage adds the draw's matrices
 * (SGS_GLSL_DRAW), the mathematical ones (proj * world_view * p is the C product; the renderer
 * that runs the twin uploads them to match), and its inputs. */
#define SGS_GLSL_HEADER                                                                            \
    "#version 450\n"                                                                               \
    "layout(std430, set = 0, binding = 0) readonly buffer SgUniforms { float u[]; };\n"
#define SGS_GLSL_DRAW "layout(push_constant) uniform SgDraw { mat4 world_view; mat4 proj; };\n"
#define SGS_GLSL_INPUTS                                                                            \
    "layout(location = 0) in vec4 sg_position;\n"                                                  \
    "layout(location = 1) in vec4 sg_color;\n"                                                     \
    "layout(location = 2) in vec3 sg_normal;\n"                                                    \
    "layout(location = 3) in vec2 sg_texcoord;\n"                                                  \
    "layout(location = 4) in vec4 sg_attribute0;\n"
#define SGS_GLSL_TEXTURES "layout(set = 0, binding = 1) uniform sampler2D sg_textures[8];\n"
#define SGS_GLSL_OUTPUT   "layout(location = 0) out vec4 sg_frag_color;\n"

/* vec3 of three consecutive uniforms. */
#define SGS_GLSL_U3 "vec3 u3(int k) { return vec3(u[k], u[k + 1], u[k + 2]); }\n"

/* ---- scalar helpers ----------------------------------------------------------------------------
 */

static inline float sgs_min(float a, float b) {
    return a < b ? a : b;
}
static inline float sgs_max(float a, float b) {
    return a > b ? a : b;
}
/* Two selects, not one nested in another: a three-way choice keeps AVX2 and AVX-512 loops from
 * vectorising. NaN gives 0. */
static inline float sgs_clamp01(float v) {
    float c = v > 0.0f ? v : 0.0f;
    return c < 1.0f ? c : 1.0f;
}
static inline float sgs_sqrt(float v) {
    return __builtin_sqrtf(v); /* one instruction; no errno for the values used here (>= 0) */
}

/* floor, by truncation and a correction: a conversion the SIMD sets all have (floorf needs
 * SSE4.1 to be inlined). Exactly floor, as GLSL's. From 2^23 up every float is an integer, its
 * own floor, and not converted: past 2^31 (a uniform gone wild) the conversion would be undefined.
 * Two selects, as sgs_clamp01's, so that a lane loop still vectorises. */
static inline float sgs_floor(float x) {
    const int small = (x > -8388608.0f) & (x < 8388608.0f); /* NaN: not small */
    float c = small ? x : 0.0f;
    float t = (float)(int32_t)c, below = t - 1.0f;
    float r = t > c ? below : t;
    return small ? r : x;
}

/* 1 / |v|, 0 for a zero length (never NaN), as the fixed lighting normalises (light.h).
 *
 * Here and below, every operation is computed whatever a condition says and the condition only
 * selects between results: a floating-point operation under a condition is a possible trap the
 * compiler will not move out of it, which keeps the lane loop from vectorising. */
static inline float sgs_inv_len(float x, float y, float z) {
    float len2 = (x * x + y * y) + z * z;
    float inv = 1.0f / sgs_sqrt(len2);
    return len2 > 0.0f ? inv : 0.0f;
}

/* floor lane by lane: sgs_floor's bits within +-2^23. Past 2^31 the conversion gives a different
 * value on each set (x86 gives INT_MIN, NEON saturates), so an argument that far out (a
 * uniform gone wild) differs between sets. For the hot loops, where three more operations a lane
 * show: sin's reduction (|x| < 2^20), pow's exponent, noise's lattice (converted to integers
 * anyway) and marble's bands. */
static inline sgs_vf sgs_vfloor_small(sgs_vf x) {
    sgs_vf t = __builtin_convertvector(__builtin_convertvector(x, sgs_vi), sgs_vf),
           below = t - 1.0f;
    return sgs_vsel(t > x, below, t);
}
/* sgs_floor's bits for every value, at three more operations than sgs_vfloor_small. */
static inline sgs_vf sgs_vfloor(sgs_vf x) {
    const sgs_vi small = (x > -8388608.0f) & (x < 8388608.0f);
    return sgs_vsel(small, sgs_vfloor_small(sgs_vsel(small, x, sgs_vsplat(0.0f))), x);
}
static inline sgs_vf sgs_vclamp01(sgs_vf v) {
    sgs_vf c = sgs_vsel(v > 0.0f, v, sgs_vsplat(0.0f));
    return sgs_vsel(c < 1.0f, c, sgs_vsplat(1.0f));
}
static inline sgs_vf sgs_vinv_len(sgs_vf x, sgs_vf y, sgs_vf z) {
    sgs_vf len2 = (x * x + y * y) + z * z;
    sgs_vf inv = 1.0f / sgs_vsqrt(len2);
    return sgs_vsel(len2 > 0.0f, inv, sgs_vsplat(0.0f));
}

/* sin(x) for |x| < 2^20: x less the nearest multiple of 2 pi (in two parts, so the reduction is
 * exact to float), folded into [-pi/2, pi/2], then Taylor to x^11 (error below 1e-7). */
static inline sgs_vf sgs_vsin(sgs_vf x) {
    sgs_vf k = sgs_vfloor_small(x * 0.159154943f + 0.5f);
    sgs_vf r = (x - k * 6.28318548f) - k * -1.74845553e-7f;
    sgs_vf above = 3.14159265f - r, below = -3.14159265f - r;
    r = sgs_vsel(r > 1.57079633f, above, r);
    r = sgs_vsel(r < -1.57079633f, below, r);
    sgs_vf r2 = r * r;
    sgs_vf p = sgs_vsplat(-2.50521084e-8f);
    p = p * r2 + 2.75573192e-6f;
    p = p * r2 - 1.98412698e-4f;
    p = p * r2 + 8.33333333e-3f;
    p = p * r2 - 1.66666667e-1f;
    return r + (r * r2) * p;
}
static inline sgs_vf sgs_vcos(sgs_vf x) {
    return sgs_vsin(x + 1.57079633f);
}
/* One value (lane 0 of the vector form): for per-draw constants and tests, not lane loops. */
static inline float sgs_sin(float x) {
    return sgs_vsin(sgs_vsplat(x))[0];
}
static inline float sgs_cos(float x) {
    return sgs_vcos(sgs_vsplat(x))[0];
}

/* x^s for x in [0, 1], s in [0, 128], as the fixed lighting computes it (light.h: sg_pow_unit),
 * without branches: 0 below the smallest normal float. s = 0 gives 1 for every x from FLT_MIN up
 * (2^(0 log2 x)); the caller raises x to FLT_MIN for s = 0 (sgs_light.min_x), so that 0^0 = 1
 * too without a test of s per lane. */
static inline sgs_vf sgs_vpow_unit(sgs_vf x, float s) {
    const sgs_vi normal = x >= FLT_MIN;
    sgs_vu bits = (sgs_vu)sgs_vsel(normal, x, sgs_vsplat(1.0f));
    sgs_vi e = (sgs_vi)((bits >> 23) & 255u) - 127;
    bits = (bits & 0x007fffffu) | 0x3f800000u;
    sgs_vf m = (sgs_vf)bits;
    const sgs_vi big = m > 1.41421356f;
    sgs_vf half = m * 0.5f;
    m = sgs_vsel(big, half, m);
    e = sgs_vseli(big, e + 1, e);
    sgs_vf t = (m - 1.0f) / (m + 1.0f), t2 = t * t;
    sgs_vf p = sgs_vsplat(1.0f / 11.0f);
    p = p * t2 + 1.0f / 9.0f;
    p = p * t2 + 1.0f / 7.0f;
    p = p * t2 + 1.0f / 5.0f;
    p = p * t2 + 1.0f / 3.0f;
    p = p * t2 + 1.0f;
    sgs_vf z = s * (__builtin_convertvector(e, sgs_vf) + (p * t) * 2.88539008f);
    const sgs_vi above = z >= -126.0f;
    sgs_vf zc = sgs_vsel(above, z, sgs_vsplat(-126.0f));
    sgs_vf n = sgs_vfloor_small(zc + 0.5f);
    sgs_vf y = (zc - n) * 0.693147181f;
    sgs_vf q = sgs_vsplat(1.0f / 5040.0f);
    q = q * y + 1.0f / 720.0f;
    q = q * y + 1.0f / 120.0f;
    q = q * y + 1.0f / 24.0f;
    q = q * y + 1.0f / 6.0f;
    q = q * y + 0.5f;
    q = q * y + 1.0f;
    q = q * y + 1.0f;
    sgs_vu sb = (sgs_vu)(__builtin_convertvector(n, sgs_vi) + 127) << 23;
    sgs_vf r = q * (sgs_vf)sb;
    r = sgs_vsel(above, r, sgs_vsplat(0.0f));
    return sgs_vsel(normal, r, sgs_vsplat(0.0f));
}
static inline float sgs_pow_unit(float x, float s) {
    return sgs_vpow_unit(sgs_vsplat(x), s)[0];
}
#define SGS_GLSL_POW_UNIT                                                                          \
    "float pow_unit(float x, float s) {\n"                                                         \
    "    return s == 0.0 ? 1.0 : (x > 0.0 ? pow(x, s) : 0.0);\n"                                   \
    "}\n"

/* ---- the normal matrix -------------------------------------------------------------------------
 */

/* The inverse transpose of world_view's upper-left 3 x 3 (row-major), in double, as the fixed
 * lighting's; a singular matrix gives zeros. Once per batch. */
static inline void sgs_normal_matrix(const float *wv, float nm[9]) {
    double a = wv[0], b = wv[1], c = wv[2], d = wv[4], e = wv[5], f = wv[6], g = wv[8], h = wv[9],
           i = wv[10];
    /* (A^-1)^T is the cofactor matrix over the determinant. */
    double cof[9] = {e * i - f * h, f * g - d * i, d * h - e * g, c * h - b * i, a * i - c * g,
                     b * g - a * h, b * f - c * e, c * d - a * f, a * e - b * d};
    double det = a * cof[0] + b * cof[1] + c * cof[2];
    for (int k = 0; k < 9; k++) nm[k] = det != 0.0 ? (float)(cof[k] / det) : 0.0f;
}

/* Lane i of the clip position (proj x (world_view x p)) into b->clip, the view-space position
 * (world_view x p) into varyings vp..vp+2 and the normal (normal matrix x n) into vn..vn+2 (-1:
 * not written), from positions p[4] and normals n[3] of 16 lanes each. */
static inline void sgs_transform_from(sgVertexBatch *b, const float (*p)[SGS_LANES],
                                      const float (*n)[SGS_LANES], int vp, int vn) {
    const float *m = b->world_view, *pr = b->proj;
    float nm[9];
    sgs_normal_matrix(m, nm);
    /* On vectors: as a loop over lanes, the compiler could not rule out that the stores into the
     * batch change the inputs p and n, and kept it scalar. */
    SGS_EACH_VECTOR(h) {
        const sgs_vf x = sgs_vload(p[0] + h), y = sgs_vload(p[1] + h), z = sgs_vload(p[2] + h),
                     w = sgs_vload(p[3] + h);
        const sgs_vf v0 = ((m[0] * x + m[1] * y) + m[2] * z) + m[3] * w;
        const sgs_vf v1 = ((m[4] * x + m[5] * y) + m[6] * z) + m[7] * w;
        const sgs_vf v2 = ((m[8] * x + m[9] * y) + m[10] * z) + m[11] * w;
        const sgs_vf v3 = ((m[12] * x + m[13] * y) + m[14] * z) + m[15] * w;
        sgs_vf nx = {0}, ny = {0}, nz = {0};
        if (vn >= 0) nx = sgs_vload(n[0] + h), ny = sgs_vload(n[1] + h), nz = sgs_vload(n[2] + h);
        sgs_vstore(b->clip[0] + h, ((pr[0] * v0 + pr[1] * v1) + pr[2] * v2) + pr[3] * v3);
        sgs_vstore(b->clip[1] + h, ((pr[4] * v0 + pr[5] * v1) + pr[6] * v2) + pr[7] * v3);
        sgs_vstore(b->clip[2] + h, ((pr[8] * v0 + pr[9] * v1) + pr[10] * v2) + pr[11] * v3);
        sgs_vstore(b->clip[3] + h, ((pr[12] * v0 + pr[13] * v1) + pr[14] * v2) + pr[15] * v3);
        if (vp >= 0) {
            sgs_vstore(b->varying[vp] + h, v0);
            sgs_vstore(b->varying[vp + 1] + h, v1);
            sgs_vstore(b->varying[vp + 2] + h, v2);
        }
        if (vn >= 0) {
            sgs_vstore(b->varying[vn] + h, (nm[0] * nx + nm[1] * ny) + nm[2] * nz);
            sgs_vstore(b->varying[vn + 1] + h, (nm[3] * nx + nm[4] * ny) + nm[5] * nz);
            sgs_vstore(b->varying[vn + 2] + h, (nm[6] * nx + nm[7] * ny) + nm[8] * nz);
        }
    }
}

/* The same from the batch's own positions and normals. */
static inline void sgs_transform(sgVertexBatch *b, int vp, int vn) {
    sgs_transform_from(b, (const float(*)[SGS_LANES])b->position,
                       (const float(*)[SGS_LANES])b->normal, vp, vn);
}

/* ---- one directional light ---------------------------------------------------------------------
 *
 * The fixed lighting's equation (light.h) for one directional light with a local viewer:
 *   N = normalize(n), V = normalize(-P), L = -normalize(direction), H = normalize(L + V)
 *   colour = clamp(base ambient + base max(N.L, 0) light, 0, 1)
 *            + (N.L > 0 ? pow(max(N.H, 0), shininess) : 0) light specular
 * (the sum clamped to [0, 1] by the output). L is prepared once per draw call of the stage. */

typedef struct sgs_light {
    float ambient[3], dir[3], color[3], specular[3], shininess;
    float min_x; /* the least base sgs_pow_unit is given: FLT_MIN when shininess is 0, else 0 */
    /* 0: the specular term adds +0 or -0 to every lane (specular 0, the light's colour finite),
     * which changes no sum, so it is not computed */
    int specular_on;
} sgs_light;

/* Reads ambient, direction (the way the light travels, view space), colour, specular and
 * shininess from u at the given offsets (specular < 0: no specular term) and prepares L. */
static inline sgs_light sgs_light_read(const float *u, int ambient, int direction, int color,
                                       int specular, int shininess) {
    sgs_light l;
    for (int k = 0; k < 3; k++) {
        l.ambient[k] = u[ambient + k];
        l.color[k] = u[color + k];
        l.specular[k] = specular >= 0 ? u[specular + k] : 0.0f;
    }
    float inv = sgs_inv_len(u[direction], u[direction + 1], u[direction + 2]);
    for (int k = 0; k < 3; k++) l.dir[k] = -u[direction + k] * inv;
    l.shininess = shininess >= 0 ? u[shininess] : 0.0f;
    if (!(l.shininess >= 0.0f)) l.shininess = 0.0f;
    if (l.shininess > 128.0f) l.shininess = 128.0f;
    l.min_x = l.shininess == 0.0f ? FLT_MIN : 0.0f;
    l.specular_on = 0;
    for (int k = 0; k < 3; k++)
        l.specular_on |=
            l.specular[k] != 0.0f || !(l.color[k] >= -FLT_MAX && l.color[k] <= FLT_MAX);
    return l;
}

/* The equation for a vector of lanes: view-space point (px, py, pz), normal (nx, ny, nz), base
 * colour. */
static inline void sgs_vlight_eval(const sgs_light *l, sgs_vf px, sgs_vf py, sgs_vf pz, sgs_vf nx,
                                   sgs_vf ny, sgs_vf nz, const sgs_vf base[3], sgs_vf out[3]) {
    sgs_vf in = sgs_vinv_len(nx, ny, nz);
    nx *= in, ny *= in, nz *= in;
    sgs_vf ndotl = (nx * l->dir[0] + ny * l->dir[1]) + nz * l->dir[2];
    if (!l->specular_on) {
        const sgs_vf d = sgs_vsel(ndotl > 0.0f, ndotl, sgs_vsplat(0.0f));
        for (int k = 0; k < 3; k++)
            out[k] = sgs_vclamp01(base[k] * l->ambient[k] + base[k] * (d * l->color[k]));
        return;
    }
    sgs_vf iv = sgs_vinv_len(px, py, pz);
    sgs_vf vx = -px * iv, vy = -py * iv, vz = -pz * iv;
    sgs_vf hx = l->dir[0] + vx, hy = l->dir[1] + vy, hz = l->dir[2] + vz;
    sgs_vf ih = sgs_vinv_len(hx, hy, hz);
    hx *= ih, hy *= ih, hz *= ih;
    sgs_vf ndoth = (nx * hx + ny * hy) + nz * hz;
    sgs_vf pw =
        sgs_vpow_unit(sgs_vsel(ndoth > l->min_x, ndoth, sgs_vsplat(l->min_x)), l->shininess);
    const sgs_vi lit = ndotl > 0.0f;
    sgs_vf d = sgs_vsel(lit, ndotl, sgs_vsplat(0.0f)), s = sgs_vsel(lit, pw, sgs_vsplat(0.0f));
    for (int k = 0; k < 3; k++)
        out[k] = sgs_vclamp01(base[k] * l->ambient[k] + base[k] * (d * l->color[k])) +
                 (s * l->color[k]) * l->specular[k];
}

/* The equation on a fragment batch whose varyings from `first` are its view-space point, its
 * normal and its base colour (three each), into colour channels 0..2. */
static inline void sgs_vlight_varyings(const sgs_light *l, sgFragmentBatch *b, int first) {
    float(*v)[SGS_LANES] = b->varying + first;
    SGS_EACH_VECTOR(h) {
        const sgs_vf base[3] = {sgs_vload(v[6] + h), sgs_vload(v[7] + h), sgs_vload(v[8] + h)};
        sgs_vf c[3];
        sgs_vlight_eval(l, sgs_vload(v[0] + h), sgs_vload(v[1] + h), sgs_vload(v[2] + h),
                        sgs_vload(v[3] + h), sgs_vload(v[4] + h), sgs_vload(v[5] + h), base, c);
        for (int k = 0; k < 3; k++) sgs_vstore(b->color[k] + h, c[k]);
    }
}

/* normalize, 0 for a zero length (sgs_vinv_len's). */
#define SGS_GLSL_SAFE_NORMALIZE                                                                    \
    "vec3 safe_normalize(vec3 v) {\n"                                                              \
    "    precise float len2 = (v.x * v.x + v.y * v.y) + v.z * v.z;\n"                              \
    "    return len2 > 0.0 ? v / sqrt(len2) : vec3(0.0);\n"                                        \
    "}\n"

/* A lit twin's vertex stage: the view-space position, the normal (normal matrix x n) and the base
 * colour (the vertex colour x u[0..3]) at locations 0, 1 and 2, as sgs_transform and the C stages
 * write them. SGS_GLSL_LIT_VERTEX_OUT before main, SGS_GLSL_LIT_VERTEX in it. */
#define SGS_GLSL_LIT_VERTEX_OUT                                                                    \
    "layout(location = 0) out vec3 v_pos;\n"                                                       \
    "layout(location = 1) out vec3 v_normal;\n"                                                    \
    "layout(location = 2) out vec4 v_base;\n"
#define SGS_GLSL_LIT_VERTEX                                                                        \
    "    vec4 p = world_view * sg_position;\n"                                                     \
    "    gl_Position = proj * p;\n"                                                                \
    "    v_pos = p.xyz;\n"                                                                         \
    "    v_normal = transpose(inverse(mat3(world_view))) * sg_normal;\n"                           \
    "    v_base = sg_color * vec4(u[0], u[1], u[2], u[3]);\n"

/* The same in GLSL: light(P, n, base, ambient, direction, colour, specular, shininess) with the
 * uniform offsets; spec < 0: none. */
#define SGS_GLSL_LIGHT                                                                             \
    SGS_GLSL_U3 SGS_GLSL_POW_UNIT SGS_GLSL_SAFE_NORMALIZE                                          \
        "vec3 light(vec3 P, vec3 n, vec3 base, int amb, int dir, int col, int spec, int shin) {\n" \
        "    vec3 N = safe_normalize(n), V = safe_normalize(-P);\n"                                \
        "    vec3 L = -safe_normalize(u3(dir));\n"                                                 \
        "    vec3 c = u3(col);\n"                                                                  \
        "    float ndotl = dot(N, L);\n"                                                           \
        "    vec3 prim = clamp(base * u3(amb) + base * (max(ndotl, 0.0) * c), 0.0, 1.0);\n"        \
        "    if (spec < 0 || !(ndotl > 0.0)) return prim;\n"                                       \
        "    float s = shin >= 0 ? clamp(u[shin], 0.0, 128.0) : 0.0;\n"                            \
        "    float ndoth = dot(N, safe_normalize(L + V));\n"                                       \
        "    return prim + (pow_unit(max(ndoth, 0.0), s) * c) * u3(spec);\n"                       \
        "}\n"

/* ---- value noise ------------------------------------------------------------------------------
 *
 * 3D value noise on the integer lattice: each lattice point gets a value in [0, 1) from an
 * integer hash of its coordinates (32-bit unsigned arithmetic, exactly the same in C and GLSL),
 * and the eight around a point are blended with the smooth fade t^2 (3 - 2t). Only products and
 * sums of small numbers follow the hash, so C and GLSL agree to a few units of the last place. */

static inline float sgs_hash3(int32_t x, int32_t y, int32_t z) {
    uint32_t h =
        ((uint32_t)x * 0x8da6b343u) ^ ((uint32_t)y * 0xd8163841u) ^ ((uint32_t)z * 0xcb1ab31fu);
    h ^= h >> 16;
    h *= 0x7feb352du;
    h ^= h >> 15;
    h *= 0x846ca68bu;
    h ^= h >> 16;
    return (float)(h >> 8) * (1.0f / 16777216.0f);
}
static inline sgs_vf sgs_vhash3(sgs_vi x, sgs_vi y, sgs_vi z) {
    sgs_vu h = ((sgs_vu)x * 0x8da6b343u) ^ ((sgs_vu)y * 0xd8163841u) ^ ((sgs_vu)z * 0xcb1ab31fu);
    h ^= h >> 16;
    h *= 0x7feb352du;
    h ^= h >> 15;
    h *= 0x846ca68bu;
    h ^= h >> 16;
    /* below 2^24: the signed conversion is exact, as the scalar unsigned one */
    return __builtin_convertvector((sgs_vi)(h >> 8), sgs_vf) * (1.0f / 16777216.0f);
}

static inline sgs_vf sgs_vlerp(sgs_vf a, sgs_vf b, sgs_vf t) {
    return a + (b - a) * t;
}

static inline sgs_vf sgs_vnoise3(sgs_vf x, sgs_vf y, sgs_vf z) {
    sgs_vf fx = sgs_vfloor_small(x), fy = sgs_vfloor_small(y), fz = sgs_vfloor_small(z);
    sgs_vi ix = __builtin_convertvector(fx, sgs_vi), iy = __builtin_convertvector(fy, sgs_vi),
           iz = __builtin_convertvector(fz, sgs_vi);
    sgs_vf tx = x - fx, ty = y - fy, tz = z - fz;
    tx = tx * tx * (3.0f - 2.0f * tx);
    ty = ty * ty * (3.0f - 2.0f * ty);
    tz = tz * tz * (3.0f - 2.0f * tz);
    sgs_vf a = sgs_vlerp(sgs_vhash3(ix, iy, iz), sgs_vhash3(ix + 1, iy, iz), tx);
    sgs_vf b = sgs_vlerp(sgs_vhash3(ix, iy + 1, iz), sgs_vhash3(ix + 1, iy + 1, iz), tx);
    sgs_vf c = sgs_vlerp(sgs_vhash3(ix, iy, iz + 1), sgs_vhash3(ix + 1, iy, iz + 1), tx);
    sgs_vf d = sgs_vlerp(sgs_vhash3(ix, iy + 1, iz + 1), sgs_vhash3(ix + 1, iy + 1, iz + 1), tx);
    return sgs_vlerp(sgs_vlerp(a, b, ty), sgs_vlerp(c, d, ty), tz);
}

/* Turbulence: octaves of |2 noise - 1|, each of twice the frequency and half the weight, over
 * their total weight: in [0, 1]. */
static inline sgs_vf sgs_vturb1(sgs_vf x, sgs_vf y, sgs_vf z) {
    sgs_vf n = 2.0f * sgs_vnoise3(x, y, z) - 1.0f;
    return sgs_vsel(n < 0.0f, -n, n);
}
static inline sgs_vf sgs_vturbulence(sgs_vf x, sgs_vf y, sgs_vf z) {
    sgs_vf sum = sgs_vturb1(x, y, z);
    sum = sum + 0.5f * sgs_vturb1(x * 2.0f, y * 2.0f, z * 2.0f);
    sum = sum + 0.25f * sgs_vturb1(x * 4.0f, y * 4.0f, z * 4.0f);
    sum = sum + 0.125f * sgs_vturb1(x * 8.0f, y * 8.0f, z * 8.0f);
    return sum * (1.0f / 1.875f); /* 1 + 1/2 + 1/4 + 1/8 */
}

/* Fractal sum: octaves of noise, each of twice the frequency and half the weight, over their
 * total weight: in [0, 1), mostly near 1/2. */
static inline sgs_vf sgs_vfbm(sgs_vf x, sgs_vf y, sgs_vf z) {
    sgs_vf sum = sgs_vnoise3(x, y, z);
    sum = sum + 0.5f * sgs_vnoise3(x * 2.0f, y * 2.0f, z * 2.0f);
    sum = sum + 0.25f * sgs_vnoise3(x * 4.0f, y * 4.0f, z * 4.0f);
    sum = sum + 0.125f * sgs_vnoise3(x * 8.0f, y * 8.0f, z * 8.0f);
    return sum * (1.0f / 1.875f);
}

/* One value (lane 0 of the vector forms), for tests. */
static inline float sgs_noise3(float x, float y, float z) {
    return sgs_vnoise3(sgs_vsplat(x), sgs_vsplat(y), sgs_vsplat(z))[0];
}
static inline float sgs_turbulence(float x, float y, float z) {
    return sgs_vturbulence(sgs_vsplat(x), sgs_vsplat(y), sgs_vsplat(z))[0];
}
static inline float sgs_fbm(float x, float y, float z) {
    return sgs_vfbm(sgs_vsplat(x), sgs_vsplat(y), sgs_vsplat(z))[0];
}

/* The same in GLSL; `precise` keeps the compiler from fusing products and sums (SPIR-V
 * NoContraction), as the C is compiled without contraction. */
#define SGS_GLSL_HASH                                                                              \
    "float hash3(ivec3 p) {\n"                                                                     \
    "    uvec3 q = uvec3(p);\n"                                                                    \
    "    uint h = (q.x * 0x8da6b343u) ^ (q.y * 0xd8163841u) ^ (q.z * 0xcb1ab31fu);\n"              \
    "    h ^= h >> 16; h *= 0x7feb352du; h ^= h >> 15; h *= 0x846ca68bu; h ^= h >> 16;\n"          \
    "    return float(h >> 8) * (1.0 / 16777216.0);\n"                                             \
    "}\n"
#define SGS_GLSL_NOISE                                                                             \
    SGS_GLSL_HASH                                                                                  \
    "precise float lerp1(float a, float b, float t) { return a + (b - a) * t; }\n"                 \
    "float noise3(vec3 p) {\n"                                                                     \
    "    vec3 f = floor(p);\n"                                                                     \
    "    ivec3 i = ivec3(f);\n"                                                                    \
    "    precise vec3 t = p - f;\n"                                                                \
    "    t = t * t * (3.0 - 2.0 * t);\n"                                                           \
    "    float a = lerp1(hash3(i), hash3(i + ivec3(1, 0, 0)), t.x);\n"                             \
    "    float b = lerp1(hash3(i + ivec3(0, 1, 0)), hash3(i + ivec3(1, 1, 0)), t.x);\n"            \
    "    float c = lerp1(hash3(i + ivec3(0, 0, 1)), hash3(i + ivec3(1, 0, 1)), t.x);\n"            \
    "    float d = lerp1(hash3(i + ivec3(0, 1, 1)), hash3(i + ivec3(1, 1, 1)), t.x);\n"            \
    "    return lerp1(lerp1(a, b, t.y), lerp1(c, d, t.y), t.z);\n"                                 \
    "}\n"                                                                                          \
    "float turbulence(vec3 p) {\n"                                                                 \
    "    precise float sum = 0.0;\n"                                                               \
    "    float amp = 1.0;\n"                                                                       \
    "    for (int o = 0; o < 4; o++) {\n"                                                          \
    "        precise float n = 2.0 * noise3(p) - 1.0;\n"                                           \
    "        sum = sum + amp * abs(n);\n"                                                          \
    "        amp = amp * 0.5;\n"                                                                   \
    "        p = p * 2.0;\n"                                                                       \
    "    }\n"                                                                                      \
    "    return sum * (1.0 / 1.875);\n"                                                            \
    "}\n"                                                                                          \
    "float fbm(vec3 p) {\n"                                                                        \
    "    precise float sum = 0.0;\n"                                                               \
    "    float amp = 1.0;\n"                                                                       \
    "    for (int o = 0; o < 4; o++) {\n"                                                          \
    "        sum = sum + amp * noise3(p);\n"                                                       \
    "        amp = amp * 0.5;\n"                                                                   \
    "        p = p * 2.0;\n"                                                                       \
    "    }\n"                                                                                      \
    "    return sum * (1.0 / 1.875);\n"                                                            \
    "}\n"

#endif
