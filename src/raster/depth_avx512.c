/* depth_avx512.c - the visibility tile functions in AVX-512 (see depth.h), for every compare, with
 * and without depth write: a whole tile a vector, z as depth_simd.h computes it; the coverage mask
 * is the compare and store mask. */
#include "raster/depth.h"

#include "raster/depth_simd.h"
#include "raster/depth_walk.h"

#if defined(__AVX512F__)
#include <immintrin.h>

static inline __attribute__((always_inline)) void vis_avx512(const void *vctx, const sg_tri *t,
                                                             int x0, int y0, uint32_t mask,
                                                             const int zmode, const int zwrite) {
    const sg_vis_ctx *v = vctx;
    int base = sg_bin_tile_offset(x0 - v->bx0, y0 - v->by0);
    uint32_t *ids = sg_vis_tile_ids(v, base);
    __mmask16 pass = (__mmask16)mask;
    if (zmode != Z_NONE || zwrite) {
        float *dp = v->depth + base;
        __m512 dx, dy;
        sg_tile_dxdy16(t, x0, y0, &dx, &dy);
        __m512 z = sg_z16(t, dx, dy);
        if (zmode != Z_NONE)
            pass = sg_compare16(zmode == Z_LESS ? SG_COMPARE_LESS : v->compare, pass, z,
                                _mm512_loadu_ps(dp));
        /* No test of an empty mask: the masked stores then write nothing, and a small
         * triangle's tiles pass or fail in no pattern a branch predictor follows. */
        if (zwrite) _mm512_mask_storeu_ps(dp, pass, z);
    }
    _mm512_mask_storeu_epi32(ids, pass, _mm512_set1_epi32((int)v->id));
}

SG_VIS_SET(vis_avx512, vis_avx512)

SG_VIS_SAMPLES_SET(vis_samples_avx512, vis_avx512)

sg_vis_fns sg_depth_avx512(sgCompare compare, bool depth_write) {
    static const sg_raster_fn one[3][2] = SG_VIS_TABLE(vis_avx512);
    static const sg_raster_samples_fn samples[3][2] = SG_VIS_TABLE(vis_samples_avx512);
    return sg_vis_pick(one, samples, compare, depth_write);
}

static void walk_any(const sg_tri *t, int x0, int y0, int x1, int y1, sg_tile_fn fn,
                     const void *ctx) {
    sg_rast_walk(t, x0, y0, x1, y1, fn, ctx);
}

sg_walk_fn sg_walk_avx512(void) {
    return walk_any;
}

#else

sg_vis_fns sg_depth_avx512(sgCompare compare, bool depth_write) {
    (void)compare;
    (void)depth_write;
    return (sg_vis_fns){NULL, NULL};
}

sg_walk_fn sg_walk_avx512(void) {
    return NULL;
}

#endif
