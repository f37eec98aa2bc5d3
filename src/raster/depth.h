/* depth.h - visibility: which triangle is seen at each pixel of a screen bin.
 *
 * A bin's triangles are rasterised in submission order into the bin's depth and triangle-id
 * buffers (no colour yet). A covered pixel that passes the pipeline's depth test takes the
 * triangle's id (and its depth when the pipeline writes depth). With no blending, the colour a
 * forward renderer would leave in a pixel is exactly the colour of the last triangle that passed
 * there, so shading the surviving ids once (rast_bin.c) gives the same bytes at any overdraw.
 */
#ifndef SG_DEPTH_H
#define SG_DEPTH_H

#include <stdbool.h>
#include <stdint.h>
#include <string.h>
#if defined(__SSE2__)
#include <emmintrin.h>
#elif defined(__aarch64__) && defined(__ARM_NEON)
#include <arm_neon.h>
#endif

#include "raster/rast_tile.h"
#include "raster/shade.h"
#include "sgapi/sgapi.h"

struct sg_vis_ctx;

/* Work a draw shaded in place leaves for later in a bin: the shading jobs of a textured blended
 * draw's triangles, batched across its triangles (blend_avx2.c, blend_avx512.c: the pixels of
 * one job are shaded and blended in the order the jobs came, so a pixel still sees the triangles
 * in order), or the fragments of an opaque shader draw with independent lanes waiting in the
 * bin's ids (shade_shader.c). The bin runs them (flush) before anything else touches its colour:
 * a triangle of another draw, the opaque ids' shading, the bin's end. */
enum { SG_PENDING_BYTES = 8192 };
typedef struct sg_blend_pending {
    void (*flush)(struct sg_blend_pending *p, const struct sg_vis_ctx *v);
    int n;         /* jobs waiting */
    uint32_t draw; /* their draw */
    int flat;      /* their triangles' sg_tri.flat, all the same */
    /* Shader draws' fragments waiting in the ids (shade_shader.c) write depth. */
    bool depth_write;
    _Alignas(64) unsigned char jobs[SG_PENDING_BYTES];
} sg_blend_pending;

/* A triangle's tiles where some sample passed, as a recording sample walk found them (a
 * multisampled bin's triangles shaded in place, rast_msaa.c): tile[i]'s passing pixels of sample
 * k in mask[i][k]; such a walk writes depth as its draw does, but neither ids nor reached marks. */
typedef struct sg_vis_record {
    int n;
    uint16_t tile[256];
    uint16_t mask[256][4];
} sg_vis_record;

/* The bin being rasterised: both buffers hold 64 x 64 pixels as 16 x 16 tiles of 4 x 4. */
typedef struct sg_vis_ctx {
    float *depth;     /* NULL when the pass has no depth target */
    uint32_t *ids;    /* 0: no triangle; else index + 1 of the triangle in the pass */
    uint8_t *reached; /* SG_REACHED_BYTES, a byte a tile: not 0 once some triangle reached it */
    int bx0, by0;     /* the bin's top-left pixel */
    uint32_t id;      /* id of the triangle being rasterised */
    sgCompare compare;
    /* Blended draws only (blend.c): they shade and blend into the bin's colour at once. */
    uint32_t *color;
    sg_shade_fn shade;
    const sg_shade_ctx *shade_ctx;
    sg_blend_pending *pending;
    /* Multisampled bins only, vis[0]'s (NULL elsewhere): bits a tile, SG_REACHED_WORDS words of
     * tiles whose ids are taken as 0 (never written, or shaded since), then as many of tiles
     * whose planes 1-3 of depth are taken as plane 0's; the walks set both at a tile's touch
     * (sg_vis_samples_touch), so a bin clears and copies only the tiles it draws. */
    uint64_t *fresh;
    /* vis[0]'s, for a recording sample walk (sg_vis_fns.record); NULL elsewhere. */
    sg_vis_record *record;
} sg_vis_ctx;

/* Rasterises a triangle's part in the rectangle [x0, x1) x [y0, y1) into the bin's buffers (ctx:
 * an sg_vis_ctx): the walk of rast_walk.h with one visibility tile function inlined. */
typedef void (*sg_raster_fn)(const sg_tri *t, int x0, int y0, int x1, int y1, const void *ctx);

/* The walk of rast_walk.h as compiled for one instruction set, with any tile function: the
 * coverage tests (test_watertight) run every set's walk. */
typedef void (*sg_walk_fn)(const sg_tri *t, int x0, int y0, int x1, int y1, sg_tile_fn fn,
                           const void *ctx);
/** The walk compiled for `isa` (the baseline one when that set's code is not built). */
sg_walk_fn sg_walk_select(sg_isa isa);
sg_walk_fn sg_walk_avx2(void);
sg_walk_fn sg_walk_avx512(void);

/** The visibility function for a resolved depth state. */
sg_raster_fn sg_depth_select(sgCompare compare, bool depth_write, sg_isa isa);

/** Window depth of a triangle at (dx, dy) pixels from its bounds' first pixel, clamped to the
 *  depth range [0, 1] (a NaN stays NaN): every visibility function computes it this way. */
static inline float sg_tri_depth(const sg_tri *t, float dx, float dy) {
    float z = t->z + t->z_dx * dx + t->z_dy * dy;
    return z < 0.0f ? 0.0f : (z > 1.0f ? 1.0f : z);
}

/** Whether depth z passes the compare against the stored d. */
static inline bool sg_depth_passes(sgCompare op, float z, float d) {
    switch (op) {
    case SG_COMPARE_NEVER:
        return false;
    case SG_COMPARE_LESS:
        return z < d;
    case SG_COMPARE_EQUAL:
        return z == d;
    case SG_COMPARE_LESS_EQUAL:
        return z <= d;
    case SG_COMPARE_GREATER:
        return z > d;
    case SG_COMPARE_NOT_EQUAL:
        return z != d;
    case SG_COMPARE_GREATER_EQUAL:
        return z >= d;
    default:
        return true;
    }
}

/** Whether every pixel of t in the rectangle [x0, x1] x [y0, y1] (inclusive) passes compare `op`
 *  against every stored depth in [lo, hi], whatever the pixel's value there: a bound of t's plane
 *  with a margin for rounding. False also for the compares it does not bound (EQUAL, NOT_EQUAL,
 *  NEVER, ALWAYS). */
bool sg_depth_passes_all(const sg_tri *t, sgCompare op, int x0, int y0, int x1, int y1, float lo,
                         float hi);

/** The tile's ids in the bin, the tile marked as reached: shading visits only reached tiles.
 *  (No branch on a first visit: one that mispredicts once per tile costs more than clearing the
 *  bin's ids up front. A byte a tile, stored, not a bit or-ed into a word: a mesh's small
 *  triangles reach tile after tile of one word, and each or waited for the one before.) */
static inline uint32_t *sg_vis_tile_ids(const sg_vis_ctx *v, int base) {
    v->reached[base >> 4] = 1;
    return v->ids + base;
}

/* A bin's tiles in words of 64 (sg_reached_word); the reached bytes of a bin, its 256 tiles' and
 * a spare one that no word holds, padded to a cache line. */
enum { SG_REACHED_WORDS = 4, SG_REACHED_SPARE = 256, SG_REACHED_BYTES = 320 };

/** sg_vis_tile_ids for a tile function that the walk also calls with empty masks
 *  (sg_rast_walk_any): such a tile is not marked (its mark goes to the spare byte). */
static inline uint32_t *sg_vis_tile_ids_of(const sg_vis_ctx *v, int base, uint32_t mask) {
    v->reached[mask ? base >> 4 : SG_REACHED_SPARE] = 1;
    return v->ids + base;
}

/** Tiles 64 word .. 64 word + 63 that the visibility functions reached, a bit a tile. */
static inline uint64_t sg_reached_word(const uint8_t *reached, int word) {
    const uint8_t *r = reached + 64 * word;
#if defined(__SSE2__)
    uint64_t none = 0;
    for (int j = 0; j < 4; j++) {
        __m128i v = _mm_loadu_si128((const __m128i *)(const void *)(r + 16 * j));
        none |= (uint64_t)(uint32_t)_mm_movemask_epi8(_mm_cmpeq_epi8(v, _mm_setzero_si128()))
                << (16 * j);
    }
    return ~none;
#else
    uint64_t bits = 0;
    for (int i = 0; i < 64; i++) bits |= (uint64_t)(r[i] != 0) << i;
    return bits;
#endif
}

/* Multisampled passes (rast_msaa.h): a pixel's samples. */
enum { SG_VIS_SAMPLES = 4 };

/* The visibility of a triangle's samples in the rectangle [x0, x1) x [y0, y1): st[k] is the
 * triangle as sample k sees it (sg_msaa_sample_tri), vis[k] sample k's plane of ids and depth.
 * The planes end as SG_VIS_SAMPLES calls of the sg_raster_fn of the same depth state would leave
 * them, one a sample, but the triangle is walked once (depth_walk.h). */
typedef void (*sg_raster_samples_fn)(const sg_tri *st, int x0, int y0, int x1, int y1,
                                     sg_vis_ctx *vis);

/** The sample visibility function for a resolved depth state. */
sg_raster_samples_fn sg_depth_samples_select(sgCompare compare, bool depth_write, sg_isa isa);
/** The recording one (sg_vis_record), or NULL where the set has none. */
sg_raster_samples_fn sg_depth_record_select(sgCompare compare, bool depth_write, sg_isa isa);

/* A set's visibility functions of one depth state: one sample, and the four samples at once. */
typedef struct sg_vis_fns {
    sg_raster_fn one; /* NULL: the set has none for this state, or is not built */
    sg_raster_samples_fn samples;
    sg_raster_samples_fn record; /* samples, recording (sg_vis_record); NULL where none */
} sg_vis_fns;

/** The AVX2 visibility functions of a compare (depth_avx2.c); NULLs where AVX2 code is not built.
 */
sg_vis_fns sg_depth_avx2(sgCompare compare, bool depth_write);
/** The AVX-512 ones (depth_avx512.c); NULLs where AVX-512 code is not built. */
sg_vis_fns sg_depth_avx512(sgCompare compare, bool depth_write);
/** The NEON LESS ones (depth_neon.c); NULLs off AArch64. */
sg_vis_fns sg_depth_less_neon(bool depth_write);

/** Mask of the pixels of a tile (16 ids) that see triangle `id`. */
static inline uint32_t sg_tile_same_id(const uint32_t *ids, uint32_t id) {
#if defined(__SSE2__)
    __m128i v = _mm_set1_epi32((int32_t)id);
    uint32_t mask = 0;
    for (int j = 0; j < 4; j++) {
        __m128i row = _mm_load_si128((const __m128i *)(const void *)(ids + 4 * j));
        mask |= (uint32_t)_mm_movemask_ps(_mm_castsi128_ps(_mm_cmpeq_epi32(row, v))) << (4 * j);
    }
    return mask;
#elif defined(__aarch64__) && defined(__ARM_NEON)
    const uint32x4_t v = vdupq_n_u32(id), place = {1, 2, 4, 8};
    uint32x4_t bits = vdupq_n_u32(0);
    for (int j = 0; j < 4; j++) /* each row's bits shifted to its place; they are disjoint */
        bits = vorrq_u32(bits, vshlq_u32(vandq_u32(vceqq_u32(vld1q_u32(ids + 4 * j), v), place),
                                         vdupq_n_s32(4 * j)));
    return vaddvq_u32(bits);
#else
    uint32_t mask = 0;
    for (int i = 0; i < SG_TILE_PIXELS; i++) mask |= (uint32_t)(ids[i] == id) << i;
    return mask;
#endif
}

/* id into the pixels of mask of a tile's ids (lane i is pixel i), the others kept. */
static inline void sg_tile_put_id(uint32_t *ids, uint32_t mask, uint32_t id) {
#if defined(__SSE2__)
    const __m128i v = _mm_set1_epi32((int32_t)id), lanes = _mm_setr_epi32(1, 2, 4, 8);
    for (int j = 0; j < 4; j++) {
        const uint32_t bits = mask >> (4 * j) & 15u;
        if (!bits) continue;
        const __m128i m =
            _mm_cmpeq_epi32(_mm_and_si128(_mm_set1_epi32((int32_t)bits), lanes), lanes);
        __m128i *row = (__m128i *)(void *)(ids + 4 * j);
        _mm_store_si128(row, _mm_or_si128(_mm_and_si128(m, v), _mm_andnot_si128(m, *row)));
    }
#elif defined(__aarch64__) && defined(__ARM_NEON)
    const uint32x4_t v = vdupq_n_u32(id), lanes = {1, 2, 4, 8};
    for (int j = 0; j < 4; j++) {
        const uint32x4_t m = vtstq_u32(vdupq_n_u32(mask >> (4 * j) & 15u), lanes);
        vst1q_u32(ids + 4 * j, vbslq_u32(m, v, vld1q_u32(ids + 4 * j)));
    }
#else
    for (uint32_t m = mask; m; m &= m - 1) ids[__builtin_ctz(m)] = id;
#endif
}

/** Offset of the tile holding pixel (x, y) in a bin's buffers, relative to the bin's origin. */
static inline int sg_bin_tile_offset(int x, int y) {
    return ((y >> 2) * 16 + (x >> 2)) * 16;
}

/* The fresh bits (sg_vis_ctx.fresh) of the tile at offset `base`: whether its ids are taken as 0
 * (*ids) and its planes 1-3 of depth as plane 0's (*depth). With take_ids, take_depth (constants)
 * those bits are cleared: the caller then makes them true. */
static inline void sg_vis_samples_fresh(const sg_vis_ctx *vis, int base, const bool take_ids,
                                        const bool take_depth, bool *ids, bool *depth) {
    *ids = *depth = false;
    uint64_t *fresh = vis[0].fresh;
    if (!fresh) return;
    uint64_t *iw = fresh + (base >> 10), *dw = iw + SG_REACHED_WORDS; /* tile base >> 4 */
    const uint64_t bit = (uint64_t)1 << (base >> 4 & 63);
    if (!((*iw | *dw) & bit)) return; /* the common case: touched before */
    *ids = *iw & bit;
    *depth = *dw & bit;
    if (take_ids) *iw &= ~bit;
    if (take_depth) *dw &= ~bit;
}

/* The tile at (x0, y0) made ready for a walk (sg_vis_ctx.fresh): its ids 0 and every sample's
 * depth plane 0's, where they are only taken so. */
static inline void sg_vis_samples_touch(sg_vis_ctx *vis, int x0, int y0) {
    const int base = sg_bin_tile_offset(x0 - vis[0].bx0, y0 - vis[0].by0);
    bool ids, depth;
    sg_vis_samples_fresh(vis, base, true, true, &ids, &depth);
    if (ids)
        for (int k = 0; k < SG_VIS_SAMPLES; k++)
            memset(vis[k].ids + base, 0, SG_TILE_PIXELS * sizeof(uint32_t));
    if (depth && vis[0].depth)
        for (int k = 1; k < SG_VIS_SAMPLES; k++)
            memcpy(vis[k].depth + base, vis[0].depth + base, SG_TILE_PIXELS * sizeof(float));
}

/* The fresh bits (sg_vis_samples_fresh) that a four-sample body which readies fresh tiles itself
 * (SG_VIS_BODY_TOUCHES) takes over for the tile at base, (x0, y0): a recording walk, which writes
 * no ids, the depth bit where it writes depth; a walk that writes ids and depth, both bits; any
 * other walk touches the tile instead, and takes none. */
static inline void sg_vis_samples_take(sg_vis_ctx *vis, int x0, int y0, int base, const int zwrite,
                                       const int rec, bool *ids, bool *depth) {
    if (rec) {
        sg_vis_samples_fresh(vis, base, false, zwrite, ids, depth);
    } else if (zwrite) {
        sg_vis_samples_fresh(vis, base, true, true, ids, depth);
    } else {
        *ids = *depth = false;
        sg_vis_samples_touch(vis, x0, y0);
    }
}

#endif
