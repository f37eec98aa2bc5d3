/* sample16_avx512.c - the AVX-512 copy of the 16-lane lookups (tex/sample16.h): the fixed
 * shading's texel fetch and filter (raster/shade_avx512.h: a texel window or 64-bit pair gathers,
 * then the 16-bit filter), which give sg_sample's bits, so the same bits as the portable copy.
 * This file alone is compiled with -mavx512f/bw/vl/dq; off x86-64 it is empty. */
#include "tex/sample16.h"

#include "raster/shade_avx512.h"

#if SG_SAMPLE16_X86
#if !defined(SG_SHADE_AVX512)
#error "compile this file with the AVX-512 flags CMakeLists.txt gives it"
#endif

/* Every lane of texture tv at (s[i], t[i]). */
INLINE void lookup_all(const sg_texview *tv, bool bilinear, bool repeat, bool window,
                       const float *s, const float *t, __m512i c[4]) {
    lookup16(tv, _mm512_loadu_ps(s), _mm512_loadu_ps(t), 0xffff, bilinear, repeat, 1, window, c);
}

void sg_sample16_avx512(const sg_texview *tv, bool bilinear, bool repeat, bool window,
                        const float s[SG_SHADER_LANES], const float t[SG_SHADER_LANES],
                        int32_t texel[4][SG_SHADER_LANES]) {
    __m512i c[4];
    lookup_all(tv, bilinear, repeat, window, s, t, c);
    for (int k = 0; k < 4; k++) _mm512_storeu_si512(texel[k], c[k]);
}

/* Each quad's levels and weight spread to its lanes, then mip16_lookup. */
void sg_sample16_mip_avx512(const sg_mip_chain *m, const sg_mip_pick pick[4], bool bilinear,
                            bool repeat, bool window, const float s[SG_SHADER_LANES],
                            const float t[SG_SHADER_LANES], int32_t texel[4][SG_SHADER_LANES]) {
    /* Lane i belongs to quad (i >> 1 & 1) | (i >> 3) << 1. */
    const __m512i quad = _mm512_setr_epi32(0, 0, 1, 1, 0, 0, 1, 1, 2, 2, 3, 3, 2, 2, 3, 3);
#define SG_SPREAD(field)                                                                           \
    _mm512_permutexvar_epi32(quad,                                                                 \
                             _mm512_setr_epi32(pick[0].field, pick[1].field, pick[2].field,        \
                                               pick[3].field, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0))
    __m512i c[4];
    mip16_lookup(m, SG_SPREAD(level0), SG_SPREAD(level1), SG_SPREAD(f), _mm512_loadu_ps(s),
                 _mm512_loadu_ps(t), bilinear, repeat, window, c);
#undef SG_SPREAD
    for (int k = 0; k < 4; k++) _mm512_storeu_si512(texel[k], c[k]);
}

/* c / 255.0f without a division: q = c (1 / 255) in float is within an ulp of the quotient, and
 * one correction step, q + (c - 255 q) (1 / 255), with the remainder c - 255 q exact in a fused
 * multiply-add, gives the correctly rounded quotient for every c in 0 .. 255 (test_sample checks
 * all 256). The fused operations are written out; the library is compiled without contraction. */
INLINE __m512 unit16(__m512i texel) {
    const __m512 r = _mm512_set1_ps(1.0f / 255.0f), d = _mm512_set1_ps(255.0f);
    const __m512 c = _mm512_cvtepi32_ps(texel), q = _mm512_mul_ps(c, r);
    return _mm512_fmadd_ps(_mm512_fnmadd_ps(q, d, c), r, q);
}

void sg_texels_to_unit_avx512(const int32_t texel[4][SG_SHADER_LANES],
                              float out[4][SG_SHADER_LANES]) {
    for (int k = 0; k < 4; k++) _mm512_storeu_ps(out[k], unit16(_mm512_loadu_si512(texel[k])));
}

/* The lookups and the conversion in one call, the channels kept in registers between them. */
void sg_sample16_unit_avx512(const sg_texview *tv, bool bilinear, bool repeat, bool window,
                             const float s[SG_SHADER_LANES], const float t[SG_SHADER_LANES],
                             float out[4][SG_SHADER_LANES]) {
    __m512i c[4];
    lookup_all(tv, bilinear, repeat, window, s, t, c);
    for (int k = 0; k < 4; k++) _mm512_storeu_ps(out[k], unit16(c[k]));
}

#endif
