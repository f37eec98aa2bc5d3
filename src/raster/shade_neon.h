/* shade_neon.h - the NEON shading helpers (AArch64; internal to the raster): texture coordinates,
 * texel fetches, nearest and bilinear filtering, and float colours to RGBA8, four pixels a vector
 * (one row of a tile). shade_neon.c makes the shading table of them, shade_phong_neon.c the
 * per-pixel lighting. Each is the scalar reference's computation (shade.c, sample.h) transcribed
 * lane by lane: the same IEEE operations in the same order, the same branches as selects (compares
 * and bit selects, never FMIN/FMAX, whose NaN and signed-zero rules differ from the C code's), and
 * bilinear filtering in the reference's own 32-bit integer sums.
 */
#ifndef SG_SHADE_NEON_H
#define SG_SHADE_NEON_H

#include <float.h>

#include "raster/shade.h"

/* FLT_EVAL_METHOD 0: the scalar code rounds each operation to float, as NEON does. AArch64's
 * Advanced SIMD honours the FPCR (no flush to zero by default), unlike 32-bit ARM's NEON. */
#if defined(__aarch64__) && defined(__ARM_NEON) && FLT_EVAL_METHOD == 0
#define SG_SHADE_NEON 1

#include <arm_neon.h>
#include <string.h>

#include "raster/framebuffer.h"

#define INLINE static inline __attribute__((always_inline))

/* The bound texture, broadcast: "scale" is what the texcoord functions multiply by (n, or 256 n
 * when bilinear), "hi" the bilinear clamp's upper limit 256 (n + 1). */
typedef struct tex4n {
    const uint8_t *texels;
    float32x4_t scale_x, scale_y, hi_x, hi_y;
    int32x4_t n_x, n_y, last_x, last_y; /* n and n - 1 */
} tex4n;

INLINE tex4n tex4n_of(const sg_texview *tv, const int bilinear) {
    const int w = tv->width, h = tv->height;
    const float sc = bilinear ? 256.0f : 1.0f;
    tex4n tx;
    tx.texels = tv->texels;
    tx.scale_x = vdupq_n_f32(sc * (float)w);
    tx.scale_y = vdupq_n_f32(sc * (float)h);
    tx.hi_x = vdupq_n_f32(256.0f * (float)(w + 1));
    tx.hi_y = vdupq_n_f32(256.0f * (float)(h + 1));
    tx.n_x = vdupq_n_s32(w);
    tx.n_y = vdupq_n_s32(h);
    tx.last_x = vdupq_n_s32(w - 1);
    tx.last_y = vdupq_n_s32(h - 1);
    return tx;
}

/* a where m, else b, for a constant b. */
INLINE float32x4_t sel_f(uint32x4_t m, float32x4_t a, float b) {
    return vbslq_f32(m, a, vdupq_n_f32(b));
}

/* sg_texcoord_repeat: FRINTM is floorf exactly (NaN and infinities included); x >= 0 fails for
 * NaN, which gives 0. */
INLINE float32x4_t coord_repeat(float32x4_t s, float32x4_t scale) {
    float32x4_t x = vmulq_f32(vsubq_f32(s, vrndmq_f32(s)), scale);
    return sel_f(vcgeq_f32(x, vdupq_n_f32(0.0f)), x, 0.0f);
}

/* sg_texcoord_clamp: s >= -1 fails for NaN, which gives -1. */
INLINE float32x4_t coord_clamp(float32x4_t s, float32x4_t scale) {
    s = sel_f(vcgeq_f32(s, vdupq_n_f32(-1.0f)), s, -1.0f);
    s = vbslq_f32(vcgtq_f32(s, vdupq_n_f32(2.0f)), vdupq_n_f32(2.0f), s);
    return vmulq_f32(s, scale);
}

/* sg_wrap_index */
INLINE int32x4_t wrap_index(int32x4_t i, int32x4_t n, int32x4_t last, const int repeat) {
    if (repeat) {
        i = vaddq_s32(i, vandq_s32(vreinterpretq_s32_u32(vcltzq_s32(i)), n));
        return vsubq_s32(i, vandq_s32(vreinterpretq_s32_u32(vcgeq_s32(i, n)), n));
    }
    return vminq_s32(vmaxq_s32(i, vdupq_n_s32(0)), last);
}

/* Index of texel (i, j), row j counted from the bottom (sg_texel_at): below 2^30 texels. */
INLINE int32x4_t texel_index(const tex4n *tx, int32x4_t i, int32x4_t j) {
    return vaddq_s32(vmulq_s32(vsubq_s32(tx->last_y, j), tx->n_x), i);
}

/* Four texels by index, one scalar load each (NEON has no gather). */
INLINE uint32x4_t fetch4(const uint8_t *texels, int32x4_t idx) {
    uint32_t v[4];
    for (int l = 0; l < 4; l++) {
        uint32_t k = (uint32_t)vgetq_lane_s32(idx, 0);
        idx = vextq_s32(idx, idx, 1);
        memcpy(&v[l], texels + (size_t)k * 4, 4);
    }
    return vld1q_u32(v);
}

/* sg_sample_nearest of four pixels, as packed RGBA8 texels. */
INLINE uint32x4_t nearest4(const tex4n *tx, float32x4_t s, float32x4_t u, const int repeat) {
    float32x4_t x = repeat ? coord_repeat(s, tx->scale_x) : coord_clamp(s, tx->scale_x);
    float32x4_t y = repeat ? coord_repeat(u, tx->scale_y) : coord_clamp(u, tx->scale_y);
    /* FCVTMS: (int)floorf, for values well inside int32 here. */
    int32x4_t i = wrap_index(vcvtmq_s32_f32(x), tx->n_x, tx->last_x, repeat);
    int32x4_t j = wrap_index(vcvtmq_s32_f32(y), tx->n_y, tx->last_y, repeat);
    return fetch4(tx->texels, texel_index(tx, i, j));
}

/* The coordinate of sg_sample_bilinear: scaled by 256 n, and with clamp also limited to
 * [-256, 256 (n + 1)] (x < -256 fails for NaN, but coord_clamp leaves none). */
INLINE float32x4_t bilinear_coord(float32x4_t s, float32x4_t scale, float32x4_t hi,
                                  const int repeat) {
    if (repeat) return coord_repeat(s, scale);
    float32x4_t x = coord_clamp(s, scale);
    const float32x4_t lo = vdupq_n_f32(-256.0f);
    return vbslq_f32(vcltq_f32(x, lo), lo, vbslq_f32(vcgtq_f32(x, hi), hi, x));
}

/* sg_bilinear_split: v = floor(x) - 128 + 512, i0 = (v >> 8) - 2, frac = v & 255. */
INLINE void bilinear_split(float32x4_t x, int32x4_t *i0, uint32x4_t *frac) {
    int32x4_t v = vaddq_s32(vcvtmq_s32_f32(x), vdupq_n_s32(-128 + 512));
    *i0 = vsubq_s32(vshrq_n_s32(v, 8), vdupq_n_s32(2));
    *frac = vandq_u32(vreinterpretq_u32_s32(v), vdupq_n_u32(255));
}

/* Channel k (0 .. 255) of four packed RGBA8 texels. */
INLINE uint32x4_t channel(uint32x4_t t, int k) {
    return vandq_u32(vshlq_u32(t, vdupq_n_s32(-8 * k)), vdupq_n_u32(255));
}

/* sg_sample_bilinear of four pixels, planar: c[k] gets channel k of the four pixels. The four
 * weights and the sum are the reference's integers: (256 - f) and f below 2^9, products at most
 * 2^16, the sum at most 255 * 2^16 + 2^15, all exact in 32-bit lanes. */
INLINE void bilinear4(const tex4n *tx, float32x4_t s, float32x4_t u, const int repeat,
                      uint32x4_t c[4]) {
    int32x4_t i0, j0;
    uint32x4_t fx, fy;
    bilinear_split(bilinear_coord(s, tx->scale_x, tx->hi_x, repeat), &i0, &fx);
    bilinear_split(bilinear_coord(u, tx->scale_y, tx->hi_y, repeat), &j0, &fy);
    const int32x4_t one = vdupq_n_s32(1);
    int32x4_t i1 = wrap_index(vaddq_s32(i0, one), tx->n_x, tx->last_x, repeat);
    int32x4_t j1 = wrap_index(vaddq_s32(j0, one), tx->n_y, tx->last_y, repeat);
    i0 = wrap_index(i0, tx->n_x, tx->last_x, repeat);
    j0 = wrap_index(j0, tx->n_y, tx->last_y, repeat);
    uint32x4_t p00 = fetch4(tx->texels, texel_index(tx, i0, j0));
    uint32x4_t p10 = fetch4(tx->texels, texel_index(tx, i1, j0));
    uint32x4_t p01 = fetch4(tx->texels, texel_index(tx, i0, j1));
    uint32x4_t p11 = fetch4(tx->texels, texel_index(tx, i1, j1));
    const uint32x4_t w256 = vdupq_n_u32(256);
    uint32x4_t gx = vsubq_u32(w256, fx), gy = vsubq_u32(w256, fy);
    uint32x4_t w00 = vmulq_u32(gx, gy), w10 = vmulq_u32(fx, gy), w01 = vmulq_u32(gx, fy),
               w11 = vmulq_u32(fx, fy);
    for (int k = 0; k < 4; k++) {
        uint32x4_t sum = vmulq_u32(channel(p00, k), w00);
        sum = vmlaq_u32(sum, channel(p10, k), w10);
        sum = vmlaq_u32(sum, channel(p01, k), w01);
        sum = vmlaq_u32(sum, channel(p11, k), w11);
        c[k] = vshrq_n_u32(vaddq_u32(sum, vdupq_n_u32(32768)), 16);
    }
}

/* Four RGBA8 texels to planar channels. */
INLINE void unpack_texels(uint32x4_t t, uint32x4_t c[4]) {
    for (int k = 0; k < 4; k++) c[k] = channel(t, k);
}

/* Planar channels (0 .. 255) to RGBA8, sg_pack_rgba8. */
INLINE uint32x4_t pack4(const uint32x4_t c[4]) {
    return vorrq_u32(vorrq_u32(c[0], vshlq_n_u32(c[1], 8)),
                     vorrq_u32(vshlq_n_u32(c[2], 16), vshlq_n_u32(c[3], 24)));
}

/* sg_to_unorm8 of each lane: v > 0 fails for NaN and -0 (both give 0), v >= 1 gives 255 through
 * the same v * 255 + 0.5 truncation (255.5 -> 255). */
INLINE uint32x4_t unorm8(float32x4_t v) {
    v = sel_f(vcgtq_f32(v, vdupq_n_f32(0.0f)), v, 0.0f);
    v = vbslq_f32(vcgeq_f32(v, vdupq_n_f32(1.0f)), vdupq_n_f32(1.0f), v);
    return vcvtq_u32_f32(vaddq_f32(vmulq_f32(v, vdupq_n_f32(255.0f)), vdupq_n_f32(0.5f)));
}

/* Float colours to packed RGBA8. */
INLINE uint32x4_t pack_unorm8(const float32x4_t col[4]) {
    uint32x4_t c[4];
    for (int k = 0; k < 4; k++) c[k] = unorm8(col[k]);
    return pack4(c);
}

/* Writes the lanes of `m` (4 bits) of a row; other pixels are not touched. */
INLINE void store_row(uint32_t *dst, uint32x4_t v, unsigned m) {
    if (m != 15) {
        const uint32x4_t bits = {1, 2, 4, 8};
        v = vbslq_u32(vtstq_u32(vdupq_n_u32(m), bits), v, vld1q_u32(dst));
    }
    vst1q_u32(dst, v);
}

/* dx of the four pixels of a tile row: the tile's offset from the bounds plus 0, 1, 2, 3 (exact).
 */
INLINE float32x4_t row_dx(float ox) {
    const float32x4_t i = {0.0f, 1.0f, 2.0f, 3.0f};
    return vaddq_f32(vdupq_n_f32(ox), i);
}

#endif
#endif
