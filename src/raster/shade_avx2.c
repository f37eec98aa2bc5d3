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

/* The body of every variant, as shade_pixels in shade.c; the constant arguments fold away. */
INLINE void shade_rows(const sg_shade_ctx *c, const sg_tri *t, const sg_tri_ext *ext, int x0,
                       int y0, uint32_t mask, uint32_t *dst, const int textured, const int bilinear,
                       const int repeat, const int flat, const int sec) {
    const int e = SG_LIT_SEC - SG_TRI_ATTRS; /* the secondary colour in ext */
    if (!textured && flat != SG_FLAT_NONE) { /* one colour, converted once */
        uint32_t px = sg_flat_pixel(t, ext, sec);
        for (int r = 0; r < 4; r += 2) {
            unsigned m = (mask >> (4 * r)) & 255u;
            if (m) store_rows(dst + 4 * r, _mm256_set1_epi32((int)px), m);
        }
        return;
    }
    const float ox = (float)(x0 - t->minx), oy = (float)(y0 - t->miny);
    const __m256 dx = _mm256_add_ps(_mm256_set1_ps(ox),
                                    _mm256_setr_ps(0.0f, 1.0f, 2.0f, 3.0f, 0.0f, 1.0f, 2.0f, 3.0f));
    /* Everything but the a_dy * dy terms is the same on every row: q + q_dx dx and a + a_dx dx. */
    const __m256 qx =
        _mm256_add_ps(_mm256_set1_ps(t->q), _mm256_mul_ps(_mm256_set1_ps(t->q_dx), dx));
    const int nattr = textured ? 6 : 4;
    __m256 ax[6];
    for (int k = 0; k < nattr; k++) {
        if (k < 4 && flat != SG_FLAT_NONE)
            ax[k] = _mm256_set1_ps(t->color[k]);
        else
            ax[k] = _mm256_add_ps(_mm256_set1_ps(t->a[k]),
                                  _mm256_mul_ps(_mm256_set1_ps(t->a_dx[k]), dx));
    }
    __m256 sx[3]; /* the secondary colour's a + a_dx dx, or the flat colour */
    for (int k = 0; sec && k < 3; k++)
        sx[k] = flat != SG_FLAT_NONE
                    ? _mm256_set1_ps(ext->a[e + k])
                    : _mm256_add_ps(_mm256_set1_ps(ext->a[e + k]),
                                    _mm256_mul_ps(_mm256_set1_ps(ext->a_dx[e + k]), dx));
    tex8 tx;
    if (textured) tx = tex8_of(&c->tex, bilinear);
    for (int r = 0; r < 4; r += 2) {
        unsigned m = (mask >> (4 * r)) & 255u;
        if (!m) continue;
        /* dy of row r in the low half, of row r + 1 in the high half */
        const __m256 dy =
            _mm256_set_m128(_mm_set1_ps(oy + (float)(r + 1)), _mm_set1_ps(oy + (float)r));
        const __m256 w = _mm256_div_ps(
            _mm256_set1_ps(1.0f), _mm256_add_ps(qx, _mm256_mul_ps(_mm256_set1_ps(t->q_dy), dy)));
        __m256 col[4];
        for (int k = 0; k < 4; k++)
            col[k] =
                flat != SG_FLAT_NONE
                    ? ax[k]
                    : _mm256_mul_ps(
                          _mm256_add_ps(ax[k], _mm256_mul_ps(_mm256_set1_ps(t->a_dy[k]), dy)), w);
        if (textured) {
            __m256 s = _mm256_mul_ps(
                _mm256_add_ps(ax[4], _mm256_mul_ps(_mm256_set1_ps(t->a_dy[4]), dy)), w);
            __m256 u = _mm256_mul_ps(
                _mm256_add_ps(ax[5], _mm256_mul_ps(_mm256_set1_ps(t->a_dy[5]), dy)), w);
            __m256i tc[4];
            if (bilinear) {
                __m256i x[4];
                bilinear8(&tx, s, u, repeat, x);
                if (flat == SG_FLAT_WHITE && !sec) {
                    store_rows(dst + 4 * r, pack_hi8(x), m);
                    continue;
                }
                for (int k = 0; k < 4; k++) tc[k] = _mm256_srli_epi32(x[k], 16);
            } else {
                __m256i texel = nearest8(&tx, s, u, repeat);
                if (flat == SG_FLAT_WHITE &&
                    !sec) { /* the texel is the colour, as in the reference */
                    store_rows(dst + 4 * r, texel, m);
                    continue;
                }
                unpack_texels(texel, tc);
            }
            for (int k = 0; k < 4; k++)
                col[k] = _mm256_mul_ps(col[k], _mm256_mul_ps(_mm256_cvtepi32_ps(tc[k]),
                                                             _mm256_set1_ps(1.0f / 255.0f)));
        }
        for (int k = 0; sec && k < 3; k++)
            col[k] = _mm256_add_ps(
                col[k],
                flat != SG_FLAT_NONE
                    ? sx[k]
                    : _mm256_mul_ps(
                          _mm256_add_ps(sx[k], _mm256_mul_ps(_mm256_set1_ps(ext->a_dy[e + k]), dy)),
                          w));
        store_rows(dst + 4 * r, pack_unorm8(col), m);
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
