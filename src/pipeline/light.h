/* light.h - the lighting equation (OpenGL 1.x fixed-function lighting with a local viewer, colour
 * material ambient-and-diffuse and a separate specular colour), in the scalar form every lighting
 * mode evaluates: flat per triangle (assemble.c), Gouraud per vertex (vertex.c), Phong per pixel
 * (shade_phong.c, whose SIMD variants compute the same IEEE operations in the same order).
 *
 *   N = normalize(n), V = normalize(-P)
 *   per light: directional L = -normalize(direction), att = 1;
 *     point v = position - P, d = |v|, L = v / d, att = 1 / max((c + l d) + q d^2, FLT_MIN);
 *     the light a shadow map hides: att x visibility (0 .. 1);
 *     where N.L > 0: diffuse += (att N.L) color,
 *                    specular += (att pow(max(N.H, 0), shininess)) color, H = normalize(L + V)
 *   primary = clamp(base ambient + base diffuse, 0, 1) per r, g, b; alpha = base alpha
 *   secondary = specular x material specular
 *
 * Flat and Gouraud draws that receive a shadow map evaluate it split (sg_light_eval_split): the
 * shadowed light's diffuse and specular terms apart from the rest, unclamped, so that each
 * pixel scales the light's part by its own visibility (sg_light_split_combine):
 *   primary = clamp(rest + vis x light, 0, 1), secondary = rest secondary + vis x light's.
 *
 * A zero-length vector normalises to 0 (so a zero normal, or a light at the surface point,
 * contributes nothing), never to NaN; pow(x, 0) = 1, as in OpenGL. Sums run left to right:
 * (x x' + y y') + z z'.
 */
#ifndef SG_LIGHT_H
#define SG_LIGHT_H

#include <stdarg.h>
#include <float.h>
#include <math.h>
#include <stdbool.h>
#include <string.h>

#include "sgapi/sgapi.h"

/* The attributes of a lit draw's vertices, in the order they are interpolated (the first
 * SG_TRI_ATTRS live in sg_tri, the others in sg_tri_ext). */
enum {
    SG_LIT_COLOR = 0, /* 4: primary colour (flat, Gouraud) or base colour (Phong; flat before
                         lighting) */
    SG_LIT_ST = 4,    /* 2: texcoords (0 when the draw samples no texture) */
    SG_LIT_SEC = 6,   /* 3: secondary colour (flat and Gouraud with a specular material) */
    SG_LIT_POS = 6,   /* 3: view-space position (Phong; flat before lighting) */
    SG_LIT_NRM = 9,   /* 3: normal, not normalised (Phong) */
    /* Flat and Gouraud draws receiving a shadow map (split): SG_LIT_COLOR holds the unclamped
     * rest of the primary colour (and alpha), SG_LIT_POS the view position, then: */
    SG_LIT_SPLIT_D = 9,    /* 3: the shadowed light's diffuse part of the primary colour */
    SG_LIT_SPLIT_SEC = 12, /* 3: the rest of the secondary colour (with a specular material) */
    SG_LIT_SPLIT_S = 15,   /* 3: the shadowed light's secondary colour (same) */
    SG_LIT_SPLIT_END = 18
};

/* The lights and material of a draw, prepared once per draw (sg_light_prepare). */
typedef struct sg_lights {
    int count;
    float ambient[3];
    struct {
        int point;      /* else directional */
        float v[3];     /* directional: L = -normalize(direction); point: position */
        float color[3]; /* r, g, b */
        float att[3];   /* point: constant, linear, quadratic */
    } light[SG_MAX_LIGHTS];
    float specular[3];
    float shininess;
    bool has_specular; /* some specular channel > 0: the secondary colour is not always 0 */
} sg_lights;

/* Told why a draw's lighting is refused: an sgResult code and a printf message naming the field
 * (the device's error, in the library). */
typedef void (*sg_light_fail_fn)(void *user, int code, const char *fmt, va_list ap);

/** Checks and prepares a draw's lighting (NULL: none); false, after calling fail (when not NULL)
 *  with user, when a value is out of range. */
bool sg_light_prepare(const sgLighting *in, const float specular[3], float shininess,
                      sg_lights *out, sg_light_fail_fn fail, void *user);

/** The normal matrix: the inverse transpose of worldView's upper-left 3x3, row-major 3x3,
 *  computed in double. A singular matrix gives zeros (every normal becomes 0). */
void sg_normal_matrix(const float world_view[16], float out[9]);

static inline float sg_dot3(const float a[3], const float b[3]) {
    return (a[0] * b[0] + a[1] * b[1]) + a[2] * b[2];
}

/* v / |v|, by one division and three products; 0 for a zero (or non-finite) length. */
static inline void sg_normalize3(const float v[3], float out[3]) {
    float len2 = sg_dot3(v, v);
    float inv = len2 > 0.0f && len2 <= FLT_MAX ? 1.0f / sqrtf(len2) : 0.0f;
    out[0] = v[0] * inv;
    out[1] = v[1] * inv;
    out[2] = v[2] * inv;
}

/* log2 of a normal positive float: exponent, then log2 of the mantissa m in [sqrt(1/2),
 * sqrt(2)) by the series 2/ln2 (t + t^3/3 + ... + t^11/11), t = (m - 1) / (m + 1), |t| < 0.172. */
static inline float sg_log2_pos(float x) {
    unsigned int bits;
    memcpy(&bits, &x, sizeof bits);
    int e = (int)((bits >> 23) & 255u) - 127;
    bits = (bits & 0x007fffffu) | 0x3f800000u; /* mantissa in [1, 2) */
    float m;
    memcpy(&m, &bits, sizeof m);
    if (m > 1.41421356f) {
        m = m * 0.5f;
        e = e + 1;
    }
    float t = (m - 1.0f) / (m + 1.0f), t2 = t * t;
    float p = 1.0f / 11.0f;
    p = p * t2 + 1.0f / 9.0f;
    p = p * t2 + 1.0f / 7.0f;
    p = p * t2 + 1.0f / 5.0f;
    p = p * t2 + 1.0f / 3.0f;
    p = p * t2 + 1.0f;
    return (float)e + (p * t) * 2.88539008f; /* 2 / ln 2 */
}

/* 2^z for z <= 0: z = n + f with n = floor(z + 1/2), |f| <= 1/2, and e^(f ln 2) by its series to
 * the 7th power; 0 below 2^-126. */
static inline float sg_exp2_neg(float z) {
    if (!(z >= -126.0f)) return 0.0f;
    float n = floorf(z + 0.5f);
    float x = (z - n) * 0.693147181f;
    float p = 1.0f / 5040.0f;
    p = p * x + 1.0f / 720.0f;
    p = p * x + 1.0f / 120.0f;
    p = p * x + 1.0f / 24.0f;
    p = p * x + 1.0f / 6.0f;
    p = p * x + 0.5f;
    p = p * x + 1.0f;
    p = p * x + 1.0f;
    unsigned int bits = (unsigned int)((int)n + 127) << 23;
    float scale;
    memcpy(&scale, &bits, sizeof scale);
    return p * scale;
}

/* x^s for x in [0, 1] and s in [0, 128]: 1 when s = 0 (0^0 = 1, as in OpenGL), 0 for x below
 * the smallest normal float. */
static inline float sg_pow_unit(float x, float s) {
    if (s == 0.0f) return 1.0f;
    if (!(x >= FLT_MIN)) return 0.0f;
    return sg_exp2_neg(s * sg_log2_pos(x));
}

/* Light i seen from view-space point P: the unit vector L towards it (0 for a point light at P)
 * and its attenuation (1 for a directional light). */
static inline __attribute__((always_inline)) float sg_light_vector(const sg_lights *ls, int i,
                                                                   const float P[3], float L[3]) {
    if (!ls->light[i].point) {
        memcpy(L, ls->light[i].v, 3 * sizeof *L);
        return 1.0f;
    }
    const float *lp = ls->light[i].v, *k = ls->light[i].att;
    float v[3] = {lp[0] - P[0], lp[1] - P[1], lp[2] - P[2]};
    float d2 = sg_dot3(v, v), d = sqrtf(d2);
    float inv = d > 0.0f && d <= FLT_MAX ? 1.0f / d : 0.0f;
    L[0] = v[0] * inv;
    L[1] = v[1] * inv;
    L[2] = v[2] * inv;
    float den = (k[0] + k[1] * d) + k[2] * d2;
    return 1.0f / (den > FLT_MIN ? den : FLT_MIN);
}

/** The equation at one point: view-space position P, unnormalised normal n, base colour (rgba).
 *  primary rgba, secondary rgb. Light `shadowed` (-1: none) is seen by the fraction `vis` of the
 *  point (shadow maps): its attenuation is multiplied by it. */
static inline __attribute__((always_inline)) void
sg_light_eval_shadowed(const sg_lights *ls, const float P[3], const float n[3], const float base[4],
                       int shadowed, float vis, float prim[4], float sec[3]) {
    float N[3], V[3], mp[3] = {-P[0], -P[1], -P[2]};
    sg_normalize3(n, N);
    sg_normalize3(mp, V);
    float diff[3] = {0.0f, 0.0f, 0.0f}, spec[3] = {0.0f, 0.0f, 0.0f};
    for (int i = 0; i < ls->count; i++) {
        float L[3], att = sg_light_vector(ls, i, P, L);
        const float *c = ls->light[i].color;
        if (i == shadowed) att = att * vis;
        float ndotl = sg_dot3(N, L);
        if (!(ndotl > 0.0f)) continue;
        float f = att * ndotl;
        for (int k = 0; k < 3; k++) diff[k] = diff[k] + f * c[k];
        if (ls->has_specular) {
            float h[3] = {L[0] + V[0], L[1] + V[1], L[2] + V[2]}, H[3];
            sg_normalize3(h, H);
            float ndoth = sg_dot3(N, H);
            float g = att * sg_pow_unit(ndoth > 0.0f ? ndoth : 0.0f, ls->shininess);
            for (int k = 0; k < 3; k++) spec[k] = spec[k] + g * c[k];
        }
    }
    for (int k = 0; k < 3; k++) {
        /* A light at the surface with a huge colour can overflow the sums to infinity, which
         * times a zero base or specular colour would be NaN: they stop at FLT_MAX. */
        diff[k] = diff[k] < FLT_MAX ? diff[k] : FLT_MAX;
        spec[k] = spec[k] < FLT_MAX ? spec[k] : FLT_MAX;
        float v = base[k] * ls->ambient[k] + base[k] * diff[k];
        prim[k] = v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f;
        sec[k] = spec[k] * ls->specular[k];
    }
    prim[3] = base[3];
}

/* A split part beyond this magnitude is held to it: far past saturation, and its interpolation
 * stays finite. */
#define SG_LIT_SPLIT_MAX 65536.0f

static inline float sg_split_bound(float v) {
    v = v < SG_LIT_SPLIT_MAX ? v : SG_LIT_SPLIT_MAX;
    return v > -SG_LIT_SPLIT_MAX ? v : -SG_LIT_SPLIT_MAX;
}

/** The equation at one point, split for a shadow map (flat and Gouraud lighting): rest = base
 *  ambient + base diffuse of every light but `shadowed`, unclamped, and base alpha; light = base
 *  diffuse of light `shadowed`; rest_sec and light_sec the same split of the secondary colour.
 *  sg_light_split_combine with visibility 0 is the equation without that light. */
static inline __attribute__((always_inline)) void
sg_light_eval_split(const sg_lights *ls, const float P[3], const float n[3], const float base[4],
                    int shadowed, float rest[4], float light[3], float rest_sec[3],
                    float light_sec[3]) {
    float N[3], V[3], mp[3] = {-P[0], -P[1], -P[2]};
    sg_normalize3(n, N);
    sg_normalize3(mp, V);
    float diff[2][3] = {{0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f}};
    float spec[2][3] = {{0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f}};
    for (int i = 0; i < ls->count; i++) {
        float L[3], att = sg_light_vector(ls, i, P, L);
        const float *c = ls->light[i].color;
        float ndotl = sg_dot3(N, L);
        if (!(ndotl > 0.0f)) continue;
        const int j = i == shadowed;
        float f = att * ndotl;
        for (int k = 0; k < 3; k++) diff[j][k] = diff[j][k] + f * c[k];
        if (ls->has_specular) {
            float h[3] = {L[0] + V[0], L[1] + V[1], L[2] + V[2]}, H[3];
            sg_normalize3(h, H);
            float ndoth = sg_dot3(N, H);
            float g = att * sg_pow_unit(ndoth > 0.0f ? ndoth : 0.0f, ls->shininess);
            for (int k = 0; k < 3; k++) spec[j][k] = spec[j][k] + g * c[k];
        }
    }
    for (int k = 0; k < 3; k++) {
        for (int j = 0; j < 2; j++) { /* as in sg_light_eval_shadowed */
            diff[j][k] = diff[j][k] < FLT_MAX ? diff[j][k] : FLT_MAX;
            spec[j][k] = spec[j][k] < FLT_MAX ? spec[j][k] : FLT_MAX;
        }
        rest[k] = sg_split_bound(base[k] * ls->ambient[k] + base[k] * diff[0][k]);
        light[k] = sg_split_bound(base[k] * diff[1][k]);
        rest_sec[k] = sg_split_bound(spec[0][k] * ls->specular[k]);
        light_sec[k] = sg_split_bound(spec[1][k] * ls->specular[k]);
    }
    rest[3] = base[3];
}

/** The colours of a split evaluation at a point the shadowed light reaches by the fraction vis:
 *  prim = clamp(rest + vis x light, 0, 1) (alpha: rest's); with sec (a specular material), sec =
 *  rest_sec + vis x light_sec. */
static inline __attribute__((always_inline)) void
sg_light_split_combine(const float rest[4], const float light[3], float vis, float prim[4]) {
    for (int k = 0; k < 3; k++) {
        float v = rest[k] + vis * light[k];
        prim[k] = v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f;
    }
    prim[3] = rest[3];
}

/** The equation at one point, every light seen (sg_light_eval_shadowed). */
static inline void sg_light_eval(const sg_lights *ls, const float P[3], const float n[3],
                                 const float base[4], float prim[4], float sec[3]) {
    sg_light_eval_shadowed(ls, P, n, base, -1, 1.0f, prim, sec);
}

#endif
