/* blend.c - the raster functions of blended draws (see blend.h): per covered tile, the depth
 * test, then the pipeline's shading of the passing pixels, then each blended into the bin's
 * colour. */
#include "raster/blend.h"

#include "raster/rast_walk.h"

enum { Z_NONE, Z_ANY };

static inline __attribute__((always_inline)) void blend_tile(const void *vctx, const sg_tri *t,
                                                             int x0, int y0, uint32_t mask,
                                                             const int zmode, const int zwrite) {
    const sg_vis_ctx *v = vctx;
    int base = sg_bin_tile_offset(x0 - v->bx0, y0 - v->by0);
    if (zmode != Z_NONE || zwrite) {
        float *dp = v->depth + base;
        float ox = (float)(x0 - t->minx), oy = (float)(y0 - t->miny);
        uint32_t pass = 0;
        for (uint32_t left = mask; left; left &= left - 1) {
            int bit = __builtin_ctz(left);
            float z = sg_tri_depth(t, ox + (float)(bit & 3), oy + (float)(bit >> 2));
            if (zmode == Z_ANY && !sg_depth_passes(v->compare, z, dp[bit])) continue;
            if (zwrite) dp[bit] = z;
            pass |= 1u << bit;
        }
        mask = pass;
    }
    if (!mask) return;
    uint32_t src[SG_TILE_PIXELS];
    v->shade(v->shade_ctx, t, x0, y0, mask, src);
    uint32_t *dst = v->color + base;
    for (; mask; mask &= mask - 1) {
        int bit = __builtin_ctz(mask);
        dst[bit] = sg_blend_rgba8(src[bit], dst[bit]);
    }
}

#define SG_BLEND_FN(name, zm, zw)                                                                  \
    static inline void name##_tile(const void *c, const sg_tri *t, int x0, int y0, uint32_t m) {   \
        blend_tile(c, t, x0, y0, m, zm, zw);                                                       \
    }                                                                                              \
    static void name(const sg_tri *t, int x0, int y0, int x1, int y1, const void *c) {             \
        sg_rast_walk(t, x0, y0, x1, y1, name##_tile, c);                                           \
    }
SG_BLEND_FN(blend_none_0, Z_NONE, 0)
SG_BLEND_FN(blend_none_1, Z_NONE, 1)
SG_BLEND_FN(blend_any_0, Z_ANY, 0)
SG_BLEND_FN(blend_any_1, Z_ANY, 1)

sg_raster_fn sg_blend_select(sgCompare compare, bool depth_write, sg_isa isa) {
    (void)isa;
    if (compare == SG_COMPARE_ALWAYS) return depth_write ? blend_none_1 : blend_none_0;
    return depth_write ? blend_any_1 : blend_any_0;
}
