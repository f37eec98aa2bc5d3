/* blend_avx2.c - the raster functions of blended draws in AVX2 (see blend.h): two rows of a tile
 * a vector; the same depth (z, clamp, compare) as the scalar and SSE2 code and the same integer
 * blend, so the same bytes. */
#include "raster/blend.h"

#include "raster/depth_simd.h"
#include "raster/blend_walk.h"

#if defined(__AVX2__)
#include <immintrin.h>

/* x y / 255 as sg_mul_unorm8 rounds it, in 16-bit lanes. */
static inline __m256i mul_unorm8(__m256i x, __m256i y) {
    __m256i t = _mm256_mullo_epi16(x, y);
    t = _mm256_add_epi16(_mm256_add_epi16(t, _mm256_srli_epi16(t, 8)), _mm256_set1_epi16(128));
    return _mm256_srli_epi16(t, 8);
}

/* Pixels in 16-bit lanes (r g b a ...): src over dst by src's alpha. */
static inline __m256i blend_lanes(__m256i s, __m256i d) {
    __m256i a = _mm256_shufflehi_epi16(_mm256_shufflelo_epi16(s, 0xff), 0xff);
    __m256i ia = _mm256_sub_epi16(_mm256_set1_epi16(255), a);
    return _mm256_add_epi16(mul_unorm8(s, a), mul_unorm8(d, ia));
}

static inline __attribute__((always_inline)) void blend_avx2(const void *vctx, const sg_tri *t,
                                                             int x0, int y0, uint32_t mask,
                                                             const int zmode, const int zwrite) {
    const sg_vis_ctx *v = vctx;
    int base = sg_bin_tile_offset(x0 - v->bx0, y0 - v->by0);
    const __m256i lanes = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
    if (zmode != Z_NONE || zwrite) {
        float *dp = v->depth + base;
        const sg_zrows8 zr = sg_zrows8_at(t, x0, y0);
        uint32_t pass = 0;
        for (int h = 0; h < 2; h++) {
            uint32_t bits = (mask >> (8 * h)) & 255u;
            if (!bits) continue;
            __m256 z = sg_zrows8_half(&zr, h);
            __m256 d = _mm256_load_ps(dp + 8 * h);
            __m256 p =
                _mm256_and_ps(sg_compare8(v->compare, z, d),
                              _mm256_castsi256_ps(_mm256_cmpeq_epi32(
                                  _mm256_and_si256(_mm256_set1_epi32((int)bits), lanes), lanes)));
            if (zwrite) _mm256_store_ps(dp + 8 * h, _mm256_blendv_ps(d, z, p));
            pass |= (uint32_t)_mm256_movemask_ps(p) << (8 * h);
        }
        mask = pass;
    }
    if (!mask) return;
    _Alignas(32) uint32_t src[SG_TILE_PIXELS];
    v->shade(v->shade_ctx, t, x0, y0, mask, src);
    uint32_t *dst = v->color + base;
    const __m256i zero = _mm256_setzero_si256();
    for (int h = 0; h < 2; h++) {
        uint32_t bits = (mask >> (8 * h)) & 255u;
        if (!bits) continue;
        __m256i *pd = (__m256i *)(void *)(dst + 8 * h);
        __m256i s = _mm256_load_si256((const __m256i *)(const void *)(src + 8 * h));
        __m256i d = _mm256_load_si256(pd);
        __m256i lo = blend_lanes(_mm256_unpacklo_epi8(s, zero), _mm256_unpacklo_epi8(d, zero));
        __m256i hi = blend_lanes(_mm256_unpackhi_epi8(s, zero), _mm256_unpackhi_epi8(d, zero));
        __m256i sel =
            _mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32((int)bits), lanes), lanes);
        _mm256_store_si256(pd, _mm256_blendv_epi8(d, _mm256_packus_epi16(lo, hi), sel));
    }
}

SG_BLEND_FN(blend_none_0, blend_avx2, Z_NONE, 0)
SG_BLEND_FN(blend_none_1, blend_avx2, Z_NONE, 1)
SG_BLEND_FN(blend_any_0, blend_avx2, Z_ANY, 0)
SG_BLEND_FN(blend_any_1, blend_avx2, Z_ANY, 1)

sg_raster_fn sg_blend_avx2(bool depth_test, bool depth_write) {
    static const sg_raster_fn fns[2][2] = {{blend_none_0, blend_none_1},
                                           {blend_any_0, blend_any_1}};
    return fns[depth_test][depth_write];
}

#else

sg_raster_fn sg_blend_avx2(bool depth_test, bool depth_write) {
    (void)depth_test;
    (void)depth_write;
    return NULL;
}

#endif
