/* sample16.h - a whole 4 x 4 tile of texture lookups at once: what sg_sample and sg_sample_mip
 * (tex/sample.h, tex/mip.h) give each lane, bit for bit, on 16-lane vectors. Lane i is the tile's
 * pixel i, row by row, so lanes 0, 1, 4, 5 are its first 2 x 2 quad. */
#ifndef SG_SAMPLE16_H
#define SG_SAMPLE16_H

#include <stdbool.h>
#include <stdint.h>

#include "tex/mip.h"

/* Each function in two copies: _portable, and _avx512 (x86-64 only, for a CPU that runs
 * SG_ISA_AVX512); the inline dispatchers below take the choice, made once per draw. */
#if defined(__x86_64__) && defined(__GNUC__)
#define SG_SAMPLE16_AVX512 1
#else
#define SG_SAMPLE16_AVX512 0
#endif

#define SG_SAMPLE16_DECLARE(suffix)                                                                \
    void sg_sample16_##suffix(const uint8_t *texels, int w, int h, bool bilinear, bool repeat,     \
                              const float s[SG_SHADER_LANES], const float t[SG_SHADER_LANES],      \
                              int32_t texel[4][SG_SHADER_LANES]);                                  \
    void sg_sample16_mip_##suffix(const sg_mip_chain *m, const sg_mip_pick pick[4], bool bilinear, \
                                  bool repeat, const float s[SG_SHADER_LANES],                     \
                                  const float t[SG_SHADER_LANES],                                  \
                                  int32_t texel[4][SG_SHADER_LANES]);                              \
    void sg_texels_to_unit_##suffix(const int32_t texel[4][SG_SHADER_LANES],                       \
                                    float out[4][SG_SHADER_LANES]);                                \
    void sg_sample16_unit_##suffix(const uint8_t *texels, int w, int h, bool bilinear,             \
                                   bool repeat, const float s[SG_SHADER_LANES],                    \
                                   const float t[SG_SHADER_LANES], float out[4][SG_SHADER_LANES]);
SG_SAMPLE16_DECLARE(portable)
#if SG_SAMPLE16_AVX512
SG_SAMPLE16_DECLARE(avx512)
#endif

/* The copy `avx512` names (the CPU runs SG_ISA_AVX512) of function `name`, called with the
 * arguments that follow. */
#if SG_SAMPLE16_AVX512
#define SG_SAMPLE16_CALL(avx512, name, ...)                                                        \
    ((avx512) ? name##_avx512(__VA_ARGS__) : name##_portable(__VA_ARGS__))
#else
#define SG_SAMPLE16_CALL(avx512, name, ...) ((void)(avx512), name##_portable(__VA_ARGS__))
#endif

/** RGBA8 texels (top row first, width w, height h) at the 16 coordinates (s[i], t[i]): each
 *  lane's channels 0 .. 255 in texel[channel][lane], as sg_sample gives them; avx512: the CPU
 *  runs SG_ISA_AVX512 (same bits). */
static inline void sg_sample16(bool avx512, const uint8_t *texels, int w, int h, bool bilinear,
                               bool repeat, const float s[SG_SHADER_LANES],
                               const float t[SG_SHADER_LANES], int32_t texel[4][SG_SHADER_LANES]) {
    SG_SAMPLE16_CALL(avx512, sg_sample16, texels, w, h, bilinear, repeat, s, t, texel);
}

/** The same from a mipmap chain, each quad q (lanes of its 2 x 2 block) with its levels pick[q],
 *  as sg_sample_mip gives them. */
static inline void sg_sample16_mip(bool avx512, const sg_mip_chain *m, const sg_mip_pick pick[4],
                                   bool bilinear, bool repeat, const float s[SG_SHADER_LANES],
                                   const float t[SG_SHADER_LANES],
                                   int32_t texel[4][SG_SHADER_LANES]) {
    SG_SAMPLE16_CALL(avx512, sg_sample16_mip, m, pick, bilinear, repeat, s, t, texel);
}

/** Channels 0 .. 255 (texel[channel][lane]) to floats c / 255.0f, bit for bit. */
static inline void sg_texels_to_unit(bool avx512, const int32_t texel[4][SG_SHADER_LANES],
                                     float out[4][SG_SHADER_LANES]) {
    SG_SAMPLE16_CALL(avx512, sg_texels_to_unit, texel, out);
}

/** sg_sample16's channels as sg_texels_to_unit gives them, in one call. */
static inline void sg_sample16_unit(bool avx512, const uint8_t *texels, int w, int h, bool bilinear,
                                    bool repeat, const float s[SG_SHADER_LANES],
                                    const float t[SG_SHADER_LANES], float out[4][SG_SHADER_LANES]) {
    SG_SAMPLE16_CALL(avx512, sg_sample16_unit, texels, w, h, bilinear, repeat, s, t, out);
}

#endif
