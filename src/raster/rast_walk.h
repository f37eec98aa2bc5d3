/* rast_walk.h - the tile walk of rast_tile.c as always-inline code (see rast_tile.c for how it
 * works). Code that walks with one fixed tile function (the visibility functions of depth.c)
 * includes it and calls sg_rast_walk with that function, so the compiler inlines the tile
 * function into the walk: no call per tile.
 */
#ifndef SG_RAST_WALK_H
#define SG_RAST_WALK_H

#include <stdbool.h>
#include <stdint.h>

#include "raster/framebuffer.h"
#include "raster/rast_tile.h"

#if defined(__AVX512F__) || defined(__AVX2__)
#include <immintrin.h>
#elif defined(__SSE2__)
#include <emmintrin.h>
#elif defined(__aarch64__) && defined(__ARM_NEON)
#include <arm_neon.h>
#endif

#define SG_WALK_INLINE static inline __attribute__((always_inline))

#if defined(__aarch64__) && defined(__ARM_NEON) && !defined(__SSE2__)
/* The sign bits of four rows of four int32 lanes as a 16-bit mask, bit 4 j + i for lane i of row j
 * (NEON has no movemask: each sign bit is moved to its place, and the disjoint bits summed). */
SG_WALK_INLINE uint32_t sg_walk_signs16(const int32x4_t r[4]) {
    const int32x4_t place = {0, 1, 2, 3};
    uint32x4_t bits = vdupq_n_u32(0);
    for (int j = 0; j < 4; j++)
        bits = vorrq_u32(bits, vshlq_u32(vshrq_n_u32(vreinterpretq_u32_s32(r[j]), 31),
                                         vaddq_s32(place, vdupq_n_s32(4 * j))));
    return vaddvq_u32(bits);
}
#endif

/* With AVX-512 and AVX2, triangles whose tiles fit a square of this many tiles a side (a whole
 * bin) are tested a tile at a time without the 64-bit walk, when their edge values there fit in
 * int32 (see small_triangle): a compare per edge and tile is cheaper than the walk's tests. */
#define SG_SMALL_TILES 16

#if defined(__AVX512F__)
/* i dx + j dy for the 16 pixels (i, j) of a tile, in wrapping 32-bit arithmetic (callers make
 * sure the true values fit). */
SG_WALK_INLINE __m512i sg_walk_offsets(uint32_t dx, uint32_t dy) {
    const __m512i i = _mm512_setr_epi32(0, 1, 2, 3, 0, 1, 2, 3, 0, 1, 2, 3, 0, 1, 2, 3);
    const __m512i j = _mm512_setr_epi32(0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2, 3, 3, 3, 3);
    return _mm512_add_epi32(_mm512_mullo_epi32(_mm512_set1_epi32((int32_t)dx), i),
                            _mm512_mullo_epi32(_mm512_set1_epi32((int32_t)dy), j));
}
#elif defined(__AVX2__)
/* i dx + j dy for the 8 pixels (i, j) of a tile's rows 0 and 1 (half 0) or 2 and 3 (half 1), in
 * wrapping 32-bit arithmetic (callers make sure the true values fit). */
SG_WALK_INLINE __m256i sg_walk_offsets8(uint32_t dx, uint32_t dy, int half) {
    const __m256i i = _mm256_setr_epi32(0, 1, 2, 3, 0, 1, 2, 3);
    const __m256i j = _mm256_setr_epi32(0, 0, 0, 0, 1, 1, 1, 1);
    return _mm256_add_epi32(_mm256_add_epi32(_mm256_mullo_epi32(_mm256_set1_epi32((int32_t)dx), i),
                                             _mm256_mullo_epi32(_mm256_set1_epi32((int32_t)dy), j)),
                            _mm256_set1_epi32((int32_t)(2u * (uint32_t)half * dy)));
}

/* The covered pixels of a tile from its 8 + 8 edge values per edge: a pixel is out when any
 * edge's value there is negative, so the sign bits of the values or-ed together say it. */
SG_WALK_INLINE uint32_t sg_walk_in8(__m256i lo0, __m256i lo1, __m256i lo2, __m256i hi0, __m256i hi1,
                                    __m256i hi2) {
    __m256i lo = _mm256_or_si256(_mm256_or_si256(lo0, lo1), lo2);
    __m256i hi = _mm256_or_si256(_mm256_or_si256(hi0, hi1), hi2);
    uint32_t out = (uint32_t)_mm256_movemask_ps(_mm256_castsi256_ps(lo)) |
                   (uint32_t)_mm256_movemask_ps(_mm256_castsi256_ps(hi)) << 8;
    return ~out & 0xffffu;
}
#endif

/* Mask of the pixels of a tile at (x0, y0) inside the triangle's pixel bounds (which overlap the
 * tile): columns lo..hi of rows lo..hi. */
SG_WALK_INLINE uint32_t bounds_mask(const sg_tri *t, int x0, int y0) {
    int cl = t->minx - x0 > 0 ? t->minx - x0 : 0, ch = t->maxx - x0 < 3 ? t->maxx - x0 : 3;
    int rl = t->miny - y0 > 0 ? t->miny - y0 : 0, rh = t->maxy - y0 < 3 ? t->maxy - y0 : 3;
    uint32_t cols = (2u << ch) - (1u << cl);
    uint32_t rows = (1u << (4 * rh + 4)) - (1u << (4 * rl));
    return cols * 0x1111u & rows;
}

/* Offsets from a square's first pixel centre to the corner where each edge is largest (hi, for
 * rejection) and smallest (lo, for acceptance), for a square of `span` + 1 pixels a side. */
SG_WALK_INLINE void corners(const sg_tri *t, int64_t span, int64_t hi[3], int64_t lo[3]) {
    for (int e = 0; e < 3; e++) {
        int64_t ax = span * t->edge_dx[e], ay = span * t->edge_dy[e];
        hi[e] = (ax > 0 ? ax : 0) + (ay > 0 ? ay : 0);
        lo[e] = (ax < 0 ? ax : 0) + (ay < 0 ? ay : 0);
    }
}

/* The prepared triangle: corner offsets and, for narrow triangles, the 32-bit offset of each
 * pixel of a tile from its first pixel, per edge. */
typedef struct walk {
    const sg_tri *t;
    int64_t hi[3], lo[3];   /* 4x4 tile */
    int64_t bhi[3], blo[3]; /* 16x16 block */
    bool narrow;
#if defined(__AVX512F__)
    __m512i offs[3];    /* per edge: i dx + j dy of pixel (i, j) of a tile, in 32 bits */
    __m512i wide[3][2]; /* not narrow: the same in 64 bits, rows 0-1 and rows 2-3 */
#elif defined(__AVX2__)
    __m256i offs[3][2]; /* the same, rows 0-1 and rows 2-3 */
    __m256i wide[3][4]; /* not narrow: the same in 64 bits, a row a vector */
#elif defined(__SSE2__)
    __m128i lane[3], step[3]; /* per edge: 0, dx, 2 dx, 3 dx; and dy, in 32 bits */
#elif defined(__aarch64__) && defined(__ARM_NEON)
    int32x4_t lane[3], step[3]; /* as with SSE2 */
#else
    int32_t offs[3][SG_TILE_PIXELS];
#endif
} walk;

/* Covered pixels of a tile some edge crosses; e0: edge values at its first pixel. */
SG_WALK_INLINE uint32_t crossed_mask(const walk *w, const int64_t e0[3]) {
    const sg_tri *t = w->t;
    uint32_t mask = 0xffffu;
    if (w->narrow) {
#if defined(__AVX512F__)
        /* A whole tile a vector: an add and a compare per edge the tile straddles (only there
         * do the values fit in int32). */
        __mmask16 in = 0xffff;
        for (int e = 0; e < 3; e++) {
            if (e0[e] + w->lo[e] >= 0) continue;
            in = _mm512_mask_cmpge_epi32_mask(
                in,
                _mm512_add_epi32(_mm512_set1_epi32((int32_t)(uint32_t)(uint64_t)e0[e]), w->offs[e]),
                _mm512_setzero_si512());
        }
        return in;
#elif defined(__AVX2__)
        /* Half a tile a vector; an edge that holds the whole tile adds nothing (zero: no sign). */
        __m256i v[3][2];
        for (int e = 0; e < 3; e++) {
            if (e0[e] + w->lo[e] >= 0) {
                v[e][0] = v[e][1] = _mm256_setzero_si256();
                continue;
            }
            __m256i b = _mm256_set1_epi32((int32_t)(uint32_t)(uint64_t)e0[e]);
            v[e][0] = _mm256_add_epi32(b, w->offs[e][0]);
            v[e][1] = _mm256_add_epi32(b, w->offs[e][1]);
        }
        return sg_walk_in8(v[0][0], v[1][0], v[2][0], v[0][1], v[1][1], v[2][1]);
#elif defined(__SSE2__)
        for (int e = 0; e < 3; e++) {
            if (e0[e] + w->lo[e] >= 0) continue; /* this edge holds the whole tile */
            /* Exact: every value fits in int32, so wrapping 32-bit sums give it. */
            __m128i v =
                _mm_add_epi32(_mm_set1_epi32((int32_t)(uint32_t)(uint64_t)e0[e]), w->lane[e]);
            uint32_t out = 0;
            for (int j = 0; j < SG_TILE; j++) {
                out |= (uint32_t)_mm_movemask_ps(_mm_castsi128_ps(v)) << (4 * j);
                v = _mm_add_epi32(v, w->step[e]);
            }
            mask &= ~out; /* sign bit set: outside */
        }
        return mask;
#elif defined(__aarch64__) && defined(__ARM_NEON)
        /* Per row, the OR of the crossing edges' values: its sign bit is "outside some edge". */
        int32x4_t out[SG_TILE] = {vdupq_n_s32(0), vdupq_n_s32(0), vdupq_n_s32(0), vdupq_n_s32(0)};
        for (int e = 0; e < 3; e++) {
            if (e0[e] + w->lo[e] >= 0) continue; /* this edge holds the whole tile */
            /* Exact: every value fits in int32, so wrapping 32-bit sums give it. */
            int32x4_t v = vaddq_s32(vdupq_n_s32((int32_t)(uint32_t)(uint64_t)e0[e]), w->lane[e]);
            for (int j = 0; j < SG_TILE; j++) {
                out[j] = vorrq_s32(out[j], v);
                v = vaddq_s32(v, w->step[e]);
            }
        }
        return mask & ~sg_walk_signs16(out);
#else
        for (int e = 0; e < 3; e++) {
            if (e0[e] + w->lo[e] >= 0) continue;
            uint32_t base = (uint32_t)(uint64_t)e0[e];
            for (int i = 0; i < SG_TILE_PIXELS; i++)
                if ((int32_t)(base + (uint32_t)w->offs[e][i]) < 0) mask &= ~(1u << i);
        }
        return mask;
#endif
    }
#if defined(__AVX512F__)
    /* Wide (long lines, large triangles): the same test in 64-bit lanes, half a tile a vector. */
    for (int e = 0; e < 3; e++) {
        if (e0[e] + w->lo[e] >= 0) continue;
        const __m512i base = _mm512_set1_epi64(e0[e]), zero = _mm512_setzero_si512();
        uint32_t lo = _mm512_cmpge_epi64_mask(_mm512_add_epi64(base, w->wide[e][0]), zero);
        uint32_t hi = _mm512_cmpge_epi64_mask(_mm512_add_epi64(base, w->wide[e][1]), zero);
        mask &= lo | hi << 8;
    }
    return mask;
#elif defined(__AVX2__)
    /* Wide: a row of a tile a vector of 64-bit lanes; the sign bits are "outside". */
    for (int e = 0; e < 3; e++) {
        if (e0[e] + w->lo[e] >= 0) continue;
        const __m256i base = _mm256_set1_epi64x(e0[e]);
        for (int j = 0; j < SG_TILE; j++) {
            __m256d v = _mm256_castsi256_pd(_mm256_add_epi64(base, w->wide[e][j]));
            mask &= ~((uint32_t)_mm256_movemask_pd(v) << (4 * j));
        }
    }
    return mask;
#endif
    for (int i = 0; i < SG_TILE_PIXELS; i++) {
        int64_t ox = i & 3, oy = i >> 2;
        for (int e = 0; e < 3; e++)
            if (e0[e] + ox * t->edge_dx[e] + oy * t->edge_dy[e] < 0) mask &= ~(1u << i);
    }
    return mask;
}

SG_WALK_INLINE int64_t edge_at(const sg_tri *t, int e, int x, int y) {
    return t->edge[e] + (int64_t)(x - t->minx) * t->edge_dx[e] +
           (int64_t)(y - t->miny) * t->edge_dy[e];
}

/* Whether a tile at (x0, y0) lies inside the triangle's pixel bounds. */
SG_WALK_INLINE bool inner_tile(const sg_tri *t, int x0, int y0) {
    return x0 >= t->minx && x0 + SG_TILE - 1 <= t->maxx && y0 >= t->miny &&
           y0 + SG_TILE - 1 <= t->maxy;
}

/* The tiles tx0..tx1, ty0..ty1 of a block the triangle covers whole: no edge to test. */
SG_WALK_INLINE void accepted_tiles(const sg_tri *t, int tx0, int ty0, int tx1, int ty1,
                                   sg_tile_fn fn, const void *ctx) {
    for (int ty = ty0; ty <= ty1; ty++)
        for (int tx = tx0; tx <= tx1; tx++) {
            int x0 = tx << SG_TILE_SHIFT, y0 = ty << SG_TILE_SHIFT;
            uint32_t mask =
                !t->rect_cut || inner_tile(t, x0, y0) ? 0xffffu : bounds_mask(t, x0, y0);
            if (mask) fn(ctx, t, x0, y0, mask);
        }
}

/* The tiles tx0..tx1, ty0..ty1 of a block some edge crosses. */
SG_WALK_INLINE void walk_tiles(const walk *w, int tx0, int ty0, int tx1, int ty1, sg_tile_fn fn,
                               const void *ctx) {
    const sg_tri *t = w->t;
    for (int ty = ty0; ty <= ty1; ty++) {
        int y0 = ty << SG_TILE_SHIFT;
        int64_t row[3];
        for (int e = 0; e < 3; e++) row[e] = edge_at(t, e, tx0 << SG_TILE_SHIFT, y0);
        for (int tx = tx0; tx <= tx1; tx++) {
            int x0 = tx << SG_TILE_SHIFT;
            int64_t e0[3];
            bool reject = false, accept = true;
            for (int e = 0; e < 3; e++) {
                e0[e] = row[e];
                row[e] += SG_TILE * t->edge_dx[e];
                if (e0[e] + w->hi[e] < 0) reject = true;
                if (e0[e] + w->lo[e] < 0) accept = false;
            }
            if (reject) continue;
            uint32_t mask = accept ? 0xffffu : crossed_mask(w, e0);
            /* Tiles on cut bounds also hold pixels outside the setup rectangle. */
            if (t->rect_cut && !inner_tile(t, x0, y0)) mask &= bounds_mask(t, x0, y0);
            if (mask) fn(ctx, t, x0, y0, mask);
        }
    }
}

#if defined(__SSE2__) || (defined(__aarch64__) && defined(__ARM_NEON))
#if defined(__AVX512F__) || defined(__AVX2__)
/* A tile's edge values, the true ones (which fit in int32 there), a lane a pixel: with AVX-512 a
 * vector an edge, with AVX2 two (rows 0-1, rows 2-3). */
typedef struct sg_walk_edges {
#if defined(__AVX512F__)
    __m512i v[3];
#else
    __m256i v[3][2];
#endif
} sg_walk_edges;

/* A tile function that also takes the tile's edge values. */
typedef void (*sg_tile_edges_fn)(const void *ctx, const sg_tri *tri, int x0, int y0, uint32_t mask,
                                 const sg_walk_edges *v);
#endif

#if defined(__AVX512F__)
/* small_triangle with AVX-512: each tile visited goes to fe with its edge values when fe is not
 * NULL (a constant), else to fn. */
SG_WALK_INLINE bool small_triangle_vec(const sg_tri *t, int tx0, int ty0, int tx1, int ty1,
                                       sg_tile_fn fn, sg_tile_edges_fn fe, const void *ctx,
                                       const bool empty) {
    int x0 = tx0 << SG_TILE_SHIFT, y0 = ty0 << SG_TILE_SHIFT;
    int64_t hi[3], lo[3];
    /* A tile a vector: its first pixel's value plus i dx + j dy. A row of up to 16 tiles is first
     * tested a tile a lane, each tile by its largest value (the corner of corners()): only the
     * tiles that may hold covered pixels are then tested pixel by pixel, and visited. */
    corners(t, SG_SMALL_TILES * SG_TILE - 1, hi, lo);
    int64_t thi[3], tlo[3];
    corners(t, SG_TILE - 1, thi, tlo);
    const __m512i lane = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
    /* Per edge, in wrapping 32-bit lanes (the true values fit in int32): the pixels of tile
     * (tx0, ty0), each tile's largest value along the row, and the steps across and down. */
    __m512i first[3], best[3], down[3];
    uint32_t across[3]; /* unsigned: k * across wraps, as the lanes do */
    for (int e = 0; e < 3; e++) {
        int64_t e0 = edge_at(t, e, x0, y0);
        if (e0 + hi[e] < 0) return true;
        if (e0 + lo[e] < INT32_MIN || e0 + hi[e] > INT32_MAX) return false;
        uint32_t dx = (uint32_t)(uint64_t)t->edge_dx[e], dy = (uint32_t)(uint64_t)t->edge_dy[e];
        first[e] = _mm512_add_epi32(_mm512_set1_epi32((int32_t)(uint32_t)(uint64_t)e0),
                                    sg_walk_offsets(dx, dy));
        best[e] = _mm512_add_epi32(_mm512_set1_epi32((int32_t)(uint32_t)(uint64_t)(e0 + thi[e])),
                                   _mm512_mullo_epi32(_mm512_set1_epi32((int32_t)(4 * dx)), lane));
        across[e] = 4 * dx;
        down[e] = _mm512_set1_epi32((int32_t)(4 * dy));
    }
    const __m512i zero = _mm512_setzero_si512();
    const __mmask16 cols = (__mmask16)((2u << (tx1 - tx0)) - 1);
    for (int ty = ty0; ty <= ty1; ty++) {
        unsigned cand =
            empty && tx1 - tx0 < 2
                ? cols
                : _mm512_mask_cmpge_epi32_mask(
                      _mm512_mask_cmpge_epi32_mask(
                          _mm512_mask_cmpge_epi32_mask(cols, best[0], zero), best[1], zero),
                      best[2], zero);
        int ty_px = ty << SG_TILE_SHIFT;
        while (cand) {
            int k = __builtin_ctz(cand);
            cand &= cand - 1;
            sg_walk_edges v;
            __mmask16 in = 0xffff;
            for (int e = 0; e < 3; e++) {
                v.v[e] = _mm512_add_epi32(first[e],
                                          _mm512_set1_epi32((int32_t)((uint32_t)k * across[e])));
                in = _mm512_mask_cmpge_epi32_mask(in, v.v[e], zero);
            }
            int tx_px = (tx0 + k) << SG_TILE_SHIFT;
            uint32_t mask = in;
            if (t->rect_cut) mask &= bounds_mask(t, tx_px, ty_px);
            if (!empty && !mask) continue;
            if (fe)
                fe(ctx, t, tx_px, ty_px, mask, &v);
            else
                fn(ctx, t, tx_px, ty_px, mask);
        }
        for (int e = 0; e < 3; e++) {
            first[e] = _mm512_add_epi32(first[e], down[e]);
            best[e] = _mm512_add_epi32(best[e], down[e]);
        }
    }
    return true;
}
#elif defined(__AVX2__)
/* small_triangle with AVX2, fe as with AVX-512. */
SG_WALK_INLINE bool small_triangle_vec(const sg_tri *t, int tx0, int ty0, int tx1, int ty1,
                                       sg_tile_fn fn, sg_tile_edges_fn fe, const void *ctx,
                                       const bool empty) {
    int x0 = tx0 << SG_TILE_SHIFT, y0 = ty0 << SG_TILE_SHIFT;
    int64_t hi[3], lo[3];
    /* As with AVX-512, with half a tile a vector and a row of up to 16 tiles in two vectors of
     * eight lanes, a tile a lane. */
    corners(t, SG_SMALL_TILES * SG_TILE - 1, hi, lo);
    int64_t thi[3], tlo[3];
    corners(t, SG_TILE - 1, thi, tlo);
    const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
    /* Per edge, in wrapping 32-bit lanes (the true values fit in int32): the pixels of tile
     * (tx0, ty0) (two halves), the largest value of tiles 0-7 and 8-15 of the row, and the steps
     * across and down. */
    __m256i first[3][2], best[3][2], down[3];
    uint32_t across[3]; /* unsigned: k * across wraps, as the lanes do */
    for (int e = 0; e < 3; e++) {
        int64_t e0 = edge_at(t, e, x0, y0);
        if (e0 + hi[e] < 0) return true;
        if (e0 + lo[e] < INT32_MIN || e0 + hi[e] > INT32_MAX) return false;
        uint32_t dx = (uint32_t)(uint64_t)t->edge_dx[e], dy = (uint32_t)(uint64_t)t->edge_dy[e];
        __m256i b = _mm256_set1_epi32((int32_t)(uint32_t)(uint64_t)e0);
        first[e][0] = _mm256_add_epi32(b, sg_walk_offsets8(dx, dy, 0));
        first[e][1] = _mm256_add_epi32(b, sg_walk_offsets8(dx, dy, 1));
        best[e][0] =
            _mm256_add_epi32(_mm256_set1_epi32((int32_t)(uint32_t)(uint64_t)(e0 + thi[e])),
                             _mm256_mullo_epi32(_mm256_set1_epi32((int32_t)(4 * dx)), lane));
        best[e][1] = _mm256_add_epi32(best[e][0], _mm256_set1_epi32((int32_t)(32 * dx)));
        across[e] = 4 * dx;
        down[e] = _mm256_set1_epi32((int32_t)(4 * dy));
    }
    const uint32_t cols = (2u << (tx1 - tx0)) - 1;
    const bool wide = tx1 - tx0 >= 8; /* tiles 8-15 of the row are looked at */
    for (int ty = ty0; ty <= ty1; ty++) {
        uint32_t out = (uint32_t)_mm256_movemask_ps(_mm256_castsi256_ps(
            _mm256_or_si256(_mm256_or_si256(best[0][0], best[1][0]), best[2][0])));
        if (wide)
            out |= (uint32_t)_mm256_movemask_ps(_mm256_castsi256_ps(
                       _mm256_or_si256(_mm256_or_si256(best[0][1], best[1][1]), best[2][1])))
                   << 8;
        unsigned cand = empty && tx1 - tx0 < 2 ? cols : ~out & cols;
        int ty_px = ty << SG_TILE_SHIFT;
        while (cand) {
            int k = __builtin_ctz(cand);
            cand &= cand - 1;
            sg_walk_edges w;
            __m256i(*v)[2] = w.v;
            for (int e = 0; e < 3; e++) {
                __m256i step = _mm256_set1_epi32((int32_t)((uint32_t)k * across[e]));
                v[e][0] = _mm256_add_epi32(first[e][0], step);
                v[e][1] = _mm256_add_epi32(first[e][1], step);
            }
            uint32_t mask = sg_walk_in8(v[0][0], v[1][0], v[2][0], v[0][1], v[1][1], v[2][1]);
            int tx_px = (tx0 + k) << SG_TILE_SHIFT;
            if (t->rect_cut) mask &= bounds_mask(t, tx_px, ty_px);
            if (!empty && !mask) continue;
            if (fe)
                fe(ctx, t, tx_px, ty_px, mask, &w);
            else
                fn(ctx, t, tx_px, ty_px, mask);
        }
        for (int e = 0; e < 3; e++) {
            first[e][0] = _mm256_add_epi32(first[e][0], down[e]);
            first[e][1] = _mm256_add_epi32(first[e][1], down[e]);
            best[e][0] = _mm256_add_epi32(best[e][0], down[e]);
            best[e][1] = _mm256_add_epi32(best[e][1], down[e]);
        }
    }
    return true;
}
#endif

/* Triangles within 2 x 2 tiles (SG_SMALL_TILES a side with AVX-512 and AVX2; most of a mesh's):
 * the pixels of those tiles are tested at once in 32-bit edge values, four pixels a vector (a
 * tile with AVX-512, half a tile with AVX2), when every edge's values over the square fit in int32
 * (they are linear, so the square's corners bound them). False: not taken. With `empty` (a
 * constant), fn takes tiles with an empty mask too (with AVX-512 and AVX2): a triangle of a
 * tile or two across then has its row's tiles visited without the row's tile test, and no tile
 * waits on a branch on its mask, which a dense mesh's small triangles set in no pattern a
 * predictor follows. */
SG_WALK_INLINE bool small_triangle(const sg_tri *t, int tx0, int ty0, int tx1, int ty1,
                                   sg_tile_fn fn, const void *ctx, const bool empty) {
#if defined(__AVX512F__) || defined(__AVX2__)
    return small_triangle_vec(t, tx0, ty0, tx1, ty1, fn, NULL, ctx, empty);
#else
    int x0 = tx0 << SG_TILE_SHIFT, y0 = ty0 << SG_TILE_SHIFT;
    int64_t hi[3], lo[3];
#if defined(__SSE2__)
    (void)empty; /* here fn is called for tiles with a covered pixel only */
    corners(t, 2 * SG_TILE - 1, hi, lo);
    __m128i v[3], step[3], four[3];
    for (int e = 0; e < 3; e++) {
        int64_t e0 = edge_at(t, e, x0, y0);
        if (e0 + hi[e] < 0) return true; /* the whole square is outside this edge */
        if (e0 + lo[e] < INT32_MIN || e0 + hi[e] > INT32_MAX) return false;
        int32_t dx = (int32_t)t->edge_dx[e], dy = (int32_t)t->edge_dy[e];
        v[e] = _mm_add_epi32(_mm_set1_epi32((int32_t)e0), _mm_setr_epi32(0, dx, 2 * dx, 3 * dx));
        step[e] = _mm_set1_epi32(dy);
        four[e] = _mm_set1_epi32(4 * dx);
    }
    uint32_t masks[4] = {0, 0, 0, 0};     /* tiles (0,0) (1,0) (0,1) (1,1) */
    int rows = (ty1 - ty0 + 1) * SG_TILE; /* only the tiles of the range */
    bool right = tx1 > tx0;
    for (int j = 0; j < rows; j++) {
        __m128i out_l = _mm_setzero_si128(), out_r = _mm_setzero_si128();
        for (int e = 0; e < 3; e++) { /* sign bit: outside */
            out_l = _mm_or_si128(out_l, v[e]);
            if (right) out_r = _mm_or_si128(out_r, _mm_add_epi32(v[e], four[e]));
            v[e] = _mm_add_epi32(v[e], step[e]);
        }
        int shift = 4 * (j & 3), half = (j >> 2) * 2;
        masks[half] |= (uint32_t)(~_mm_movemask_ps(_mm_castsi128_ps(out_l)) & 15) << shift;
        masks[half + 1] |= (uint32_t)(~_mm_movemask_ps(_mm_castsi128_ps(out_r)) & 15) << shift;
    }
    for (int k = 0; k < 4; k++) {
        int tx = tx0 + (k & 1), ty = ty0 + (k >> 1);
        if (tx > tx1 || ty > ty1 || !masks[k])
            continue; /* tiles past tx1 or ty1 are not looked at */
        int tx_px = tx << SG_TILE_SHIFT, ty_px = ty << SG_TILE_SHIFT;
        uint32_t mask = t->rect_cut ? masks[k] & bounds_mask(t, tx_px, ty_px) : masks[k];
        if (mask) fn(ctx, t, tx_px, ty_px, mask);
    }
    return true;
#else
    (void)empty;
    /* As the SSE2 code: per edge, four pixels of a row a vector, the right tile four columns on. */
    corners(t, 2 * SG_TILE - 1, hi, lo);
    int32x4_t v[3], step[3], four[3];
    for (int e = 0; e < 3; e++) {
        int64_t e0 = edge_at(t, e, x0, y0);
        if (e0 + hi[e] < 0) return true; /* the whole square is outside this edge */
        if (e0 + lo[e] < INT32_MIN || e0 + hi[e] > INT32_MAX) return false;
        /* Wrapping 32-bit products and sums: the true values fit, so they are exact. */
        uint32_t dx = (uint32_t)(uint64_t)t->edge_dx[e], dy = (uint32_t)(uint64_t)t->edge_dy[e];
        const uint32x4_t i = {0, 1, 2, 3};
        v[e] = vaddq_s32(vdupq_n_s32((int32_t)e0),
                         vreinterpretq_s32_u32(vmulq_u32(vdupq_n_u32(dx), i)));
        step[e] = vreinterpretq_s32_u32(vdupq_n_u32(dy));
        four[e] = vreinterpretq_s32_u32(vdupq_n_u32(4 * dx));
    }
    const bool right = tx1 > tx0;
    for (int ty = ty0; ty <= ty1; ty++) {
        int32x4_t out_l[SG_TILE], out_r[SG_TILE]; /* sign bit: outside some edge */
        for (int j = 0; j < SG_TILE; j++) {
            out_l[j] = vorrq_s32(vorrq_s32(v[0], v[1]), v[2]);
            out_r[j] = vorrq_s32(vorrq_s32(vaddq_s32(v[0], four[0]), vaddq_s32(v[1], four[1])),
                                 vaddq_s32(v[2], four[2]));
            for (int e = 0; e < 3; e++) v[e] = vaddq_s32(v[e], step[e]);
        }
        int ty_px = ty << SG_TILE_SHIFT;
        for (int k = 0; k <= (right ? 1 : 0); k++) {
            uint32_t mask = ~sg_walk_signs16(k ? out_r : out_l) & 0xffffu;
            int tx_px = (tx0 + k) << SG_TILE_SHIFT;
            if (t->rect_cut) mask &= bounds_mask(t, tx_px, ty_px);
            if (mask) fn(ctx, t, tx_px, ty_px, mask);
        }
    }
    return true;
#endif
#endif
}
#endif

static inline int64_t sg_walk_floor_div(int64_t a, int64_t b) { /* b > 0 */
    int64_t q = a / b;
    return q - (a % b < 0);
}

/* A line (line.h): one pixel a major column (x for an x-major line, y for a y-major one), at the
 * minor coordinate min_lo + floor(F / minor_step), F being edge 0's value at (that column,
 * min_lo): there edge 0 is in [0, minor_step) and edge 1, minor_step - 1 minus edge 0, is not
 * negative, and at no other pixel of the column are both. F changes by major_step a column and
 * |major_step| <= minor_step, so an integer DDA follows the quotient exactly (the pixels are the
 * edge functions' own), a step moving it by at most one. */
typedef struct sg_line_dda {
    bool xm;    /* x-major: u is x, v is y */
    int u0, u1; /* the columns to draw */
    int v0, v1; /* the minor range to draw (a pixel outside is skipped) */
    int v;      /* the pixel of the current column (u0 at the start) */
    int dir;    /* where v moves: +1 or -1 */
    int64_t r;  /* a remainder in [0, minor_step) that grows by `grow` a column */
    int64_t grow, minor_step;
} sg_line_dda;

/* The DDA of line t at its first column within [rx0, rx1) x [ry0, ry1); false: no pixel there. */
SG_WALK_INLINE bool sg_line_dda_start(const sg_tri *t, int rx0, int ry0, int rx1, int ry1,
                                      sg_line_dda *d) {
    const bool xm = t->line == 1;
    const int64_t major_step = xm ? t->edge_dx[0] : t->edge_dy[0];
    const int64_t minor_step = -(xm ? t->edge_dy[0] : t->edge_dx[0]); /* > 0 */
    const int maj_lo = xm ? t->minx : t->miny, min_lo = xm ? t->miny : t->minx;
    /* The columns and the minor range to draw: the line's bounds within [rx0, rx1) x [ry0, ry1). */
    int u0 = maj_lo, u1 = xm ? t->maxx : t->maxy;
    int v0 = min_lo, v1 = xm ? t->maxy : t->maxx;
    const int ru0 = xm ? rx0 : ry0, ru1 = (xm ? rx1 : ry1) - 1;
    const int rv0 = xm ? ry0 : rx0, rv1 = (xm ? ry1 : rx1) - 1;
    if (u0 < ru0) u0 = ru0;
    if (u1 > ru1) u1 = ru1;
    if (v0 < rv0) v0 = rv0;
    if (v1 > rv1) v1 = rv1;
    if (u0 > u1 || v0 > v1) return false;
    const int64_t f = t->edge[0] + (int64_t)(u0 - maj_lo) * major_step;
    const int64_t q0 = sg_walk_floor_div(f, minor_step), rem = f - q0 * minor_step;
    /* Going down, r is minor_step - 1 minus the true remainder, which falls by |major_step| and
     * moves v when it turns negative. */
    *d = (sg_line_dda){xm,
                       u0,
                       u1,
                       v0,
                       v1,
                       min_lo + (int)q0, /* within the snapped coordinates / 256: it fits */
                       major_step < 0 ? -1 : 1,
                       major_step < 0 ? minor_step - 1 - rem : rem,
                       major_step < 0 ? -major_step : major_step,
                       minor_step};
    return true;
}

/* On to the next column. */
SG_WALK_INLINE void sg_line_dda_step(sg_line_dda *d) {
    d->r += d->grow; /* without branches: where v moves is not predictable */
    const bool move = d->r >= d->minor_step;
    d->v += move ? d->dir : 0;
    d->r -= move ? d->minor_step : 0;
}

/* The pixels of the next `lanes` columns of which n (1 .. lanes) are drawn, the DDA moved past
 * those n: their minor coordinates in vs (the lanes past n repeat the next pixel, unused), and
 * the bits of the lanes inside the minor range. */
SG_WALK_INLINE uint32_t sg_line_dda_columns(sg_line_dda *d, int32_t *vs, const int lanes, int n) {
    uint32_t bits = 0;
    for (int k = 0; k < lanes; k++) {
        vs[k] = d->v;
        if (k >= n) continue;
        bits |= (uint32_t)(d->v >= d->v0 && d->v <= d->v1) << k;
        sg_line_dda_step(d);
    }
    return bits;
}

/* The tile walk of a line: each four columns' pixels fall in one or two tiles, whose masks are
 * built here: no tile is tested, none is visited without a pixel. */
SG_WALK_INLINE void line_walk(const sg_tri *t, int rx0, int ry0, int rx1, int ry1, sg_tile_fn fn,
                              const void *ctx) {
    sg_line_dda d;
    if (!sg_line_dda_start(t, rx0, ry0, rx1, ry1, &d)) return;
    const bool xm = d.xm;
    for (int ub = d.u0 & ~(SG_TILE - 1); ub <= d.u1; ub += SG_TILE) {
        /* The tile column's pixels in the tiles `first` and first + 1 across (a 16-bit mask
         * each, the low and the high half): the first column's pixel fixes `first`, and the
         * others are within 3 of it, on the side the line goes. */
        const int first =
            (d.v >> SG_TILE_SHIFT) - (d.dir < 0 && (d.v & (SG_TILE - 1)) < SG_TILE - 1);
        uint32_t mask = 0;
        const int ue = ub + SG_TILE - 1 < d.u1 ? ub + SG_TILE - 1 : d.u1;
        for (int u = ub > d.u0 ? ub : d.u0; u <= ue; u++) {
            const int v = d.v;
            if (v >= d.v0 && v <= d.v1) {
                const int at = ((v >> SG_TILE_SHIFT) - first) * SG_TILE_PIXELS +
                               (xm ? (v & (SG_TILE - 1)) * SG_TILE + (u & (SG_TILE - 1))
                                   : (u & (SG_TILE - 1)) * SG_TILE + (v & (SG_TILE - 1)));
                mask |= 1u << at;
            }
            sg_line_dda_step(&d);
        }
        for (int k = 0; k < 2; k++, mask >>= SG_TILE_PIXELS) {
            if (!(mask & 0xffffu)) continue;
            const int vt = (first + k) << SG_TILE_SHIFT;
            if (xm)
                fn(ctx, t, ub, vt, mask & 0xffffu);
            else
                fn(ctx, t, vt, ub, mask & 0xffffu);
        }
    }
}

/* The walk of triangle t prepared: corner offsets, and each edge's offsets over a tile. */
SG_WALK_INLINE void sg_walk_prepare(const sg_tri *t, walk *w) {
    w->t = t;
    corners(t, SG_TILE - 1, w->hi, w->lo);
    w->narrow = true;
    for (int e = 0; e < 3; e++) w->narrow &= w->hi[e] - w->lo[e] < ((int64_t)1 << 31);
    if (w->narrow) /* then 3 |dx| and 3 |dy| fit in int32 too */
        for (int e = 0; e < 3; e++) {
            int32_t dx = (int32_t)t->edge_dx[e], dy = (int32_t)t->edge_dy[e];
#if defined(__AVX512F__)
            w->offs[e] = sg_walk_offsets((uint32_t)dx, (uint32_t)dy);
#elif defined(__AVX2__)
            w->offs[e][0] = sg_walk_offsets8((uint32_t)dx, (uint32_t)dy, 0);
            w->offs[e][1] = sg_walk_offsets8((uint32_t)dx, (uint32_t)dy, 1);
#elif defined(__SSE2__)
            w->lane[e] = _mm_setr_epi32(0, dx, 2 * dx, 3 * dx);
            w->step[e] = _mm_set1_epi32(dy);
#elif defined(__aarch64__) && defined(__ARM_NEON)
            const int32x4_t i = {0, 1, 2, 3};
            w->lane[e] = vmulq_s32(vdupq_n_s32(dx), i);
            w->step[e] = vdupq_n_s32(dy);
#else
            for (int i = 0; i < SG_TILE_PIXELS; i++) w->offs[e][i] = (i & 3) * dx + (i >> 2) * dy;
#endif
        }
#if defined(__AVX512F__) || defined(__AVX2__)
    else
        for (int e = 0; e < 3; e++) {
            int64_t o[SG_TILE_PIXELS];
            for (int i = 0; i < SG_TILE_PIXELS; i++)
                o[i] = (i & 3) * t->edge_dx[e] + (i >> 2) * t->edge_dy[e];
#if defined(__AVX512F__)
            for (int h = 0; h < 2; h++) w->wide[e][h] = _mm512_loadu_si512(o + 8 * h);
#else
            for (int j = 0; j < SG_TILE; j++)
                w->wide[e][j] = _mm256_loadu_si256((const __m256i *)(const void *)(o + 4 * j));
#endif
        }
#endif
}

/* The tiles tx0..tx1, ty0..ty1 of t's bounds within [rx0, rx1) x [ry0, ry1); false: none. */
SG_WALK_INLINE bool sg_walk_tile_range(const sg_tri *t, int rx0, int ry0, int rx1, int ry1,
                                       int *tx0, int *ty0, int *tx1, int *ty1) {
    *tx0 = (t->minx > rx0 ? t->minx : rx0) >> SG_TILE_SHIFT;
    *ty0 = (t->miny > ry0 ? t->miny : ry0) >> SG_TILE_SHIFT;
    *tx1 = (t->maxx < rx1 - 1 ? t->maxx : rx1 - 1) >> SG_TILE_SHIFT;
    *ty1 = (t->maxy < ry1 - 1 ? t->maxy : ry1 - 1) >> SG_TILE_SHIFT;
    return *tx0 <= *tx1 && *ty0 <= *ty1;
}

/* sg_rast_walk, with `empty` (a constant) as small_triangle takes it: fn may be called for a tile
 * of a small triangle with an empty mask. */
SG_WALK_INLINE void sg_rast_walk_any(const sg_tri *t, int rx0, int ry0, int rx1, int ry1,
                                     sg_tile_fn fn, const void *ctx, const bool empty) {
    int tx0, ty0, tx1, ty1;
    if (!sg_walk_tile_range(t, rx0, ry0, rx1, ry1, &tx0, &ty0, &tx1, &ty1)) return;
#if defined(__AVX512F__) || defined(__AVX2__)
    if (tx1 - tx0 < SG_SMALL_TILES && ty1 - ty0 < SG_SMALL_TILES &&
        small_triangle(t, tx0, ty0, tx1, ty1, fn, ctx, empty))
        return;
#elif defined(__SSE2__) || (defined(__aarch64__) && defined(__ARM_NEON))
    if (tx1 - tx0 < 2 && ty1 - ty0 < 2 && small_triangle(t, tx0, ty0, tx1, ty1, fn, ctx, empty))
        return;
#endif
    if (t->line) {
        line_walk(t, rx0, ry0, rx1, ry1, fn, ctx);
        return;
    }
    walk w;
    sg_walk_prepare(t, &w);
    /* Small triangles: one block at most, so go straight to the tiles. */
    if (tx1 - tx0 < 4 && ty1 - ty0 < 4) {
        walk_tiles(&w, tx0, ty0, tx1, ty1, fn, ctx);
        return;
    }
    corners(t, 4 * SG_TILE - 1, w.bhi, w.blo);
    for (int by = ty0 & ~3; by <= ty1; by += 4)
        for (int bx = tx0 & ~3; bx <= tx1; bx += 4) {
            bool reject = false, accept = true;
            for (int e = 0; e < 3; e++) {
                int64_t v = edge_at(t, e, bx << SG_TILE_SHIFT, by << SG_TILE_SHIFT);
                if (v + w.bhi[e] < 0) reject = true;
                if (v + w.blo[e] < 0) accept = false;
            }
            if (reject) continue;
            int x0 = bx > tx0 ? bx : tx0, y0 = by > ty0 ? by : ty0;
            int x1 = bx + 3 < tx1 ? bx + 3 : tx1, y1 = by + 3 < ty1 ? by + 3 : ty1;
            if (accept)
                accepted_tiles(t, x0, y0, x1, y1, fn, ctx);
            else
                walk_tiles(&w, x0, y0, x1, y1, fn, ctx);
        }
}

/* The tiles of triangle t within [rx0, rx1) x [ry0, ry1) that hold a covered pixel, each once
 * with its mask (fn is never called with an empty one). */
SG_WALK_INLINE void sg_rast_walk(const sg_tri *t, int rx0, int ry0, int rx1, int ry1, sg_tile_fn fn,
                                 const void *ctx) {
    sg_rast_walk_any(t, rx0, ry0, rx1, ry1, fn, ctx, false);
}

#endif
