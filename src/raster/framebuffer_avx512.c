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

static uint32_t same(const void *vecs, int k, uint32_t id) {
    return _mm512_cmpeq_epi32_mask(((const __m512i *)vecs)[k], _mm512_set1_epi32((int)id));
}

static int split_ids(const uint32_t *const planes[4], uint32_t *ids, uint64_t *samples) {
    __m512i v[4];
    uint32_t left[4];
    for (int k = 0; k < 4; k++) {
        v[k] = _mm512_load_si512(planes[k]);
        left[k] = _mm512_test_epi32_mask(v[k], v[k]);
    }
    return sg_fb_split_ids_with(planes, v, left, same, ids, samples);
}

static inline bool tile_alike(const uint32_t *const planes[4], size_t base) {
    const __m512i first = _mm512_load_si512(planes[0] + base);
    const __m512i diff = _mm512_or_si512(
        _mm512_xor_si512(first, _mm512_load_si512(planes[1] + base)),
        _mm512_or_si512(_mm512_xor_si512(first, _mm512_load_si512(planes[2] + base)),
                        _mm512_xor_si512(first, _mm512_load_si512(planes[3] + base))));
    return _mm512_test_epi32_mask(diff, diff) == 0;
}

static uint64_t alike_tiles(const uint32_t *const planes[4], uint64_t tiles) {
    return sg_fb_alike_tiles_with(planes, tiles, tile_alike);
}

static void put_samples(uint32_t *const planes[4], size_t base, const uint32_t *src,
                        uint64_t samples) {
    const __m512i v = _mm512_load_si512(src);
    for (int k = 0; k < 4; k++) /* an empty mask stores nothing */
        _mm512_mask_store_epi32(planes[k] + base, (__mmask16)(samples >> (16 * k)), v);
}

/* x y / 255 as sg_mul_unorm8 rounds it, in 16-bit lanes (x, y <= 255: no lane overflows). */
static inline __m512i mul8(__m512i x, __m512i y) {
    const __m512i t = _mm512_mullo_epi16(x, y);
    return _mm512_srli_epi16(
        _mm512_add_epi16(_mm512_add_epi16(t, _mm512_srli_epi16(t, 8)), _mm512_set1_epi16(128)), 8);
}

/* sg_blend16_rgba8's operations, the source's products with its alpha formed once for the four
 * planes: the same 16-bit halves, so the same bits. */
static void blend_samples(uint32_t *const planes[4], size_t base, const uint32_t *src,
                          uint64_t samples) {
    const __m512i m8 = _mm512_set1_epi32(0x00ff00ff);
    const __m512i s = _mm512_load_si512(src), lo = _mm512_srli_epi32(s, 24);
    const __m512i a = _mm512_or_si512(lo, _mm512_slli_epi32(lo, 16));
    const __m512i ia = _mm512_sub_epi16(_mm512_set1_epi16(255), a);
    const __m512i sr = mul8(_mm512_and_si512(s, m8), a);
    const __m512i sg = mul8(_mm512_and_si512(_mm512_srli_epi32(s, 8), m8), a);
    for (int k = 0; k < 4; k++) { /* an empty mask stores nothing */
        uint32_t *dst = planes[k] + base;
        const __m512i d = _mm512_load_si512(dst);
        const __m512i r = _mm512_add_epi16(sr, mul8(_mm512_and_si512(d, m8), ia));
        const __m512i g =
            _mm512_add_epi16(sg, mul8(_mm512_and_si512(_mm512_srli_epi32(d, 8), m8), ia));
        _mm512_mask_store_epi32(dst, (__mmask16)(samples >> (16 * k)),
                                _mm512_or_si512(r, _mm512_slli_epi32(g, 8)));
    }
}
#define SG_FB_BLEND_SAMPLES 1

#define SG_FB_VECTOR_BYTES 64
#define SG_FB_TABLE        sg_fb_ops_avx512
#include "raster/framebuffer_table.h"
#else
const sg_fb_ops sg_fb_ops_avx512 = {sg_fb_fill_color,   sg_fb_fill_depth,   sg_fb_depth_range,
                                    sg_fb_put_masked,   sg_fb_blend_masked, sg_fb_average4_planes,
                                    sg_fb_split_ids,    sg_fb_alike_tiles,  sg_fb_put_samples,
                                    sg_fb_blend_samples};
#endif
