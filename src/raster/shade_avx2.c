/* shade_avx2.c - the shading functions of shade.h in AVX2 (this file alone is compiled with
 * -mavx2; no FMA, which would round differently), made of the helpers of shade_avx2.h. A tile is
 * shaded two rows at a time, eight pixels per __m256 (row r in the low half, row r + 1 in the
 * high half) and a vector per channel: 1/q, the colours and the texture coordinates are the scalar
 * reference's float operations (shade.c, sample.h) in the same order, so the bytes are the same;
 * pixels are written with a masked store. Without AVX2 (or off x86) every variant is NULL and the
 * SSE2 or scalar code is used.
 */
#include "raster/shade_avx2.h"

#if defined(SG_SHADE_AVX2)

/* The body of every variant, as shade_pixels in shade.c: sg_shade8_at of each pair of rows that
 * has pixels in the mask; the constant arguments fold away. */
INLINE void shade_rows(const sg_shade_ctx *c, const sg_tri *t, const sg_tri_ext *ext, int x0,
                       int y0, uint32_t mask, uint32_t *dst, const int textured, const int bilinear,
                       const int repeat, const int flat, const int sec) {
    for (int h = 0; h < 2; h++) {
        unsigned m = (mask >> (8 * h)) & 255u;
        if (!m) continue;
        __m256 dx, dy;
        sg_rows_dxdy8(t, x0, y0, h, &dx, &dy);
        store_rows(dst + 8 * h,
                   sg_shade8_at(c, t, ext, dx, dy, textured, bilinear, repeat, flat, sec), m);
    }
}

#define SG_SHADE_TABLE sg_shade_avx2
#include "raster/shade_variants.h"

#else

sg_shade_fn sg_shade_avx2(int index) {
    (void)index;
    return NULL;
}

#endif
