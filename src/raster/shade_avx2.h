/* shade_avx2.h - the AVX2 shading helpers (internal to the raster; included only by files
 * compiled with -mavx2, no FMA): texel fetches with gathers, bilinear filtering in exact integer
 * arithmetic on 16-bit lanes, and float colours to RGBA8, eight pixels a vector (two rows of a
 * tile). shade_avx2.c makes the shading table of them, shade_phong_avx2.c the per-pixel lighting,
 * blend_avx2.c inlines shade8_sets into the raster functions of blended draws.
 * Each computes the scalar reference's operations (shade.c, sample.h) in the same order.
 */
#ifndef SG_SHADE_AVX2_H
#define SG_SHADE_AVX2_H

#include <float.h>
#include <string.h>

#include "raster/shade.h"
#include "raster/shade_mixed.h"

/* FLT_EVAL_METHOD 0: the scalar code rounds each operation to float, as AVX does. */
#if (defined(__x86_64__) || defined(__i386__)) && defined(__AVX2__) && FLT_EVAL_METHOD == 0
#define SG_SHADE_AVX2 1

#include <immintrin.h>

#include "raster/framebuffer.h"

/* Texel rows and row * width are computed in 16-bit lanes (pmaddwd). */
_Static_assert(SG_MAX_IMAGE_SIZE < 32768, "texture sides must fit signed 16 bits");

#define INLINE static inline __attribute__((always_inline))

/* The bound texture, broadcast; "scale" is the size the texcoord functions multiply by (n, or
 * 256 n when bilinear) and "hi" the clamp's upper limit (n - 1 texels, or 256 (n + 1)). */
typedef struct tex8 {
    const int *texels;
    int width, height;
    __m256 scale_x, scale_y, hi_x, hi_y;
    __m256i n_x, n_y, last_x, last_y; /* n and n - 1 */
} tex8;

/* sg_texcoord_repeat: vroundps is floorf exactly (NaN and infinities included), and max turns the
 * NaN that NaN and infinite s give into 0, as the reference's x >= 0 test does. */
INLINE __m256 coord_repeat(__m256 s, __m256 scale) {
    __m256 x = _mm256_mul_ps(_mm256_sub_ps(s, _mm256_floor_ps(s)), scale);
    return _mm256_max_ps(x, _mm256_setzero_ps());
}

/* Column (or row) of sg_sample_nearest. Repeat: x is in [0, n], so truncation is floor and only n
 * wraps. Clamp: flooring then clamping to [0, n - 1] is clamping then truncating, and the clamp to
 * [-1, 2] before the scaling changes nothing after it; max turns NaN into 0 as the reference does
 * (NaN -> -1 -> -n -> 0). */
INLINE __m256i nearest_index(__m256 s, __m256 scale, __m256 hi, __m256i n, __m256i last,
                             const int repeat) {
    if (repeat) {
        __m256i i = _mm256_cvttps_epi32(coord_repeat(s, scale));
        return _mm256_sub_epi32(i, _mm256_and_si256(_mm256_cmpgt_epi32(i, last), n));
    }
    __m256 x = _mm256_max_ps(_mm256_mul_ps(s, scale), _mm256_setzero_ps());
    return _mm256_cvttps_epi32(_mm256_min_ps(x, hi));
}

/* The split of sg_sample_bilinear: g = floor(x) - 128, whose low byte is the 8-bit fraction and
 * g >> 8 the column (or row) i0, the reference's split without its +512. Clamp: the reference
 * clamps s to [-1, 2] and then x to [-256, 256 (n + 1)], which is x = s * 256 n clamped to the
 * latter alone (NaN -> -256 with max). */
INLINE __m256i bilinear_split(__m256 s, __m256 scale, __m256 hi, const int repeat) {
    __m256i fl;
    if (repeat) {
        fl = _mm256_cvttps_epi32(coord_repeat(s, scale)); /* x >= 0: truncation is floor */
    } else {
        __m256 x = _mm256_max_ps(_mm256_mul_ps(s, scale), _mm256_set1_ps(-256.0f));
        /* Truncation, not floor: where they differ (x < 0) i0 and i1 both clamp to 0, and the
         * fraction then only weighs a texel against itself. */
        fl = _mm256_cvttps_epi32(_mm256_min_ps(x, hi));
    }
    return _mm256_sub_epi32(fl, _mm256_set1_epi32(128));
}

/* i0 and i1 = i0 + 1 of a split, wrapped. Repeat: x >= 0, so i0 is in [-1, n - 1] and i1 in
 * [0, n]; an unsigned min with i0 + n (i1 - n) wraps -1 (n) and keeps the rest. */
INLINE void bilinear_wrap(__m256i g, __m256i n, __m256i last, const int repeat, __m256i *i0,
                          __m256i *i1) {
    __m256i a = _mm256_srai_epi32(g, 8), b = _mm256_add_epi32(a, _mm256_set1_epi32(1));
    if (repeat) {
        *i0 = _mm256_min_epu32(a, _mm256_add_epi32(a, n));
        *i1 = _mm256_min_epu32(b, _mm256_sub_epi32(b, n));
    } else {
        *i0 = _mm256_min_epi32(_mm256_max_epi32(a, _mm256_setzero_si256()), last);
        *i1 = _mm256_min_epi32(_mm256_max_epi32(b, _mm256_setzero_si256()), last);
    }
}

/* The fraction of a split (the low byte of g) in both 16-bit halves of its lane. */
INLINE __m256i frac2(__m256i g) {
    const __m256i dup = _mm256_setr_epi8(0, -1, 0, -1, 4, -1, 4, -1, 8, -1, 8, -1, 12, -1, 12, -1,
                                         0, -1, 0, -1, 4, -1, 4, -1, 8, -1, 8, -1, 12, -1, 12, -1);
    return _mm256_shuffle_epi8(g, dup);
}

/* Index of the first texel of row j counted from the bottom (sg_texel_at): (n_y - 1 - j) * width
 * with one pmaddwd (faster than pmulld), both factors being below 2^15 in the low half of a lane.
 */
INLINE __m256i row_start(__m256i j, const tex8 *tx) {
    return _mm256_madd_epi16(_mm256_sub_epi32(tx->last_y, j), tx->n_x);
}

/* base[idx] of the eight lanes: eight plain loads put together, which cost about half what a
 * gather of eight does (docs/performance.md). */
INLINE __m256i sg_load8(const int *base, __m256i idx) {
    _Alignas(32) int at[8];
    _mm256_store_si256((__m256i *)(void *)at, idx);
    __m128i lo = _mm_cvtsi32_si128(base[at[0]]), hi = _mm_cvtsi32_si128(base[at[4]]);
    lo = _mm_insert_epi32(lo, base[at[1]], 1);
    hi = _mm_insert_epi32(hi, base[at[5]], 1);
    lo = _mm_insert_epi32(lo, base[at[2]], 2);
    hi = _mm_insert_epi32(hi, base[at[6]], 2);
    lo = _mm_insert_epi32(lo, base[at[3]], 3);
    hi = _mm_insert_epi32(hi, base[at[7]], 3);
    return _mm256_inserti128_si256(_mm256_castsi128_si256(lo), hi, 1);
}

/* Every lane's index is inside the texture, whatever its coordinates, so lanes outside the mask
 * need not be masked off. */
INLINE __m256i fetch8(const tex8 *tx, __m256i idx) {
    return sg_load8(tx->texels, idx);
}

/* Texels idx0, idx0 + 1 (row pair 0) and idx1, idx1 + 1 (row pair 1) of each of the eight lanes,
 * as t[0] to t[3]: a 64-bit load of each pair, both pairs of a lane in one 128-bit half, then a
 * 4 x 4 transpose of 32-bit texels. Sixteen plain loads cost less than four 64-bit gathers
 * (docs/performance.md). All four texels must lie in the texture for every lane. */
INLINE void pair_fetch8(const tex8 *tx, __m256i idx0, __m256i idx1, __m256i t[4]) {
    _Alignas(32) int o0[8], o1[8];
    _mm256_store_si256((__m256i *)(void *)o0, idx0);
    _mm256_store_si256((__m256i *)(void *)o1, idx1);
    const int *base = tx->texels;
#define SG_TWO(k)                                                                                  \
    _mm_castps_si128(_mm_loadh_pi(                                                                 \
        _mm_castsi128_ps(_mm_loadl_epi64((const __m128i *)(const void *)(base + o0[k]))),          \
        (const __m64 *)(const void *)(base + o1[k])))
#define SG_LANES(k) _mm256_inserti128_si256(_mm256_castsi128_si256(SG_TWO(k)), SG_TWO(k + 4), 1)
    const __m256i a = SG_LANES(0), b = SG_LANES(1), c = SG_LANES(2), d = SG_LANES(3);
#undef SG_LANES
#undef SG_TWO
    const __m256i ab0 = _mm256_unpacklo_epi32(a, b), ab1 = _mm256_unpackhi_epi32(a, b);
    const __m256i cd0 = _mm256_unpacklo_epi32(c, d), cd1 = _mm256_unpackhi_epi32(c, d);
    t[0] = _mm256_unpacklo_epi64(ab0, cd0);
    t[1] = _mm256_unpackhi_epi64(ab0, cd0);
    t[2] = _mm256_unpacklo_epi64(ab1, cd1);
    t[3] = _mm256_unpackhi_epi64(ab1, cd1);
}

INLINE __m256i nearest8(const tex8 *tx, __m256 s, __m256 u, const int repeat) {
    __m256i i = nearest_index(s, tx->scale_x, tx->hi_x, tx->n_x, tx->last_x, repeat);
    __m256i j = nearest_index(u, tx->scale_y, tx->hi_y, tx->n_y, tx->last_y, repeat);
    return fetch8(tx, _mm256_add_epi32(row_start(j, tx), i));
}

/* Texels from an 8 x 4 window of the texture around the first lane's texel, when every texel the
 * eight lanes need lies in it (a magnified or about 1:1 texture, away from the texture's edge):
 * four row loads and in-register permutes instead of gathers; the same texels, so the same bytes
 * (as window_fetch in shade_avx512.h, whose window is 8 x 8). a and b are the split's columns
 * and rows before any wrap or clamp: where every lane has a - wx in [0, 6] and b - wy in [0, 2],
 * columns a, a + 1 and rows b, b + 1 are all inside the texture and the window, so no wrap or
 * clamp would change them, in either mode. False: the footprint is wider or crosses an edge; the
 * caller wraps and gathers. */
INLINE bool window_fetch8(const tex8 *tx, __m256i a, __m256i b, __m256i t[4]) {
    const int tw = tx->width, th = tx->height;
    if (tw < 8 || th < 4) return false;
    int wx = _mm_cvtsi128_si32(_mm256_castsi256_si128(a)) - 3;
    int wy = _mm_cvtsi128_si32(_mm256_castsi256_si128(b)) - 1;
    wx = wx < 0 ? 0 : (wx > tw - 8 ? tw - 8 : wx);
    wy = wy < 0 ? 0 : (wy > th - 4 ? th - 4 : wy);
    const __m256i c = _mm256_sub_epi32(a, _mm256_set1_epi32(wx));
    const __m256i d = _mm256_sub_epi32(b, _mm256_set1_epi32(wy));
    /* Unsigned c <= 6 and d <= 2: min leaves them as they are. */
    const __m256i in =
        _mm256_and_si256(_mm256_cmpeq_epi32(_mm256_min_epu32(c, _mm256_set1_epi32(6)), c),
                         _mm256_cmpeq_epi32(_mm256_min_epu32(d, _mm256_set1_epi32(2)), d));
    if (_mm256_movemask_ps(_mm256_castsi256_ps(in)) != 255) return false;
    /* Texture row j is memory row th - 1 - j (top row first); window row r is row wy + r. */
    const int *row = tx->texels + (size_t)(th - 1 - wy) * (size_t)tw + (size_t)wx;
    __m256i w[4], p[4], q[4];
    for (int r = 0; r < 4; r++)
        w[r] = _mm256_loadu_si256((const __m256i *)(const void *)(row - (size_t)r * (size_t)tw));
    const __m256i c1 = _mm256_add_epi32(c, _mm256_set1_epi32(1));
    for (int r = 0; r < 4; r++) {
        p[r] = _mm256_permutevar8x32_epi32(w[r], c);  /* column a of window row r */
        q[r] = _mm256_permutevar8x32_epi32(w[r], c1); /* column a + 1 */
    }
    /* d is 0, 1 or 2: its bit 0 and bit 1 moved to the sign bit pick the row. */
    const __m256 d0 = _mm256_castsi256_ps(_mm256_slli_epi32(d, 31));
    const __m256 d1 = _mm256_castsi256_ps(_mm256_slli_epi32(d, 30));
#define SG_PICK(v, r)                                                                              \
    _mm256_castps_si256(_mm256_blendv_ps(                                                          \
        _mm256_blendv_ps(_mm256_castsi256_ps(v[r]), _mm256_castsi256_ps(v[r + 1]), d0),            \
        _mm256_castsi256_ps(v[r + 2]), d1))
    t[0] = SG_PICK(p, 0);
    t[1] = SG_PICK(q, 0);
    t[2] = SG_PICK(p, 1);
    t[3] = SG_PICK(q, 1);
#undef SG_PICK
    return true;
}

/* The four texels of each lane's footprint (t00, t10, t01, t11) for split coordinates gx, gy:
 * from the texel window where it holds them, else gathered. */
INLINE void bilinear_fetch8(const tex8 *tx, __m256i gx, __m256i gy, const int repeat,
                            __m256i t[4]) {
    if (window_fetch8(tx, _mm256_srai_epi32(gx, 8), _mm256_srai_epi32(gy, 8), t)) return;
    __m256i i0, i1, j0, j1;
    bilinear_wrap(gx, tx->n_x, tx->last_x, repeat, &i0, &i1);
    bilinear_wrap(gy, tx->n_y, tx->last_y, repeat, &j0, &j1);
    __m256i r0 = row_start(j0, tx), r1 = row_start(j1, tx);
    /* Where every lane's split column is in [0, n - 2], i1 = i0 + 1 in every wrap mode and the
     * two columns are adjacent in memory: fetched as pairs. */
    __m256i a = _mm256_srai_epi32(gx, 8);
    __m256i outside =
        _mm256_or_si256(_mm256_cmpgt_epi32(_mm256_setzero_si256(), a),
                        _mm256_cmpgt_epi32(a, _mm256_sub_epi32(tx->last_x, _mm256_set1_epi32(1))));
    if (_mm256_testz_si256(outside, outside)) {
        pair_fetch8(tx, _mm256_add_epi32(r0, a), _mm256_add_epi32(r1, a), t);
    } else {
        t[0] = fetch8(tx, _mm256_add_epi32(r0, i0));
        t[1] = fetch8(tx, _mm256_add_epi32(r0, i1));
        t[2] = fetch8(tx, _mm256_add_epi32(r1, i0));
        t[3] = fetch8(tx, _mm256_add_epi32(r1, i1));
    }
}

/* The filter of bilinear8 on fetched texels: x[k] gets channel k in bits 16 to 23. */
INLINE void bilinear_filter8(__m256i gx, __m256i gy, const __m256i t[4], __m256i x[4]) {
    const __m256i lo8 = _mm256_set1_epi32(0x00ff00ff);
    const __m256i bias = _mm256_set1_epi32((int)0x80008000u);
    const __m256i w256 = _mm256_set1_epi16(256);
    const __m256i round = _mm256_set1_epi32(128 * 65536 + 32768);
    __m256i fy2 = frac2(gy), fx2 = frac2(gx);
    __m256i gy2 = _mm256_sub_epi16(w256, fy2);
    __m256i wx = _mm256_blend_epi16(_mm256_sub_epi16(w256, fx2), fx2, 0xaa); /* 256 - fx, fx */
#define SG_VBLEND(a, b)                                                                            \
    _mm256_xor_si256(_mm256_add_epi16(_mm256_mullo_epi16(a, gy2), _mm256_mullo_epi16(b, fy2)), bias)
    __m256i rb0 = SG_VBLEND(_mm256_and_si256(t[0], lo8), _mm256_and_si256(t[2], lo8));
    __m256i rb1 = SG_VBLEND(_mm256_and_si256(t[1], lo8), _mm256_and_si256(t[3], lo8));
    __m256i ga0 = SG_VBLEND(_mm256_srli_epi16(t[0], 8), _mm256_srli_epi16(t[2], 8));
    __m256i ga1 = SG_VBLEND(_mm256_srli_epi16(t[1], 8), _mm256_srli_epi16(t[3], 8));
#undef SG_VBLEND
#define SG_HBLEND(v) _mm256_add_epi32(_mm256_madd_epi16(v, wx), round)
    x[0] = SG_HBLEND(_mm256_blend_epi16(rb0, _mm256_slli_epi32(rb1, 16), 0xaa));
    x[1] = SG_HBLEND(_mm256_blend_epi16(ga0, _mm256_slli_epi32(ga1, 16), 0xaa));
    x[2] = SG_HBLEND(_mm256_blend_epi16(_mm256_srli_epi32(rb0, 16), rb1, 0xaa));
    x[3] = SG_HBLEND(_mm256_blend_epi16(_mm256_srli_epi32(ga0, 16), ga1, 0xaa));
#undef SG_HBLEND
}

/* sg_sample_bilinear of eight pixels, planar: x[k] gets channel k of the eight pixels in bits 16
 * to 23 of each lane, zeros above. Channels r, b and g, a are blended as pairs of 16-bit lanes. The
 * vertical blends t0 (256 - fy) + t1 fy are at most 255 * 256, exact in unsigned 16 bits; biased
 * by -32768 (the xor) they are signed, and the blends of columns i0 and i1 of a channel, put side
 * by side in a 32-bit lane, go through pmaddwd with (256 - fx, fx), whose sum brings the bias back
 * as 32768 * 256. That is the reference's four-weight sum exactly, plus 32768: its >> 16 is the
 * reference's result. No shuffles: all lanes stay in place. */
INLINE void bilinear8(const tex8 *tx, __m256 s, __m256 u, const int repeat, __m256i x[4]) {
    __m256i gx = bilinear_split(s, tx->scale_x, tx->hi_x, repeat);
    __m256i gy = bilinear_split(u, tx->scale_y, tx->hi_y, repeat);
    __m256i t[4];
    bilinear_fetch8(tx, gx, gy, repeat, t);
    bilinear_filter8(gx, gy, t, x);
}

/* Four channels in bits 16 to 23 of their lanes, zeros above, to RGBA8 (sg_pack_rgba8). */
INLINE __m256i pack_hi8(const __m256i x[4]) {
    __m256i rb = _mm256_blend_epi16(_mm256_srli_epi32(x[0], 16), x[2], 0xaa);
    __m256i ga = _mm256_blend_epi16(_mm256_srli_epi32(x[1], 16), x[3], 0xaa);
    return _mm256_or_si256(rb, _mm256_slli_epi32(ga, 8));
}

/* Eight RGBA8 texels to planar channels. */
INLINE void unpack_texels(__m256i t, __m256i c[4]) {
    const __m256i lo8 = _mm256_set1_epi32(255);
    c[0] = _mm256_and_si256(t, lo8);
    c[1] = _mm256_and_si256(_mm256_srli_epi32(t, 8), lo8);
    c[2] = _mm256_and_si256(_mm256_srli_epi32(t, 16), lo8);
    c[3] = _mm256_srli_epi32(t, 24);
}

/* sg_to_unorm8 of each lane but its clamp to [0, 255], left to pack_unorm8: min puts v above 1 at
 * 1 and keeps NaN, whose conversion gives INT_MIN, as v far below 0 does; every v <= 0 gives a
 * value <= 0 (-0 and tiny v: 0), every other v its unorm8. */
INLINE __m256i unorm8(__m256 v) {
    v = _mm256_min_ps(_mm256_set1_ps(1.0f), v); /* the second operand, v, when it is NaN */
    return _mm256_cvttps_epi32(
        _mm256_add_ps(_mm256_mul_ps(v, _mm256_set1_ps(255.0f)), _mm256_set1_ps(0.5f)));
}

/* Planar float colours to RGBA8 (sg_to_unorm8, sg_pack_rgba8): the saturating packs clamp to
 * [0, 255], then a byte shuffle turns the 4x4 blocks of channel bytes of each 128-bit half into
 * pixels. */
INLINE __m256i pack_unorm8(const __m256 col[4]) {
    __m256i p01 = _mm256_packs_epi32(unorm8(col[0]), unorm8(col[1]));
    __m256i p23 = _mm256_packs_epi32(unorm8(col[2]), unorm8(col[3]));
    const __m256i tr = _mm256_setr_epi8(0, 4, 8, 12, 1, 5, 9, 13, 2, 6, 10, 14, 3, 7, 11, 15, 0, 4,
                                        8, 12, 1, 5, 9, 13, 2, 6, 10, 14, 3, 7, 11, 15);
    return _mm256_shuffle_epi8(_mm256_packus_epi16(p01, p23), tr);
}

/* The bound texture for the filter (bilinear: coordinates in 1/256 texel). */
INLINE tex8 tex8_of(const sg_texview *tv, const int bilinear) {
    const sg_texsizes *z = &tv->size;
    tex8 tx;
    tx.texels = (const int *)(const void *)tv->texels;
    tx.width = tv->width;
    tx.height = tv->height;
    tx.scale_x = _mm256_set1_ps(z->scale[bilinear][0]);
    tx.scale_y = _mm256_set1_ps(z->scale[bilinear][1]);
    tx.hi_x = _mm256_set1_ps(z->hi[bilinear][0]);
    tx.hi_y = _mm256_set1_ps(z->hi[bilinear][1]);
    tx.n_x = _mm256_set1_epi32(z->n[0]);
    tx.n_y = _mm256_set1_epi32(z->n[1]);
    tx.last_x = _mm256_set1_epi32(z->last[0]);
    tx.last_y = _mm256_set1_epi32(z->last[1]);
    return tx;
}

/* Channel k (0 .. 255) of each lane in c[k]: nearest or bilinear, on one level. */
INLINE void lookup8(const sg_texview *tv, __m256 s, __m256 u, const int bilinear, const int repeat,
                    __m256i c[4]) {
    const tex8 tx = tex8_of(tv, bilinear);
    if (bilinear) {
        __m256i x[4];
        bilinear8(&tx, s, u, repeat, x);
        for (int k = 0; k < 4; k++) c[k] = _mm256_srli_epi32(x[k], 16);
    } else {
        unpack_texels(nearest8(&tx, s, u, repeat), c);
    }
}

/* Mipmapped lookups (tex/mip.h) on a set of two rows of a tile, whose two 2 x 2 quads are lanes
 * 0, 1, 4, 5 and lanes 2, 3, 6, 7: mip16_pick and mip16_lookup of shade_avx512.h on eight lanes,
 * sg_mip_select's operations on the same values in the same order, so the same levels, weights
 * and bytes. Each lane takes its quad's levels l0, l1 and weight f (0 .. 255). */
INLINE void mip8_pick(const sg_mip_chain *m, __m256 s, __m256 u, const int linear, __m256i *l0,
                      __m256i *l1, __m256i *f) {
    const __m256i base = _mm256_setr_epi32(0, 0, 2, 2, 0, 0, 2, 2);
    const __m256i one = _mm256_set1_epi32(1), zero = _mm256_setzero_si256();
    const __m256i right = _mm256_add_epi32(base, one),
                  down = _mm256_add_epi32(base, _mm256_set1_epi32(4));
    const __m256 s0 = _mm256_permutevar8x32_ps(s, base), u0 = _mm256_permutevar8x32_ps(u, base);
    const __m256 w = _mm256_set1_ps(m->level[0].size.scale[0][0]); /* (float) width */
    const __m256 h = _mm256_set1_ps(m->level[0].size.scale[0][1]);
    const __m256 ax = _mm256_mul_ps(_mm256_sub_ps(_mm256_permutevar8x32_ps(s, right), s0), w);
    const __m256 bx = _mm256_mul_ps(_mm256_sub_ps(_mm256_permutevar8x32_ps(u, right), u0), h);
    const __m256 ay = _mm256_mul_ps(_mm256_sub_ps(_mm256_permutevar8x32_ps(s, down), s0), w);
    const __m256 by = _mm256_mul_ps(_mm256_sub_ps(_mm256_permutevar8x32_ps(u, down), u0), h);
    const __m256 rx = _mm256_add_ps(_mm256_mul_ps(ax, ax), _mm256_mul_ps(bx, bx));
    const __m256 ry = _mm256_add_ps(_mm256_mul_ps(ay, ay), _mm256_mul_ps(by, by));
    /* rx > ry ? rx : ry (ry when either is NaN) */
    const __m256 rho2 = _mm256_blendv_ps(ry, rx, _mm256_cmp_ps(rx, ry, _CMP_GT_OQ));
    const __m256i bits = _mm256_castps_si256(rho2);
    const __m256i e =
        _mm256_sub_epi32(_mm256_and_si256(_mm256_srli_epi32(bits, 23), _mm256_set1_epi32(0xff)),
                         _mm256_set1_epi32(127));
    const __m256i last = _mm256_set1_epi32(m->levels - 1);
    if (!linear) { /* round(log2 rho) = (exponent + 1) >> 1, arithmetic */
        const __m256i l = _mm256_srai_epi32(_mm256_add_epi32(e, one), 1);
        *l0 = *l1 = _mm256_min_epi32(_mm256_max_epi32(l, zero), last);
        *f = zero;
        return;
    }
    const __m256 mant = _mm256_castsi256_ps(_mm256_or_si256(
        _mm256_and_si256(bits, _mm256_set1_epi32(0x007fffff)), _mm256_set1_epi32(0x3f800000)));
    const __m256 lod = _mm256_mul_ps(
        _mm256_add_ps(_mm256_cvtepi32_ps(_mm256_sub_epi32(e, one)), mant), _mm256_set1_ps(0.5f));
    const __m256 fl = _mm256_floor_ps(lod);
    const __m256i finite =
        _mm256_castps_si256(_mm256_and_ps(_mm256_cmp_ps(lod, _mm256_set1_ps(-1e9f), _CMP_GE_OQ),
                                          _mm256_cmp_ps(lod, _mm256_set1_ps(1e9f), _CMP_LE_OQ)));
    const __m256i i = _mm256_and_si256(finite, _mm256_cvttps_epi32(fl));
    const __m256 frac = _mm256_and_ps(_mm256_castsi256_ps(finite), _mm256_sub_ps(lod, fl));
    /* below level 0 or from the last level on: one level, weight 0 */
    const __m256i low = _mm256_cmpgt_epi32(zero, i),
                  high =
                      _mm256_andnot_si256(low, _mm256_cmpgt_epi32(i, _mm256_sub_epi32(last, one)));
    const __m256i two = _mm256_andnot_si256(_mm256_or_si256(low, high), _mm256_set1_epi32(-1));
    *l0 = _mm256_or_si256(_mm256_and_si256(two, i), _mm256_and_si256(high, last));
    *l1 = _mm256_or_si256(_mm256_and_si256(two, _mm256_add_epi32(i, one)),
                          _mm256_and_si256(high, last));
    *f = _mm256_and_si256(two, _mm256_cvttps_epi32(_mm256_mul_ps(frac, _mm256_set1_ps(256.0f))));
}

/* mip8_pick for the pixels of the 8-bit mask `bits` (all eight when 255): a quad without a covered
 * pixel takes the other quad's levels, so that it reads no level of its own. */
INLINE void mip8_levels(const sg_mip_chain *m, __m256 s, __m256 u, unsigned bits, const int linear,
                        __m256i *l0, __m256i *l1, __m256i *f) {
    mip8_pick(m, s, u, linear, l0, l1, f);
    if (!(bits & 0x33u) == !(bits & 0xccu)) return; /* both quads covered */
    const __m256i from = _mm256_set1_epi32(bits & 0x33u ? 0 : 2);
    *l0 = _mm256_permutevar8x32_epi32(*l0, from);
    *l1 = _mm256_permutevar8x32_epi32(*l1, from);
    *f = _mm256_permutevar8x32_epi32(*f, from);
}

/* sg_sample_mip in every lane with its levels and weight: each level the lanes read is looked up
 * once, for all eight (a lane whose second level weighs 0 does not ask for it). Channels in c[k].
 */
INLINE void mip8_lookup(const sg_mip_chain *m, __m256i l0, __m256i l1, __m256i f, __m256 s,
                        __m256 u, const int bilinear, const int repeat, __m256i c[4]) {
    const __m256i one = _mm256_set1_epi32(1);
    const __m256i unweighed = _mm256_cmpeq_epi32(f, _mm256_setzero_si256());
    const __m256i bits = _mm256_or_si256(
        _mm256_sllv_epi32(one, l0), _mm256_andnot_si256(unweighed, _mm256_sllv_epi32(one, l1)));
    __m128i x = _mm_or_si128(_mm256_castsi256_si128(bits), _mm256_extracti128_si256(bits, 1));
    x = _mm_or_si128(x, _mm_shuffle_epi32(x, 0x4e));
    x = _mm_or_si128(x, _mm_shuffle_epi32(x, 0xb1));
    uint32_t want = (uint32_t)_mm_cvtsi128_si32(x);
    /* Every weight 0 (nearest mipmaps, magnified sets): each lane's first level's texel, which
     * the blend below would give; and with one level for all, that level's lookup as it is. */
    const bool weighed = _mm256_movemask_epi8(unweighed) != -1;
    if (!weighed && !(want & (want - 1))) {
        lookup8(&m->level[__builtin_ctz(want)], s, u, bilinear, repeat, c);
        return;
    }
    __m256i a[4], b[4];
    for (int k = 0; k < 4; k++) a[k] = b[k] = _mm256_setzero_si256();
    for (; want; want &= want - 1) {
        const int level = __builtin_ctz(want);
        const __m256i lv = _mm256_set1_epi32(level);
        const __m256i in0 = _mm256_cmpeq_epi32(l0, lv), in1 = _mm256_cmpeq_epi32(l1, lv);
        __m256i t[4];
        lookup8(&m->level[level], s, u, bilinear, repeat, t);
        for (int k = 0; k < 4; k++) {
            a[k] = _mm256_blendv_epi8(a[k], t[k], in0);
            b[k] = _mm256_blendv_epi8(b[k], t[k], in1);
        }
    }
    for (int k = 0; k < 4; k++) {
        if (!weighed) {
            c[k] = a[k];
            continue;
        }
        const __m256i d = _mm256_mullo_epi32(_mm256_sub_epi32(b[k], a[k]), f);
        c[k] = _mm256_add_epi32(a[k], _mm256_srai_epi32(d, 8));
    }
}

/* The texturing step of shade8_sets: the texels at coordinates (s[i], u[i]) of n sets of eight
 * pixels (textured: 1, or a mipmap chain, SG_TEX_MIP*, whose sets hold the pixels of mask[i], or
 * all eight where mask is NULL) modulate their colours col[i]; an opaque white triangle without a
 * secondary colour takes the texel as it is, and then out[i] is the result already (true). */
INLINE bool texture8_sets(const sg_shade_ctx *c, const int n, const __m256 s[], const __m256 u[],
                          const unsigned mask[], __m256 col[][4], __m256i out[], const int textured,
                          const int bilinear, const int repeat, const int flat, const int sec) {
    const tex8 tx = tex8_of(&c->tex, bilinear);
    __m256i tc[4][4];
    if (textured >= SG_TEX_MIP) {
        /* every set's levels first: their chains of dependent steps side by side */
        __m256i l0[4], l1[4], f[4];
        for (int i = 0; i < n; i++)
            mip8_levels(c->mips, s[i], u[i], mask ? mask[i] : 255u, textured == SG_TEX_MIP_LINEAR,
                        &l0[i], &l1[i], &f[i]);
        for (int i = 0; i < n; i++)
            mip8_lookup(c->mips, l0[i], l1[i], f[i], s[i], u[i], bilinear, repeat, tc[i]);
        if (flat == SG_FLAT_WHITE && !sec) { /* the texel, as in shade_mip.c */
            for (int i = 0; i < n; i++)
                out[i] = _mm256_or_si256(_mm256_or_si256(tc[i][0], _mm256_slli_epi32(tc[i][1], 8)),
                                         _mm256_or_si256(_mm256_slli_epi32(tc[i][2], 16),
                                                         _mm256_slli_epi32(tc[i][3], 24)));
            return true;
        }
    } else if (bilinear) {
        __m256i gx[4], gy[4], texels[4][4], x[4][4];
        for (int i = 0; i < n; i++) {
            gx[i] = bilinear_split(s[i], tx.scale_x, tx.hi_x, repeat);
            gy[i] = bilinear_split(u[i], tx.scale_y, tx.hi_y, repeat);
        }
        for (int i = 0; i < n; i++) bilinear_fetch8(&tx, gx[i], gy[i], repeat, texels[i]);
        for (int i = 0; i < n; i++) bilinear_filter8(gx[i], gy[i], texels[i], x[i]);
        if (flat == SG_FLAT_WHITE && !sec) {
            for (int i = 0; i < n; i++) out[i] = pack_hi8(x[i]);
            return true;
        }
        for (int i = 0; i < n; i++)
            for (int k = 0; k < 4; k++) tc[i][k] = _mm256_srli_epi32(x[i][k], 16);
    } else {
        __m256i texel[4];
        for (int i = 0; i < n; i++) texel[i] = nearest8(&tx, s[i], u[i], repeat);
        if (flat == SG_FLAT_WHITE && !sec) { /* the colour, as in the reference */
            for (int i = 0; i < n; i++) out[i] = texel[i];
            return true;
        }
        for (int i = 0; i < n; i++) unpack_texels(texel[i], tc[i]);
    }
    for (int i = 0; i < n; i++)
        for (int k = 0; k < 4; k++)
            col[i][k] = _mm256_mul_ps(col[i][k], _mm256_mul_ps(_mm256_cvtepi32_ps(tc[i][k]),
                                                               _mm256_set1_ps(1.0f / 255.0f)));
    return false;
}

/* The colours of eight pixels at offsets (dx, dy) from the triangle's bounds, as RGBA8 lanes, for
 * n sets of eight (n is 1, 2 or 4, a constant): the body of every variant (the constant arguments
 * fold away), in the reference's operation order ((a + a_dx dx) + a_dy dy, then times 1/q). Each
 * step is done for every set before the next, so the sets' long chains of dependent steps run
 * side by side (as shade16_tiles in shade_avx512.h): two, or four for two whole tiles. Lanes need
 * not be neighbours: each computes what the reference computes for its pixel, wherever that is, so
 * the blend can shade pixels of several tiles together. Every lane's fetch stays in the texture
 * whatever its coordinates. With ts, set i is triangle ts[i]'s (the blend's jobs of several
 * triangles), else every set is t's. shade_rows (shade_avx2.c) is the same body for the two row
 * pairs of one tile, with the terms both pairs share computed once (keep the two in step). */
INLINE void shade8_sets(const sg_shade_ctx *c, const sg_tri *t, const sg_tri *const ts[],
                        const sg_tri_ext *ext, const int n, const __m256 dx[], const __m256 dy[],
                        const unsigned mask[], __m256i out[], const int textured,
                        const int bilinear, const int repeat, const int flat, const int sec) {
    const int e = SG_LIT_SEC - SG_TRI_ATTRS; /* the secondary colour in ext */
    if (!textured && flat != SG_FLAT_NONE) { /* one colour, converted once */
        uint32_t px = sg_flat_pixel(t, ext, sec);
        for (int i = 0; i < n; i++) out[i] = _mm256_set1_epi32((int)px);
        return;
    }
/* Set i's triangle: ts[i] when given (the blend's jobs of several triangles), else t. */
#define SG_T(i) (ts ? ts[i] : t)
#define SG_PLANE(a, adx, ady, i)                                                                   \
    _mm256_add_ps(_mm256_add_ps(_mm256_set1_ps(a), _mm256_mul_ps(_mm256_set1_ps(adx), dx[i])),     \
                  _mm256_mul_ps(_mm256_set1_ps(ady), dy[i]))
    __m256 w[4], col[4][4];
    for (int i = 0; i < n; i++)
        w[i] = _mm256_div_ps(_mm256_set1_ps(1.0f),
                             SG_PLANE(SG_T(i)->q, SG_T(i)->q_dx, SG_T(i)->q_dy, i));
    for (int i = 0; i < n; i++)
        for (int k = 0; k < 4; k++)
            col[i][k] =
                flat != SG_FLAT_NONE
                    ? _mm256_set1_ps(SG_T(i)->color[k])
                    : _mm256_mul_ps(SG_PLANE(SG_T(i)->a[k], SG_T(i)->a_dx[k], SG_T(i)->a_dy[k], i),
                                    w[i]);
    if (textured) {
        __m256 s[4], u[4];
        for (int i = 0; i < n; i++) {
            s[i] =
                _mm256_mul_ps(SG_PLANE(SG_T(i)->a[4], SG_T(i)->a_dx[4], SG_T(i)->a_dy[4], i), w[i]);
            u[i] =
                _mm256_mul_ps(SG_PLANE(SG_T(i)->a[5], SG_T(i)->a_dx[5], SG_T(i)->a_dy[5], i), w[i]);
        }
        if (texture8_sets(c, n, s, u, mask, col, out, textured, bilinear, repeat, flat, sec))
            return;
    }
    for (int i = 0; i < n; i++)
        for (int k = 0; sec && k < 3; k++)
            col[i][k] = _mm256_add_ps(
                col[i][k],
                flat != SG_FLAT_NONE
                    ? _mm256_set1_ps(ext->a[e + k])
                    : _mm256_mul_ps(SG_PLANE(ext->a[e + k], ext->a_dx[e + k], ext->a_dy[e + k], i),
                                    w[i]));
#undef SG_T
#undef SG_PLANE
    for (int i = 0; i < n; i++) out[i] = pack_unorm8(col[i]);
}

/* dx and dy of rows 2h and 2h + 1 of the tile at (x0, y0), from the triangle's bounds: row 2h in
 * the low half, 2h + 1 in the high half (exact small integers). */
INLINE void sg_rows_dxdy8(const sg_tri *t, int x0, int y0, int h, __m256 *dx, __m256 *dy) {
    const float r0 = (float)(y0 - t->miny + 2 * h);
    *dx = _mm256_add_ps(_mm256_set1_ps((float)(x0 - t->minx)),
                        _mm256_setr_ps(0.0f, 1.0f, 2.0f, 3.0f, 0.0f, 1.0f, 2.0f, 3.0f));
    *dy = _mm256_set_m128(_mm_set1_ps(r0 + 1.0f), _mm_set1_ps(r0));
}

/* Up to eight pixels of a triangle waiting to be shaded together (a partly covered pair of rows
 * fills few lanes, and a shading pass costs the same for one pixel as for eight): their offsets
 * from the triangle's bounds and in the bin's colour, lanes 0 to n - 1 (the others hold earlier
 * pixels, or zeros: shaded but not stored). */
typedef struct sg_queue8 {
    __m256 dx, dy;
    __m256i off;
    int n;
} sg_queue8;

/* Appends the pixels of bits (8 bits) of the rows at (dx, dy), bin offset off, to q: the lanes of
 * bits are packed (a permutation from their positions) and rotated to start at lane n. When that
 * fills the queue, full gets the eight lanes to shade and q keeps the rest; true then. */
INLINE bool sg_enqueue8(sg_queue8 *q, __m256 dx, __m256 dy, int off, unsigned bits,
                        sg_queue8 *full) {
    /* The positions of the set bits of each 4-bit value, packed in bytes (the rest: any lane). */
    static const uint32_t set_bits4[16] = {0x00000000, 0x00000000, 0x00000001, 0x00000100,
                                           0x00000002, 0x00000200, 0x00000201, 0x00020100,
                                           0x00000003, 0x00000300, 0x00000301, 0x00030100,
                                           0x00000302, 0x00030200, 0x00030201, 0x03020100};
    const int n = q->n, k = __builtin_popcount(bits), lo = __builtin_popcount(bits & 15u);
    uint64_t pos = (uint64_t)set_bits4[bits & 15u] |
                   ((uint64_t)(set_bits4[bits >> 4] + 0x04040404u) << (8 * lo));
    const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
    /* Lane j takes packed pixel (j - n) mod 8: the first 8 - n go after the queue's n, the ones
     * that do not fit into lanes 0 to n + k - 9. */
    __m256i from = _mm256_permutevar8x32_epi32(
        _mm256_cvtepu8_epi32(_mm_cvtsi64_si128((long long)pos)),
        _mm256_and_si256(_mm256_sub_epi32(lane, _mm256_set1_epi32(n)), _mm256_set1_epi32(7)));
    __m256 rdx = _mm256_permutevar8x32_ps(dx, from), rdy = _mm256_permutevar8x32_ps(dy, from);
    __m256i roff = _mm256_add_epi32(_mm256_set1_epi32(off), from);
    __m256i keep = _mm256_cmpgt_epi32(_mm256_set1_epi32(n), lane);
    __m256 keepf = _mm256_castsi256_ps(keep);
    sg_queue8 merged = {_mm256_blendv_ps(rdx, q->dx, keepf), _mm256_blendv_ps(rdy, q->dy, keepf),
                        _mm256_blendv_epi8(roff, q->off, keep), n + k};
    if (n + k < 8) {
        *q = merged;
        return false;
    }
    *full = merged;
    *q = (sg_queue8){rdx, rdy, roff, n + k - 8};
    return true;
}

/* The lanes of the 8-bit mask `bits`, all bits set in each. */
INLINE __m256 sg_lanes8(unsigned bits) {
    const __m256i sel = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
    return _mm256_castsi256_ps(
        _mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32((int)bits), sel), sel));
}

/* Eight lanes of pixels to shade: their offsets from the triangle's bounds (dx, dy) and in the
 * bin (off), and the lanes to store (mask). */
typedef struct sg_set8 {
    __m256 dx, dy;
    __m256i off;
    unsigned mask;
} sg_set8;

/* The set of the pixels `bits` of a pair of rows at (dx, dy), bin offsets off + lane. */
INLINE sg_set8 sg_set8_of(__m256 dx, __m256 dy, int off, unsigned bits) {
    return (sg_set8){
        dx, dy, _mm256_add_epi32(_mm256_set1_epi32(off), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7)),
        bits};
}

/* A pair of rows of a tile holds two 2 x 2 quads, lanes 0, 1, 4, 5 and 2, 3, 6, 7; a mipmapped set
 * must hold whole quads. */
enum { SG_QUAD8_LEFT = 0x33u, SG_QUAD8_RIGHT = 0xccu };

/* Whether the pixels `bits` of a pair of rows lie in both of its quads. */
INLINE bool sg_both_quads8(unsigned bits) {
    return (bits & SG_QUAD8_LEFT) && (bits & SG_QUAD8_RIGHT);
}

/* Adds the lone quad of the pixels `bits` of the rows at (dx, dy), bin offsets off + lane, to q,
 * the quad waiting (mask 0: none): when one waits, the two make a set, in *full, and true (the new
 * one moved to the other quad's lanes when both sit on the same side); else it waits. */
INLINE bool sg_pair_quad8(sg_set8 *q, __m256 dx, __m256 dy, int off, unsigned bits, sg_set8 *full) {
    sg_set8 in = sg_set8_of(dx, dy, off, bits);
    if (!q->mask) {
        *q = in;
        return false;
    }
    /* on the same side: lanes 0, 1, 4, 5 <-> 2, 3, 6, 7 */
    if (!(bits & SG_QUAD8_LEFT) == !(q->mask & SG_QUAD8_LEFT)) {
        in.dx = _mm256_permute_ps(in.dx, _MM_SHUFFLE(1, 0, 3, 2));
        in.dy = _mm256_permute_ps(in.dy, _MM_SHUFFLE(1, 0, 3, 2));
        in.off = _mm256_shuffle_epi32(in.off, _MM_SHUFFLE(1, 0, 3, 2));
        in.mask = ((bits & SG_QUAD8_LEFT) << 2) | ((bits & SG_QUAD8_RIGHT) >> 2);
    }
    const __m256 side = sg_lanes8(in.mask & SG_QUAD8_LEFT ? SG_QUAD8_LEFT : SG_QUAD8_RIGHT);
    *full = (sg_set8){_mm256_blendv_ps(q->dx, in.dx, side), _mm256_blendv_ps(q->dy, in.dy, side),
                      _mm256_castps_si256(_mm256_blendv_ps(_mm256_castsi256_ps(q->off),
                                                           _mm256_castsi256_ps(in.off), side)),
                      q->mask | in.mask};
    q->mask = 0;
    return true;
}

/* Writes v's lanes of `bits` (32-bit values) at their offsets in dst, in 4-byte units (different
 * offsets). */
INLINE void sg_scatter8(void *dst, __m256i off, __m256i v, unsigned bits) {
    _Alignas(32) uint32_t val[8];
    _Alignas(32) int32_t at[8];
    _mm256_store_si256((__m256i *)(void *)val, v);
    _mm256_store_si256((__m256i *)(void *)at, off);
    for (; bits; bits &= bits - 1) {
        const int k = __builtin_ctz(bits);
        memcpy((uint32_t *)dst + at[k], &val[k], 4);
    }
}

/* Writes the lanes of `m` (8 bits) of two rows; other pixels are not touched. */
INLINE void store_rows(uint32_t *dst, __m256i v, unsigned m) {
    if (m == 255) {
        _mm256_storeu_si256((__m256i *)(void *)dst, v);
        return;
    }
    const __m256i bits = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
    __m256i sel = _mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32((int)m), bits), bits);
    _mm256_maskstore_epi32((int *)(void *)dst, sel, v);
}

/* The colours of `count` (1 or 2, a constant) tiles' pixels that several triangles of one draw
 * share (sg_mixed_tile), as RGBA8 lanes: out[2 i + h] holds rows 2h and 2h + 1 of tile i (lanes of
 * other pixels undefined); every triangle has the flat kind `flat`. As sg_shade16_mixed of
 * shade_avx512.h: each lane takes its own triangle's values where shade8_sets broadcasts one
 * triangle's and goes through the same operations, so a lane's bytes are those of its triangle's
 * shading; the lanes of uncovered pixels take the tile's first triangle's values. */
INLINE void sg_shade8_mixed(const sg_shade_ctx *c, const sg_mixed_tile *tiles, const int count,
                            __m256i out[], const int textured, const int bilinear, const int repeat,
                            const int flat) {
    const int sets = 2 * count;
    if (!textured && flat != SG_FLAT_NONE) { /* each triangle's colour, as shade8_sets packs it */
        for (int i = 0; i < sets; i++) {
            const sg_mixed_tile *m = &tiles[i / 2];
            out[i] = _mm256_setzero_si256();
            for (int j = 0; j < m->n; j++)
                out[i] = _mm256_castps_si256(_mm256_blendv_ps(
                    _mm256_castsi256_ps(out[i]),
                    _mm256_castsi256_ps(_mm256_set1_epi32((int)sg_flat_pixel(m->ts[j], NULL, 0))),
                    sg_lanes8(m->masks[j] >> (8 * (i % 2)) & 255u)));
        }
        return;
    }
    /* Per lane: its triangle's offset from the rows to the triangle's bounds, and its planes. */
    __m256 v[4][SG_MIX_VALUES];
#define SG_SET(f, x)   v[i][f] = _mm256_set1_ps(x)
#define SG_MERGE(f, x) v[i][f] = _mm256_blendv_ps(v[i][f], _mm256_set1_ps(x), m)
    for (int i = 0; i < sets; i++) {
        const sg_mixed_tile *mt = &tiles[i / 2];
        const int x0 = mt->x0, y0 = mt->y0 + 2 * (i % 2); /* rows 2h and 2h + 1 of the tile */
        SG_MIXED_VALUES(mt->ts[0], x0, y0, flat, textured, SG_SET);
        for (int j = 1; j < mt->n; j++) {
            const __m256 m = sg_lanes8(mt->masks[j] >> (8 * (i % 2)) & 255u);
            SG_MIXED_VALUES(mt->ts[j], x0, y0, flat, textured, SG_MERGE);
        }
    }
#undef SG_SET
#undef SG_MERGE
    /* Lane i of a pair of rows is its column i % 4, row i / 4 (as sg_rows_dxdy8). */
    const __m256 lane_x = _mm256_setr_ps(0.0f, 1.0f, 2.0f, 3.0f, 0.0f, 1.0f, 2.0f, 3.0f);
    const __m256 lane_y = _mm256_setr_ps(0.0f, 0.0f, 0.0f, 0.0f, 1.0f, 1.0f, 1.0f, 1.0f);
    __m256 dx[4], dy[4], w[4], col[4][4], s[4], u[4];
    SG_MIXED_PLANES(_mm256_add_ps, _mm256_mul_ps, _mm256_div_ps, _mm256_set1_ps, sets, v, lane_x,
                    lane_y, dx, dy, w, col, s, u, flat, textured);
    if (textured && texture8_sets(c, sets, s, u, NULL, col, out, 1, bilinear, repeat, flat, 0))
        return;
    for (int i = 0; i < sets; i++) out[i] = pack_unorm8(col[i]);
}

#endif
#endif
