/* framebuffer_avx2.c - a bin's fills and its write into the target images half a cache line
 * (8 pixels) a store (see sg_fb_ops in framebuffer.h). */
#include "raster/framebuffer.h"

#if defined(__AVX2__)
#include <immintrin.h>
#include <string.h>

static void fill_color(uint32_t *dst, size_t n, uint32_t value) {
    const __m256i v = _mm256_set1_epi32((int32_t)value);
    for (size_t i = 0; i < n; i += 8) _mm256_store_si256((__m256i *)(void *)(dst + i), v);
}

/* The four rows of 8 pixels of two tiles side by side at s (16 pixels a tile): the 128-bit tile
 * rows of the two exchanged. */
static inline void pair_rows(const uint32_t *s, __m256i r[4]) {
    const __m256i a01 = _mm256_loadu_si256((const __m256i *)(const void *)s);
    const __m256i a23 = _mm256_loadu_si256((const __m256i *)(const void *)(s + 8));
    const __m256i b01 = _mm256_loadu_si256((const __m256i *)(const void *)(s + 16));
    const __m256i b23 = _mm256_loadu_si256((const __m256i *)(const void *)(s + 24));
    r[0] = _mm256_permute2x128_si256(a01, b01, 0x20);
    r[1] = _mm256_permute2x128_si256(a01, b01, 0x31);
    r[2] = _mm256_permute2x128_si256(a23, b23, 0x20);
    r[3] = _mm256_permute2x128_si256(a23, b23, 0x31);
}

/* Tiles side by side become rows: four tiles (16 x 4 pixels) give each of four rows a whole
 * 64-byte line, written in one go; then two tiles, half a line; a last single tile is copied a
 * tile row at a time. */
static void to_linear(void *dst, size_t pitch, const uint32_t *tiles, int w, int h, int tx) {
    for (int y = 0; y < h; y += 4) {
        const uint32_t *src = tiles + (size_t)(y >> 2) * (size_t)tx * 16;
        uint8_t *row = (uint8_t *)dst + (size_t)y * pitch;
        const int rows = h - y < 4 ? h - y : 4;
        int x = 0;
        for (; x + 16 <= w; x += 16) { /* four tiles: each row's whole line, both halves */
            __m256i r[2][4];
            for (int p = 0; p < 2; p++) pair_rows(src + (size_t)(x + 8 * p) * 4, r[p]);
            uint8_t *out = row + (size_t)x * 4;
            for (int k = 0; k < rows; k++) {
                _mm256_storeu_si256((__m256i *)(void *)(out + (size_t)k * pitch), r[0][k]);
                _mm256_storeu_si256((__m256i *)(void *)(out + (size_t)k * pitch + 32), r[1][k]);
            }
        }
        for (; x + 8 <= w; x += 8) {
            __m256i r[4];
            pair_rows(src + (size_t)x * 4, r);
            uint8_t *out = row + (size_t)x * 4;
            for (int k = 0; k < rows; k++)
                _mm256_storeu_si256((__m256i *)(void *)(out + (size_t)k * pitch), r[k]);
        }
        for (; x < w; x += 4) { /* at most one tile, maybe partly inside */
            const uint32_t *s = src + (size_t)x * 4;
            const int cols = w - x < 4 ? w - x : 4;
            for (int k = 0; k < rows; k++)
                for (int i = 0; i < cols; i++)
                    memcpy(row + (size_t)k * pitch + (size_t)(x + i) * 4, s + 4 * k + i, 4);
        }
    }
}

static void fill_linear(void *dst, size_t pitch, int w, int h, uint32_t value) {
    const __m256i v = _mm256_set1_epi32((int32_t)value);
    for (int y = 0; y < h; y++) {
        uint32_t *row = (uint32_t *)(void *)((uint8_t *)dst + (size_t)y * pitch);
        int x = 0;
        for (; x + 8 <= w; x += 8) _mm256_storeu_si256((__m256i *)(void *)(row + x), v);
        for (; x < w; x++) row[x] = value;
    }
}

#define SG_FB_TABLE sg_fb_ops_avx2
#include "raster/framebuffer_table.h"
#else
const sg_fb_ops sg_fb_ops_avx2 = {sg_fb_fill_color, sg_fb_fill_depth, sg_tile_to_linear_rgba8,
                                  sg_tile_to_linear_f32, sg_fill_linear_u32};
#endif
