/* shade_avx512.c - the shading functions of shade.h in AVX-512 (this file alone is compiled with
 * -mavx512f/bw/vl/dq; no FMA, which would round differently), made of the body in
 * shade_avx512.h. Without AVX-512 (or off x86) every variant is NULL and the AVX2, SSE2 or scalar
 * code is used.
 */
#include "raster/shade_avx512.h"

#if defined(SG_SHADE_AVX512)

/* The mask is the store mask: pixels outside it are not written. */
INLINE void shade_rows(const sg_shade_ctx *c, const sg_tri *t, const sg_tri_ext *ext, int x0,
                       int y0, uint32_t mask, uint32_t *dst, const int textured, const int bilinear,
                       const int repeat, const int flat, const int sec) {
    __m512i v = sg_shade16(c, t, ext, x0, y0, mask, textured, bilinear, repeat, flat, sec);
    _mm512_mask_storeu_epi32(dst, (__mmask16)mask, v);
}

#define SG_SHADE_TABLE sg_shade_avx512
#include "raster/shade_variants.h"

#else

sg_shade_fn sg_shade_avx512(int index) {
    (void)index;
    return NULL;
}

#endif
