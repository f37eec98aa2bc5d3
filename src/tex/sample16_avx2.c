/* sample16_avx2.c - the AVX2 copy of the 16-lane lookups (tex/sample16.h): the fixed shading's
 * texel fetch and filter (raster/shade_avx2.h), eight lanes at a time, which give sg_sample's
 * bits, so the same bits as the portable copy. A half of the tile (two rows) holds two whole 2 x 2
 * quads, as a set of the fixed shading does. This file alone is compiled with -mavx2 (no FMA);
 * off x86-64 it is empty. */
#include "tex/sample16.h"

#include "raster/shade_avx2.h"

#if SG_SAMPLE16_X86
#if !defined(SG_SHADE_AVX2)
#error "compile this file with the AVX2 flags CMakeLists.txt gives it"
#endif

/* Both halves of texture tv at (s[i], t[i]): lanes 8 h to 8 h + 7 in c[h]. */
INLINE void lookup_all(const sg_texview *tv, bool bilinear, bool repeat, const float *s,
                       const float *t, __m256i c[2][4]) {
    for (int half = 0; half < 2; half++)
        lookup8(tv, _mm256_loadu_ps(s + 8 * half), _mm256_loadu_ps(t + 8 * half), bilinear, repeat,
                c[half]);
}

void sg_sample16_avx2(const sg_texview *tv, bool bilinear, bool repeat, bool window,
                      const float s[SG_SHADER_LANES], const float t[SG_SHADER_LANES],
                      int32_t texel[4][SG_SHADER_LANES]) {
    (void)window; /* the AVX2 lookups always try their window (sg_shade_ctx.texel_window) */
    __m256i c[2][4];
    lookup_all(tv, bilinear, repeat, s, t, c);
    for (int half = 0; half < 2; half++)
        for (int k = 0; k < 4; k++)
            _mm256_storeu_si256((__m256i *)(void *)(texel[k] + 8 * half), c[half][k]);
}

/* Each half's two quads' levels and weight spread to their lanes, then mip8_lookup. */
void sg_sample16_mip_avx2(const sg_mip_chain *m, const sg_mip_pick pick[4], bool bilinear,
                          bool repeat, bool window, const float s[SG_SHADER_LANES],
                          const float t[SG_SHADER_LANES], int32_t texel[4][SG_SHADER_LANES]) {
    (void)window;
    for (int half = 0; half < 2; half++) {
        const sg_mip_pick *a = &pick[2 * half], *b = &pick[2 * half + 1];
#define SG_SPREAD(field)                                                                           \
    _mm256_setr_epi32(a->field, a->field, b->field, b->field, a->field, a->field, b->field,        \
                      b->field)
        __m256i c[4];
        mip8_lookup(m, SG_SPREAD(level0), SG_SPREAD(level1), SG_SPREAD(f),
                    _mm256_loadu_ps(s + 8 * half), _mm256_loadu_ps(t + 8 * half), bilinear, repeat,
                    c);
#undef SG_SPREAD
        for (int k = 0; k < 4; k++)
            _mm256_storeu_si256((__m256i *)(void *)(texel[k] + 8 * half), c[k]);
    }
}

/* c / 255.0f: the division itself (AVX2 without FMA has no cheaper exact form). */
INLINE __m256 unit8(__m256i texel) {
    return _mm256_div_ps(_mm256_cvtepi32_ps(texel), _mm256_set1_ps(255.0f));
}

void sg_texels_to_unit_avx2(const int32_t texel[4][SG_SHADER_LANES],
                            float out[4][SG_SHADER_LANES]) {
    for (int k = 0; k < 4; k++)
        for (int half = 0; half < 2; half++)
            _mm256_storeu_ps(
                out[k] + 8 * half,
                unit8(_mm256_loadu_si256((const __m256i *)(const void *)(texel[k] + 8 * half))));
}

/* sg_sample16_unit_fn_of's copies (sample16.c): the lookup of one filter and wrap and the
 * conversion, a leaf of four arguments that sgSample jumps to. (The AVX2 lookups always try their
 * window, so there is no copy without it.) */
INLINE void unit_leaf(const sg_texview *tv, const int bilinear, const int repeat, const float *s,
                      const float *t, float out[4][SG_SHADER_LANES]) {
    __m256i c[2][4];
    lookup_all(tv, bilinear, repeat, s, t, c);
    for (int half = 0; half < 2; half++)
        for (int k = 0; k < 4; k++) _mm256_storeu_ps(out[k] + 8 * half, unit8(c[half][k]));
}

#define SG_UNIT_LEAF(name, bilinear, repeat)                                                       \
    void name(const sg_texview *tv, const float s[SG_SHADER_LANES],                                \
              const float t[SG_SHADER_LANES], float out[4][SG_SHADER_LANES]) {                     \
        unit_leaf(tv, bilinear, repeat, s, t, out);                                                \
    }
SG_UNIT_LEAF(sg_sample16_nearest_clamp_avx2, 0, 0)
SG_UNIT_LEAF(sg_sample16_nearest_repeat_avx2, 0, 1)
SG_UNIT_LEAF(sg_sample16_bilinear_clamp_avx2, 1, 0)
SG_UNIT_LEAF(sg_sample16_bilinear_repeat_avx2, 1, 1)
#undef SG_UNIT_LEAF

/* The lookups and the conversion in one call, the channels kept in registers between them. */
void sg_sample16_unit_avx2(const sg_texview *tv, bool bilinear, bool repeat, bool window,
                           const float s[SG_SHADER_LANES], const float t[SG_SHADER_LANES],
                           float out[4][SG_SHADER_LANES]) {
    (void)window;
    __m256i c[2][4];
    lookup_all(tv, bilinear, repeat, s, t, c);
    for (int half = 0; half < 2; half++)
        for (int k = 0; k < 4; k++) _mm256_storeu_ps(out[k] + 8 * half, unit8(c[half][k]));
}

#endif
