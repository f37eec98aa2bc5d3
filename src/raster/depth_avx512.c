/* depth_avx512.c - the LESS visibility tile functions in AVX-512 (see depth.h): a whole tile a
 * vector, z as depth_simd.h computes it; the coverage mask is the compare and store mask. */
#include "raster/depth.h"

#include "raster/depth_simd.h"
#include "raster/rast_walk.h"

#if defined(__AVX512F__)
#include <immintrin.h>

static inline __attribute__((always_inline)) void
vis_avx512(const void *vctx, const sg_tri *t, int x0, int y0, uint32_t mask, const int zwrite) {
    const sg_vis_ctx *v = vctx;
    int base = sg_bin_tile_offset(x0 - v->bx0, y0 - v->by0);
    uint32_t *ids = sg_vis_tile_ids(v, base);
    float *dp = v->depth + base;
    __m512 dx, dy;
    sg_tile_dxdy16(t, x0, y0, &dx, &dy);
    __m512 z = sg_z16(t, dx, dy);
    __mmask16 pass = sg_compare16(SG_COMPARE_LESS, (__mmask16)mask, z, _mm512_loadu_ps(dp));
    if (!pass) return;
    if (zwrite) _mm512_mask_storeu_ps(dp, pass, z);
    _mm512_mask_storeu_epi32(ids, pass, _mm512_set1_epi32((int)v->id));
}

static inline void vis_less_0_tile(const void *c, const sg_tri *t, int x0, int y0, uint32_t m) {
    vis_avx512(c, t, x0, y0, m, 0);
}
static inline void vis_less_1_tile(const void *c, const sg_tri *t, int x0, int y0, uint32_t m) {
    vis_avx512(c, t, x0, y0, m, 1);
}
/* The walk with the tile function inlined (rast_walk.h). */
static void vis_less_0_avx512(const sg_tri *t, int x0, int y0, int x1, int y1, const void *c) {
    sg_rast_walk(t, x0, y0, x1, y1, vis_less_0_tile, c);
}
static void vis_less_1_avx512(const sg_tri *t, int x0, int y0, int x1, int y1, const void *c) {
    sg_rast_walk(t, x0, y0, x1, y1, vis_less_1_tile, c);
}

sg_raster_fn sg_depth_less_avx512(bool depth_write) {
    return depth_write ? vis_less_1_avx512 : vis_less_0_avx512;
}

static void walk_any(const sg_tri *t, int x0, int y0, int x1, int y1, sg_tile_fn fn,
                     const void *ctx) {
    sg_rast_walk(t, x0, y0, x1, y1, fn, ctx);
}

sg_walk_fn sg_walk_avx512(void) {
    return walk_any;
}

#else

sg_raster_fn sg_depth_less_avx512(bool depth_write) {
    (void)depth_write;
    return NULL;
}

sg_walk_fn sg_walk_avx512(void) {
    return NULL;
}

#endif
