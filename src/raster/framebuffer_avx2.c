/* framebuffer_avx2.c - a bin's fills half a cache line (8 pixels) a store (see sg_fb_ops in
 * framebuffer.h). */
#include "raster/framebuffer.h"

#include "raster/blend.h"

#if defined(__AVX2__)
#include <immintrin.h>

static void fill_color(uint32_t *dst, size_t n, uint32_t value) {
    const __m256i v = _mm256_set1_epi32((int32_t)value);
    for (size_t i = 0; i < n; i += 8) _mm256_store_si256((__m256i *)(void *)(dst + i), v);
}

/* The lanes of the 8 pixels at dst that bits (one a pixel) selects, as 32-bit masks. */
static inline __m256i lanes_of(uint32_t bits) {
    const __m256i lanes = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
    return _mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32((int)bits), lanes), lanes);
}

static void put_masked(uint32_t *dst, const uint32_t *src, uint32_t mask) {
    for (int h = 0; h < 2; h++)
        _mm256_maskstore_epi32((int *)(void *)(dst + 8 * h), lanes_of((mask >> (8 * h)) & 255u),
                               _mm256_load_si256((const __m256i *)(const void *)(src + 8 * h)));
}

/* x y / 255 as sg_mul_unorm8 rounds it, in 16-bit lanes (x, y <= 255: no lane overflows). */
static inline __m256i mul8(__m256i x, __m256i y) {
    const __m256i t = _mm256_mullo_epi16(x, y);
    return _mm256_srli_epi16(
        _mm256_add_epi16(_mm256_add_epi16(t, _mm256_srli_epi16(t, 8)), _mm256_set1_epi16(128)), 8);
}

/* sg_blend16_rgba8 on 8 pixels a vector (the same operations on the same 16-bit halves), stored
 * under the mask. sg_blend16_rgba8 itself works on 64-byte vectors, which GCC 12 builds for AVX2
 * with 16-byte spills and reloads of whole 32-byte vectors: several times slower. */
static void blend_masked(uint32_t *dst, const uint32_t *src, uint32_t mask) {
    const __m256i m8 = _mm256_set1_epi32(0x00ff00ff);
    for (int h = 0; h < 2; h++) {
        __m256i *dp = (__m256i *)(void *)(dst + 8 * h);
        const __m256i s = _mm256_load_si256((const __m256i *)(const void *)(src + 8 * h));
        const __m256i d = _mm256_load_si256(dp);
        const __m256i lo = _mm256_srli_epi32(s, 24);
        const __m256i a = _mm256_or_si256(lo, _mm256_slli_epi32(lo, 16));
        const __m256i ia = _mm256_sub_epi16(_mm256_set1_epi16(255), a);
        const __m256i r =
            _mm256_add_epi16(mul8(_mm256_and_si256(s, m8), a), mul8(_mm256_and_si256(d, m8), ia));
        const __m256i g = _mm256_add_epi16(mul8(_mm256_and_si256(_mm256_srli_epi32(s, 8), m8), a),
                                           mul8(_mm256_and_si256(_mm256_srli_epi32(d, 8), m8), ia));
        const __m256i out = _mm256_or_si256(r, _mm256_slli_epi32(g, 8));
        _mm256_maskstore_epi32((int *)(void *)dp, lanes_of((mask >> (8 * h)) & 255u), out);
    }
}

static uint32_t same(const void *vecs, int k, uint32_t id) {
    const __m256i *v = (const __m256i *)vecs + 2 * k, b = _mm256_set1_epi32((int)id);
    return (uint32_t)_mm256_movemask_ps(_mm256_castsi256_ps(_mm256_cmpeq_epi32(v[0], b))) |
           (uint32_t)_mm256_movemask_ps(_mm256_castsi256_ps(_mm256_cmpeq_epi32(v[1], b))) << 8;
}

static int split_ids(const uint32_t *const planes[4], uint32_t *ids, uint64_t *samples) {
    __m256i v[8];
    uint32_t left[4];
    for (int k = 0; k < 4; k++) {
        for (int h = 0; h < 2; h++)
            v[2 * k + h] = _mm256_load_si256((const __m256i *)(const void *)(planes[k] + 8 * h));
        left[k] = ~same(v, k, 0) & 0xffffu;
    }
    return sg_fb_split_ids_with(planes, v, left, same, ids, samples);
}

static inline bool tile_alike(const uint32_t *const planes[4], size_t base) {
    __m256i diff = _mm256_setzero_si256();
    for (int h = 0; h < 2; h++) {
        const __m256i first =
            _mm256_load_si256((const __m256i *)(const void *)(planes[0] + base + 8 * h));
        for (int k = 1; k < 4; k++)
            diff = _mm256_or_si256(
                diff, _mm256_xor_si256(
                          first, _mm256_load_si256(
                                     (const __m256i *)(const void *)(planes[k] + base + 8 * h))));
    }
    return _mm256_testz_si256(diff, diff);
}

static uint64_t alike_tiles(const uint32_t *const planes[4], uint64_t tiles) {
    return sg_fb_alike_tiles_with(planes, tiles, tile_alike);
}

static void put_samples(uint32_t *const planes[4], size_t base, const uint32_t *src,
                        uint64_t samples) {
    const __m256i v[2] = {_mm256_load_si256((const __m256i *)(const void *)src),
                          _mm256_load_si256((const __m256i *)(const void *)(src + 8))};
    for (int k = 0; k < 4; k++) {
        const uint32_t m = (uint32_t)(samples >> (16 * k)) & 0xffffu;
        if (!m) continue;
        for (int h = 0; h < 2; h++)
            _mm256_maskstore_epi32((int *)(void *)(planes[k] + base + 8 * h),
                                   lanes_of((m >> (8 * h)) & 255u), v[h]);
    }
}

/* blend_masked's operations, the source's products with its alpha formed once for the four
 * planes (as framebuffer_avx512.c's): the same 16-bit halves, so the same bits. A plane without a
 * sample of the tile is skipped. */
static void blend_samples(uint32_t *const planes[4], size_t base, const uint32_t *src,
                          uint64_t samples) {
    const __m256i m8 = _mm256_set1_epi32(0x00ff00ff);
    __m256i sr[2], sg[2], ia[2];
    for (int h = 0; h < 2; h++) {
        const __m256i s = _mm256_load_si256((const __m256i *)(const void *)(src + 8 * h));
        const __m256i lo = _mm256_srli_epi32(s, 24);
        const __m256i a = _mm256_or_si256(lo, _mm256_slli_epi32(lo, 16));
        ia[h] = _mm256_sub_epi16(_mm256_set1_epi16(255), a);
        sr[h] = mul8(_mm256_and_si256(s, m8), a);
        sg[h] = mul8(_mm256_and_si256(_mm256_srli_epi32(s, 8), m8), a);
    }
    for (int k = 0; k < 4; k++) {
        const uint32_t m = (uint32_t)(samples >> (16 * k)) & 0xffffu;
        if (!m) continue;
        for (int h = 0; h < 2; h++) {
            __m256i *dp = (__m256i *)(void *)(planes[k] + base + 8 * h);
            const __m256i d = _mm256_load_si256(dp);
            const __m256i r = _mm256_add_epi16(sr[h], mul8(_mm256_and_si256(d, m8), ia[h]));
            const __m256i g =
                _mm256_add_epi16(sg[h], mul8(_mm256_and_si256(_mm256_srli_epi32(d, 8), m8), ia[h]));
            _mm256_maskstore_epi32((int *)(void *)dp, lanes_of((m >> (8 * h)) & 255u),
                                   _mm256_or_si256(r, _mm256_slli_epi32(g, 8)));
        }
    }
}
#define SG_FB_BLEND_SAMPLES 1

#define SG_FB_VECTOR_BYTES 32
#define SG_FB_TABLE        sg_fb_ops_avx2
#include "raster/framebuffer_table.h"
#else
const sg_fb_ops sg_fb_ops_avx2 = {sg_fb_fill_color,   sg_fb_fill_depth,   sg_fb_depth_range,
                                  sg_fb_put_masked,   sg_fb_blend_masked, sg_fb_average4_planes,
                                  sg_fb_split_ids,    sg_fb_alike_tiles,  sg_fb_put_samples,
                                  sg_fb_blend_samples};
#endif
