/* shade_sse2.c - the shading functions of shade.h in SSE2, the x86-64 baseline. A tile is shaded
 * one row of four pixels at a time, a pixel per lane and a vector per channel: 1/q, the colours
 * and the texture coordinates are the scalar reference's float operations (shade.c, sample.h) in
 * the same order, so the bytes are the same. Texel indices are computed in vectors and the texels
 * loaded one by one (SSE2 has no gather), two at a time where a bilinear footprint allows;
 * bilinear filtering is exact integer arithmetic on 16-bit lanes. Where SSE math is not the
 * scalar float math (x87) or not x86, every variant is NULL and the scalar functions are used.
 */
#include "raster/shade.h"

#include <float.h>

/* FLT_EVAL_METHOD 0: the scalar code rounds each operation to float, as SSE does (x87 would not).
 */
#if (defined(__x86_64__) || defined(__i386__)) && defined(__SSE2__) && FLT_EVAL_METHOD == 0

#include <emmintrin.h>
#include <string.h>

#include "raster/framebuffer.h"

/* Texel columns, rows and row * width are computed in 16-bit lanes (pmaddwd, pminsw). */
_Static_assert(SG_MAX_IMAGE_SIZE < 32768, "texture sides must fit signed 16 bits");

#define INLINE static inline __attribute__((always_inline))

/* The bound texture, broadcast; "scale" is the size the texcoord functions multiply by (n, or
 * 256 n when bilinear) and "hi" the clamp's upper limit (n - 1 texels, or 256 (n + 1)). */
typedef struct tex4 {
    const uint8_t *texels;
    __m128 scale_x, scale_y, hi_x, hi_y;
    __m128i n_x, n_y, last_x, last_y; /* n and n - 1 */
} tex4;

/* sg_texcoord_repeat. Beyond +-2^23 every float is an integer, its fraction 0: clamping s there
 * (min also turns NaN into 2^23) keeps the truncating conversion exact, and floor is the truncation
 * minus one where that is above s. NaN and infinities give x = 0 as in the reference (which gets
 * there through a NaN fraction); x is never negative, so the reference's x >= 0 test is moot. */
INLINE __m128 coord_repeat(__m128 s, __m128 scale) {
    s = _mm_max_ps(_mm_min_ps(s, _mm_set1_ps(8388608.0f)), _mm_set1_ps(-8388608.0f));
    __m128 tr = _mm_cvtepi32_ps(_mm_cvttps_epi32(s));
    __m128 fl = _mm_sub_ps(tr, _mm_and_ps(_mm_cmpgt_ps(tr, s), _mm_set1_ps(1.0f)));
    return _mm_mul_ps(_mm_sub_ps(s, fl), scale);
}

/* Column (or row) of sg_sample_nearest. Repeat: x is in [0, n], so truncation is floor and only n
 * wraps. Clamp: flooring then clamping to [0, n - 1] is clamping then truncating, and the clamp to
 * [-1, 2] before the scaling changes nothing after it; max turns NaN into 0 as the reference does
 * (NaN -> -1 -> -n -> 0). */
INLINE __m128i nearest_index(__m128 s, __m128 scale, __m128 hi, __m128i n, __m128i last,
                             const int repeat) {
    if (repeat) {
        __m128i i = _mm_cvttps_epi32(coord_repeat(s, scale));
        return _mm_sub_epi32(i, _mm_and_si128(_mm_cmpgt_epi32(i, last), n));
    }
    return _mm_cvttps_epi32(_mm_min_ps(_mm_max_ps(_mm_mul_ps(s, scale), _mm_setzero_ps()), hi));
}

/* Columns i0, i1 (wrapped) and 8-bit fraction of sg_sample_bilinear; (floor(x) - 128) >> 8 and
 * & 255 are the reference's split without its +512. Clamp: the reference clamps s to [-1, 2] and
 * then x to [-256, 256 (n + 1)], which is x = s * 256 n clamped to the latter alone (NaN -> -256
 * with max). Repeat: x >= 0, i0 in [-1, n - 1], i1 in [0, n]. Clamped indices fit 16 bits. */
INLINE void bilinear_index(__m128 s, __m128 scale, __m128 hi, __m128i n, __m128i last,
                           const int repeat, __m128i *i0, __m128i *i1, __m128i *frac) {
    __m128i fl;
    if (repeat) {
        fl = _mm_cvttps_epi32(coord_repeat(s, scale));
    } else {
        /* Truncation, not floor: where they differ (x < 0) i0 and i1 both clamp to 0, and the
         * fraction then only weighs a texel against itself. */
        fl = _mm_cvttps_epi32(
            _mm_min_ps(_mm_max_ps(_mm_mul_ps(s, scale), _mm_set1_ps(-256.0f)), hi));
    }
    __m128i g = _mm_sub_epi32(fl, _mm_set1_epi32(128));
    __m128i a = _mm_srai_epi32(g, 8), b = _mm_add_epi32(a, _mm_set1_epi32(1));
    *frac = _mm_and_si128(g, _mm_set1_epi32(255));
    if (repeat) {
        a = _mm_add_epi32(a, _mm_and_si128(_mm_srai_epi32(a, 31), n));
        b = _mm_sub_epi32(b, _mm_and_si128(_mm_cmpgt_epi32(b, last), n));
    } else {
        a = _mm_min_epi16(_mm_max_epi16(a, _mm_setzero_si128()), last);
        b = _mm_min_epi16(_mm_max_epi16(b, _mm_setzero_si128()), last);
    }
    *i0 = a;
    *i1 = b;
}

/* Index of the first texel of row j counted from the bottom (sg_texel_at): (n_y - 1 - j) * width
 * with one pmaddwd, both factors being below 2^15 in the low half of each lane. */
INLINE __m128i row_start(__m128i j, const tex4 *tx) {
    return _mm_madd_epi16(_mm_sub_epi32(tx->last_y, j), tx->n_x);
}

/* Four texels by index, one scalar load each. */
INLINE __m128i fetch4(const uint8_t *texels, __m128i idx) {
    _Alignas(16) uint32_t k[4];
    uint32_t v[4];
    _mm_store_si128((__m128i *)(void *)k, idx);
    for (int i = 0; i < 4; i++) memcpy(&v[i], texels + (size_t)k[i] * 4, 4);
    return _mm_setr_epi32((int)v[0], (int)v[1], (int)v[2], (int)v[3]);
}

/* Texels idx and idx + 1 of four pixels with one 8-byte load each, when every i1 is i0 + 1 (the
 * common case, away from the edges and the repeat seam): both are then in the same row. */
INLINE void fetch4_pairs(const uint8_t *texels, __m128i idx, __m128i *t0, __m128i *t1) {
    _Alignas(16) uint32_t k[4];
    _mm_store_si128((__m128i *)(void *)k, idx);
    __m128i q[4];
    for (int i = 0; i < 4; i++)
        q[i] = _mm_loadl_epi64((const __m128i *)(const void *)(texels + (size_t)k[i] * 4));
    __m128 a = _mm_castsi128_ps(_mm_unpacklo_epi64(q[0], q[1])); /* t0 t1 of pixels 0, 1 */
    __m128 b = _mm_castsi128_ps(_mm_unpacklo_epi64(q[2], q[3]));
    *t0 = _mm_castps_si128(_mm_shuffle_ps(a, b, _MM_SHUFFLE(2, 0, 2, 0)));
    *t1 = _mm_castps_si128(_mm_shuffle_ps(a, b, _MM_SHUFFLE(3, 1, 3, 1)));
}

INLINE __m128i nearest4(const tex4 *tx, __m128 s, __m128 u, const int repeat) {
    __m128i i = nearest_index(s, tx->scale_x, tx->hi_x, tx->n_x, tx->last_x, repeat);
    __m128i j = nearest_index(u, tx->scale_y, tx->hi_y, tx->n_y, tx->last_y, repeat);
    return fetch4(tx->texels, _mm_add_epi32(row_start(j, tx), i));
}

/* sg_sample_bilinear of four pixels, planar: c[k] gets channel k of the four pixels. Channels
 * r, b and g, a are blended as pairs of 16-bit lanes. The vertical blends t0 (256 - fy) + t1 fy are
 * at most 255 * 256, exact in unsigned 16 bits; biased by -32768 (the xor) they are signed, and the
 * blends of columns i0 and i1 of a channel, put side by side in a 32-bit lane, go through pmaddwd
 * with (256 - fx, fx), whose sum brings the bias back as 32768 * 256. That is the reference's
 * four-weight sum exactly, then (sum + 32768) >> 16. */
INLINE void bilinear4(const tex4 *tx, __m128 s, __m128 u, const int repeat, __m128i c[4]) {
    __m128i i0, i1, fx, j0, j1, fy;
    bilinear_index(s, tx->scale_x, tx->hi_x, tx->n_x, tx->last_x, repeat, &i0, &i1, &fx);
    bilinear_index(u, tx->scale_y, tx->hi_y, tx->n_y, tx->last_y, repeat, &j0, &j1, &fy);
    __m128i r0 = row_start(j0, tx), r1 = row_start(j1, tx), t00, t10, t01, t11;
    if (_mm_movemask_epi8(_mm_cmpeq_epi32(i1, _mm_add_epi32(i0, _mm_set1_epi32(1)))) == 0xffff) {
        fetch4_pairs(tx->texels, _mm_add_epi32(r0, i0), &t00, &t10);
        fetch4_pairs(tx->texels, _mm_add_epi32(r1, i0), &t01, &t11);
    } else {
        t00 = fetch4(tx->texels, _mm_add_epi32(r0, i0));
        t10 = fetch4(tx->texels, _mm_add_epi32(r0, i1));
        t01 = fetch4(tx->texels, _mm_add_epi32(r1, i0));
        t11 = fetch4(tx->texels, _mm_add_epi32(r1, i1));
    }
    const __m128i lo8 = _mm_set1_epi32(0x00ff00ff), lo16 = _mm_set1_epi32(0xffff);
    const __m128i bias = _mm_set1_epi32((int)0x80008000u);
    __m128i fy2 = _mm_or_si128(fy, _mm_slli_epi32(fy, 16)); /* both 16-bit halves */
    __m128i gy2 = _mm_sub_epi16(_mm_set1_epi16(256), fy2);
    __m128i wx = _mm_or_si128(_mm_sub_epi32(_mm_set1_epi32(256), fx), _mm_slli_epi32(fx, 16));
#define SG_VBLEND(a, b)                                                                            \
    _mm_xor_si128(_mm_add_epi16(_mm_mullo_epi16(a, gy2), _mm_mullo_epi16(b, fy2)), bias)
    __m128i rb0 = SG_VBLEND(_mm_and_si128(t00, lo8), _mm_and_si128(t01, lo8));
    __m128i rb1 = SG_VBLEND(_mm_and_si128(t10, lo8), _mm_and_si128(t11, lo8));
    __m128i ga0 = SG_VBLEND(_mm_srli_epi16(t00, 8), _mm_srli_epi16(t01, 8));
    __m128i ga1 = SG_VBLEND(_mm_srli_epi16(t10, 8), _mm_srli_epi16(t11, 8));
#undef SG_VBLEND
    const __m128i round = _mm_set1_epi32(128 * 65536 + 32768);
#define SG_HBLEND(v) _mm_srli_epi32(_mm_add_epi32(_mm_madd_epi16(v, wx), round), 16)
    c[0] = SG_HBLEND(_mm_or_si128(_mm_and_si128(rb0, lo16), _mm_slli_epi32(rb1, 16)));
    c[1] = SG_HBLEND(_mm_or_si128(_mm_and_si128(ga0, lo16), _mm_slli_epi32(ga1, 16)));
    c[2] = SG_HBLEND(_mm_or_si128(_mm_srli_epi32(rb0, 16), _mm_andnot_si128(lo16, rb1)));
    c[3] = SG_HBLEND(_mm_or_si128(_mm_srli_epi32(ga0, 16), _mm_andnot_si128(lo16, ga1)));
#undef SG_HBLEND
}

/* Four RGBA8 texels to planar channels. */
INLINE void unpack_texels(__m128i t, __m128i c[4]) {
    const __m128i lo8 = _mm_set1_epi32(255);
    c[0] = _mm_and_si128(t, lo8);
    c[1] = _mm_and_si128(_mm_srli_epi32(t, 8), lo8);
    c[2] = _mm_and_si128(_mm_srli_epi32(t, 16), lo8);
    c[3] = _mm_srli_epi32(t, 24);
}

/* sg_to_unorm8 of each lane: max puts NaN at 0, and clamping to [0, 1] first gives the
 * reference's 0 and 255 through the same v * 255 + 0.5 truncation. */
INLINE __m128i unorm8(__m128 v) {
    v = _mm_min_ps(_mm_max_ps(v, _mm_setzero_ps()), _mm_set1_ps(1.0f));
    return _mm_cvttps_epi32(_mm_add_ps(_mm_mul_ps(v, _mm_set1_ps(255.0f)), _mm_set1_ps(0.5f)));
}

/* Planar channels (0 .. 255) to RGBA8, sg_pack_rgba8. */
INLINE __m128i pack4(const __m128i c[4]) {
    return _mm_or_si128(_mm_or_si128(c[0], _mm_slli_epi32(c[1], 8)),
                        _mm_or_si128(_mm_slli_epi32(c[2], 16), _mm_slli_epi32(c[3], 24)));
}

/* Writes the lanes of `m` (4 bits) of a row; a partial row is blended with what dst holds, which
 * the caller alone owns. */
INLINE void store_row(uint32_t *dst, __m128i v, unsigned m) {
    if (m != 15) {
        const __m128i bits = _mm_setr_epi32(1, 2, 4, 8);
        __m128i sel = _mm_cmpeq_epi32(_mm_and_si128(_mm_set1_epi32((int)m), bits), bits);
        __m128i old = _mm_loadu_si128((const __m128i *)(const void *)dst);
        v = _mm_or_si128(_mm_and_si128(sel, v), _mm_andnot_si128(sel, old));
    }
    _mm_storeu_si128((__m128i *)(void *)dst, v);
}

/* The body of every variant, as shade_pixels in shade.c; the constant arguments fold away. */
/* No secondary colour here (SG_SHADE_NO_SECONDARY): lit draws with one take the scalar code on
 * an SSE2-only CPU. */
INLINE void shade_rows(const sg_shade_ctx *c, const sg_tri *t, const sg_tri_ext *ext, int x0,
                       int y0, uint32_t mask, uint32_t *dst, const int textured, const int bilinear,
                       const int repeat, const int flat, const int sec) {
    (void)sec;
    if (!textured && flat != SG_FLAT_NONE) { /* one colour, converted once */
        uint32_t px = sg_flat_pixel(t, ext, 0);
        for (int r = 0; r < 4; r++) {
            unsigned m = (mask >> (4 * r)) & 15u;
            if (m) store_row(dst + 4 * r, _mm_set1_epi32((int)px), m);
        }
        return;
    }
    const float ox = (float)(x0 - t->minx), oy = (float)(y0 - t->miny);
    const __m128 dx = _mm_add_ps(_mm_set1_ps(ox), _mm_setr_ps(0.0f, 1.0f, 2.0f, 3.0f));
    /* Everything but the a_dy * dy terms is the same on every row: q + q_dx dx and a + a_dx dx. */
    const __m128 qx = _mm_add_ps(_mm_set1_ps(t->q), _mm_mul_ps(_mm_set1_ps(t->q_dx), dx));
    const int nattr = textured ? 6 : 4;
    __m128 ax[6];
    for (int k = 0; k < nattr; k++) {
        if (k < 4 && flat != SG_FLAT_NONE)
            ax[k] = _mm_set1_ps(t->color[k]);
        else
            ax[k] = _mm_add_ps(_mm_set1_ps(t->a[k]), _mm_mul_ps(_mm_set1_ps(t->a_dx[k]), dx));
    }
    tex4 tx;
    if (textured) {
        const int w = c->tex.width, h = c->tex.height;
        const float sc = bilinear ? 256.0f : 1.0f;
        tx.texels = c->tex.texels;
        tx.scale_x = _mm_set1_ps(sc * (float)w);
        tx.scale_y = _mm_set1_ps(sc * (float)h);
        tx.hi_x = _mm_set1_ps(bilinear ? 256.0f * (float)(w + 1) : (float)(w - 1));
        tx.hi_y = _mm_set1_ps(bilinear ? 256.0f * (float)(h + 1) : (float)(h - 1));
        tx.n_x = _mm_set1_epi32(w);
        tx.n_y = _mm_set1_epi32(h);
        tx.last_x = _mm_set1_epi32(w - 1);
        tx.last_y = _mm_set1_epi32(h - 1);
    }
    for (int r = 0; r < 4; r++) {
        unsigned m = (mask >> (4 * r)) & 15u;
        if (!m) continue;
        const float dy = oy + (float)r;
        const __m128 w = _mm_div_ps(_mm_set1_ps(1.0f), _mm_add_ps(qx, _mm_set1_ps(t->q_dy * dy)));
        __m128 col[4];
        for (int k = 0; k < 4; k++)
            col[k] = flat != SG_FLAT_NONE
                         ? ax[k]
                         : _mm_mul_ps(_mm_add_ps(ax[k], _mm_set1_ps(t->a_dy[k] * dy)), w);
        if (textured) {
            __m128 s = _mm_mul_ps(_mm_add_ps(ax[4], _mm_set1_ps(t->a_dy[4] * dy)), w);
            __m128 u = _mm_mul_ps(_mm_add_ps(ax[5], _mm_set1_ps(t->a_dy[5] * dy)), w);
            __m128i tc[4];
            if (bilinear) {
                bilinear4(&tx, s, u, repeat, tc);
                if (flat == SG_FLAT_WHITE) {
                    store_row(dst + 4 * r, pack4(tc), m);
                    continue;
                }
            } else {
                __m128i texel = nearest4(&tx, s, u, repeat);
                if (flat == SG_FLAT_WHITE) { /* the texel is the colour, as in the reference */
                    store_row(dst + 4 * r, texel, m);
                    continue;
                }
                unpack_texels(texel, tc);
            }
            for (int k = 0; k < 4; k++)
                col[k] = _mm_mul_ps(col[k],
                                    _mm_mul_ps(_mm_cvtepi32_ps(tc[k]), _mm_set1_ps(1.0f / 255.0f)));
        }
        __m128i out[4];
        for (int k = 0; k < 4; k++) out[k] = unorm8(col[k]);
        store_row(dst + 4 * r, pack4(out), m);
    }
}

#define SG_SHADE_TABLE sg_shade_sse2
#define SG_SHADE_NO_SECONDARY
#include "raster/shade_variants.h"

#else

sg_shade_fn sg_shade_sse2(int index) {
    (void)index;
    return NULL;
}

#endif
