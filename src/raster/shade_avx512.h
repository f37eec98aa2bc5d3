/* shade_avx512.h - the AVX-512 shading body (internal to the raster; included only by files
 * compiled with -mavx512f/bw/vl/dq): a whole 4x4 tile is one __m512, lane y * 4 + x, and a vector
 * per channel; the algorithms are those of shade_avx2.c widened (see there why each is exact), so
 * the bytes are the scalar reference's. The tile mask is the gather mask: pixels outside it are
 * not read. shade_avx512.c makes the shading table of it, blend_avx512.c inlines it into the
 * raster functions of blended draws (no call per tile).
 */
#ifndef SG_SHADE_AVX512_H
#define SG_SHADE_AVX512_H

#include <float.h>

#include "raster/depth_simd.h"
#include "raster/shade.h"
#include "raster/shade_mixed.h"

#if (defined(__x86_64__) || defined(__i386__)) && defined(__AVX512F__) && defined(__AVX512BW__) && \
    FLT_EVAL_METHOD == 0
#define SG_SHADE_AVX512 1

#include <immintrin.h>

#include "raster/framebuffer.h"

_Static_assert(SG_MAX_IMAGE_SIZE < 32768, "texture sides must fit signed 16 bits");

#define INLINE static inline __attribute__((always_inline))

/* The 16-bit lanes of odd index: the high half of each 32-bit lane. */
#define HI16 ((__mmask32)0xaaaaaaaau)

typedef struct tex16 {
    const int *texels;
    int width, height;
    bool window; /* window_fetch tried before the gathers (sg_shade_ctx.texel_window) */
    __m512 scale_x, scale_y, hi_x, hi_y;
    __m512i n_x, n_y, last_x, last_y;
} tex16;

INLINE __m512 coord_repeat(__m512 s, __m512 scale) {
    __m512 f = _mm512_roundscale_ps(s, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC);
    __m512 x = _mm512_mul_ps(_mm512_sub_ps(s, f), scale);
    return _mm512_max_ps(x, _mm512_setzero_ps()); /* NaN -> 0 */
}

INLINE __m512i nearest_index(__m512 s, __m512 scale, __m512 hi, __m512i n, __m512i last,
                             const int repeat) {
    if (repeat) {
        __m512i i = _mm512_cvttps_epi32(coord_repeat(s, scale));
        return _mm512_mask_sub_epi32(i, _mm512_cmpgt_epi32_mask(i, last), i, n);
    }
    __m512 x = _mm512_max_ps(_mm512_mul_ps(s, scale), _mm512_setzero_ps());
    return _mm512_cvttps_epi32(_mm512_min_ps(x, hi));
}

INLINE __m512i bilinear_split(__m512 s, __m512 scale, __m512 hi, const int repeat) {
    __m512i fl;
    if (repeat) {
        fl = _mm512_cvttps_epi32(coord_repeat(s, scale));
    } else {
        __m512 x = _mm512_max_ps(_mm512_mul_ps(s, scale), _mm512_set1_ps(-256.0f));
        fl = _mm512_cvttps_epi32(_mm512_min_ps(x, hi));
    }
    return _mm512_sub_epi32(fl, _mm512_set1_epi32(128));
}

INLINE void bilinear_wrap(__m512i g, __m512i n, __m512i last, const int repeat, __m512i *i0,
                          __m512i *i1) {
    __m512i a = _mm512_srai_epi32(g, 8), b = _mm512_add_epi32(a, _mm512_set1_epi32(1));
    if (repeat) {
        *i0 = _mm512_min_epu32(a, _mm512_add_epi32(a, n));
        *i1 = _mm512_min_epu32(b, _mm512_sub_epi32(b, n));
    } else {
        *i0 = _mm512_min_epi32(_mm512_max_epi32(a, _mm512_setzero_si512()), last);
        *i1 = _mm512_min_epi32(_mm512_max_epi32(b, _mm512_setzero_si512()), last);
    }
}

/* The fraction (low byte of g) in both 16-bit halves of its lane. */
INLINE __m512i frac2(__m512i g) {
    const __m512i dup = _mm512_set4_epi32(0x800c800c, 0x80088008, 0x80048004, 0x80008000);
    return _mm512_shuffle_epi8(g, dup);
}

INLINE __m512i row_start(__m512i j, const tex16 *tx) {
    return _mm512_madd_epi16(_mm512_sub_epi32(tx->last_y, j), tx->n_x);
}

/* Every index is inside the texture whatever the coordinates (as in shade_avx2.c); the mask only
 * saves the loads of pixels outside the tile mask. */
INLINE __m512i fetch16(const tex16 *tx, __m512i idx, __mmask16 m) {
    return _mm512_mask_i32gather_epi32(_mm512_setzero_si512(), m, idx, tx->texels, 4);
}

INLINE __m512i nearest16(const tex16 *tx, __m512 s, __m512 u, __mmask16 m, const int repeat) {
    __m512i i = nearest_index(s, tx->scale_x, tx->hi_x, tx->n_x, tx->last_x, repeat);
    __m512i j = nearest_index(u, tx->scale_y, tx->hi_y, tx->n_y, tx->last_y, repeat);
    return fetch16(tx, _mm512_add_epi32(row_start(j, tx), i), m);
}

/* Texels idx and idx + 1 of every lane of m, as two vectors. */
INLINE void pair_fetch(const tex16 *tx, __m512i idx, __mmask16 m, __m512i *first, __m512i *second) {
    __m512i lo = _mm512_mask_i32gather_epi64(_mm512_setzero_si512(), (__mmask8)m,
                                             _mm512_castsi512_si256(idx), tx->texels, 4);
    __m512i hi = _mm512_mask_i32gather_epi64(_mm512_setzero_si512(), (__mmask8)(m >> 8),
                                             _mm512_extracti64x4_epi64(idx, 1), tx->texels, 4);
    const __m512i even =
        _mm512_setr_epi32(0, 2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22, 24, 26, 28, 30);
    *first = _mm512_permutex2var_epi32(lo, even, hi);
    *second = _mm512_permutex2var_epi32(lo, _mm512_add_epi32(even, _mm512_set1_epi32(1)), hi);
}

/* Texels from an 8 x 8 window of the texture, when every texel the pixels of m need lies in it (a
 * magnified or about 1:1 texture, away from the texture's edge): eight row loads and two-source
 * permutes instead of gathers; the same texels, so the same bytes. The window starts 3 texels
 * before the tile's first pixel's texel, or, with `least`, at the least column and row that m's
 * pixels read: the shader stage's lookups take that (they come one tile at a time, and the first
 * misses most footprints of textures whose rows run up the screen); the fixed shading, two tiles
 * at a time, is quicker without the reductions. With `least`, a footprint of 3 x 3 split texels
 * reads only the window's first 4 x 4 texels. a and b are the split's columns and rows before
 * any wrap or clamp: where every pixel of m has a - wx and b - wy in [0, 6], columns a, a + 1 and
 * rows b, b + 1 are all inside the texture and the window, so no wrap or clamp would change them,
 * in either mode, and the four texels are window entries k, k + 1, k + 8 and k + 9. False: the
 * footprint is wider or crosses an edge; the caller wraps and gathers. */
INLINE bool window_fetch(const tex16 *tx, __m512i a, __m512i b, __mmask16 m, const int least,
                         __m512i *t00, __m512i *t10, __m512i *t01, __m512i *t11) {
    const int tw = tx->width, th = tx->height;
    if (!tx->window || tw < 8 || th < 8) return false;
    int wx, wy;
    if (least) {
        wx = _mm512_mask_reduce_min_epi32(m, a);
        wy = _mm512_mask_reduce_min_epi32(m, b);
    } else {
        wx = _mm_cvtsi128_si32(_mm512_castsi512_si128(a)) - 3;
        wy = _mm_cvtsi128_si32(_mm512_castsi512_si128(b)) - 3;
    }
    wx = wx < 0 ? 0 : (wx > tw - 8 ? tw - 8 : wx);
    wy = wy < 0 ? 0 : (wy > th - 8 ? th - 8 : wy);
    __m512i c = _mm512_sub_epi32(a, _mm512_set1_epi32(wx));
    __m512i d = _mm512_sub_epi32(b, _mm512_set1_epi32(wy));
    /* Texture row j is memory row th - 1 - j (top row first); window row r is row wy + r. */
    const int *row = tx->texels + (size_t)(th - 1 - wy) * (size_t)tw + (size_t)wx;
    if (least) {
        /* A footprint of at most 3 x 3 split texels (a magnified texture: 37-74 % of the shader
         * stage's lookups in the textured default and gapi-task scenes) lies in the window's first
         * 4 x 4 texels: one vector, one one-source permute a texel instead of two and a blend. */
        const __m512i three = _mm512_set1_epi32(3);
        if (_mm512_mask_cmplt_epu32_mask(_mm512_mask_cmplt_epu32_mask(m, c, three), d, three) ==
            m) {
#define SG_ROW4(r) _mm_loadu_si128((const __m128i *)(const void *)(row - (size_t)(r) * (size_t)tw))
            __m512i w = _mm512_castsi128_si512(SG_ROW4(0));
            w = _mm512_inserti32x4(w, SG_ROW4(1), 1);
            w = _mm512_inserti32x4(w, SG_ROW4(2), 2);
            w = _mm512_inserti32x4(w, SG_ROW4(3), 3);
#undef SG_ROW4
            const __m512i idx = _mm512_add_epi32(_mm512_slli_epi32(d, 2), c);
            *t00 = _mm512_permutexvar_epi32(idx, w);
            *t10 = _mm512_permutexvar_epi32(_mm512_add_epi32(idx, _mm512_set1_epi32(1)), w);
            *t01 = _mm512_permutexvar_epi32(_mm512_add_epi32(idx, _mm512_set1_epi32(4)), w);
            *t11 = _mm512_permutexvar_epi32(_mm512_add_epi32(idx, _mm512_set1_epi32(5)), w);
            return true;
        }
    }
    const __m512i seven = _mm512_set1_epi32(7);
    __mmask16 in = _mm512_mask_cmplt_epu32_mask(m, c, seven);
    if (_mm512_mask_cmplt_epu32_mask(in, d, seven) != m) return false;
    __m512i w[4];
    for (int k = 0; k < 4; k++) {
        const int *r0 = row - (size_t)(2 * k) * (size_t)tw, *r1 = r0 - tw;
        w[k] = _mm512_inserti64x4(
            _mm512_castsi256_si512(_mm256_loadu_si256((const __m256i *)(const void *)r0)),
            _mm256_loadu_si256((const __m256i *)(const void *)r1), 1);
    }
    const __m512i half = _mm512_set1_epi32(32);
#define SG_LOOKUP(idx)                                                                             \
    _mm512_mask_blend_epi32(_mm512_test_epi32_mask(idx, half),                                     \
                            _mm512_permutex2var_epi32(w[0], idx, w[1]),                            \
                            _mm512_permutex2var_epi32(w[2], idx, w[3]))
    __m512i idx = _mm512_add_epi32(_mm512_slli_epi32(d, 3), c);
    *t00 = SG_LOOKUP(idx);
    *t10 = SG_LOOKUP(_mm512_add_epi32(idx, _mm512_set1_epi32(1)));
    *t01 = SG_LOOKUP(_mm512_add_epi32(idx, _mm512_set1_epi32(8)));
    *t11 = SG_LOOKUP(_mm512_add_epi32(idx, _mm512_set1_epi32(9)));
#undef SG_LOOKUP
    return true;
}

/* The bound texture for the filter (bilinear: coordinates in 1/256 texel); window: whether its
 * lookups try the texel window. */
INLINE tex16 tex16_of(const sg_texview *tv, const int bilinear, const bool window) {
    const sg_texsizes *z = &tv->size;
    tex16 tx;
    tx.texels = (const int *)(const void *)tv->texels;
    tx.width = tv->width;
    tx.height = tv->height;
    tx.window = window;
    tx.scale_x = _mm512_set1_ps(z->scale[bilinear][0]);
    tx.scale_y = _mm512_set1_ps(z->scale[bilinear][1]);
    tx.hi_x = _mm512_set1_ps(z->hi[bilinear][0]);
    tx.hi_y = _mm512_set1_ps(z->hi[bilinear][1]);
    tx.n_x = _mm512_set1_epi32(z->n[0]);
    tx.n_y = _mm512_set1_epi32(z->n[1]);
    tx.last_x = _mm512_set1_epi32(z->last[0]);
    tx.last_y = _mm512_set1_epi32(z->last[1]);
    return tx;
}

/* The four texels of each pixel of m's bilinear footprint (t00, t10, t01, t11) for the split
 * coordinates gx, gy: from the texel window where it holds them, else gathered. */
INLINE void bilinear_fetch16(const tex16 *tx, __m512i gx, __m512i gy, __mmask16 m, const int repeat,
                             const int least, __m512i t[4]) {
    __m512i a = _mm512_srai_epi32(gx, 8);
    if (window_fetch(tx, a, _mm512_srai_epi32(gy, 8), m, least, &t[0], &t[1], &t[2], &t[3])) return;
    __m512i i0, i1, j0, j1;
    bilinear_wrap(gx, tx->n_x, tx->last_x, repeat, &i0, &i1);
    bilinear_wrap(gy, tx->n_y, tx->last_y, repeat, &j0, &j1);
    __m512i r0 = row_start(j0, tx), r1 = row_start(j1, tx);
    /* Where no pixel of the mask has a split column outside [0, n - 2], i1 = i0 + 1 for every
     * wrap mode and columns i0 and i1 are adjacent in memory: one 64-bit gather fetches both, half
     * the loads (64-bit gathers of 8 cost about as much as 32-bit ones of 16, per element). */
    if (_mm512_mask_cmplt_epu32_mask(m, a, tx->last_x) == m) {
        pair_fetch(tx, _mm512_add_epi32(r0, a), m, &t[0], &t[1]);
        pair_fetch(tx, _mm512_add_epi32(r1, a), m, &t[2], &t[3]);
    } else {
        t[0] = fetch16(tx, _mm512_add_epi32(r0, i0), m);
        t[1] = fetch16(tx, _mm512_add_epi32(r0, i1), m);
        t[2] = fetch16(tx, _mm512_add_epi32(r1, i0), m);
        t[3] = fetch16(tx, _mm512_add_epi32(r1, i1), m);
    }
}

/* bilinear8's filter (shade_avx2.c) on a whole tile: x[k] gets channel k in bits 16 to 23 of
 * each lane. */
INLINE void bilinear_filter16(__m512i gx, __m512i gy, const __m512i t[4], __m512i x[4]) {
    const __m512i lo8 = _mm512_set1_epi32(0x00ff00ff);
    const __m512i bias = _mm512_set1_epi32((int)0x80008000u);
    const __m512i w256 = _mm512_set1_epi16(256);
    const __m512i round = _mm512_set1_epi32(128 * 65536 + 32768);
    __m512i fy2 = frac2(gy), fx2 = frac2(gx);
    __m512i gy2 = _mm512_sub_epi16(w256, fy2);
    __m512i wx = _mm512_mask_blend_epi16(HI16, _mm512_sub_epi16(w256, fx2), fx2);
#define SG_VBLEND(a, b)                                                                            \
    _mm512_xor_si512(_mm512_add_epi16(_mm512_mullo_epi16(a, gy2), _mm512_mullo_epi16(b, fy2)), bias)
    __m512i rb0 = SG_VBLEND(_mm512_and_si512(t[0], lo8), _mm512_and_si512(t[2], lo8));
    __m512i rb1 = SG_VBLEND(_mm512_and_si512(t[1], lo8), _mm512_and_si512(t[3], lo8));
    __m512i ga0 = SG_VBLEND(_mm512_srli_epi16(t[0], 8), _mm512_srli_epi16(t[2], 8));
    __m512i ga1 = SG_VBLEND(_mm512_srli_epi16(t[1], 8), _mm512_srli_epi16(t[3], 8));
#undef SG_VBLEND
#define SG_HBLEND(v) _mm512_add_epi32(_mm512_madd_epi16(v, wx), round)
    x[0] = SG_HBLEND(_mm512_mask_blend_epi16(HI16, rb0, _mm512_slli_epi32(rb1, 16)));
    x[1] = SG_HBLEND(_mm512_mask_blend_epi16(HI16, ga0, _mm512_slli_epi32(ga1, 16)));
    x[2] = SG_HBLEND(_mm512_mask_blend_epi16(HI16, _mm512_srli_epi32(rb0, 16), rb1));
    x[3] = SG_HBLEND(_mm512_mask_blend_epi16(HI16, _mm512_srli_epi32(ga0, 16), ga1));
#undef SG_HBLEND
}

/* bilinear8 of shade_avx2.c on a whole tile: x[k] gets channel k in bits 16 to 23 of each lane. */
INLINE void bilinear16(const tex16 *tx, __m512 s, __m512 u, __mmask16 m, const int repeat,
                       const int least, __m512i x[4]) {
    __m512i gx = bilinear_split(s, tx->scale_x, tx->hi_x, repeat);
    __m512i gy = bilinear_split(u, tx->scale_y, tx->hi_y, repeat);
    __m512i t[4];
    bilinear_fetch16(tx, gx, gy, m, repeat, least, t);
    bilinear_filter16(gx, gy, t, x);
}

INLINE void unpack_texels(__m512i t, __m512i c[4]) {
    const __m512i lo8 = _mm512_set1_epi32(255);
    c[0] = _mm512_and_si512(t, lo8);
    c[1] = _mm512_and_si512(_mm512_srli_epi32(t, 8), lo8);
    c[2] = _mm512_and_si512(_mm512_srli_epi32(t, 16), lo8);
    c[3] = _mm512_srli_epi32(t, 24);
}

/* Channel k (0 .. 255) of each lane of m in c[k] (others may be 0): nearest or bilinear. */
INLINE void lookup16(const sg_texview *tv, __m512 s, __m512 u, __mmask16 m, const int bilinear,
                     const int repeat, const int least, const bool window, __m512i c[4]) {
    const tex16 tx = tex16_of(tv, bilinear, window);
    if (bilinear) { /* repeat as a constant in each call, where a caller's is not */
        __m512i x[4];
        if (repeat)
            bilinear16(&tx, s, u, m, 1, least, x);
        else
            bilinear16(&tx, s, u, m, 0, least, x);
        for (int k = 0; k < 4; k++) c[k] = _mm512_srli_epi32(x[k], 16);
    } else {
        unpack_texels(repeat ? nearest16(&tx, s, u, m, 1) : nearest16(&tx, s, u, m, 0), c);
    }
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
#error "unpack_texels and the filter read channel 0 from the low byte"
#endif
}

/* Mipmapped lookups (tex/mip.h), for the textured kinds SG_TEX_MIP and SG_TEX_MIP_LINEAR. */

/* sg_mip_select of a tile's four 2 x 2 quads at once, each lane taking its quad's (lanes 0, 1, 4,
 * 5 are the first quad): the same operations on the same values, so the same levels and
 * weights. */
INLINE void mip16_pick(const sg_mip_chain *m, __m512 s, __m512 u, const int linear, __m512i *l0,
                       __m512i *l1, __m512i *f) {
    const __m512i base = _mm512_setr_epi32(0, 0, 2, 2, 0, 0, 2, 2, 8, 8, 10, 10, 8, 8, 10, 10);
    const __m512i one = _mm512_set1_epi32(1);
    const __m512i right = _mm512_add_epi32(base, one),
                  down = _mm512_add_epi32(base, _mm512_set1_epi32(4));
    const __m512 s0 = _mm512_permutexvar_ps(base, s), u0 = _mm512_permutexvar_ps(base, u);
    const __m512 w = _mm512_set1_ps(m->level[0].size.scale[0][0]); /* (float) width */
    const __m512 h = _mm512_set1_ps(m->level[0].size.scale[0][1]);
    const __m512 ax = _mm512_mul_ps(_mm512_sub_ps(_mm512_permutexvar_ps(right, s), s0), w);
    const __m512 bx = _mm512_mul_ps(_mm512_sub_ps(_mm512_permutexvar_ps(right, u), u0), h);
    const __m512 ay = _mm512_mul_ps(_mm512_sub_ps(_mm512_permutexvar_ps(down, s), s0), w);
    const __m512 by = _mm512_mul_ps(_mm512_sub_ps(_mm512_permutexvar_ps(down, u), u0), h);
    const __m512 rx = _mm512_add_ps(_mm512_mul_ps(ax, ax), _mm512_mul_ps(bx, bx));
    const __m512 ry = _mm512_add_ps(_mm512_mul_ps(ay, ay), _mm512_mul_ps(by, by));
    /* rx > ry ? rx : ry (ry when either is NaN) */
    const __m512 rho2 = _mm512_mask_blend_ps(_mm512_cmp_ps_mask(rx, ry, _CMP_GT_OQ), ry, rx);
    const __m512i bits = _mm512_castps_si512(rho2);
    const __m512i e =
        _mm512_sub_epi32(_mm512_and_si512(_mm512_srli_epi32(bits, 23), _mm512_set1_epi32(0xff)),
                         _mm512_set1_epi32(127));
    const __m512i zero = _mm512_setzero_si512(), last = _mm512_set1_epi32(m->levels - 1);
    if (!linear) { /* round(log2 rho) = (exponent + 1) >> 1, arithmetic */
        const __m512i l = _mm512_srai_epi32(_mm512_add_epi32(e, one), 1);
        *l0 = *l1 = _mm512_min_epi32(_mm512_max_epi32(l, zero), last);
        *f = zero;
        return;
    }
    const __m512 mant = _mm512_castsi512_ps(_mm512_or_si512(
        _mm512_and_si512(bits, _mm512_set1_epi32(0x007fffff)), _mm512_set1_epi32(0x3f800000)));
    const __m512 lod = _mm512_mul_ps(
        _mm512_add_ps(_mm512_cvtepi32_ps(_mm512_sub_epi32(e, one)), mant), _mm512_set1_ps(0.5f));
    const __m512 fl = _mm512_roundscale_ps(lod, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC);
    const __mmask16 finite = _mm512_cmp_ps_mask(lod, _mm512_set1_ps(-1e9f), _CMP_GE_OQ) &
                             _mm512_cmp_ps_mask(lod, _mm512_set1_ps(1e9f), _CMP_LE_OQ);
    const __m512i i = _mm512_maskz_cvttps_epi32(finite, fl);
    const __m512 frac = _mm512_maskz_sub_ps(finite, lod, fl);
    /* below level 0 or from the last level on: one level, weight 0 */
    const __mmask16 low = _mm512_cmplt_epi32_mask(i, zero),
                    high = _mm512_cmpge_epi32_mask(i, last) & (__mmask16)~low,
                    two = (__mmask16) ~(low | high);
    *l0 = _mm512_mask_mov_epi32(_mm512_maskz_mov_epi32(two, i), high, last);
    *l1 = _mm512_mask_mov_epi32(_mm512_maskz_mov_epi32(two, _mm512_add_epi32(i, one)), high, last);
    *f = _mm512_maskz_cvttps_epi32(two, _mm512_mul_ps(frac, _mm512_set1_ps(256.0f)));
}

/* sg_sample_mip in every lane, with the levels l0, l1 and weight f of its lane (0 .. 255): each
 * level the lanes read is looked up once, for the lanes that take it (a lane whose second level
 * weighs 0 does not read that level: its blend gives the first level's texel). Channels in c[k]. */
INLINE void mip16_lookup(const sg_mip_chain *m, __m512i l0, __m512i l1, __m512i f, __m512 s,
                         __m512 u, const int bilinear, const int repeat, const bool window,
                         __m512i c[4]) {
    const __mmask16 weighed = _mm512_test_epi32_mask(f, f);
    const __m512i one = _mm512_set1_epi32(1);
    const __m512i bits =
        _mm512_mask_or_epi32(_mm512_sllv_epi32(one, l0), weighed, _mm512_sllv_epi32(one, l0),
                             _mm512_sllv_epi32(one, l1));
    uint32_t want = (uint32_t)_mm512_reduce_or_epi32(bits);
    /* Every weight 0 (nearest mipmaps, magnified tiles): each lane's first level's texel, which
     * the blend below would give; and with one level for all, that level's lookup as it is. */
    if (!weighed && !(want & (want - 1))) {
        lookup16(&m->level[__builtin_ctz(want)], s, u, 0xffff, bilinear, repeat, 0, window, c);
        return;
    }
    __m512i a[4], b[4];
    for (int k = 0; k < 4; k++) a[k] = b[k] = _mm512_setzero_si512();
    for (; want; want &= want - 1) {
        const int level = __builtin_ctz(want);
        const __m512i lv = _mm512_set1_epi32(level);
        const __mmask16 in0 = _mm512_cmpeq_epi32_mask(l0, lv),
                        in1 = _mm512_cmpeq_epi32_mask(l1, lv);
        __m512i t[4];
        lookup16(&m->level[level], s, u, in0 | (in1 & weighed), bilinear, repeat, 0, window, t);
        for (int k = 0; k < 4; k++) {
            a[k] = _mm512_mask_blend_epi32(in0, a[k], t[k]);
            b[k] = _mm512_mask_blend_epi32(in1, b[k], t[k]);
        }
    }
    for (int k = 0; k < 4; k++) {
        if (!weighed) {
            c[k] = a[k];
            continue;
        }
        const __m512i d = _mm512_mullo_epi32(_mm512_sub_epi32(b[k], a[k]), f);
        c[k] = _mm512_add_epi32(a[k], _mm512_srai_epi32(d, 8));
    }
}

/* The levels and weights (mip16_pick) of the pixels of `mask` of a tile at (s, u), as shade_mip.c
 * takes them: a quad without a covered pixel takes a covered quad's, so that it reads no level of
 * its own. */
INLINE void mip16_levels(const sg_mip_chain *m, __m512 s, __m512 u, uint32_t mask, const int linear,
                         __m512i *l0p, __m512i *l1p, __m512i *fp) {
    __m512i l0, l1, f;
    mip16_pick(m, s, u, linear, &l0, &l1, &f);
    uint32_t quads = 0;
    for (int q = 0; q < 4; q++) {
        const uint32_t lanes = 0x33u << ((q & 1) * 2 + (q >> 1) * 8);
        if (mask & lanes) quads |= lanes;
    }
    if (quads != 0xffffu && quads) {
        const __m512i lane = _mm512_set1_epi32(__builtin_ctz(quads));
        l0 = _mm512_mask_mov_epi32(_mm512_permutexvar_epi32(lane, l0), (__mmask16)quads, l0);
        l1 = _mm512_mask_mov_epi32(_mm512_permutexvar_epi32(lane, l1), (__mmask16)quads, l1);
        f = _mm512_mask_mov_epi32(_mm512_permutexvar_epi32(lane, f), (__mmask16)quads, f);
    }
    *l0p = l0;
    *l1p = l1;
    *fp = f;
}

/* Four channels in bits 16 to 23 of their lanes, zeros above, to RGBA8. */
INLINE __m512i pack_hi8(const __m512i x[4]) {
    __m512i rb = _mm512_mask_blend_epi16(HI16, _mm512_srli_epi32(x[0], 16), x[2]);
    __m512i ga = _mm512_mask_blend_epi16(HI16, _mm512_srli_epi32(x[1], 16), x[3]);
    return _mm512_or_si512(rb, _mm512_slli_epi32(ga, 8));
}

/* sg_to_unorm8 but the clamp to [0, 255], left to pack_unorm8 (see shade_avx2.c). */
INLINE __m512i unorm8(__m512 v) {
    v = _mm512_min_ps(_mm512_set1_ps(1.0f), v); /* the second operand, v, when it is NaN */
    return _mm512_cvttps_epi32(
        _mm512_add_ps(_mm512_mul_ps(v, _mm512_set1_ps(255.0f)), _mm512_set1_ps(0.5f)));
}

/* Planar float colours to RGBA8: each 128-bit lane is one row, packed as in shade_avx2.c. */
INLINE __m512i pack_unorm8(const __m512 col[4]) {
    __m512i p01 = _mm512_packs_epi32(unorm8(col[0]), unorm8(col[1]));
    __m512i p23 = _mm512_packs_epi32(unorm8(col[2]), unorm8(col[3]));
    const __m512i tr = _mm512_set4_epi32(0x0f0b0703, 0x0e0a0602, 0x0d090501, 0x0c080400);
    return _mm512_shuffle_epi8(_mm512_packus_epi16(p01, p23), tr);
}

/* The texturing step of shade16_tiles: the texels at coordinates (s[i], u[i]) of n tiles' pixels,
 * lanes of mask[i] (textured: 1, or a mipmap chain, SG_TEX_MIP*), modulate their colours col[i];
 * an opaque white triangle without a secondary colour takes the texel as it is, and then out[i] is
 * the result already (true). */
INLINE bool texture16_tiles(const sg_shade_ctx *c, const int n, const __m512 s[], const __m512 u[],
                            const uint32_t mask[], __m512 col[][4], __m512i out[],
                            const int textured, const int bilinear, const int repeat,
                            const int flat, const int sec) {
    const tex16 tx = tex16_of(&c->tex, bilinear, true); /* see sg_shade_ctx.texel_window */
    __m512i tc[4][4];
    if (textured >= SG_TEX_MIP) {
        /* every tile's levels first: their chains of dependent steps side by side */
        __m512i l0[4], l1[4], f[4];
        for (int i = 0; i < n; i++)
            mip16_levels(c->mips, s[i], u[i], mask[i], textured == SG_TEX_MIP_LINEAR, &l0[i],
                         &l1[i], &f[i]);
        for (int i = 0; i < n; i++)
            mip16_lookup(c->mips, l0[i], l1[i], f[i], s[i], u[i], bilinear, repeat, c->texel_window,
                         tc[i]);
        if (flat == SG_FLAT_WHITE && !sec) { /* the texel, as in shade_mip.c */
            for (int i = 0; i < n; i++)
                out[i] = _mm512_or_si512(_mm512_or_si512(tc[i][0], _mm512_slli_epi32(tc[i][1], 8)),
                                         _mm512_or_si512(_mm512_slli_epi32(tc[i][2], 16),
                                                         _mm512_slli_epi32(tc[i][3], 24)));
            return true;
        }
    } else if (bilinear) {
        __m512i gx[4], gy[4], texels[4][4], x[4][4];
        for (int i = 0; i < n; i++) {
            gx[i] = bilinear_split(s[i], tx.scale_x, tx.hi_x, repeat);
            gy[i] = bilinear_split(u[i], tx.scale_y, tx.hi_y, repeat);
        }
        for (int i = 0; i < n; i++)
            bilinear_fetch16(&tx, gx[i], gy[i], (__mmask16)mask[i], repeat, 0, texels[i]);
        for (int i = 0; i < n; i++) bilinear_filter16(gx[i], gy[i], texels[i], x[i]);
        if (flat == SG_FLAT_WHITE && !sec) {
            for (int i = 0; i < n; i++) out[i] = pack_hi8(x[i]);
            return true;
        }
        for (int i = 0; i < n; i++)
            for (int k = 0; k < 4; k++) tc[i][k] = _mm512_srli_epi32(x[i][k], 16);
    } else {
        __m512i texel[4];
        for (int i = 0; i < n; i++)
            texel[i] = nearest16(&tx, s[i], u[i], (__mmask16)mask[i], repeat);
        if (flat == SG_FLAT_WHITE && !sec) { /* the colour, as in the reference */
            for (int i = 0; i < n; i++) out[i] = texel[i];
            return true;
        }
        for (int i = 0; i < n; i++) unpack_texels(texel[i], tc[i]);
    }
    for (int i = 0; i < n; i++)
        for (int k = 0; k < 4; k++)
            col[i][k] = _mm512_mul_ps(col[i][k], _mm512_mul_ps(_mm512_cvtepi32_ps(tc[i][k]),
                                                               _mm512_set1_ps(1.0f / 255.0f)));
    return false;
}

/* The colours of n tiles' pixels (n is 1, 2 or 4, a constant) at offsets (dx[i], dy[i]) from the
 * triangle's bounds, lanes of mask[i], as RGBA8 lanes in out[i] (others undefined): the body of
 * every variant, as shade_rows in shade.c; the constant arguments fold away. Each lane computes
 * what the reference computes for its pixel, wherever that pixel is. The tiles go through each
 * step together (planes, then texel coordinates, then fetches, then filters): a tile's steps
 * form one long chain of dependent operations, and two chains side by side keep the vector
 * units busy where one waits (a floor shades a sixth faster two tiles at a time; the blend's
 * jobs go four at a time). With ts, tile i is triangle ts[i]'s (the blend's jobs of several
 * triangles), else every tile is t's. */
INLINE void shade16_tiles(const sg_shade_ctx *c, const sg_tri *t, const sg_tri *const ts[],
                          const sg_tri_ext *ext, const int n, const __m512 dx[], const __m512 dy[],
                          const uint32_t mask[], __m512i out[], const int textured,
                          const int bilinear, const int repeat, const int flat, const int sec) {
    const int e = SG_LIT_SEC - SG_TRI_ATTRS; /* the secondary colour in ext */
    if (!textured && flat != SG_FLAT_NONE) {
        float f[4] = {t->color[0], t->color[1], t->color[2], t->color[3]};
        if (sec)
            for (int k = 0; k < 3; k++) f[k] += ext->a[e + k];
        uint32_t px = sg_pack_rgba8(sg_to_unorm8(f[0]), sg_to_unorm8(f[1]), sg_to_unorm8(f[2]),
                                    sg_to_unorm8(f[3]));
        for (int i = 0; i < n; i++) out[i] = _mm512_set1_epi32((int)px);
        return;
    }
/* Set i's triangle: ts[i] when given (the blend's jobs of several triangles), else t. */
#define SG_T(i) (ts ? ts[i] : t)
#define SG_PLANE(a, adx, ady, i)                                                                   \
    _mm512_add_ps(_mm512_add_ps(_mm512_set1_ps(a), _mm512_mul_ps(_mm512_set1_ps(adx), dx[i])),     \
                  _mm512_mul_ps(_mm512_set1_ps(ady), dy[i]))
    __m512 w[4], col[4][4];
    for (int i = 0; i < n; i++)
        w[i] = _mm512_div_ps(_mm512_set1_ps(1.0f),
                             SG_PLANE(SG_T(i)->q, SG_T(i)->q_dx, SG_T(i)->q_dy, i));
    for (int i = 0; i < n; i++)
        for (int k = 0; k < 4; k++)
            col[i][k] =
                flat != SG_FLAT_NONE
                    ? _mm512_set1_ps(SG_T(i)->color[k])
                    : _mm512_mul_ps(SG_PLANE(SG_T(i)->a[k], SG_T(i)->a_dx[k], SG_T(i)->a_dy[k], i),
                                    w[i]);
    if (textured) {
        __m512 s[4], u[4];
        for (int i = 0; i < n; i++) {
            s[i] =
                _mm512_mul_ps(SG_PLANE(SG_T(i)->a[4], SG_T(i)->a_dx[4], SG_T(i)->a_dy[4], i), w[i]);
            u[i] =
                _mm512_mul_ps(SG_PLANE(SG_T(i)->a[5], SG_T(i)->a_dx[5], SG_T(i)->a_dy[5], i), w[i]);
        }
        if (texture16_tiles(c, n, s, u, mask, col, out, textured, bilinear, repeat, flat, sec))
            return;
    }
    for (int i = 0; i < n; i++)
        for (int k = 0; sec && k < 3; k++)
            col[i][k] = _mm512_add_ps(
                col[i][k],
                flat != SG_FLAT_NONE
                    ? _mm512_set1_ps(ext->a[e + k])
                    : _mm512_mul_ps(SG_PLANE(ext->a[e + k], ext->a_dx[e + k], ext->a_dy[e + k], i),
                                    w[i]));
#undef SG_T
#undef SG_PLANE
    for (int i = 0; i < n; i++) out[i] = pack_unorm8(col[i]);
}

/* The colours of the pixels at offsets (dx, dy) from the triangle's bounds, lanes of `mask`, as
 * RGBA8 lanes (others undefined): shade16_tiles on one tile. */
INLINE __m512i sg_shade16_at(const sg_shade_ctx *c, const sg_tri *t, const sg_tri_ext *ext,
                             __m512 dx, __m512 dy, uint32_t mask, const int textured,
                             const int bilinear, const int repeat, const int flat, const int sec) {
    __m512i out;
    shade16_tiles(c, t, NULL, ext, 1, &dx, &dy, &mask, &out, textured, bilinear, repeat, flat, sec);
    return out;
}

/* Up to sixteen pixels of a triangle waiting to be shaded together (a partly covered tile fills
 * few lanes, and the shading costs the same for 1 pixel as for 16): their offsets from the
 * triangle's bounds and in the bin's colour, lanes 0 to n - 1. */
typedef struct sg_queue16 {
    __m512 dx, dy;
    __m512i off;
    int n;
} sg_queue16;

/* Appends the pixels of mask of a tile (offsets dx, dy; colour at bin offset base) to q: packed,
 * then rotated to start at lane n. When that fills the queue, full gets the sixteen lanes to
 * shade and q keeps the rest; true then. */
INLINE bool sg_enqueue16(sg_queue16 *q, __m512 dx, __m512 dy, int base, __mmask16 mask,
                         sg_queue16 *full) {
    const __m512i lane = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
    const int n = q->n, k = __builtin_popcount(mask);
    /* Lane j takes packed pixel (j - n) mod 16: the first 16 - n go after the queue's n, the ones
     * that do not fit into lanes 0 to n + k - 17. */
    __m512i from =
        _mm512_and_si512(_mm512_sub_epi32(lane, _mm512_set1_epi32(n)), _mm512_set1_epi32(15));
    __m512 rdx = _mm512_permutexvar_ps(from, _mm512_maskz_compress_ps(mask, dx));
    __m512 rdy = _mm512_permutexvar_ps(from, _mm512_maskz_compress_ps(mask, dy));
    __m512i roff = _mm512_permutexvar_epi32(
        from, _mm512_maskz_compress_epi32(mask, _mm512_add_epi32(_mm512_set1_epi32(base), lane)));
    const __mmask16 keep = (__mmask16)((1u << n) - 1u);
    sg_queue16 merged = {_mm512_mask_mov_ps(rdx, keep, q->dx), _mm512_mask_mov_ps(rdy, keep, q->dy),
                         _mm512_mask_mov_epi32(roff, keep, q->off), n + k};
    if (n + k < 16) {
        *q = merged;
        return false;
    }
    *full = merged;
    *q = (sg_queue16){rdx, rdy, roff, n + k - 16};
    return true;
}

/* A mipmapped triangle's partly covered tiles: their 2 x 2 quads that hold a covered pixel,
 * packed four to a vector, each quad's four pixels (its level of detail needs them all) in the
 * lanes a quad of a tile has (mip16_pick), with their offsets from the triangle's bounds and in
 * the bin's colour; the covered ones in mask. */
typedef struct sg_quad_queue {
    __m512 dx, dy;
    __m512i off;
    uint32_t mask;
    int n; /* quads held */
} sg_quad_queue;

/* Whether every quad of a tile holds a pixel of mask (then the tile is shaded as it is). */
INLINE bool sg_every_quad(uint32_t mask) {
    return (mask & 0x0033u) && (mask & 0x00ccu) && (mask & 0x3300u) && (mask & 0xcc00u);
}

/* Appends the quads of a tile (offsets dx, dy; colour at bin offset base) that hold a pixel of
 * mask, not all of them, to q. When four are there, full gets them and q starts again with the
 * rest; true then (once at most: a tile adds three quads at most). */
INLINE bool sg_enqueue_quads(sg_quad_queue *q, __m512 dx, __m512 dy, int base, uint32_t mask,
                             sg_quad_queue *full) {
    const __m512i lane = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
    const __m512i off = _mm512_add_epi32(_mm512_set1_epi32(base), lane);
    bool filled = false;
    for (int k = 0; k < 4; k++) {
        const int from = (k & 1) * 2 + (k >> 1) * 8; /* quad k's first lane */
        const uint32_t bits = mask >> from & 0x33u;
        if (!bits) continue;
        const int to = (q->n & 1) * 2 + (q->n >> 1) * 8;
        const __mmask16 lanes = (__mmask16)(0x33u << to);
        const __m512i idx = _mm512_add_epi32(lane, _mm512_set1_epi32(from - to));
        q->dx = _mm512_mask_permutexvar_ps(q->dx, lanes, idx, dx);
        q->dy = _mm512_mask_permutexvar_ps(q->dy, lanes, idx, dy);
        q->off = _mm512_mask_permutexvar_epi32(q->off, lanes, idx, off);
        q->mask |= bits << to;
        if (++q->n == 4) {
            *full = *q;
            q->n = 0;
            q->mask = 0;
            filled = true;
        }
    }
    return filled;
}

/* sg_shade16_at for the pixels of `mask` of the tile at (x0, y0), lane y * 4 + x. */
INLINE __m512i sg_shade16(const sg_shade_ctx *c, const sg_tri *t, const sg_tri_ext *ext, int x0,
                          int y0, uint32_t mask, const int textured, const int bilinear,
                          const int repeat, const int flat, const int sec) {
    __m512 dx, dy;
    sg_tile_dxdy16(t, x0, y0, &dx, &dy);
    return sg_shade16_at(c, t, ext, dx, dy, mask, textured, bilinear, repeat, flat, sec);
}

/* The colours of `count` (1 or 2, a constant) tiles' pixels that several triangles of one draw
 * share (sg_mixed_tile), as RGBA8 lanes in out[i] (lanes outside `all[i]`, the union of tile i's
 * masks, undefined); every triangle has the flat kind `flat`. Each lane takes its own triangle's
 * values where shade16_tiles broadcasts one triangle's, and goes through the same operations, so
 * a lane's bytes are those of its triangle's shading; the tiles go through each step together, as
 * in shade16_tiles. The lanes outside `all` take the tile's first triangle's values, which keeps
 * them near the others (the texel window of bilinear_fetch16 starts at lane 0). */
INLINE void sg_shade16_mixed(const sg_shade_ctx *c, const sg_mixed_tile *tiles, const int count,
                             const uint32_t all[], __m512i out[], const int textured,
                             const int bilinear, const int repeat, const int flat) {
    if (!textured && flat != SG_FLAT_NONE) { /* each triangle's colour, as shade16_tiles packs it */
        for (int i = 0; i < count; i++) {
            out[i] = _mm512_setzero_si512();
            for (int j = 0; j < tiles[i].n; j++) {
                const float *f = tiles[i].ts[j]->color;
                uint32_t px = sg_pack_rgba8(sg_to_unorm8(f[0]), sg_to_unorm8(f[1]),
                                            sg_to_unorm8(f[2]), sg_to_unorm8(f[3]));
                out[i] = _mm512_mask_mov_epi32(out[i], (__mmask16)tiles[i].masks[j],
                                               _mm512_set1_epi32((int)px));
            }
        }
        return;
    }
    /* Per lane: its triangle's offset from the tile to the triangle's bounds, and its planes. */
    __m512 v[2][SG_MIX_VALUES];
#define SG_SET(f, x)   v[i][f] = _mm512_set1_ps(x)
#define SG_MERGE(f, x) v[i][f] = _mm512_mask_mov_ps(v[i][f], m, _mm512_set1_ps(x))
    for (int i = 0; i < count; i++) {
        const int x0 = tiles[i].x0, y0 = tiles[i].y0;
        SG_MIXED_VALUES(tiles[i].ts[0], x0, y0, flat, textured, SG_SET);
        for (int j = 1; j < tiles[i].n; j++) {
            const __mmask16 m = (__mmask16)tiles[i].masks[j];
            SG_MIXED_VALUES(tiles[i].ts[j], x0, y0, flat, textured, SG_MERGE);
        }
    }
#undef SG_SET
#undef SG_MERGE
    /* Lane i of a tile is its column i % 4, row i / 4 (as sg_tile_dxdy16). */
    const __m512 lane_x = _mm512_set4_ps(3.0f, 2.0f, 1.0f, 0.0f);
    const __m512 lane_y = _mm512_setr_ps(0.0f, 0.0f, 0.0f, 0.0f, 1.0f, 1.0f, 1.0f, 1.0f, 2.0f, 2.0f,
                                         2.0f, 2.0f, 3.0f, 3.0f, 3.0f, 3.0f);
    __m512 dx[2], dy[2], w[2], col[2][4], s[2], u[2];
    SG_MIXED_PLANES(_mm512_add_ps, _mm512_mul_ps, _mm512_div_ps, _mm512_set1_ps, count, v, lane_x,
                    lane_y, dx, dy, w, col, s, u, flat, textured);
    if (textured &&
        texture16_tiles(c, count, s, u, all, col, out, textured, bilinear, repeat, flat, 0))
        return;
    for (int i = 0; i < count; i++) out[i] = pack_unorm8(col[i]);
}

#endif
#endif
