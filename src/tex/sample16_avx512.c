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

/* c / 255.0f without a division, for a channel c held at bit `at` (0, 8 or 16) of each lane:
 * c / 255 = N / (2^24 - 1) with N = 65793 c < 2^24, so q = N 2^-24 (the product of c 2^at and
 * 0x1.0101p-8 2^-at, exact in float) is c / 255 less a tail of q (2^-24 + 2^-48 + ...), and
 * q + q 2^-24, rounded once in a fused multiply-add, rounds as c / 255 does: the tail beyond it
 * could only matter at a halfway point, which q + q 2^-24 is only when N is a power of two
 * (c = 0). So a channel needs no shift down, and the quotient one product and one fused
 * operation (test_sample checks all 256 values). The library is compiled without contraction. */
INLINE __m512 unit16_at(__m512i texel, const int at) {
    const __m512 q =
        _mm512_mul_ps(_mm512_cvtepi32_ps(texel), _mm512_set1_ps(0x1.0101p-8f / (float)(1 << at)));
    return _mm512_fmadd_ps(q, _mm512_set1_ps(0x1p-24f), q);
}

void sg_texels_to_unit_avx512(const int32_t texel[4][SG_SHADER_LANES],
                              float out[4][SG_SHADER_LANES]) {
    for (int k = 0; k < 4; k++)
        _mm512_storeu_ps(out[k], unit16_at(_mm512_loadu_si512(texel[k]), 0));
}

/* The nearest gather and the conversion, its texels' channels converted where they lie. */
INLINE void nearest_unit(const sg_texview *tv, const int repeat, const float *s, const float *t,
                         float out[4][SG_SHADER_LANES]) {
    const tex16 tx = tex16_of(tv, 0, false);
    const __m512i x = nearest16(&tx, _mm512_loadu_ps(s), _mm512_loadu_ps(t), 0xffff, repeat);
    for (int k = 0; k < 3; k++)
        _mm512_storeu_ps(out[k],
                         unit16_at(_mm512_and_si512(x, _mm512_set1_epi32(255 << 8 * k)), 8 * k));
    _mm512_storeu_ps(out[3], unit16_at(_mm512_srli_epi32(x, 24), 0));
}

/* sg_sample16_unit_fn_of's copies (sample16.c). */
void sg_sample16_nearest_clamp_avx512(const sg_texview *tv, const float s[SG_SHADER_LANES],
                                      const float t[SG_SHADER_LANES],
                                      float out[4][SG_SHADER_LANES]) {
    nearest_unit(tv, 0, s, t, out);
}

void sg_sample16_nearest_repeat_avx512(const sg_texview *tv, const float s[SG_SHADER_LANES],
                                       const float t[SG_SHADER_LANES],
                                       float out[4][SG_SHADER_LANES]) {
    nearest_unit(tv, 1, s, t, out);
}

/* The bilinear lookup and the conversion, filter, wrap and window constants of each copy. */
INLINE void bilinear_unit(const sg_texview *tv, const int repeat, const int window, const float *s,
                          const float *t, float out[4][SG_SHADER_LANES]) {
    __m512i c[4];
    lookup16(tv, _mm512_loadu_ps(s), _mm512_loadu_ps(t), 0xffff, 1, repeat, 1, window, c);
    for (int k = 0; k < 4; k++) _mm512_storeu_ps(out[k], unit16_at(c[k], 0));
}

#define SG_BILINEAR_UNIT(name, repeat, window)                                                     \
    void name(const sg_texview *tv, const float s[SG_SHADER_LANES],                                \
              const float t[SG_SHADER_LANES], float out[4][SG_SHADER_LANES]) {                     \
        bilinear_unit(tv, repeat, window, s, t, out);                                              \
    }
SG_BILINEAR_UNIT(sg_sample16_bilinear_clamp_avx512, 0, 0)
SG_BILINEAR_UNIT(sg_sample16_bilinear_repeat_avx512, 1, 0)
SG_BILINEAR_UNIT(sg_sample16_bilinear_clamp_window_avx512, 0, 1)
SG_BILINEAR_UNIT(sg_sample16_bilinear_repeat_window_avx512, 1, 1)
#undef SG_BILINEAR_UNIT

/* The lookups and the conversion in one call, the channels kept in registers between them. */
void sg_sample16_unit_avx512(const sg_texview *tv, bool bilinear, bool repeat, bool window,
                             const float s[SG_SHADER_LANES], const float t[SG_SHADER_LANES],
                             float out[4][SG_SHADER_LANES]) {
    if (!bilinear && !window) { /* on its own: merged with the others, the channels were spilled */
        if (repeat)
            nearest_unit(tv, 1, s, t, out);
        else
            nearest_unit(tv, 0, s, t, out);
        return;
    }
    __m512i c[4];
    lookup_all(tv, bilinear, repeat, window, s, t, c);
    for (int k = 0; k < 4; k++) _mm512_storeu_ps(out[k], unit16_at(c[k], 0));
}

#endif
