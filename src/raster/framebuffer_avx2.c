/* framebuffer_avx2.c - a bin's fills half a cache line (8 pixels) a store (see sg_fb_ops in
 * framebuffer.h). */
#include "raster/framebuffer.h"

#if defined(__AVX2__)
#include <immintrin.h>

static void fill_color(uint32_t *dst, size_t n, uint32_t value) {
    const __m256i v = _mm256_set1_epi32((int32_t)value);
    for (size_t i = 0; i < n; i += 8) _mm256_store_si256((__m256i *)(void *)(dst + i), v);
}

#define SG_FB_TABLE sg_fb_ops_avx2
#include "raster/framebuffer_table.h"
#else
const sg_fb_ops sg_fb_ops_avx2 = {sg_fb_fill_color, sg_fb_fill_depth, sg_fb_depth_range};
#endif
