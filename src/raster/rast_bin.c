/* rast_bin.c - one screen bin of a render pass, from clear to the target images (see
 * rast_bin.h). */
#include "raster/rast_bin.h"

#include <string.h>

#include "core/stage_times.h"
#include "raster/depth.h"
#include "raster/framebuffer.h"
#include "raster/rast_msaa.h"
#include "raster/runs.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#elif defined(__aarch64__) && defined(__ARM_NEON)
#include <arm_neon.h>
#endif

enum { BIN_TILES = SG_BIN_SIZE / SG_TILE, BIN_PIXELS = SG_BIN_SIZE * SG_BIN_SIZE };
_Static_assert(SG_REACHED_WORDS * 64 == BIN_TILES * BIN_TILES &&
                   SG_REACHED_SPARE == BIN_TILES * BIN_TILES,
               "a bin's reached bytes (depth.h): a tile each, then the spare one");

/* The pixels of `mask` of a tile that see triangle `id`: shaded now, or collected in s when the
 * draw packs runs and the tile is partly covered (s is NULL when no draw of the pass does). */
static inline void shade_run(const sg_bin_pass *p, sg_run_set *s, uint32_t id, int tile, int x0,
                             int y0, uint32_t mask, uint32_t *color) {
    const sg_tri *t = &p->binner->tris[id - 1];
    const sg_draw_state *d = &p->draws[t->draw];
    if (s && d->runs_fn && mask != 0xffffu) {
        const sg_run_target to = {color, NULL, x0, y0};
        sg_runs_add(p, s, id, tile, mask, 0, &to);
        return;
    }
    d->shade_fn(&d->ctx, t, x0 + ((tile % BIN_TILES) << SG_TILE_SHIFT),
                y0 + ((tile / BIN_TILES) << SG_TILE_SHIFT), mask, color + tile * SG_TILE_PIXELS);
}

/* Tiles that several triangles share waiting to be shaded two at a time (their draw's
 * sg_shade_mixed_fn), one at most: of `draw`. */
typedef struct mixed_set {
    sg_mixed_tile tile[2];
    int count;
    const sg_draw_state *draw;
} mixed_set;

/* Shades the waiting tile, if any. */
static inline void flush_mixed(mixed_set *m) {
    if (m->count) m->draw->mixed_fn(&m->draw->ctx, m->tile, 1);
    m->count = 0;
}

/* A tile that several triangles share, shaded in one pass (their draw's sg_shade_mixed_fn), in a
 * pair with the waiting one when that is of the same draw and flat kind, else left waiting; false
 * when they are not all of one draw that has one and of one flat kind (nothing done). first: a
 * triangle of the tile, covering `mask`; left: the tile's other covered pixels. */
static inline bool shade_mixed(const sg_bin_pass *p, mixed_set *m, const uint32_t *ids,
                               uint32_t first, uint32_t mask, uint32_t left, int x, int y,
                               uint32_t *dst) {
    const sg_tri *tris = p->binner->tris, *t = &tris[first - 1];
    const sg_draw_state *d = &p->draws[t->draw];
    if (!d->mixed_fn) return false;
    if (m->count && (m->draw != d || m->tile[0].ts[0]->flat != t->flat)) flush_mixed(m);
    sg_mixed_tile *mt = &m->tile[m->count];
    mt->ts[0] = t;
    mt->masks[0] = mask;
    int n = 1;
    while (left) {
        const uint32_t id = ids[__builtin_ctz(left)];
        const sg_tri *o = &tris[id - 1];
        if (o->draw != t->draw || o->flat != t->flat) return false;
        mt->ts[n] = o;
        mt->masks[n] = sg_tile_same_id(ids, id);
        left &= ~mt->masks[n++];
    }
    mt->n = n;
    mt->x0 = x;
    mt->y0 = y;
    mt->dst = dst;
    m->draw = d;
    if (++m->count == 2) {
        d->mixed_fn(&d->ctx, m->tile, 2);
        m->count = 0;
    }
    return true;
}

/* A tile whose covered pixels `left` all see triangles shaded once (sg_tri.shader_const): their
 * colours put in dst straight from the triangles, no batch set up; false (nothing done) when one
 * of them is shaded pixel by pixel. */
static inline bool put_const_tile(const sg_bin_pass *p, const uint32_t *ids, uint32_t left,
                                  uint32_t *dst) {
    const sg_tri *tris = p->binner->tris;
    uint32_t px[SG_TILE_PIXELS];
    for (uint32_t m = left; m; m &= m - 1) {
        const int i = __builtin_ctz(m);
        const sg_tri *t = &tris[ids[i] - 1];
        if (!t->shader_const) return false;
        px[i] = t->sh.color;
    }
    sg_fb_put_lanes(dst, px, left);
    return true;
}

/* Shades the visible pixels of one tile: in one pass when several triangles share it and
 * shade_mixed takes it, else each run of pixels that see the same triangle is one call of that
 * triangle's shading function (or collected in s, see shade_run). */
static inline __attribute__((always_inline)) void shade_tile(const sg_bin_pass *p, sg_run_set *s,
                                                             mixed_set *m, const uint32_t *ids,
                                                             int tile, int x0, int y0,
                                                             uint32_t *color) {
    uint32_t first = ids[0], mask = 0;
    if (first) { /* the first pixel's triangle first: often the tile's only one */
        mask = sg_tile_same_id(ids, first);
        if (mask == 0xffffu) {
            shade_run(p, s, first, tile, x0, y0, mask, color);
            return;
        }
    }
    uint32_t left = ~sg_tile_same_id(ids, 0) & 0xffffu;
    if (p->any_konst && left && put_const_tile(p, ids, left, color + tile * SG_TILE_PIXELS)) return;
    if (p->any_mixed && left) {
        if (!first) { /* then the first covered pixel's */
            first = ids[__builtin_ctz(left)];
            mask = sg_tile_same_id(ids, first);
        }
        if (mask != left &&
            shade_mixed(p, m, ids, first, mask, left & ~mask,
                        x0 + ((tile % BIN_TILES) << SG_TILE_SHIFT),
                        y0 + ((tile / BIN_TILES) << SG_TILE_SHIFT), color + tile * SG_TILE_PIXELS))
            return;
    }
    while (left) {
        uint32_t id = ids[__builtin_ctz(left)], mask = sg_tile_same_id(ids, id);
        shade_run(p, s, id, tile, x0, y0, mask, color);
        left &= ~mask;
    }
}

/* The draw of tile `tile` and the next reached tile `next` when both are wholly one triangle's
 * and that draw shades two tiles at once (shade2_fn); NULL otherwise. */
static inline const sg_draw_state *pair_draw(const sg_bin_pass *p, const uint32_t *ids, int tile,
                                             int next) {
    const uint32_t *a = ids + tile * SG_TILE_PIXELS, *b = ids + next * SG_TILE_PIXELS;
    const uint32_t id = a[0];
    if (!id || b[0] != id || sg_tile_same_id(a, id) != 0xffffu || sg_tile_same_id(b, id) != 0xffffu)
        return NULL;
    const sg_draw_state *d = &p->draws[p->binner->tris[id - 1].draw];
    return d->shade2_fn ? d : NULL;
}

/* Shades the visible ids of every reached tile into the colour: two at a time where the next
 * reached tile is, like this one, wholly one triangle's (the draw's sg_shade2_fn), else one by
 * one, partly covered tiles of draws that pack runs collected in `runs` and shaded at the end
 * (all before this returns). With `forget`, also sets them back to 0 and the tiles to unreached:
 * what visibility decided so far is final before a triangle shaded in place (blended, or a line)
 * writes the colour. */
static inline __attribute__((always_inline)) void
shade_reached(const sg_bin_pass *p, sg_run_set *runs, uint32_t *ids, uint8_t *reached, int x0,
              int y0, uint32_t *color, const bool forget) {
    mixed_set mixed;
    mixed.count = 0;
    for (int word = 0; word < SG_REACHED_WORDS; word++) {
        for (uint64_t left = sg_reached_word(reached, word); left; left &= left - 1) {
            int tile = word * 64 + __builtin_ctzll(left);
            int tx = tile % BIN_TILES, ty = tile / BIN_TILES;
            uint32_t *tids = ids + tile * SG_TILE_PIXELS;
            const uint64_t rest = left & (left - 1);
            const int next = rest ? word * 64 + __builtin_ctzll(rest) : -1;
            const sg_draw_state *d =
                p->any_pair && next >= 0 ? pair_draw(p, ids, tile, next) : NULL;
            if (d) {
                int nx = next % BIN_TILES, ny = next / BIN_TILES;
                d->shade2_fn(&d->ctx, &p->binner->tris[tids[0] - 1], x0 + (tx << SG_TILE_SHIFT),
                             y0 + (ty << SG_TILE_SHIFT), x0 + (nx << SG_TILE_SHIFT),
                             y0 + (ny << SG_TILE_SHIFT), color + tile * SG_TILE_PIXELS,
                             color + next * SG_TILE_PIXELS);
                if (forget) memset(ids + next * SG_TILE_PIXELS, 0, SG_TILE_PIXELS * sizeof *tids);
                left = rest; /* the loop's step then drops `next` too */
            } else {
                shade_tile(p, runs, &mixed, tids, tile, x0, y0, color);
            }
            if (forget) memset(tids, 0, SG_TILE_PIXELS * sizeof *tids);
        }
        if (forget) memset(reached + 64 * word, 0, 64);
    }
    flush_mixed(&mixed);
    if (runs && runs->n) {
        const sg_run_target to = {color, NULL, x0, y0};
        sg_runs_flush(p, runs, &to);
    }
}

void sg_shade_bin_tiles(const sg_bin_pass *p, uint32_t *ids, uint8_t *reached, int x0, int y0,
                        uint32_t *color) {
    shade_reached(p, NULL, ids, reached, x0, y0, color, false);
}

/* Where a bin's pixels are in the target images. */
typedef sg_bin_view bin_view;

/* The bin's depth from the pass's load or clear (nothing without a depth target). */
static void start_depth(const sg_bin_pass *p, const bin_view *v, float *depth) {
    if (!v->depth) return;
    if (p->load_depth)
        sg_tile_from_linear_f32(depth, v->depth, v->pitch, v->w, v->h, BIN_TILES);
    else
        p->fb->fill_depth(depth, BIN_PIXELS, p->clear_depth);
}

static void start_color(const sg_bin_pass *p, const bin_view *v, uint32_t *color) {
    if (p->load_color)
        sg_tile_from_linear_rgba8(color, v->color, v->pitch, v->w, v->h, BIN_TILES);
    else
        p->fb->fill_color(color, BIN_PIXELS, p->clear_color);
}

/* The bin's rows of the colour target are written at its end (write_bin): asked for before the
 * shading, whose work then hides the wait for their cache lines (the light scenes' frames are
 * 4-5 % shorter so). Only for bins of at least PREFETCH_TRIS triangles: a bin of a few large
 * triangles shades too quickly for that, and its prefetches then only crowd its own writes and
 * the other threads' (the default 01-04 took 9-15 % longer at two threads with them). */
enum { PREFETCH_TRIS = 8 };
static void prefetch_target(const bin_view *v) {
    for (int y = 0; y < v->h; y++)
        for (int x = 0; x < v->w * 4; x += 64)
            __builtin_prefetch(v->color + (size_t)y * v->pitch + (size_t)x, 1, 3);
}

/* The bin's pixels written once to the targets. */
static void write_bin(const sg_bin_pass *p, const bin_view *v, const uint32_t *color,
                      const float *depth) {
    sg_tile_to_linear_rgba8(v->color, v->pitch, color, v->w, v->h, BIN_TILES);
    if (v->depth && p->store_depth)
        sg_tile_to_linear_f32(v->depth, v->pitch, depth, v->w, v->h, BIN_TILES);
}

/* Whether triangle t passes its depth compare at each of its pixels in the bin at (x0, y0), so
 * that its raster function without the test draws the same (depth_range.c). */
static bool passes_bin(const sg_bin_pass *p, sg_depth_range *r, const float *depth, const sg_tri *t,
                       sgCompare op, int x0, int y0) {
    if (!r->known) {
        r->valid = p->fb->depth_range(depth, BIN_PIXELS, &r->lo, &r->hi);
        r->known = true;
    }
    return r->valid && sg_depth_passes_all(t, op, x0, y0, x0 + SG_BIN_SIZE - 1,
                                           y0 + SG_BIN_SIZE - 1, r->lo, r->hi);
}

/* The visibility context of a bin at (x0, y0) with these buffers (depth NULL: no depth target). */
static sg_vis_ctx bin_vis(float *depth, uint32_t *ids, uint8_t *reached, int x0, int y0) {
    return (sg_vis_ctx){.depth = depth,
                        .ids = ids,
                        .reached = reached,
                        .bx0 = x0,
                        .by0 = y0,
                        .compare = SG_COMPARE_ALWAYS};
}

/* A bin of a pass with draws shaded in place (blended ones, lines: blend.h): the colour starts
 * from the pass's load or clear, other triangles go through visibility as usual, and before each
 * run of triangles shaded in place the visible ids so far are shaded (shade_reached), so every
 * pixel sees the triangles in submission order. Kept out of line, with its own buffers, so that
 * the opaque path of sg_rast_bin stays as it is. */
static __attribute__((noinline)) void ordered_bin(const sg_bin_pass *p, const sg_bin *bin,
                                                  const bin_view *v, const bool shaders_in_place) {
    _Alignas(64) uint32_t color[BIN_PIXELS];
    _Alignas(64) float depth[BIN_PIXELS];
    _Alignas(64) uint32_t ids[BIN_PIXELS];
    _Alignas(64) uint8_t reached[SG_REACHED_BYTES] = {0};
    SG_STAGE_START(clock);
    const int discards = p->any_shader ? __atomic_load_n(p->shader_discards, __ATOMIC_RELAXED) : 0;
    start_depth(p, v, depth);
    start_color(p, v, color);
    SG_STAGE_ADD(p->stage_times, SG_STAGE_BIN_START, clock);
    const sg_binner *b = p->binner;
    int x0 = v->x0, y0 = v->y0;
    sg_blend_pending waiting; /* its jobs are written before they are read */
    waiting.n = 0;
    sg_vis_ctx vis = bin_vis(v->depth ? depth : NULL, ids, reached, x0, y0);
    vis.color = color;
    vis.pending = &waiting;
    bool pending = false; /* ids hold opaque triangles not shaded yet */
    /* The ids are cleared when the first triangle that writes them comes: a bin of lines and
     * blends alone never reads them (16 KB a bin not cleared). */
    bool ids_clear = false;
    sg_run_set run_buf, *runs = sg_runs_start(p, &run_buf);
    /* The bin's depth range, worked out when a blend first asks for it after a depth write
     * (passes_bin). It takes every value of the buffer: a loaded bin's pixels outside the target
     * were never written, so such bins have none. */
    sg_depth_range range = {.known = !v->depth ||
                                     (p->load_depth && (v->w < SG_BIN_SIZE || v->h < SG_BIN_SIZE))};
    for (uint32_t i = 0; i < bin->count; i++) {
        uint32_t ti = bin->tris[i];
        const sg_tri *t = &b->tris[ti];
        sg_prefetch_tri(b, bin, i + SG_PREFETCH_AHEAD);
        const sg_draw_state *d = &p->draws[t->draw];
        if (waiting.n && waiting.draw != t->draw) waiting.flush(&waiting, &vis);
        vis.id = ti + 1;
        vis.compare = d->compare;
        sg_raster_fn fn = d->raster_fn;
        const bool redone = shaders_in_place && d->shader_in_place && !d->in_place;
        if (redone) fn = d->shader_in_place;
        if (d->in_place || redone) {
            if (pending) shade_reached(p, runs, ids, reached, x0, y0, color, true);
            pending = false;
            if (d->shader_in_place && !ids_clear) { /* a shader draw's fragments may wait there */
                memset(ids, 0, sizeof ids);
                ids_clear = true;
            }
            vis.shade = d->shade_fn;
            vis.shade_ctx = &d->ctx;
            if (d->raster_pass_fn && passes_bin(p, &range, depth, t, d->compare, x0, y0))
                fn = d->raster_pass_fn;
        } else {
            if (!ids_clear) memset(ids, 0, sizeof ids);
            ids_clear = true;
            pending = true;
        }
        fn(t, x0, y0, x0 + SG_BIN_SIZE, y0 + SG_BIN_SIZE, &vis);
        if (d->writes_depth && range.valid) range.known = false;
    }
    if (waiting.n) waiting.flush(&waiting, &vis);
    if (pending) shade_reached(p, runs, ids, reached, x0, y0, color, true);
    SG_STAGE_ADD(p->stage_times, SG_STAGE_SHADE, clock);
    if (!shaders_in_place && p->any_shader &&
        __atomic_load_n(p->shader_discards, __ATOMIC_RELAXED) != discards) {
        ordered_bin(p, bin, v, true); /* a discard: as in sg_rast_bin */
        return;
    }
    write_bin(p, v, color, depth);
    SG_STAGE_ADD(p->stage_times, SG_STAGE_BIN_WRITE, clock);
}

/* Visibility of a bin's triangles in submission order (depth.h): each draw's raster function
 * into the bin's depth and ids. */
static inline __attribute__((always_inline)) void visibility(const sg_bin_pass *p,
                                                             const sg_bin *bin, sg_vis_ctx *vis) {
    const sg_binner *b = p->binner;
    for (uint32_t i = 0; i < bin->count; i++) {
        uint32_t ti = bin->tris[i];
        const sg_tri *t = &b->tris[ti];
        sg_prefetch_tri(b, bin, i + SG_PREFETCH_AHEAD);
        const sg_draw_state *d = &p->draws[t->draw];
        vis->id = ti + 1;
        vis->compare = d->compare;
        d->raster_fn(t, vis->bx0, vis->by0, vis->bx0 + SG_BIN_SIZE, vis->by0 + SG_BIN_SIZE, vis);
    }
}

/* A bin of a depth-only pass: visibility alone, then the depth written (sgDraw gave every draw
 * its plain depth function, blended or not). The ids the depth functions leave are never read
 * (cleared all the same: some functions merge into them). */
static __attribute__((noinline)) void depth_only_bin(const sg_bin_pass *p, const sg_bin *bin,
                                                     const bin_view *v) {
    _Alignas(64) float depth[BIN_PIXELS];
    _Alignas(64) uint32_t ids[BIN_PIXELS];
    _Alignas(64) uint8_t reached[SG_REACHED_BYTES] = {0};
    memset(ids, 0, sizeof ids);
    SG_STAGE_START(clock);
    start_depth(p, v, depth);
    SG_STAGE_ADD(p->stage_times, SG_STAGE_BIN_START, clock);
    int x0 = v->x0, y0 = v->y0;
    sg_vis_ctx vis = bin_vis(depth, ids, reached, x0, y0);
    visibility(p, bin, &vis);
    SG_STAGE_ADD(p->stage_times, SG_STAGE_VISIBILITY, clock);
    if (p->store_depth) sg_tile_to_linear_f32(v->depth, v->pitch, depth, v->w, v->h, BIN_TILES);
    SG_STAGE_ADD(p->stage_times, SG_STAGE_BIN_WRITE, clock);
}

sg_bin_view sg_bin_view_of(const sg_bin_pass *p, int index) {
    const sg_binner *b = p->binner;
    sg_bin_view v;
    v.index = index;
    v.x0 = (index % b->bins_x) << SG_BIN_SHIFT;
    v.y0 = (index / b->bins_x) << SG_BIN_SHIFT;
    v.w = p->width - v.x0 < SG_BIN_SIZE ? p->width - v.x0 : SG_BIN_SIZE;
    v.h = p->height - v.y0 < SG_BIN_SIZE ? p->height - v.y0 : SG_BIN_SIZE;
    v.pitch = (size_t)p->width * 4;
    v.color = p->color ? p->color + (size_t)v.y0 * v.pitch + (size_t)v.x0 * 4 : NULL;
    v.depth =
        p->depth ? (float *)(void *)((uint8_t *)p->depth + (size_t)v.y0 * v.pitch) + v.x0 : NULL;
    return v;
}

void sg_bin_fill_empty(const sg_bin_pass *p, const sg_bin_view *v) {
    if (v->color && !p->load_color) {
        /* Not again where an earlier pass's clear is still there (the same bytes): a render loop
         * into one target rewrites only the bins something is drawn in. */
        uint8_t *known = p->cleared ? p->cleared + v->index : NULL;
        if (!known || !*known) sg_fill_linear_u32(v->color, v->pitch, v->w, v->h, p->clear_color);
        if (known) *known = 1;
    }
    if (v->depth && p->store_depth && !p->load_depth) {
        uint32_t bits;
        memcpy(&bits, &p->clear_depth, 4);
        sg_fill_linear_u32(v->depth, v->pitch, v->w, v->h, bits);
    }
}

void sg_rast_bin(const sg_bin_pass *p, int index) {
    /* Only an empty bin's clear (sg_bin_fill_empty) keeps the target's cleared pixels known:
     * whatever else this call does may write them. */
    if (p->cleared &&
        (p->binner->bins[index].count || (p->samples > 1 && (p->msaa_load || p->msaa_store))))
        p->cleared[index] = 0;
    if (p->samples > 1) { /* its own path: this one stays as it is */
        sg_rast_bin_msaa(p, index);
        return;
    }
    const sg_binner *b = p->binner;
    const sg_bin *bin = &b->bins[index];
    bin_view v = sg_bin_view_of(p, index);
    int x0 = v.x0, y0 = v.y0;
    SG_STAGE_START(clock);
    if (!bin->count) { /* nothing drawn here: the pass's load and clear are the result */
        sg_bin_fill_empty(p, &v);
        SG_STAGE_ADD(p->stage_times, SG_STAGE_BIN_WRITE, clock);
        return;
    }
    if (!v.color) {
        depth_only_bin(p, bin, &v);
        return;
    }
    if (p->any_in_place) {
        ordered_bin(p, bin, &v, false);
        return;
    }
    const int discards = p->any_shader ? __atomic_load_n(p->shader_discards, __ATOMIC_RELAXED) : 0;

    _Alignas(64) uint32_t color[BIN_PIXELS];
    _Alignas(64) float depth[BIN_PIXELS];
    _Alignas(64) uint32_t ids[BIN_PIXELS];
    _Alignas(64) uint8_t reached[SG_REACHED_BYTES] = {0};
    memset(ids, 0, sizeof ids);
    start_depth(p, &v, depth);
    SG_STAGE_ADD(p->stage_times, SG_STAGE_BIN_START, clock);
    sg_vis_ctx vis = bin_vis(v.depth ? depth : NULL, ids, reached, x0, y0);
    visibility(p, bin, &vis);
    SG_STAGE_ADD(p->stage_times, SG_STAGE_VISIBILITY, clock);

    if (bin->count >= PREFETCH_TRIS) prefetch_target(&v);
    start_color(p, &v, color);
    SG_STAGE_ADD(p->stage_times, SG_STAGE_BIN_START, clock);
    /* Only tiles some triangle reached hold ids (depth.h). */
    sg_run_set run_buf, *runs = sg_runs_start(p, &run_buf);
    shade_reached(p, runs, ids, reached, x0, y0, color, false);
    SG_STAGE_ADD(p->stage_times, SG_STAGE_SHADE, clock);
    /* A fragment stage discarded (here, or in a bin another thread shades now): what is behind
     * a discarded pixel was never kept, so the bin starts again, shader draws in place. Exact
     * either way, so the image does not depend on which bins redo. */
    if (p->any_shader && __atomic_load_n(p->shader_discards, __ATOMIC_RELAXED) != discards) {
        ordered_bin(p, bin, &v, true);
        return;
    }
    write_bin(p, &v, color, depth);
    SG_STAGE_ADD(p->stage_times, SG_STAGE_BIN_WRITE, clock);
}
