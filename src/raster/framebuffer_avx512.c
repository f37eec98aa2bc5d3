/* framebuffer_avx512.c - a bin's fills a whole cache line (16 pixels) a store (see sg_fb_ops in
 * framebuffer.h). */
#include "raster/framebuffer.h"

#include "raster/blend.h"

#if defined(__AVX512F__)
#include <immintrin.h>

static void fill_color(uint32_t *dst, size_t n, uint32_t value) {
    const __m512i v = _mm512_set1_epi32((int32_t)value);
    for (size_t i = 0; i < n; i += 16) _mm512_store_si512(dst + i, v);
}

static void put_masked(uint32_t *dst, const uint32_t *src, uint32_t mask) {
    _mm512_mask_store_epi32(dst, (__mmask16)mask, _mm512_load_si512(src));
}

/* The blend on whole vectors (blend.h's code, compiled for the set), stored under the mask. */
static void blend_masked(uint32_t *dst, const uint32_t *src, uint32_t mask) {
    __m512i px;
    sg_blend16_rgba8(src, dst, (uint32_t *)(void *)&px);
    _mm512_mask_store_epi32(dst, (__mmask16)mask, px);
}

/* 16 pixels a vector: each channel's four values summed in 16-bit lanes (even and odd bytes
 * apart), as sg_fb_average4 does in 32-bit words. */
static void average4(uint32_t *p0, const uint32_t *p1, const uint32_t *p2, const uint32_t *p3,
                     size_t n) {
    const __m512i m = _mm512_set1_epi32(0x00ff00ff), half = _mm512_set1_epi32(0x00020002);
    for (size_t i = 0; i < n; i += 16) {
        const __m512i a = _mm512_load_si512(p0 + i), b = _mm512_load_si512(p1 + i);
        const __m512i c = _mm512_load_si512(p2 + i), d = _mm512_load_si512(p3 + i);
        __m512i lo =
            _mm512_add_epi32(_mm512_add_epi32(_mm512_and_si512(a, m), _mm512_and_si512(b, m)),
                             _mm512_add_epi32(_mm512_and_si512(c, m), _mm512_and_si512(d, m)));
        __m512i hi =
            _mm512_add_epi32(_mm512_add_epi32(_mm512_and_si512(_mm512_srli_epi32(a, 8), m),
                                              _mm512_and_si512(_mm512_srli_epi32(b, 8), m)),
                             _mm512_add_epi32(_mm512_and_si512(_mm512_srli_epi32(c, 8), m),
                                              _mm512_and_si512(_mm512_srli_epi32(d, 8), m)));
        lo = _mm512_and_si512(_mm512_srli_epi32(_mm512_add_epi32(lo, half), 2), m);
        hi = _mm512_and_si512(_mm512_srli_epi32(_mm512_add_epi32(hi, half), 2), m);
        _mm512_store_si512(p0 + i, _mm512_or_si512(lo, _mm512_slli_epi32(hi, 8)));
    }
}

#define SG_FB_TABLE sg_fb_ops_avx512
#include "raster/framebuffer_table.h"
#else
const sg_fb_ops sg_fb_ops_avx512 = {sg_fb_fill_color, sg_fb_fill_depth,   sg_fb_depth_range,
                                    sg_fb_put_masked, sg_fb_blend_masked, sg_fb_average4_planes};
#endif
