/* light_avx2.h - the vector operations of light_simd.h in AVX2 (eight lanes), then the equation
 * itself. Included by files compiled with -mavx2 (and no FMA) that check SG_LIGHT_AVX2 after it:
 * the per-pixel lighting (shade_phong_avx2.c) and the per-vertex one (vertex_lit_avx2.c). */
#ifndef SG_LIGHT_AVX2_H
#define SG_LIGHT_AVX2_H

#include <float.h>

/* FLT_EVAL_METHOD 0: the scalar code rounds each operation to float, as AVX does. */
#if (defined(__x86_64__) || defined(__i386__)) && defined(__AVX2__) && FLT_EVAL_METHOD == 0
#define SG_LIGHT_AVX2 1

#include <immintrin.h>

typedef __m256 LV;
typedef __m256 LM; /* all ones in a lane that passes */
typedef __m256i LI;
#define lv_set1(f)         _mm256_set1_ps(f)
#define li_set1(i)         _mm256_set1_epi32(i)
#define lv_add             _mm256_add_ps
#define lv_sub             _mm256_sub_ps
#define lv_mul             _mm256_mul_ps
#define lv_div             _mm256_div_ps
#define lv_sqrt            _mm256_sqrt_ps
#define lv_floor(v)        _mm256_round_ps(v, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC)
#define lv_neg(v)          _mm256_xor_ps(v, _mm256_set1_ps(-0.0f))
#define lm_gt(a, b)        _mm256_cmp_ps(a, b, _CMP_GT_OQ)
#define lm_ge(a, b)        _mm256_cmp_ps(a, b, _CMP_GE_OQ)
#define lm_le(a, b)        _mm256_cmp_ps(a, b, _CMP_LE_OQ)
#define lm_lt(a, b)        _mm256_cmp_ps(a, b, _CMP_LT_OQ)
#define lm_and             _mm256_and_ps
#define lv_sel(m, a, b)    _mm256_blendv_ps(b, a, m)
#define lv_bits(v)         _mm256_castps_si256(v)
#define lv_of_bits(i)      _mm256_castsi256_ps(i)
#define lv_of_int(i)       _mm256_cvtepi32_ps(i)
#define li_of_float(v)     _mm256_cvttps_epi32(v)
#define li_and             _mm256_and_si256
#define li_or              _mm256_or_si256
#define li_add             _mm256_add_epi32
#define li_sub             _mm256_sub_epi32
#define li_mul             _mm256_mullo_epi32
#define lv_gather(p, i, m) _mm256_mask_i32gather_ps(_mm256_setzero_ps(), p, i, m, 4)
#define li_srl(i, n)       _mm256_srli_epi32(i, n)
#define li_sll(i, n)       _mm256_slli_epi32(i, n)
#include "raster/light_simd.h"

#endif
#endif
