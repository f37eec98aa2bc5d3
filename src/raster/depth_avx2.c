/* depth_avx2.c - the visibility tile functions in AVX2 (see depth.h), for every compare, with and
 * without depth write: two rows of a tile a vector, the same z = (z0 + z_dx * dx) + z_dy * dy and
 * clamp as the scalar and SSE2 ones. */
#include "raster/depth.h"

#include "raster/depth_simd.h"
#include "raster/depth_walk.h"

#if defined(__AVX2__)
#include <immintrin.h>

static inline __attribute__((always_inline)) void vis_avx2(const void *vctx, const sg_tri *t,
                                                           int x0, int y0, uint32_t mask,
                                                           const int zmode, const int zwrite) {
    const sg_vis_ctx *v = vctx;
    int base = sg_bin_tile_offset(x0 - v->bx0, y0 - v->by0);
    uint32_t *ids = sg_vis_tile_ids(v, base);
    const __m256i lanes = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
    const bool depth = zmode != Z_NONE || zwrite;
    float *dp = depth ? v->depth + base : NULL; /* NULL: the pass may have no depth target */
    const sg_zrows8 zr = depth ? sg_zrows8_at(t, x0, y0) : (sg_zrows8){0};
    __m256i id = _mm256_set1_epi32((int)v->id);
    /* Both halves tested and written whatever their masks, no branch: a lane that does not pass
     * writes back what it read, and a small triangle's halves pass or fail in no pattern a branch
     * predictor follows (docs/performance.md, "Four shading chains"). */
    for (int h = 0; h < 2; h++) {
        uint32_t bits = (mask >> (8 * h)) & 255u;
        __m256 pass = _mm256_castsi256_ps(
            _mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32((int)bits), lanes), lanes));
        if (depth) {
            __m256 z = sg_zrows8_half(&zr, h);
            __m256 d = _mm256_load_ps(dp + 8 * h);
            if (zmode != Z_NONE)
                pass = _mm256_and_ps(
                    pass, sg_compare8(zmode == Z_LESS ? SG_COMPARE_LESS : v->compare, z, d));
            if (zwrite) _mm256_store_ps(dp + 8 * h, _mm256_blendv_ps(d, z, pass));
        }
        __m256i *ip = (__m256i *)(void *)(ids + 8 * h);
        _mm256_store_si256(
            ip, _mm256_blendv_epi8(_mm256_load_si256(ip), id, _mm256_castps_si256(pass)));
    }
}

SG_VIS_SET(vis_avx2, vis_avx2)

SG_VIS_SAMPLES_SET(vis_samples_avx2, vis_avx2)

sg_vis_fns sg_depth_avx2(sgCompare compare, bool depth_write) {
    static const sg_raster_fn one[3][2] = SG_VIS_TABLE(vis_avx2);
    static const sg_raster_samples_fn samples[3][2] = SG_VIS_TABLE(vis_samples_avx2);
    return sg_vis_pick(one, samples, compare, depth_write);
}

static void walk_any(const sg_tri *t, int x0, int y0, int x1, int y1, sg_tile_fn fn,
                     const void *ctx) {
    sg_rast_walk(t, x0, y0, x1, y1, fn, ctx);
}

sg_walk_fn sg_walk_avx2(void) {
    return walk_any;
}

#else

sg_vis_fns sg_depth_avx2(sgCompare compare, bool depth_write) {
    (void)compare;
    (void)depth_write;
    return (sg_vis_fns){NULL, NULL};
}

sg_walk_fn sg_walk_avx2(void) {
    return NULL;
}

#endif
