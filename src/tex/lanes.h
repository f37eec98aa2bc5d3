/* lanes.h - 16 lanes as one value (GCC vector types), for the code that works on a whole 4 x 4
 * tile at once: the fragment stage of shader pipelines (raster/shade_shader.c) and the 16-lane
 * texture sampling (tex/sample16.c). Each operation is the scalar one in every lane, in the same
 * order (no FMA anywhere in the library), so every lane gets the scalar code's bits. */
#ifndef SG_LANES_H
#define SG_LANES_H

#include <stdbool.h>
#include <stdint.h>
#include <string.h>

#include "sgapi/sgapi.h"

typedef float sg_vf __attribute__((vector_size(4 * SG_SHADER_LANES)));
typedef int32_t sg_vi __attribute__((vector_size(4 * SG_SHADER_LANES)));

#define SEL(m, a, b)  ((sg_vf)(((m) & (sg_vi)(a)) | (~(m) & (sg_vi)(b))))
#define SELI(m, a, b) (((m) & (a)) | (~(m) & (b)))

/* GCC (12) turns vector code into scalar code, lane by lane, before it makes a function's
 * target_clones copies, and inside any function whose own target lacks 64-byte vectors (an
 * always_inline helper included): the 16 lanes are one register only in code compiled for
 * AVX-512 from the start. So the sampling code is compiled twice, the second copy a function of
 * its own with this target, chosen by the device's instruction set (the fragment stage's tile
 * code too, raster/shade_shader_tile.h, with a third copy for AVX2 on 8-lane halves). */
#if defined(__x86_64__) && defined(__GNUC__)
#define SG_LANES_AVX512      1
#define SG_LANES_AVX512_ATTR __attribute__((target("avx512f,avx512bw,avx512dq,avx512vl")))
#else
#define SG_LANES_AVX512 0
#endif

/* Byte k of an RGBA8 texel read as one 32-bit word is channel k: its shift in the word. */
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
#define CHANNEL_SHIFT(k) (8 * (3 - (k)))
#else
#define CHANNEL_SHIFT(k) (8 * (k))
#endif

/* floorf, lane by lane: truncation corrected below 2^23 in magnitude; from there up every float
 * is an integer (and NaN and the infinities are their own floor). */
#define VFLOOR(out, x)                                                                             \
    do {                                                                                           \
        const sg_vf x_ = (x);                                                                      \
        const sg_vf t_ = __builtin_convertvector(__builtin_convertvector(x_, sg_vi), sg_vf);       \
        const sg_vf f_ = SEL(t_ > x_, t_ - 1.0f, t_);                                              \
        (out) = SEL((x_ < 8388608.0f) & (x_ > -8388608.0f), f_, x_);                               \
    } while (0)

/* The texel coordinate of s scaled by size (sg_texcoord_repeat / sg_texcoord_clamp). */
#define VCOORD(out, s, size, repeat)                                                               \
    do {                                                                                           \
        const sg_vf s_ = (s);                                                                      \
        if (repeat) {                                                                              \
            sg_vf fl_;                                                                             \
            VFLOOR(fl_, s_);                                                                       \
            const sg_vf x_ = (s_ - fl_) * (size);                                                  \
            (out) = SEL(x_ >= 0.0f, x_, zero);                                                     \
        } else {                                                                                   \
            sg_vf c_ = SEL(s_ >= -1.0f, s_, zero - 1.0f);                                          \
            c_ = SEL(c_ > 2.0f, zero + 2.0f, c_);                                                  \
            (out) = c_ * (size);                                                                   \
        }                                                                                          \
    } while (0)

/* sg_wrap_index, lane by lane, on an array of 16 indices (a macro, not a function: see
 * SG_LANES_AVX512_ATTR below). */
#define SG_WRAP16(idx, n, repeat)                                                                  \
    do {                                                                                           \
        sg_vi i_;                                                                                  \
        const int n_ = (n);                                                                        \
        memcpy(&i_, (idx), sizeof i_);                                                             \
        if (repeat) {                                                                              \
            i_ = SELI(i_ < 0, i_ + n_, i_);                                                        \
            i_ = SELI(i_ >= n_, i_ - n_, i_);                                                      \
        } else {                                                                                   \
            i_ = SELI(i_ < 0, i_ - i_, i_);                                                        \
            i_ = SELI(i_ >= n_, i_ - i_ + (n_ - 1), i_);                                           \
        }                                                                                          \
        memcpy((idx), &i_, sizeof i_);                                                             \
    } while (0)

#endif
