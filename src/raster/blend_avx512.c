/* blend_avx512.c - the raster functions of blended draws in AVX-512 (see blend.h): a whole tile
 * a vector; the same depth (z, clamp, compare) as the scalar and SSE2 code and the same integer
 * blend, so the same bytes. */
#include "raster/blend.h"

#include "raster/rast_walk.h"

#if defined(__AVX512F__) && defined(__AVX512BW__)
#include <immintrin.h>

/* x y / 255 as sg_mul_unorm8 rounds it, in 16-bit lanes. */
static inline __m512i mul_unorm8(__m512i x, __m512i y) {
    __m512i t = _mm512_mullo_epi16(x, y);
    t = _mm512_add_epi16(_mm512_add_epi16(t, _mm512_srli_epi16(t, 8)), _mm512_set1_epi16(128));
    return _mm512_srli_epi16(t, 8);
}

/* Pixels in 16-bit lanes (r g b a ...): src over dst by src's alpha. */
static inline __m512i blend_lanes(__m512i s, __m512i d) {
    __m512i a = _mm512_shufflehi_epi16(_mm512_shufflelo_epi16(s, 0xff), 0xff);
    __m512i ia = _mm512_sub_epi16(_mm512_set1_epi16(255), a);
    return _mm512_add_epi16(mul_unorm8(s, a), mul_unorm8(d, ia));
}

static inline __mmask16 compare(sgCompare op, __mmask16 m, __m512 z, __m512 d) {
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

enum { Z_NONE, Z_ANY };

static inline __attribute__((always_inline)) void blend_avx512(const void *vctx, const sg_tri *t,
                                                               int x0, int y0, uint32_t mask,
                                                               const int zmode, const int zwrite) {
    const sg_vis_ctx *v = vctx;
    int base = sg_bin_tile_offset(x0 - v->bx0, y0 - v->by0);
    if (zmode != Z_NONE || zwrite) { /* as vis_avx512 (depth_avx512.c) computes and clamps z */
        float *dp = v->depth + base;
        __m512 dx = _mm512_add_ps(_mm512_set1_ps((float)(x0 - t->minx)),
                                  _mm512_set4_ps(3.0f, 2.0f, 1.0f, 0.0f));
        __m512 dy = _mm512_add_ps(_mm512_set1_ps((float)(y0 - t->miny)),
                                  _mm512_setr_ps(0.0f, 0.0f, 0.0f, 0.0f, 1.0f, 1.0f, 1.0f, 1.0f,
                                                 2.0f, 2.0f, 2.0f, 2.0f, 3.0f, 3.0f, 3.0f, 3.0f));
        __m512 z = _mm512_add_ps(
            _mm512_add_ps(_mm512_set1_ps(t->z), _mm512_mul_ps(_mm512_set1_ps(t->z_dx), dx)),
            _mm512_mul_ps(_mm512_set1_ps(t->z_dy), dy));
        z = _mm512_min_ps(_mm512_set1_ps(1.0f), _mm512_max_ps(_mm512_setzero_ps(), z));
        mask = compare(v->compare, (__mmask16)mask, z, _mm512_loadu_ps(dp));
        if (zwrite) _mm512_mask_storeu_ps(dp, (__mmask16)mask, z);
    }
    if (!mask) return;
    _Alignas(64) uint32_t src[SG_TILE_PIXELS];
    v->shade(v->shade_ctx, t, x0, y0, mask, src);
    uint32_t *dst = v->color + base;
    const __m512i zero = _mm512_setzero_si512();
    __m512i s = _mm512_load_si512(src), d = _mm512_load_si512(dst);
    __m512i lo = blend_lanes(_mm512_unpacklo_epi8(s, zero), _mm512_unpacklo_epi8(d, zero));
    __m512i hi = blend_lanes(_mm512_unpackhi_epi8(s, zero), _mm512_unpackhi_epi8(d, zero));
    _mm512_mask_storeu_epi32(dst, (__mmask16)mask, _mm512_packus_epi16(lo, hi));
}

#define SG_BLEND_FN(name, zm, zw)                                                                  \
    static inline void name##_tile(const void *c, const sg_tri *t, int x0, int y0, uint32_t m) {   \
        blend_avx512(c, t, x0, y0, m, zm, zw);                                                     \
    }                                                                                              \
    static void name(const sg_tri *t, int x0, int y0, int x1, int y1, const void *c) {             \
        sg_rast_walk(t, x0, y0, x1, y1, name##_tile, c);                                           \
    }
SG_BLEND_FN(blend_none_0, Z_NONE, 0)
SG_BLEND_FN(blend_none_1, Z_NONE, 1)
SG_BLEND_FN(blend_any_0, Z_ANY, 0)
SG_BLEND_FN(blend_any_1, Z_ANY, 1)

sg_raster_fn sg_blend_avx512(bool depth_test, bool depth_write) {
    static const sg_raster_fn fns[2][2] = {{blend_none_0, blend_none_1},
                                           {blend_any_0, blend_any_1}};
    return fns[depth_test][depth_write];
}

#else

sg_raster_fn sg_blend_avx512(bool depth_test, bool depth_write) {
    (void)depth_test;
    (void)depth_write;
    return NULL;
}

#endif
