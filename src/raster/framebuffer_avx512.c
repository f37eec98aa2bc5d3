/* framebuffer_avx512.c - a bin's fills and its write into the target images a whole cache line
 * (16 pixels) a store (see sg_fb_ops in framebuffer.h). */
#include "raster/framebuffer.h"

#if defined(__AVX512F__)
#include <immintrin.h>

static void fill_color(uint32_t *dst, size_t n, uint32_t value) {
    const __m512i v = _mm512_set1_epi32((int32_t)value);
    for (size_t i = 0; i < n; i += 16) _mm512_store_si512(dst + i, v);
}

/* The first `n` (0..16) lanes. */
static inline __mmask16 first_lanes(int n) {
    return (__mmask16)((1u << n) - 1u);
}

/* Four tiles side by side (16 x 4 pixels) become four rows of 16: a 4 x 4 transpose of their
 * 128-bit tile rows. Past the image's width, tiles are not read and lanes not stored. */
static void to_linear(void *dst, size_t pitch, const uint32_t *tiles, int w, int h, int tx) {
    for (int y = 0; y < h; y += 4) {
        const uint32_t *src = tiles + (size_t)(y >> 2) * (size_t)tx * 16;
        uint8_t *row = (uint8_t *)dst + (size_t)y * pitch;
        const int rows = h - y < 4 ? h - y : 4;
        for (int x = 0; x < w; x += 16) {
            const int cols = w - x < 16 ? w - x : 16, ntiles = (cols + 3) >> 2;
            const uint32_t *s = src + (size_t)x * 4; /* tile x / 4: 16 pixels a tile */
            __m512i t[4];
            for (int k = 0; k < 4; k++)
                t[k] = _mm512_maskz_loadu_epi32(k < ntiles ? 0xffff : 0, s + 16 * k);
            const __m512i ab_lo = _mm512_shuffle_i64x2(t[0], t[1], 0x44); /* a0 a1 b0 b1 */
            const __m512i ab_hi = _mm512_shuffle_i64x2(t[0], t[1], 0xee); /* a2 a3 b2 b3 */
            const __m512i cd_lo = _mm512_shuffle_i64x2(t[2], t[3], 0x44);
            const __m512i cd_hi = _mm512_shuffle_i64x2(t[2], t[3], 0xee);
            __m512i r[4];
            r[0] = _mm512_shuffle_i64x2(ab_lo, cd_lo, 0x88); /* a0 b0 c0 d0 */
            r[1] = _mm512_shuffle_i64x2(ab_lo, cd_lo, 0xdd); /* a1 b1 c1 d1 */
            r[2] = _mm512_shuffle_i64x2(ab_hi, cd_hi, 0x88);
            r[3] = _mm512_shuffle_i64x2(ab_hi, cd_hi, 0xdd);
            uint8_t *out = row + (size_t)x * 4;
            if (cols == 16) {
                for (int k = 0; k < rows; k++) _mm512_storeu_si512(out + (size_t)k * pitch, r[k]);
            } else {
                for (int k = 0; k < rows; k++)
                    _mm512_mask_storeu_epi32(out + (size_t)k * pitch, first_lanes(cols), r[k]);
            }
        }
    }
}

static void fill_linear(void *dst, size_t pitch, int w, int h, uint32_t value) {
    const __m512i v = _mm512_set1_epi32((int32_t)value);
    for (int y = 0; y < h; y++) {
        uint32_t *row = (uint32_t *)(void *)((uint8_t *)dst + (size_t)y * pitch);
        int x = 0;
        for (; x + 16 <= w; x += 16) _mm512_storeu_si512(row + x, v);
        if (x < w) _mm512_mask_storeu_epi32(row + x, first_lanes(w - x), v);
    }
}

#define SG_FB_TABLE sg_fb_ops_avx512
#include "raster/framebuffer_table.h"
#else
const sg_fb_ops sg_fb_ops_avx512 = {sg_fb_fill_color, sg_fb_fill_depth, sg_tile_to_linear_rgba8,
                                    sg_tile_to_linear_f32, sg_fill_linear_u32};
#endif
