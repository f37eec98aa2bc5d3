/* depth_simd.h - the window depth of a tile's pixels and its compare, in each instruction set:
 * the one computation that visibility (depth*.c) and blending (blend*.c) share, so that both
 * decide every pixel exactly as the scalar sg_tri_depth and sg_depth_passes do.
 *
 * z = (z0 + z_dx dx) + z_dy dy, each product and sum rounded as in the scalar code, then clamped
 * to [0, 1]: MAXPS/MINPS return their second operand when one is NaN, so max(0, z) and min(1, .)
 * keep a NaN z, as the scalar clamp does. Each helper is compiled only where its set is enabled.
 */
#ifndef SG_DEPTH_SIMD_H
#define SG_DEPTH_SIMD_H

#include "pipeline/setup.h"
#include "sgapi/sgapi.h"

#if defined(__SSE2__)
#include <emmintrin.h>

/* The parts of z that are the same on every row of a tile: z0 + z_dx dx per lane, z_dy, and the
 * tile's first row's dy. */
typedef struct sg_zrows4 {
    __m128 zx, zdy;
    float oy;
} sg_zrows4;

static inline sg_zrows4 sg_zrows4_at(const sg_tri *t, int x0, int y0) {
    __m128 dx = _mm_add_ps(_mm_set1_ps((float)(x0 - t->minx)), _mm_setr_ps(0.0f, 1.0f, 2.0f, 3.0f));
    sg_zrows4 r = {_mm_add_ps(_mm_set1_ps(t->z), _mm_mul_ps(_mm_set1_ps(t->z_dx), dx)),
                   _mm_set1_ps(t->z_dy), (float)(y0 - t->miny)};
    return r;
}

/* The clamped z of row j (0..3) of the tile. */
static inline __m128 sg_zrow4(const sg_zrows4 *r, int j) {
    __m128 z = _mm_add_ps(r->zx, _mm_mul_ps(r->zdy, _mm_set1_ps(r->oy + (float)j)));
    return _mm_min_ps(_mm_set1_ps(1.0f), _mm_max_ps(_mm_setzero_ps(), z));
}

/* All ones where z passes the compare against the stored d (a NaN z passes only NOT_EQUAL and
 * ALWAYS, as in the scalar code). */
static inline __m128 sg_compare4(sgCompare op, __m128 z, __m128 d) {
    switch (op) {
    case SG_COMPARE_NEVER:
        return _mm_setzero_ps();
    case SG_COMPARE_LESS:
        return _mm_cmplt_ps(z, d);
    case SG_COMPARE_EQUAL:
        return _mm_cmpeq_ps(z, d);
    case SG_COMPARE_LESS_EQUAL:
        return _mm_cmple_ps(z, d);
    case SG_COMPARE_GREATER:
        return _mm_cmplt_ps(d, z);
    case SG_COMPARE_NOT_EQUAL:
        return _mm_cmpneq_ps(z, d);
    case SG_COMPARE_GREATER_EQUAL:
        return _mm_cmple_ps(d, z);
    default:
        return _mm_castsi128_ps(_mm_set1_epi32(-1));
    }
}
#endif

#if defined(__AVX2__)
#include <immintrin.h>

/* As sg_zrows4, two rows a vector: row 2h in the low half, 2h + 1 in the high half. */
typedef struct sg_zrows8 {
    __m256 zx, zdy, oy;
} sg_zrows8;

static inline sg_zrows8 sg_zrows8_at(const sg_tri *t, int x0, int y0) {
    __m256 dx = _mm256_add_ps(_mm256_set1_ps((float)(x0 - t->minx)),
                              _mm256_setr_ps(0.0f, 1.0f, 2.0f, 3.0f, 0.0f, 1.0f, 2.0f, 3.0f));
    sg_zrows8 r = {_mm256_add_ps(_mm256_set1_ps(t->z), _mm256_mul_ps(_mm256_set1_ps(t->z_dx), dx)),
                   _mm256_set1_ps(t->z_dy), _mm256_set1_ps((float)(y0 - t->miny))};
    return r;
}

/* The clamped z of rows 2h and 2h + 1 (h = 0, 1). */
static inline __m256 sg_zrows8_half(const sg_zrows8 *r, int h) {
    float r0 = (float)(2 * h), r1 = (float)(2 * h + 1); /* the two rows, exact */
    __m256 dy = _mm256_add_ps(r->oy, _mm256_setr_ps(r0, r0, r0, r0, r1, r1, r1, r1));
    __m256 z = _mm256_add_ps(r->zx, _mm256_mul_ps(r->zdy, dy));
    return _mm256_min_ps(_mm256_set1_ps(1.0f), _mm256_max_ps(_mm256_setzero_ps(), z));
}

/* The clamped z of the pixels at (dx, dy), any lanes: the same value as sg_zrows8_half gives. */
static inline __m256 sg_z8(const sg_tri *t, __m256 dx, __m256 dy) {
    __m256 z = _mm256_add_ps(
        _mm256_add_ps(_mm256_set1_ps(t->z), _mm256_mul_ps(_mm256_set1_ps(t->z_dx), dx)),
        _mm256_mul_ps(_mm256_set1_ps(t->z_dy), dy));
    return _mm256_min_ps(_mm256_set1_ps(1.0f), _mm256_max_ps(_mm256_setzero_ps(), z));
}

static inline __m256 sg_compare8(sgCompare op, __m256 z, __m256 d) {
    switch (op) {
    case SG_COMPARE_NEVER:
        return _mm256_setzero_ps();
    case SG_COMPARE_LESS:
        return _mm256_cmp_ps(z, d, _CMP_LT_OQ);
    case SG_COMPARE_EQUAL:
        return _mm256_cmp_ps(z, d, _CMP_EQ_OQ);
    case SG_COMPARE_LESS_EQUAL:
        return _mm256_cmp_ps(z, d, _CMP_LE_OQ);
    case SG_COMPARE_GREATER:
        return _mm256_cmp_ps(z, d, _CMP_GT_OQ);
    case SG_COMPARE_NOT_EQUAL:
        return _mm256_cmp_ps(z, d, _CMP_NEQ_UQ);
    case SG_COMPARE_GREATER_EQUAL:
        return _mm256_cmp_ps(z, d, _CMP_GE_OQ);
    default:
        return _mm256_castsi256_ps(_mm256_set1_epi32(-1));
    }
}
#endif

#if defined(__AVX512F__)
#include <immintrin.h>

/* dx and dy of every pixel of the tile at (x0, y0), lane y * 4 + x, from the triangle's bounds. */
static inline void sg_tile_dxdy16(const sg_tri *t, int x0, int y0, __m512 *dx, __m512 *dy) {
    *dx = _mm512_add_ps(_mm512_set1_ps((float)(x0 - t->minx)),
                        _mm512_set4_ps(3.0f, 2.0f, 1.0f, 0.0f));
    *dy = _mm512_add_ps(_mm512_set1_ps((float)(y0 - t->miny)),
                        _mm512_setr_ps(0.0f, 0.0f, 0.0f, 0.0f, 1.0f, 1.0f, 1.0f, 1.0f, 2.0f, 2.0f,
                                       2.0f, 2.0f, 3.0f, 3.0f, 3.0f, 3.0f));
}

/* The clamped z of the pixels at (dx, dy). */
static inline __m512 sg_z16(const sg_tri *t, __m512 dx, __m512 dy) {
    __m512 z = _mm512_add_ps(
        _mm512_add_ps(_mm512_set1_ps(t->z), _mm512_mul_ps(_mm512_set1_ps(t->z_dx), dx)),
        _mm512_mul_ps(_mm512_set1_ps(t->z_dy), dy));
    return _mm512_min_ps(_mm512_set1_ps(1.0f), _mm512_max_ps(_mm512_setzero_ps(), z));
}

/* The lanes of m where z passes the compare against the stored d. */
static inline __mmask16 sg_compare16(sgCompare op, __mmask16 m, __m512 z, __m512 d) {
    switch (op) {
    case SG_COMPARE_NEVER:
        return 0;
    case SG_COMPARE_LESS:
        return _mm512_mask_cmp_ps_mask(m, z, d, _CMP_LT_OQ);
    case SG_COMPARE_EQUAL:
        return _mm512_mask_cmp_ps_mask(m, z, d, _CMP_EQ_OQ);
    case SG_COMPARE_LESS_EQUAL:
        return _mm512_mask_cmp_ps_mask(m, z, d, _CMP_LE_OQ);
    case SG_COMPARE_GREATER:
        return _mm512_mask_cmp_ps_mask(m, z, d, _CMP_GT_OQ);
    case SG_COMPARE_NOT_EQUAL:
        return _mm512_mask_cmp_ps_mask(m, z, d, _CMP_NEQ_UQ);
    case SG_COMPARE_GREATER_EQUAL:
        return _mm512_mask_cmp_ps_mask(m, z, d, _CMP_GE_OQ);
    default:
        return m;
    }
}
#endif

#endif
