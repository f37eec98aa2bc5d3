/* depth_walk.h - what the visibility and blend files of every instruction set share: the depth
 * modes their tile functions are specialised for, and the macros that bind a tile body to a mode
 * and walk it over a triangle's tiles (rast_walk.h). Included only by depth*.c and blend*.c. */
#ifndef SG_RASTER_DEPTH_WALK_H
#define SG_RASTER_DEPTH_WALK_H

#include "raster/depth.h"
#include "raster/rast_walk.h"

/* Z_NONE: no depth test (ALWAYS: every covered pixel); Z_LESS: LESS, the common case, with the
 * compare folded in; Z_ANY: the draw's compare, read per tile. */
enum { Z_NONE, Z_LESS, Z_ANY };

static inline int sg_zmode(sgCompare compare) {
    return compare == SG_COMPARE_ALWAYS ? Z_NONE : (compare == SG_COMPARE_LESS ? Z_LESS : Z_ANY);
}

/* A depth state's functions in a set's tables of each kind ([zmode][depth write], SG_VIS_TABLE;
 * record may be NULL: the set has no recording walk). */
static inline sg_vis_fns sg_vis_pick(const sg_raster_fn one[3][2],
                                     const sg_raster_samples_fn samples[3][2],
                                     const sg_raster_samples_fn (*record)[2], sgCompare compare,
                                     bool depth_write) {
    const int z = sg_zmode(compare), w = depth_write ? 1 : 0;
    return (sg_vis_fns){one[z][w], samples[z][w], record ? record[z][w] : NULL};
}

/* name(): a raster function (sg_raster_fn) that walks with body(ctx, t, x0, y0, mask, zmode,
 * zwrite) inlined per tile, zmode and zwrite constant, so each compiles without the branches it
 * does not take. */
#define SG_WALK_FN(name, body, zm, zw) SG_WALK_FN_AS(name, body, zm, zw, inline)
/* The same with the tile function declared `tile_attr` (inline, or always inlined where the
 * compiler would keep a large body out of the walk). */
#define SG_WALK_FN_AS(name, body, zm, zw, tile_attr)                                               \
    SG_WALK_FN_ANY(name, body, zm, zw, tile_attr, false)
/* SG_WALK_FN for a body that takes empty masks too (the walk then calls it for every tile a
 * small triangle's bounds hold: sg_rast_walk_any). */
#define SG_WALK_FN_EMPTY(name, body, zm, zw) SG_WALK_FN_ANY(name, body, zm, zw, inline, true)
#define SG_WALK_FN_ANY(name, body, zm, zw, tile_attr, empty)                                       \
    static tile_attr void name##_tile(const void *c, const sg_tri *t, int x0, int y0,              \
                                      uint32_t m) {                                                \
        body(c, t, x0, y0, m, zm, zw);                                                             \
    }                                                                                              \
    static void name(const sg_tri *t, int x0, int y0, int x1, int y1, const void *c) {             \
        sg_rast_walk_any(t, x0, y0, x1, y1, name##_tile, c, empty);                                \
    }

#ifndef SG_VIS_BODY_TOUCHES
#define SG_VIS_BODY_TOUCHES 0
#endif

/* The six visibility functions of a tile body, prefix_none_0 ... prefix_any_1, and their
 * [zmode][depth write] table. */
#define SG_VIS_SET(prefix, body) SG_VIS_SET_OF(SG_WALK_FN, prefix, body)
/* The six functions fn(prefix_..., body, zmode, depth write) makes of a tile body. */
#define SG_VIS_SET_OF(fn, prefix, body)                                                            \
    fn(prefix##_none_0, body, Z_NONE, 0) fn(prefix##_none_1, body, Z_NONE, 1)                      \
        fn(prefix##_less_0, body, Z_LESS, 0) fn(prefix##_less_1, body, Z_LESS, 1)                  \
            fn(prefix##_any_0, body, Z_ANY, 0) fn(prefix##_any_1, body, Z_ANY, 1)
#define SG_VIS_TABLE(prefix)                                                                       \
    {                                                                                              \
        {prefix##_none_0, prefix##_none_1}, {prefix##_less_0, prefix##_less_1}, {                  \
            prefix##_any_0, prefix##_any_1                                                         \
        }                                                                                          \
    }

/* Multisampled passes: the visibility of a triangle's four samples in one walk. The walk goes
 * over a triangle whose edges hold every pixel some sample is inside of (each edge moved by the
 * largest of the samples' offsets); per tile, each sample's coverage is then its own edges' test
 * (with AVX-512 and AVX2 a 32-bit compare per crossing edge against offsets prepared once a
 * triangle, elsewhere crossed_mask, the walk's own) and the tile body runs per sample with it.
 * With AVX-512 and AVX2 a triangle within a bin's tiles (most) skips that preparation: the walk's
 * own edge values of each tile are compared with each sample's distance from the union
 * (sg_vis_samples_small). A line's samples are all the line: its mask is theirs. */
typedef struct sg_vis_samples {
    const sg_tri *st; /* the triangle as each sample sees it */
    sg_vis_ctx *vis;  /* each sample's plane */
    walk w;           /* st[0]'s: the edge steps are the samples' */
#if defined(__AVX512F__) || defined(__AVX2__)
    /* narrow: every sample's edge values over a tile a crossing edge may give fit in int32; then
     * per edge and sample, i dx + j dy of pixel (i, j) plus the sample's edge offset from sample
     * 0's, in 32 bits (with AVX2 rows 0-1 and rows 2-3), and the extremes over the samples of the
     * tile's lowest and highest. */
    bool narrow;
#if defined(__AVX512F__)
    __m512i offs[SG_VIS_SAMPLES][3];
#else
    __m256i offs[SG_VIS_SAMPLES][3][2];
#endif
    int64_t lo[3], hi[3];
    /* Per sample and edge, the union's edge value less the sample's (0 or more), where it fits
     * in int32 (sg_vis_samples_small). */
    int32_t d[SG_VIS_SAMPLES][3];
#endif
} sg_vis_samples;

/* Each sample's covered pixels of a tile at (x0, y0) the union walk visits with mask m. */
SG_WALK_INLINE void sg_vis_samples_masks(const sg_vis_samples *s, const sg_tri *t, int x0, int y0,
                                         uint32_t m, uint32_t mk[SG_VIS_SAMPLES]) {
    int64_t at[3]; /* the edges' change from their values at the bounds' first pixel */
    for (int e = 0; e < 3; e++)
        at[e] = (int64_t)(x0 - t->minx) * t->edge_dx[e] + (int64_t)(y0 - t->miny) * t->edge_dy[e];
#if defined(__AVX512F__) || defined(__AVX2__)
    if (s->narrow) {
#if defined(__AVX512F__)
        __mmask16 in[SG_VIS_SAMPLES];
        for (int k = 0; k < SG_VIS_SAMPLES; k++) in[k] = (__mmask16)m;
        const __m512i zero = _mm512_setzero_si512();
#else
        /* Per sample, the OR of the crossing edges' values: a sign bit is "outside". */
        __m256i out[SG_VIS_SAMPLES][2];
        for (int k = 0; k < SG_VIS_SAMPLES; k++) out[k][0] = out[k][1] = _mm256_setzero_si256();
#endif
        for (int e = 0; e < 3; e++) {
            const int64_t e0 = s->st[0].edge[e] + at[e];
            if (e0 + s->lo[e] >= 0) continue; /* every sample holds the whole tile */
            if (e0 + s->hi[e] < 0) {          /* no sample holds a pixel */
                for (int k = 0; k < SG_VIS_SAMPLES; k++) mk[k] = 0;
                return;
            }
            /* A crossing edge: the values fit in int32 (narrow), wrapping sums give them. */
#if defined(__AVX512F__)
            const __m512i b = _mm512_set1_epi32((int32_t)(uint32_t)(uint64_t)e0);
            for (int k = 0; k < SG_VIS_SAMPLES; k++)
                in[k] =
                    _mm512_mask_cmpge_epi32_mask(in[k], _mm512_add_epi32(b, s->offs[k][e]), zero);
#else
            const __m256i b = _mm256_set1_epi32((int32_t)(uint32_t)(uint64_t)e0);
            for (int k = 0; k < SG_VIS_SAMPLES; k++)
                for (int h = 0; h < 2; h++)
                    out[k][h] = _mm256_or_si256(out[k][h], _mm256_add_epi32(b, s->offs[k][e][h]));
#endif
        }
        for (int k = 0; k < SG_VIS_SAMPLES; k++)
#if defined(__AVX512F__)
            mk[k] = in[k];
#else
            mk[k] = m & ~((uint32_t)_mm256_movemask_ps(_mm256_castsi256_ps(out[k][0])) |
                          (uint32_t)_mm256_movemask_ps(_mm256_castsi256_ps(out[k][1])) << 8);
#endif
        return;
    }
#endif
    for (int k = 0; k < SG_VIS_SAMPLES; k++) {
        int64_t e0[3];
        bool out = false;
        for (int e = 0; e < 3; e++) {
            e0[e] = s->st[k].edge[e] + at[e];
            out |= e0[e] + s->w.hi[e] < 0;
        }
        mk[k] = out ? 0 : m & crossed_mask(&s->w, e0);
    }
}

/* The union of triangle st's samples (not a line): `all`, st[0] until then, receives each edge's
 * largest value. */
SG_WALK_INLINE void sg_vis_samples_union(const sg_tri *st, sg_tri *all) {
    for (int k = 1; k < SG_VIS_SAMPLES; k++)
        for (int e = 0; e < 3; e++)
            if (st[k].edge[e] > all->edge[e]) all->edge[e] = st[k].edge[e];
}

/* The sample walk's preparation for triangle st (not a line). */
SG_WALK_INLINE void sg_vis_samples_prepare(sg_vis_samples *s, const sg_tri *st) {
    sg_walk_prepare(&st[0], &s->w);
#if defined(__AVX512F__) || defined(__AVX2__)
    s->narrow = s->w.narrow;
    for (int e = 0; e < 3; e++) {
        int64_t dlo = 0, dhi = 0; /* the samples' edge offsets from sample 0's: extremes */
        for (int k = 1; k < SG_VIS_SAMPLES; k++) {
            const int64_t d = st[k].edge[e] - st[0].edge[e];
            dlo = d < dlo ? d : dlo;
            dhi = d > dhi ? d : dhi;
        }
        s->lo[e] = s->w.lo[e] + dlo;
        s->hi[e] = s->w.hi[e] + dhi;
        s->narrow &= s->hi[e] - s->lo[e] < ((int64_t)1 << 31);
    }
    if (s->narrow)
        for (int k = 0; k < SG_VIS_SAMPLES; k++)
            for (int e = 0; e < 3; e++) {
                const int32_t d = (int32_t)(st[k].edge[e] - st[0].edge[e]);
#if defined(__AVX512F__)
                s->offs[k][e] = _mm512_add_epi32(s->w.offs[e], _mm512_set1_epi32(d));
#else
                for (int h = 0; h < 2; h++)
                    s->offs[k][e][h] = _mm256_add_epi32(s->w.offs[e][h], _mm256_set1_epi32(d));
#endif
            }
#endif
}

#if defined(__AVX512F__) || defined(__AVX2__)
/* Each sample's covered pixels of a tile where the union's edge values are w (m: the union's
 * mask): sample k's values are the union's less d[k][e], so a compare with d[k][e] tests them
 * without a sum, and the union's are formed once for the four samples. */
SG_WALK_INLINE void sg_vis_samples_masks_of(const sg_vis_samples *s, const sg_walk_edges *w,
                                            uint32_t m, uint32_t mk[SG_VIS_SAMPLES]) {
    for (int k = 0; k < SG_VIS_SAMPLES; k++) {
#if defined(__AVX512F__)
        __mmask16 in = (__mmask16)m;
        for (int e = 0; e < 3; e++)
            in = _mm512_mask_cmpge_epi32_mask(in, w->v[e], _mm512_set1_epi32(s->d[k][e]));
        mk[k] = in;
#else
        /* v >= d as v > d - 1 (d >= 0: no wrap), all ones where true */
        uint32_t in = 0;
        for (int h = 0; h < 2; h++) {
            __m256i all = _mm256_set1_epi32(-1);
            for (int e = 0; e < 3; e++)
                all = _mm256_and_si256(
                    all, _mm256_cmpgt_epi32(w->v[e][h], _mm256_set1_epi32(s->d[k][e] - 1)));
            in |= (uint32_t)_mm256_movemask_ps(_mm256_castsi256_ps(all)) << (8 * h);
        }
        mk[k] = m & in;
#endif
    }
}

/* The sample walk of a triangle (not a line) whose tiles in [rx0, rx1) x [ry0, ry1) fit
 * small_triangle_vec's square, the union all walked there with tile function fe, which takes the
 * union's edge values: no walk preparation, and no edge sums per sample and tile. False: not
 * taken (then as other triangles). The tiles and their masks are those of the walk of all. */
SG_WALK_INLINE bool sg_vis_samples_small(sg_vis_samples *s, const sg_tri *all, int rx0, int ry0,
                                         int rx1, int ry1, sg_tile_edges_fn fe) {
    int tx0, ty0, tx1, ty1;
    if (!sg_walk_tile_range(all, rx0, ry0, rx1, ry1, &tx0, &ty0, &tx1, &ty1)) return true;
    if (tx1 - tx0 >= SG_SMALL_TILES || ty1 - ty0 >= SG_SMALL_TILES) return false;
    for (int k = 0; k < SG_VIS_SAMPLES; k++)
        for (int e = 0; e < 3; e++) {
            const int64_t d = all->edge[e] - s->st[k].edge[e];
            if (d > INT32_MAX) return false;
            s->d[k][e] = (int32_t)d;
        }
    return small_triangle_vec(all, tx0, ty0, tx1, ty1, NULL, fe, s, false);
}

/* name_edges(): the tile function of name's small triangles (sg_vis_samples_small). */
#define SG_VIS_SAMPLES_EDGES_FN(name, body4, zm, zw)                                               \
    SG_WALK_INLINE void name##_edges(const void *c, const sg_tri *t, int x0, int y0, uint32_t m,   \
                                     const sg_walk_edges *w) {                                     \
        const sg_vis_samples *s = c;                                                               \
        uint32_t mk[SG_VIS_SAMPLES];                                                               \
        if (!SG_VIS_BODY_TOUCHES) sg_vis_samples_touch(s->vis, x0, y0);                            \
        sg_vis_samples_masks_of(s, w, m, mk);                                                      \
        body4(s, t, x0, y0, mk, zm, zw);                                                           \
    }
#define SG_VIS_SAMPLES_SMALL(name, s, all, x0, y0, x1, y1)                                         \
    sg_vis_samples_small(s, all, x0, y0, x1, y1, name##_edges)
#else
#define SG_VIS_SAMPLES_EDGES_FN(name, body4, zm, zw)
#define SG_VIS_SAMPLES_SMALL(name, s, all, x0, y0, x1, y1) false
#endif

/* name(): the sample walk with tile body body4(s, t, x0, y0, mk, zmode, zwrite), which takes each
 * sample's covered pixels mk[k] of the tile at once (a line's samples: all the line's pixels).
 * The tile is touched first (sg_vis_samples_touch), unless SG_VIS_BODY_TOUCHES is 1 where the
 * walk is defined: then the body makes it ready itself. */
#define SG_VIS_SAMPLES_FN_WITH(name, body4, zm, zw)                                                \
    SG_WALK_INLINE void name##_tile(const void *c, const sg_tri *t, int x0, int y0, uint32_t m) {  \
        const sg_vis_samples *s = c;                                                               \
        uint32_t mk[SG_VIS_SAMPLES];                                                               \
        if (!SG_VIS_BODY_TOUCHES) sg_vis_samples_touch(s->vis, x0, y0);                            \
        if (t->line)                                                                               \
            for (int k = 0; k < SG_VIS_SAMPLES; k++) mk[k] = m;                                    \
        else                                                                                       \
            sg_vis_samples_masks(s, t, x0, y0, m, mk);                                             \
        body4(s, t, x0, y0, mk, zm, zw);                                                           \
    }                                                                                              \
    SG_VIS_SAMPLES_EDGES_FN(name, body4, zm, zw)                                                   \
    static void name(const sg_tri *st, int x0, int y0, int x1, int y1, sg_vis_ctx *vis) {          \
        sg_vis_samples s;                                                                          \
        s.st = st;                                                                                 \
        s.vis = vis;                                                                               \
        sg_tri all = st[0];                                                                        \
        if (!all.line) {                                                                           \
            sg_vis_samples_union(st, &all);                                                        \
            if (SG_VIS_SAMPLES_SMALL(name, &s, &all, x0, y0, x1, y1)) return;                      \
            sg_vis_samples_prepare(&s, st);                                                        \
        }                                                                                          \
        sg_rast_walk(&all, x0, y0, x1, y1, name##_tile, &s);                                       \
    }

/* The same with the one-sample tile body once a sample. */
#define SG_VIS_SAMPLES_FN(name, body, zm, zw)                                                      \
    SG_WALK_INLINE void name##_each(const sg_vis_samples *s, const sg_tri *t, int x0, int y0,      \
                                    const uint32_t *mk, const int zmode, const int zwrite) {       \
        (void)t;                                                                                   \
        (void)zmode; /* constants, which a set's body may take as its own */                       \
        (void)zwrite;                                                                              \
        for (int k = 0; k < SG_VIS_SAMPLES; k++)                                                   \
            if (mk[k]) body(&s->vis[k], &s->st[k], x0, y0, mk[k], zmode, zwrite);                  \
    }                                                                                              \
    SG_VIS_SAMPLES_FN_WITH(name, name##_each, zm, zw)

/* The six sample visibility functions of a tile body (their table: SG_VIS_TABLE). */
#define SG_VIS_SAMPLES_SET(prefix, body) SG_VIS_SET_OF(SG_VIS_SAMPLES_FN, prefix, body)

/* The sample walks of a set's four-sample body vis4_with(s, x0, y0, mk, zmode, zwrite, rec),
 * defined before: vis_prefix_... write the passing pixels' ids, rec_prefix_... record them
 * (sg_vis_record) instead; six of each (SG_VIS_TABLE). The walk's t, the union of the samples'
 * triangles, differs from theirs in its edges only, so the bodies take the samples' own. */
#define SG_VIS4_BODY(name, rec)                                                                    \
    SG_WALK_INLINE void name(const sg_vis_samples *s, const sg_tri *t, int x0, int y0,             \
                             const uint32_t *mk, const int zmode, const int zwrite) {              \
        (void)t;                                                                                   \
        vis4_with(s, x0, y0, mk, zmode, zwrite, rec);                                              \
    }
#define SG_VIS4_FN(name, body4, zm, zw) SG_VIS_SAMPLES_FN_WITH(name, body4, zm, zw)
#define SG_VIS4_SETS(vis_prefix, rec_prefix)                                                       \
    SG_VIS4_BODY(vis_prefix##_body4, 0)                                                            \
    SG_VIS4_BODY(rec_prefix##_body4, 1)                                                            \
    SG_VIS_SET_OF(SG_VIS4_FN, vis_prefix, vis_prefix##_body4)                                      \
    SG_VIS_SET_OF(SG_VIS4_FN, rec_prefix, rec_prefix##_body4)

#endif
