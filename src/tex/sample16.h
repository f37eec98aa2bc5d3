/* sample16.h - a whole 4 x 4 tile of texture lookups at once: what sg_sample and sg_sample_mip
 * (tex/sample.h, tex/mip.h) give each lane, bit for bit, on 16-lane vectors. Lane i is the tile's
 * pixel i, row by row, so lanes 0, 1, 4, 5 are its first 2 x 2 quad. */
#ifndef SG_SAMPLE16_H
#define SG_SAMPLE16_H

#include <stdbool.h>
#include <stdint.h>

#include "tex/mip.h"

/* Each function in three copies: _portable, and _avx2 and _avx512 (x86-64 only, for a CPU that
 * runs SG_ISA_AVX2 or SG_ISA_AVX512); the inline dispatchers below take the copy `simd` names,
 * chosen once per draw. */
enum { SG_SAMPLE16_PORTABLE, SG_SAMPLE16_AVX2, SG_SAMPLE16_AVX512 };
#if defined(__x86_64__) && defined(__GNUC__)
#define SG_SAMPLE16_X86 1
#else
#define SG_SAMPLE16_X86 0
#endif

#define SG_SAMPLE16_DECLARE(suffix)                                                                \
    void sg_sample16_##suffix(const sg_texview *tv, bool bilinear, bool repeat, bool window,       \
                              const float s[SG_SHADER_LANES], const float t[SG_SHADER_LANES],      \
                              int32_t texel[4][SG_SHADER_LANES]);                                  \
    void sg_sample16_mip_##suffix(const sg_mip_chain *m, const sg_mip_pick pick[4], bool bilinear, \
                                  bool repeat, bool window, const float s[SG_SHADER_LANES],        \
                                  const float t[SG_SHADER_LANES],                                  \
                                  int32_t texel[4][SG_SHADER_LANES]);                              \
    void sg_texels_to_unit_##suffix(const int32_t texel[4][SG_SHADER_LANES],                       \
                                    float out[4][SG_SHADER_LANES]);                                \
    void sg_sample16_unit_##suffix(const sg_texview *tv, bool bilinear, bool repeat, bool window,  \
                                   const float s[SG_SHADER_LANES], const float t[SG_SHADER_LANES], \
                                   float out[4][SG_SHADER_LANES]);
SG_SAMPLE16_DECLARE(portable)
#if SG_SAMPLE16_X86
SG_SAMPLE16_DECLARE(avx2)
SG_SAMPLE16_DECLARE(avx512)
#endif

/* The copy `simd` names (SG_SAMPLE16_*) of function `name`, called with the arguments that
 * follow. */
#if SG_SAMPLE16_X86
#define SG_SAMPLE16_CALL(simd, name, ...)                                                          \
    ((simd) == SG_SAMPLE16_AVX512 ? name##_avx512(__VA_ARGS__)                                     \
     : (simd) == SG_SAMPLE16_AVX2 ? name##_avx2(__VA_ARGS__)                                       \
                                  : name##_portable(__VA_ARGS__))
#else
#define SG_SAMPLE16_CALL(simd, name, ...) ((void)(simd), name##_portable(__VA_ARGS__))
#endif

/** The RGBA8 texels of view tv (top row first; its sizes made, sg_texview_of) at the 16 coordinates
 * (s[i], t[i]): each lane's channels 0 .. 255 in texel[channel][lane], as sg_sample gives them;
 * simd: the copy, SG_SAMPLE16_* (the same bits in each); window: whether the AVX-512 copy tries the
 * texel window before gathering (sg_shade_ctx.texel_window; the same bits either way; the other
 * copies take no choice). */
static inline void sg_sample16(int simd, const sg_texview *tv, bool bilinear, bool repeat,
                               bool window, const float s[SG_SHADER_LANES],
                               const float t[SG_SHADER_LANES], int32_t texel[4][SG_SHADER_LANES]) {
    SG_SAMPLE16_CALL(simd, sg_sample16, tv, bilinear, repeat, window, s, t, texel);
}

/** The same from a mipmap chain, each quad q (lanes of its 2 x 2 block) with its levels pick[q],
 *  as sg_sample_mip gives them. */
static inline void sg_sample16_mip(int simd, const sg_mip_chain *m, const sg_mip_pick pick[4],
                                   bool bilinear, bool repeat, bool window,
                                   const float s[SG_SHADER_LANES], const float t[SG_SHADER_LANES],
                                   int32_t texel[4][SG_SHADER_LANES]) {
    SG_SAMPLE16_CALL(simd, sg_sample16_mip, m, pick, bilinear, repeat, window, s, t, texel);
}

/** Channels 0 .. 255 (texel[channel][lane]) to floats c / 255.0f, bit for bit. */
static inline void sg_texels_to_unit(int simd, const int32_t texel[4][SG_SHADER_LANES],
                                     float out[4][SG_SHADER_LANES]) {
    SG_SAMPLE16_CALL(simd, sg_texels_to_unit, texel, out);
}

/** A copy of sg_sample16_unit made for one filter, wrap and window, whose call takes only the view,
 *  the coordinates and the output. */
typedef void (*sg_sample16_unit_fn)(const sg_texview *tv, const float s[SG_SHADER_LANES],
                                    const float t[SG_SHADER_LANES], float out[4][SG_SHADER_LANES]);

/** That copy for (simd, bilinear, repeat, window), where one is made (the AVX-512 lookups, whose
 *  nearest ones gather with or without a texel window: one gather of 16 texels costs less than the
 *  window's loads, permutes and test on both the Intel and the AMD CPUs measured; the AVX2
 *  lookups, which choose their window themselves), else NULL. */
sg_sample16_unit_fn sg_sample16_unit_fn_of(int simd, bool bilinear, bool repeat, bool window);

/** sg_sample16's channels as sg_texels_to_unit gives them, in one call. */
static inline void sg_sample16_unit(int simd, const sg_texview *tv, bool bilinear, bool repeat,
                                    bool window, const float s[SG_SHADER_LANES],
                                    const float t[SG_SHADER_LANES], float out[4][SG_SHADER_LANES]) {
    SG_SAMPLE16_CALL(simd, sg_sample16_unit, tv, bilinear, repeat, window, s, t, out);
}

#endif
