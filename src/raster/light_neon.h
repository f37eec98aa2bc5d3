/* light_neon.h - the vector operations of light_simd.h in NEON (AArch64, four lanes), then the
 * equation itself. Included by the files that check SG_LIGHT_NEON after it: the per-pixel
 * lighting (shade_phong_neon.c) and the per-vertex one (vertex_lit_neon.c). */
#ifndef SG_LIGHT_NEON_H
#define SG_LIGHT_NEON_H

#include <float.h>

/* FLT_EVAL_METHOD 0: the scalar code rounds each operation to float, as NEON does. */
#if defined(__aarch64__) && defined(__ARM_NEON) && FLT_EVAL_METHOD == 0
#define SG_LIGHT_NEON 1

#include <arm_neon.h>

/* p[i] in the lanes of m (no other lane is read), 0 elsewhere: NEON has no gather. */
static inline __attribute__((always_inline)) float32x4_t gather4(const float *p, int32x4_t i,
                                                                 uint32x4_t m) {
    int32_t k[4];
    uint32_t live[4];
    float v[4];
    vst1q_s32(k, i);
    vst1q_u32(live, m);
    for (int l = 0; l < 4; l++) v[l] = live[l] ? p[k[l]] : 0.0f;
    return vld1q_f32(v);
}

typedef float32x4_t LV;
typedef uint32x4_t LM; /* all ones in a lane that passes */
typedef int32x4_t LI;
#define lv_set1(f)         vdupq_n_f32(f)
#define li_set1(i)         vdupq_n_s32(i)
#define lv_add             vaddq_f32
#define lv_sub             vsubq_f32
#define lv_mul             vmulq_f32
#define lv_div             vdivq_f32
#define lv_sqrt            vsqrtq_f32
#define lv_floor(v)        vrndmq_f32(v)
#define lv_neg(v)          vnegq_f32(v)
#define lm_gt(a, b)        vcgtq_f32(a, b)
#define lm_ge(a, b)        vcgeq_f32(a, b)
#define lm_le(a, b)        vcleq_f32(a, b)
#define lm_lt(a, b)        vcltq_f32(a, b)
#define lm_and             vandq_u32
#define lv_sel(m, a, b)    vbslq_f32(m, a, b)
#define lv_bits(v)         vreinterpretq_s32_f32(v)
#define lv_of_bits(i)      vreinterpretq_f32_s32(i)
#define lv_of_int(i)       vcvtq_f32_s32(i)
#define li_of_float(v)     vcvtq_s32_f32(v)
#define li_and             vandq_s32
#define li_or              vorrq_s32
#define li_add             vaddq_s32
#define li_sub             vsubq_s32
#define li_mul             vmulq_s32
#define lv_gather(p, i, m) gather4(p, i, m)
#define li_srl(i, n)       vreinterpretq_s32_u32(vshrq_n_u32(vreinterpretq_u32_s32(i), n))
#define li_sll(i, n)       vshlq_n_s32(i, n)
#include "raster/light_simd.h"

#endif
#endif
