/* shade_shader_walk.h - the raster functions of shader draws shaded in place (shade_shader.h):
 * blended, put, or put off (deferred), each walk with its tile body inlined. Included once per
 * instruction set, by shade_shader.c (the portable walks) and blend_avx512.c (AVX-512's: its tile
 * tests and depth a whole tile a vector), after defining
 *   SG_SHADER_TILE_DEPTH(v, t, x0, y0, mask, dp, op, z): shade_shader_tile.h's tile_depth, and
 *   SG_SHADER_PUT_TILE(v, keep, z, dp, src, dst): its put_tile,
 * with the same bits; gives sg_shader_walks[kind][depth test][depth write]. No include guard:
 * each inclusion makes a copy. */
#include "raster/blend_walk.h"
#include "raster/shade_shader.h"

/* A tile of a shader draw shaded in place: the depth test without writing, the fragment stage,
 * then depth (when written) and colour where no lane was discarded. */
static inline __attribute__((always_inline)) void in_place(const void *vctx, const sg_tri *t,
                                                           int x0, int y0, uint32_t mask,
                                                           const int zmode, const int zwrite,
                                                           const int put) {
    const sg_vis_ctx *v = vctx;
    const int base = sg_bin_tile_offset(x0 - v->bx0, y0 - v->by0);
    float *dp = v->depth ? v->depth + base : NULL;
    _Alignas(64) float z[SG_TILE_PIXELS];
    if (zmode != Z_NONE || zwrite)
        mask = SG_SHADER_TILE_DEPTH(v, t, x0, y0, mask, zmode != Z_NONE ? dp : NULL, v->compare, z);
    if (!mask) return;
    _Alignas(64) uint32_t src[SG_TILE_PIXELS];
    const uint32_t keep = sg_shader_fragments(v->shade_ctx, t, x0, y0, mask, src);
    uint32_t *dst = v->color + base;
    if (put) {
        if (keep) SG_SHADER_PUT_TILE(v, keep, z, zwrite ? dp : NULL, src, dst);
        return;
    }
    for (uint32_t m = keep; m; m &= m - 1) {
        const int bit = __builtin_ctz(m);
        if (zwrite) dp[bit] = z[bit];
        dst[bit] = sg_blend_rgba8(src[bit], dst[bit]);
    }
}

static inline __attribute__((always_inline)) void deferred(const void *vctx, const sg_tri *t,
                                                           int x0, int y0, uint32_t mask,
                                                           const int zmode, const int zwrite,
                                                           const int put) {
    (void)put;
    const sg_vis_ctx *v = vctx;
    const int base = sg_bin_tile_offset(x0 - v->bx0, y0 - v->by0), tile = base / SG_TILE_PIXELS;
    uint32_t *ids = v->ids + base;
    if (v->reached[tile] && (mask & ~sg_tile_same_id(ids, 0))) sg_shader_flush_tile(v, tile);
    if (zmode != Z_NONE) {
        _Alignas(64) float z[SG_TILE_PIXELS];
        mask = SG_SHADER_TILE_DEPTH(v, t, x0, y0, mask, v->depth ? v->depth + base : NULL,
                                    v->compare, z);
    }
    if (!mask) return;
    sg_tile_put_id(ids, mask, v->id);
    v->reached[tile] = 1;
    sg_blend_pending *w = v->pending;
    w->n = 1;
    w->draw = t->draw;
    w->depth_write = zwrite;
    w->flush = sg_shader_flush_waiting;
}

SG_IN_PLACE_BODY(shader_blend_body, in_place, 0)
SG_IN_PLACE_BODY(shader_put_body, in_place, 1)
SG_IN_PLACE_BODY(shader_defer_body, deferred, 1)
SG_IN_PLACE_SET(shader_blend, shader_blend_body)
SG_IN_PLACE_SET(shader_put, shader_put_body)
SG_IN_PLACE_SET(shader_defer, shader_defer_body)

static const sg_raster_fn sg_shader_walks[3][2][2] = {SG_IN_PLACE_TABLE(shader_put),
                                                      SG_IN_PLACE_TABLE(shader_blend),
                                                      SG_IN_PLACE_TABLE(shader_defer)};
