/* depth_avx512.c - the LESS visibility tile functions in AVX-512 (see depth.h): a whole tile a
 * vector, the same z = (z0 + z_dx * dx) + z_dy * dy and clamp as the scalar, SSE2 and AVX2 ones;
 * the coverage mask is the compare and store mask. */
#include "raster/depth.h"

#include "raster/rast_walk.h"

#if defined(__AVX512F__)
#include <immintrin.h>

static inline __attribute__((always_inline)) void
vis_avx512(const void *vctx, const sg_tri *t, int x0, int y0, uint32_t mask, const int zwrite) {
    const sg_vis_ctx *v = vctx;
    int base = sg_bin_tile_offset(x0 - v->bx0, y0 - v->by0);
    uint32_t *ids = sg_vis_tile_ids(v, base);
    float *dp = v->depth + base;
    __m512 dx = _mm512_add_ps(_mm512_set1_ps((float)(x0 - t->minx)),
                              _mm512_set4_ps(3.0f, 2.0f, 1.0f, 0.0f));
    __m512 dy = _mm512_add_ps(_mm512_set1_ps((float)(y0 - t->miny)),
                              _mm512_setr_ps(0.0f, 0.0f, 0.0f, 0.0f, 1.0f, 1.0f, 1.0f, 1.0f, 2.0f,
                                             2.0f, 2.0f, 2.0f, 3.0f, 3.0f, 3.0f, 3.0f));
    __m512 z = _mm512_add_ps(
        _mm512_add_ps(_mm512_set1_ps(t->z), _mm512_mul_ps(_mm512_set1_ps(t->z_dx), dx)),
        _mm512_mul_ps(_mm512_set1_ps(t->z_dy), dy));
    /* MAXPS/MINPS return their second operand when one is NaN: a NaN z is kept, as in depth.c */
    z = _mm512_min_ps(_mm512_set1_ps(1.0f), _mm512_max_ps(_mm512_setzero_ps(), z));
    __mmask16 pass = _mm512_mask_cmp_ps_mask((__mmask16)mask, z, _mm512_loadu_ps(dp), _CMP_LT_OQ);
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
