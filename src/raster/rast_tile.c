/* rast_tile.c - tile traversal and coverage masks (see rast_tile.h).
 *
 * The walk is hierarchical: a triangle's bounds are covered by 16x16-pixel blocks, each rejected
 * or accepted whole by its corners, and only blocks an edge crosses descend to their 4x4 tiles,
 * which are again rejected or accepted whole; only tiles an edge crosses test pixels. Edge values
 * are exact 64-bit integers; inside a crossed tile they differ from the tile's first pixel by less
 * than 3 (|dx| + |dy|), so for every triangle whose steps keep that under 2^31 (edges shorter
 * than about 5000 pixels) the 16 pixel tests run in 32 bits, four at a time in SSE2. The result is
 * the same exact comparison in every path.
 */
#include "raster/rast_tile.h"

#include <stdbool.h>

#include "raster/framebuffer.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

/* Mask of the pixels of a tile at (x0, y0) inside the triangle's pixel bounds (which overlap the
 * tile): columns lo..hi of rows lo..hi. */
static inline uint32_t bounds_mask(const sg_tri *t, int x0, int y0) {
    int cl = t->minx - x0 > 0 ? t->minx - x0 : 0, ch = t->maxx - x0 < 3 ? t->maxx - x0 : 3;
    int rl = t->miny - y0 > 0 ? t->miny - y0 : 0, rh = t->maxy - y0 < 3 ? t->maxy - y0 : 3;
    uint32_t cols = (2u << ch) - (1u << cl);
    uint32_t rows = (1u << (4 * rh + 4)) - (1u << (4 * rl));
    return cols * 0x1111u & rows;
}

/* Offsets from a square's first pixel centre to the corner where each edge is largest (hi, for
 * rejection) and smallest (lo, for acceptance), for a square of `span` + 1 pixels a side. */
static void corners(const sg_tri *t, int64_t span, int64_t hi[3], int64_t lo[3]) {
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
#if defined(__SSE2__)
    __m128i lane[3], step[3]; /* per edge: 0, dx, 2 dx, 3 dx; and dy, in 32 bits */
#else
    int32_t offs[3][SG_TILE_PIXELS];
#endif
} walk;

/* Covered pixels of a tile some edge crosses; e0: edge values at its first pixel. */
static inline uint32_t crossed_mask(const walk *w, const int64_t e0[3]) {
    const sg_tri *t = w->t;
    uint32_t mask = 0xffffu;
    if (w->narrow) {
#if defined(__SSE2__)
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
    for (int i = 0; i < SG_TILE_PIXELS; i++) {
        int64_t ox = i & 3, oy = i >> 2;
        for (int e = 0; e < 3; e++)
            if (e0[e] + ox * t->edge_dx[e] + oy * t->edge_dy[e] < 0) mask &= ~(1u << i);
    }
    return mask;
}

static inline int64_t edge_at(const sg_tri *t, int e, int x, int y) {
    return t->edge[e] + (int64_t)(x - t->minx) * t->edge_dx[e] +
           (int64_t)(y - t->miny) * t->edge_dy[e];
}

/* The tiles tx0..tx1, ty0..ty1 of one block. */
static void walk_tiles(const walk *w, int tx0, int ty0, int tx1, int ty1, bool accepted,
                       sg_tile_fn fn, const void *ctx) {
    const sg_tri *t = w->t;
    for (int ty = ty0; ty <= ty1; ty++) {
        int y0 = ty << SG_TILE_SHIFT;
        bool y_inner = y0 >= t->miny && y0 + SG_TILE - 1 <= t->maxy;
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
            if (!accepted && reject) continue;
            uint32_t mask = accepted || accept ? 0xffffu : crossed_mask(w, e0);
            /* Tiles on the bounds also hold pixels outside the target or scissor rectangle. */
            if (!(y_inner && x0 >= t->minx && x0 + SG_TILE - 1 <= t->maxx))
                mask &= bounds_mask(t, x0, y0);
            if (mask) fn(ctx, t, x0, y0, mask);
        }
    }
}

void sg_rast_triangle(const sg_tri *t, sg_tile_fn fn, const void *ctx) {
    sg_rast_triangle_in(t, 0, 0, t->maxx + 1, t->maxy + 1, fn, ctx);
}

void sg_rast_triangle_in(const sg_tri *t, int rx0, int ry0, int rx1, int ry1, sg_tile_fn fn,
                         const void *ctx) {
    int tx0 = (t->minx > rx0 ? t->minx : rx0) >> SG_TILE_SHIFT;
    int ty0 = (t->miny > ry0 ? t->miny : ry0) >> SG_TILE_SHIFT;
    int tx1 = (t->maxx < rx1 - 1 ? t->maxx : rx1 - 1) >> SG_TILE_SHIFT;
    int ty1 = (t->maxy < ry1 - 1 ? t->maxy : ry1 - 1) >> SG_TILE_SHIFT;
    if (tx0 > tx1 || ty0 > ty1) return;
    walk w;
    w.t = t;
    corners(t, SG_TILE - 1, w.hi, w.lo);
    w.narrow = true;
    for (int e = 0; e < 3; e++) w.narrow &= w.hi[e] - w.lo[e] < ((int64_t)1 << 31);
    if (w.narrow) /* then 3 |dx| and 3 |dy| fit in int32 too */
        for (int e = 0; e < 3; e++) {
            int32_t dx = (int32_t)t->edge_dx[e], dy = (int32_t)t->edge_dy[e];
#if defined(__SSE2__)
            w.lane[e] = _mm_setr_epi32(0, dx, 2 * dx, 3 * dx);
            w.step[e] = _mm_set1_epi32(dy);
#else
            for (int i = 0; i < SG_TILE_PIXELS; i++) w.offs[e][i] = (i & 3) * dx + (i >> 2) * dy;
#endif
        }
    /* Small triangles: one block at most, so go straight to the tiles. */
    if (tx1 - tx0 < 4 && ty1 - ty0 < 4) {
        walk_tiles(&w, tx0, ty0, tx1, ty1, false, fn, ctx);
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
            walk_tiles(&w, bx > tx0 ? bx : tx0, by > ty0 ? by : ty0, bx + 3 < tx1 ? bx + 3 : tx1,
                       by + 3 < ty1 ? by + 3 : ty1, accept, fn, ctx);
        }
}
