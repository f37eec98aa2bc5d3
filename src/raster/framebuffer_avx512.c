/* framebuffer_avx512.c - a bin's fills a whole cache line (16 pixels) a store (see sg_fb_ops in
 * framebuffer.h). */
#include "raster/framebuffer.h"

#if defined(__AVX512F__)
#include <immintrin.h>

static void fill_color(uint32_t *dst, size_t n, uint32_t value) {
    const __m512i v = _mm512_set1_epi32((int32_t)value);
    for (size_t i = 0; i < n; i += 16) _mm512_store_si512(dst + i, v);
}

#define SG_FB_TABLE sg_fb_ops_avx512
#include "raster/framebuffer_table.h"
#else
const sg_fb_ops sg_fb_ops_avx512 = {sg_fb_fill_color, sg_fb_fill_depth, sg_fb_depth_range};
#endif
