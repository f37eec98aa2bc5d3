/* sample16_avx512.c - the AVX-512 copy of the 16-lane lookups (tex/sample16.h): the fixed
 * shading's texel fetch and filter (raster/shade_avx512.h: a texel window or 64-bit pair gathers,
 * then the 16-bit filter), which give sg_sample's bits, so the same bits as the portable copy.
 * This file alone is compiled with -mavx512f/bw/vl/dq; off x86-64 it is empty. */
#include "tex/sample16.h"

#include "raster/shade_avx512.h"

#if SG_SAMPLE16_AVX512
#if !defined(SG_SHADE_AVX512)
#error "compile this file with the AVX-512 flags CMakeLists.txt gives it"
#endif

/* Channel k of each lane of m (others may be 0), 0 .. 255: nearest or bilinear. */
INLINE void lookup16(const sg_texview *tv, __m512 s, __m512 t, __mmask16 m, bool bilinear,
                     bool repeat, __m512i c[4]) {
    const tex16 tx = tex16_of(tv, bilinear);
    if (bilinear) {
        __m512i x[4];
        if (repeat)
            bilinear16(&tx, s, t, m, 1, x);
        else
            bilinear16(&tx, s, t, m, 0, x);
        for (int k = 0; k < 4; k++) c[k] = _mm512_srli_epi32(x[k], 16);
    } else {
        unpack_texels(repeat ? nearest16(&tx, s, t, m, 1) : nearest16(&tx, s, t, m, 0), c);
    }
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
#error "unpack_texels and the filter read channel 0 from the low byte"
#endif
}

/* Every lane of a w x h texture at (s[i], t[i]). */
INLINE void lookup_all(const uint8_t *texels, int w, int h, bool bilinear, bool repeat,
                       const float *s, const float *t, __m512i c[4]) {
    const sg_texview tv = {texels, w, h};
    lookup16(&tv, _mm512_loadu_ps(s), _mm512_loadu_ps(t), 0xffff, bilinear, repeat, c);
}

void sg_sample16_avx512(const uint8_t *texels, int w, int h, bool bilinear, bool repeat,
                        const float s[SG_SHADER_LANES], const float t[SG_SHADER_LANES],
                        int32_t texel[4][SG_SHADER_LANES]) {
    __m512i c[4];
    lookup_all(texels, w, h, bilinear, repeat, s, t, c);
    for (int k = 0; k < 4; k++) _mm512_storeu_si512(texel[k], c[k]);
}

/* Each level the quads read is looked up once, for the lanes that take it (a lane whose second
 * level weighs 0 does not read that level: its blend gives the first level's texel). */
void sg_sample16_mip_avx512(const sg_mip_chain *m, const sg_mip_pick pick[4], bool bilinear,
                            bool repeat, const float s[SG_SHADER_LANES],
                            const float t[SG_SHADER_LANES], int32_t texel[4][SG_SHADER_LANES]) {
    /* Lane i belongs to quad (i >> 1 & 1) | (i >> 3) << 1. */
    const __m512i quad = _mm512_setr_epi32(0, 0, 1, 1, 0, 0, 1, 1, 2, 2, 3, 3, 2, 2, 3, 3);
    const __m512i l0 = _mm512_permutexvar_epi32(
        quad, _mm512_setr_epi32(pick[0].level0, pick[1].level0, pick[2].level0, pick[3].level0, 0,
                                0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0));
    const __m512i l1 = _mm512_permutexvar_epi32(
        quad, _mm512_setr_epi32(pick[0].level1, pick[1].level1, pick[2].level1, pick[3].level1, 0,
                                0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0));
    const __m512i f =
        _mm512_permutexvar_epi32(quad, _mm512_setr_epi32(pick[0].f, pick[1].f, pick[2].f, pick[3].f,
                                                         0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0));
    uint32_t want = 0;
    for (int q = 0; q < 4; q++) {
        want |= 1u << pick[q].level0;
        if (pick[q].f) want |= 1u << pick[q].level1;
    }
    const __m512 vs = _mm512_loadu_ps(s), vt = _mm512_loadu_ps(t);
    const __mmask16 weighed = _mm512_test_epi32_mask(f, f);
    __m512i a[4], b[4];
    for (int k = 0; k < 4; k++) a[k] = b[k] = _mm512_setzero_si512();
    for (; want; want &= want - 1) {
        const int level = __builtin_ctz(want);
        const __m512i lv = _mm512_set1_epi32(level);
        const __mmask16 in0 = _mm512_cmpeq_epi32_mask(l0, lv),
                        in1 = _mm512_cmpeq_epi32_mask(l1, lv);
        __m512i c[4];
        lookup16(&m->level[level], vs, vt, in0 | (in1 & weighed), bilinear, repeat, c);
        for (int k = 0; k < 4; k++) {
            a[k] = _mm512_mask_blend_epi32(in0, a[k], c[k]);
            b[k] = _mm512_mask_blend_epi32(in1, b[k], c[k]);
        }
    }
    for (int k = 0; k < 4; k++) {
        const __m512i d = _mm512_mullo_epi32(_mm512_sub_epi32(b[k], a[k]), f);
        _mm512_storeu_si512(texel[k], _mm512_add_epi32(a[k], _mm512_srai_epi32(d, 8)));
    }
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
void sg_sample16_unit_avx512(const uint8_t *texels, int w, int h, bool bilinear, bool repeat,
                             const float s[SG_SHADER_LANES], const float t[SG_SHADER_LANES],
                             float out[4][SG_SHADER_LANES]) {
    __m512i c[4];
    lookup_all(texels, w, h, bilinear, repeat, s, t, c);
    for (int k = 0; k < 4; k++) _mm512_storeu_ps(out[k], unit16(c[k]));
}

#endif
