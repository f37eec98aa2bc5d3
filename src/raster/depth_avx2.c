/* depth_avx2.c - the LESS visibility tile functions in AVX2 (see depth.h): two rows of a tile a
 * vector, the same z = (z0 + z_dx * dx) + z_dy * dy and clamp as the scalar and SSE2 ones. */
#include "raster/depth.h"

#include "raster/depth_simd.h"
#include "raster/rast_walk.h"

#if defined(__AVX2__)
#include <immintrin.h>

static inline __attribute__((always_inline)) void
vis_avx2(const void *vctx, const sg_tri *t, int x0, int y0, uint32_t mask, const int zwrite) {
    const sg_vis_ctx *v = vctx;
    int base = sg_bin_tile_offset(x0 - v->bx0, y0 - v->by0);
    uint32_t *ids = sg_vis_tile_ids(v, base);
    float *dp = v->depth + base;
    const __m256i lanes = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
    const sg_zrows8 zr = sg_zrows8_at(t, x0, y0);
    __m256i id = _mm256_set1_epi32((int)v->id);
    for (int h = 0; h < 2; h++) {
        uint32_t bits = (mask >> (8 * h)) & 255u;
        if (!bits) continue;
        __m256 z = sg_zrows8_half(&zr, h);
        __m256 d = _mm256_load_ps(dp + 8 * h);
        __m256 pass = sg_compare8(SG_COMPARE_LESS, z, d);
        if (bits != 255u)
            pass = _mm256_and_ps(
                pass, _mm256_castsi256_ps(_mm256_cmpeq_epi32(
                          _mm256_and_si256(_mm256_set1_epi32((int)bits), lanes), lanes)));
        if (!_mm256_movemask_ps(pass)) continue;
        if (zwrite) _mm256_store_ps(dp + 8 * h, _mm256_blendv_ps(d, z, pass));
        __m256i *ip = (__m256i *)(void *)(ids + 8 * h);
        _mm256_store_si256(
            ip, _mm256_blendv_epi8(_mm256_load_si256(ip), id, _mm256_castps_si256(pass)));
    }
}

static inline void vis_less_0_tile(const void *c, const sg_tri *t, int x0, int y0, uint32_t m) {
    vis_avx2(c, t, x0, y0, m, 0);
}
static inline void vis_less_1_tile(const void *c, const sg_tri *t, int x0, int y0, uint32_t m) {
    vis_avx2(c, t, x0, y0, m, 1);
}
/* The walk with the tile function inlined (rast_walk.h). */
static void vis_less_0_avx2(const sg_tri *t, int x0, int y0, int x1, int y1, const void *c) {
    sg_rast_walk(t, x0, y0, x1, y1, vis_less_0_tile, c);
}
static void vis_less_1_avx2(const sg_tri *t, int x0, int y0, int x1, int y1, const void *c) {
    sg_rast_walk(t, x0, y0, x1, y1, vis_less_1_tile, c);
}

sg_raster_fn sg_depth_less_avx2(bool depth_write) {
    return depth_write ? vis_less_1_avx2 : vis_less_0_avx2;
}

static void walk_any(const sg_tri *t, int x0, int y0, int x1, int y1, sg_tile_fn fn,
                     const void *ctx) {
    sg_rast_walk(t, x0, y0, x1, y1, fn, ctx);
}

sg_walk_fn sg_walk_avx2(void) {
    return walk_any;
}

#else

sg_raster_fn sg_depth_less_avx2(bool depth_write) {
    (void)depth_write;
    return NULL;
}

sg_walk_fn sg_walk_avx2(void) {
    return NULL;
}

#endif
