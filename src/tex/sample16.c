/* sample16.c - 16 texture lookups at once (see sample16.h), the portable copy: the steps of
 * tex/sample.h on GCC vectors, float coordinates, then integer indices, weights and sums, each the
 * scalar operation in every lane, so each lane gets the scalar bits; only the texel reads go lane
 * by lane. The AVX-512 copy (sample16_avx512.c) is the fixed shading's fetch and filter. */
#include "tex/sample16.h"

#include <string.h>

#include "tex/lanes.h"

#define SG_LANES_FN(name) name##_portable
#define SG_LANES_ATTR
#include "tex/sample16_body.h"

#if SG_SAMPLE16_X86
/* sample16_avx512.c's copies, each an sg_sample16_unit_fn. */
typedef void unit_copy(const sg_texview *tv, const float *s, const float *t,
                       float (*out)[SG_SHADER_LANES]);
unit_copy sg_sample16_nearest_clamp_avx512, sg_sample16_nearest_repeat_avx512,
    sg_sample16_bilinear_clamp_avx512, sg_sample16_bilinear_repeat_avx512,
    sg_sample16_bilinear_clamp_window_avx512, sg_sample16_bilinear_repeat_window_avx512,
    sg_sample16_nearest_clamp_avx2, sg_sample16_nearest_repeat_avx2,
    sg_sample16_bilinear_clamp_avx2, sg_sample16_bilinear_repeat_avx2;
#endif

sg_sample16_unit_fn sg_sample16_unit_fn_of(int simd, bool bilinear, bool repeat, bool window) {
#if SG_SAMPLE16_X86
    if (simd == SG_SAMPLE16_AVX512 && !bilinear)
        return repeat ? sg_sample16_nearest_repeat_avx512 : sg_sample16_nearest_clamp_avx512;
    if (simd == SG_SAMPLE16_AVX512 && window)
        return repeat ? sg_sample16_bilinear_repeat_window_avx512
                      : sg_sample16_bilinear_clamp_window_avx512;
    if (simd == SG_SAMPLE16_AVX512)
        return repeat ? sg_sample16_bilinear_repeat_avx512 : sg_sample16_bilinear_clamp_avx512;
    if (simd == SG_SAMPLE16_AVX2 && !bilinear) /* the AVX2 lookups' window is their own choice */
        return repeat ? sg_sample16_nearest_repeat_avx2 : sg_sample16_nearest_clamp_avx2;
    if (simd == SG_SAMPLE16_AVX2)
        return repeat ? sg_sample16_bilinear_repeat_avx2 : sg_sample16_bilinear_clamp_avx2;
#endif
    (void)simd, (void)bilinear, (void)repeat, (void)window;
    return NULL;
}
