/* blend_neon.c - the raster functions of draws shaded in place in NEON (AArch64; see blend.h):
 * one row of a tile a vector; the same depth (z, clamp, compare) as the scalar code
 * (depth_neon.h) and the same integer blend, so the same bytes. */
#include "raster/blend.h"

#include "raster/depth_neon.h"
#include "raster/blend_walk.h"

#if defined(__aarch64__) && defined(__ARM_NEON)

/* x y / 255 as sg_mul_unorm8 rounds it, in 16-bit lanes (x, y <= 255: t + (t >> 8) + 128 stays
 * below 65536). */
static inline uint16x8_t mul_unorm8(uint16x8_t x, uint16x8_t y) {
    uint16x8_t t = vmulq_u16(x, y);
    t = vaddq_u16(vaddq_u16(t, vshrq_n_u16(t, 8)), vdupq_n_u16(128));
    return vshrq_n_u16(t, 8);
}

/* Four packed RGBA8 pixels (bytes r g b a ...) blended as sg_blend_rgba8 does. */
static inline uint8x16_t blend4(uint8x16_t s, uint8x16_t d) {
    const uint8x16_t alpha = {3, 3, 3, 3, 7, 7, 7, 7, 11, 11, 11, 11, 15, 15, 15, 15};
    uint8x16_t a = vqtbl1q_u8(s, alpha), ia = vsubq_u8(vdupq_n_u8(255), a);
    uint16x8_t lo = vaddq_u16(mul_unorm8(vmovl_u8(vget_low_u8(s)), vmovl_u8(vget_low_u8(a))),
                              mul_unorm8(vmovl_u8(vget_low_u8(d)), vmovl_u8(vget_low_u8(ia))));
    uint16x8_t hi = vaddq_u16(mul_unorm8(vmovl_high_u8(s), vmovl_high_u8(a)),
                              mul_unorm8(vmovl_high_u8(d), vmovl_high_u8(ia)));
    return vcombine_u8(vqmovn_u16(lo), vqmovn_u16(hi));
}

/* put: the fragments replace the pixels (an opaque line), else they are blended over them. */
static inline __attribute__((always_inline)) void in_place_neon(const void *vctx, const sg_tri *t,
                                                                int x0, int y0, uint32_t mask,
                                                                const int zmode, const int zwrite,
                                                                const int put) {
    const sg_vis_ctx *v = vctx;
    int base = sg_bin_tile_offset(x0 - v->bx0, y0 - v->by0);
    if (zmode != Z_NONE || zwrite) {
        float *dp = v->depth + base;
        const sg_zrows4n zr = sg_zrows4n_at(t, x0, y0);
        const uint32x4_t place = {1, 2, 4, 8};
        uint32_t pass = 0;
        for (int j = 0; j < 4; j++) {
            uint32_t bits = (mask >> (4 * j)) & 15u;
            if (!bits) continue;
            float32x4_t z = sg_zrow4n(&zr, j);
            float32x4_t d = vld1q_f32(dp + 4 * j);
            uint32x4_t p = vandq_u32(sg_lanes4n(bits), sg_compare4n(v->compare, z, d));
            if (zwrite) vst1q_f32(dp + 4 * j, vbslq_f32(p, z, d));
            pass |= vaddvq_u32(vandq_u32(p, place)) << (4 * j);
        }
        mask = pass;
    }
    if (!mask) return;
    _Alignas(16) uint32_t src[SG_TILE_PIXELS];
    v->shade(v->shade_ctx, t, x0, y0, mask, src);
    uint32_t *dst = v->color + base;
    for (int j = 0; j < 4; j++) {
        uint32_t bits = (mask >> (4 * j)) & 15u;
        if (!bits) continue;
        uint32x4_t d = vld1q_u32(dst + 4 * j), s = vld1q_u32(src + 4 * j);
        uint32x4_t out =
            put ? s
                : vreinterpretq_u32_u8(blend4(vreinterpretq_u8_u32(s), vreinterpretq_u8_u32(d)));
        vst1q_u32(dst + 4 * j, vbslq_u32(sg_lanes4n(bits), out, d));
    }
}

SG_IN_PLACE_BODY(blend_neon, in_place_neon, 0)
SG_IN_PLACE_BODY(put_neon, in_place_neon, 1)
SG_IN_PLACE_SET(blend, blend_neon)
SG_IN_PLACE_SET(put, put_neon)

sg_raster_fn sg_blend_neon(bool depth_test, bool depth_write) {
    static const sg_raster_fn fns[2][2] = SG_IN_PLACE_TABLE(blend);
    return fns[depth_test][depth_write];
}

sg_raster_fn sg_put_neon(bool depth_test, bool depth_write) {
    static const sg_raster_fn fns[2][2] = SG_IN_PLACE_TABLE(put);
    return fns[depth_test][depth_write];
}

#else

sg_raster_fn sg_blend_neon(bool depth_test, bool depth_write) {
    (void)depth_test;
    (void)depth_write;
    return NULL;
}

sg_raster_fn sg_put_neon(bool depth_test, bool depth_write) {
    (void)depth_test;
    (void)depth_write;
    return NULL;
}

#endif
