/* blend.h - alpha blending (SG_BLEND_ALPHA): out = src * a + dst * (1 - a) in 8-bit arithmetic.
 *
 * Opaque draws are rasterised visibility first (depth.h) and shaded once per pixel. A blended
 * triangle cannot wait for that: each pixel must see the triangles in submission order, so the
 * bin's visible ids are shaded first (rast_bin.c), and the blended triangle is then depth tested,
 * shaded and blended into the bin's colour tile by tile, in order.
 */
#ifndef SG_BLEND_H
#define SG_BLEND_H

#include <stdbool.h>
#include <stdint.h>

#include "raster/depth.h"
#include "sgapi/sgapi.h"

/** One unorm8 channel of SRC_ALPHA / ONE_MINUS_SRC_ALPHA blending (docs/accuracy.md). */
static inline uint32_t sg_blend_channel(uint32_t s, uint32_t d, uint32_t a) {
    uint32_t t = s * a + d * (255u - a) + 128u;
    return (t + (t >> 8)) >> 8;
}

/** A packed RGBA8 fragment blended over a packed RGBA8 pixel by the fragment's alpha. */
static inline uint32_t sg_blend_rgba8(uint32_t src, uint32_t dst) {
    uint32_t a = src >> 24, out = 0;
    for (int k = 0; k < 32; k += 8)
        out |= sg_blend_channel((src >> k) & 255u, (dst >> k) & 255u, a) << k;
    return out;
}

/** The raster function of a blended draw for a resolved depth state (ctx: an sg_vis_ctx with
 *  color, shade and shade_ctx set). */
sg_raster_fn sg_blend_select(sgCompare compare, bool depth_write, sg_isa isa);

#endif
