/* blend.h - draws shaded in place: alpha blending (SG_BLEND_ALPHA: out = src * a + dst * (1 - a)
 * in 8-bit arithmetic), and opaque lines.
 *
 * Opaque triangles are rasterised visibility first (depth.h) and shaded once per pixel. A blended
 * triangle cannot wait for that: each pixel must see the triangles in submission order, so the
 * bin's visible ids are shaded first (rast_bin.c), and the blended triangle is then depth tested,
 * shaded and blended into the bin's colour tile by tile, in order. Opaque line draws of unlit
 * shading go the same way, their fragments put in place of the pixels: a line covers a pixel or
 * two of each tile it crosses and is rarely drawn over, so shading it at once, while its tile is
 * at hand, costs less than keeping its ids for a later pass over the tiles (and gives the same
 * bytes: in both, a pixel shows the last fragment that passed the depth test). Wireframes stay
 * visibility first: a mesh's edges are shared and cross at every vertex.
 */
#ifndef SG_BLEND_H
#define SG_BLEND_H

#include <stdbool.h>
#include <stdint.h>
#include <string.h>

#include "raster/depth.h"
#include "sgapi/sgapi.h"

/** x * y / 255 for unorm8 values, rounded the way lavapipe's 8-bit blend rounds each product:
 *  (t + (t >> 8) + 128) >> 8 with t = x y (exact rounding but for 24 of the 65536 products). */
static inline uint32_t sg_mul_unorm8(uint32_t x, uint32_t y) {
    uint32_t t = x * y;
    return (t + (t >> 8) + 128u) >> 8;
}

/** One unorm8 channel of SRC_ALPHA / ONE_MINUS_SRC_ALPHA blending: each term rounded, then
 *  added (the sum never exceeds 255); docs/accuracy.md. */
static inline uint32_t sg_blend_channel(uint32_t s, uint32_t d, uint32_t a) {
    return sg_mul_unorm8(s, a) + sg_mul_unorm8(d, 255u - a);
}

/** A packed RGBA8 fragment blended over a packed RGBA8 pixel by the fragment's alpha. */
static inline uint32_t sg_blend_rgba8(uint32_t src, uint32_t dst) {
    uint32_t a = src >> 24, out = 0;
    for (int k = 0; k < 32; k += 8)
        out |= sg_blend_channel((src >> k) & 255u, (dst >> k) & 255u, a) << k;
    return out;
}

/** sg_blend_rgba8 of 16 fragments src over 16 pixels dst into out, on vectors: two channels in
 *  the 16-bit halves of each 32-bit lane (red and blue, then green and alpha). Every product and
 *  sum of sg_mul_unorm8 fits 16 bits (t <= 65025, t + t / 256 + 128 <= 65407), so each half gets
 *  the scalar function's value. */
static inline void sg_blend16_rgba8(const uint32_t src[16], const uint32_t dst[16],
                                    uint32_t out[16]) {
    typedef uint32_t vu __attribute__((vector_size(64)));
    typedef uint16_t vh __attribute__((vector_size(64)));
    vu s, d;
    memcpy(&s, src, sizeof s);
    memcpy(&d, dst, sizeof d);
    const vu lo = s >> 24;
    const vh a = (vh)(lo | lo << 16), ia = 255 - a;
#define SG_MUL8(x, y) ((((x) * (y)) + (((x) * (y)) >> 8) + 128) >> 8)
    const vh sr = (vh)(s & 0x00ff00ffu), sg = (vh)(s >> 8 & 0x00ff00ffu);
    const vh dr = (vh)(d & 0x00ff00ffu), dg = (vh)(d >> 8 & 0x00ff00ffu);
    const vu r = (vu)(SG_MUL8(sr, a) + SG_MUL8(dr, ia)) | (vu)(SG_MUL8(sg, a) + SG_MUL8(dg, ia))
                                                              << 8;
#undef SG_MUL8
    memcpy(out, &r, sizeof r);
}

/** The raster function of a blended draw for a shading variant (sg_shade_variant; -1: a lit one,
 *  shaded through the draw's function) and a resolved depth state (ctx: an sg_vis_ctx with
 *  color, shade and shade_ctx set). */
sg_raster_fn sg_blend_select(int shade_variant, sgCompare compare, bool depth_write, sg_isa isa);
/** The AVX2 and AVX-512 ones (blend_avx2.c, blend_avx512.c; NULL where not built); depth_test:
 *  the compare is not ALWAYS. Both inline the unlit shading (no call per tile); AVX2 calls the
 *  draw's shading function for a negative variant. */
sg_raster_fn sg_blend_avx2(int shade_variant, bool depth_test, bool depth_write);
sg_raster_fn sg_blend_avx512(int shade_variant, bool depth_test, bool depth_write);
/** The raster function of an unlit blended draw with mipmapped texturing (mipmap NEAREST or
 *  LINEAR): AVX-512's or AVX2's, which inline that shading, else sg_blend_select's for a lit one.
 */
sg_raster_fn sg_blend_mip_select(sgMipmap mipmap, sgFilter filter, sgWrap wrap, sgCompare compare,
                                 bool depth_write, sg_isa isa);
/** AVX-512's and AVX2's, by index linear * 4 + bilinear * 2 + repeat (NULL where not built). */
sg_raster_fn sg_blend_mip_avx512(int index, bool depth_test, bool depth_write);
sg_raster_fn sg_blend_mip_avx2(int index, bool depth_test, bool depth_write);
/** The NEON ones (blend_neon.c; NULL off AArch64). */
sg_raster_fn sg_blend_neon(bool depth_test, bool depth_write);

/** The raster function of an opaque line draw of unlit shading variant `shade_variant`
 *  (sg_shade_variant) shaded in place: its fragments replace the pixels they pass (ctx as for
 *  sg_blend_select). */
sg_raster_fn sg_put_select(int shade_variant, sgCompare compare, bool depth_write, sg_isa isa);
/** The AVX2 ones (vertex colours inlined, other variants through the draw's function), the
 *  AVX-512 ones (vertex colours only) and the NEON ones; NULL where not built. */
sg_raster_fn sg_put_avx2(int shade_variant, bool depth_test, bool depth_write);
sg_raster_fn sg_put_avx512(bool depth_test, bool depth_write);
sg_raster_fn sg_put_neon(bool depth_test, bool depth_write);

#endif
