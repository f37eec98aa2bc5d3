/* light_avx512.h - the vector operations of light_simd.h in AVX-512 (sixteen lanes), then the
 * equation itself. Included by files compiled for AVX-512 (and no FMA) that check
 * SG_LIGHT_AVX512 after it: the per-pixel lighting (shade_phong_avx512.c) and the per-vertex one
 * (vertex_lit_avx512.c). */
#ifndef SG_LIGHT_AVX512_H
#define SG_LIGHT_AVX512_H

#include <float.h>

/* FLT_EVAL_METHOD 0: the scalar code rounds each operation to float, as AVX-512 does. */
#if (defined(__x86_64__) || defined(__i386__)) && defined(__AVX512F__) && FLT_EVAL_METHOD == 0
#define SG_LIGHT_AVX512 1

#include <immintrin.h>

typedef __m512 LV;
typedef __mmask16 LM;
typedef __m512i LI;
#define lv_set1(f)         _mm512_set1_ps(f)
#define li_set1(i)         _mm512_set1_epi32(i)
#define lv_add             _mm512_add_ps
#define lv_sub             _mm512_sub_ps
#define lv_mul             _mm512_mul_ps
#define lv_div             _mm512_div_ps
#define lv_sqrt            _mm512_sqrt_ps
#define lv_floor(v)        _mm512_roundscale_ps(v, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC)
#define lv_neg(v)          _mm512_xor_ps(v, _mm512_set1_ps(-0.0f))
#define lm_gt(a, b)        _mm512_cmp_ps_mask(a, b, _CMP_GT_OQ)
#define lm_ge(a, b)        _mm512_cmp_ps_mask(a, b, _CMP_GE_OQ)
#define lm_le(a, b)        _mm512_cmp_ps_mask(a, b, _CMP_LE_OQ)
#define lm_lt(a, b)        _mm512_cmp_ps_mask(a, b, _CMP_LT_OQ)
#define lm_and(a, b)       ((__mmask16)((a) & (b)))
#define lv_sel(m, a, b)    _mm512_mask_blend_ps(m, b, a)
#define lv_bits(v)         _mm512_castps_si512(v)
#define lv_of_bits(i)      _mm512_castsi512_ps(i)
#define lv_of_int(i)       _mm512_cvtepi32_ps(i)
#define li_of_float(v)     _mm512_cvttps_epi32(v)
#define li_and             _mm512_and_si512
#define li_or              _mm512_or_si512
#define li_add             _mm512_add_epi32
#define li_sub             _mm512_sub_epi32
#define li_mul             _mm512_mullo_epi32
#define lv_gather(p, i, m) _mm512_mask_i32gather_ps(_mm512_setzero_ps(), m, i, p, 4)
#define li_srl(i, n)       _mm512_srli_epi32(i, n)
#define li_sll(i, n)       _mm512_slli_epi32(i, n)
#include "raster/light_simd.h"

#endif
#endif
