/* rast_msaa.c - one screen bin of a multisampled render pass (see rast_msaa.h). */
#include "raster/rast_msaa.h"

#include <math.h>
#include <string.h>

#include "raster/framebuffer.h"
#include "raster/runs.h"
#include "raster/shade_shader.h"

enum {
    BIN_TILES = SG_BIN_SIZE / SG_TILE,
    BIN_PIXELS = SG_BIN_SIZE * SG_BIN_SIZE,
    NS = SG_MSAA_SAMPLES
};

void sg_msaa_sample_tri(const sg_tri *t, int k, sg_tri *out) {
    *out = *t;
    if (t->line) return;
    /* edge_dx and edge_dy are whole pixels' steps, multiples of 256: a 1/256 step is exact. */
    const int64_t ox = sg_msaa_offset_x(k), oy = sg_msaa_offset_y(k);
    for (int i = 0; i < 3; i++)
        out->edge[i] = t->edge[i] + ox * (t->edge_dx[i] / SG_SUBPIXEL_ONE) +
                       oy * (t->edge_dy[i] / SG_SUBPIXEL_ONE);
    out->z = t->z + t->z_dx * ((float)ox / (float)SG_SUBPIXEL_ONE) +
             t->z_dy * ((float)oy / (float)SG_SUBPIXEL_ONE);
}

/* A bin's samples: plane k holds sample k of every pixel, tiled like a one-sample bin, so that
 * each plane is what the visibility functions expect. A plane is a cache line longer than its
 * pixels: planes of 16 KB would put a tile's twelve lines (four samples of colour, depth and ids)
 * in one set of the first-level cache, which holds eight; so each is in a set of its own. */
enum { PLANE = BIN_PIXELS + SG_TILE_PIXELS };
typedef struct msaa_bin {
    _Alignas(64) uint32_t color[NS][PLANE];
    _Alignas(64) float depth[NS][PLANE];
    _Alignas(64) uint32_t ids[NS][PLANE];
    _Alignas(64) uint8_t reached[NS][SG_REACHED_BYTES]; /* sg_vis_ctx.reached */
    /* Pixels shaded at once: a blended triangle's (in_place), or the runs of the tiles where
     * the samples see several triangles, triangle by triangle (shade_ids, runs.h). */
    _Alignas(64) uint32_t shaded[PLANE];
    /* A bit a tile: its samples' colours are all plane 0's, and planes 1-3 of the tile are not
     * kept (a cleared or loaded tile, and one that only whole pixels have been written to since).
     * The resolve then takes plane 0, and the other planes are filled in from it only when a
     * tile's samples first differ (expand). */
    uint64_t one_color[SG_REACHED_WORDS];
    /* Bits a tile: its ids taken as 0, then its planes 1-3 of depth taken as plane 0's, set at
     * a walk's touch (sg_vis_ctx.fresh). */
    uint64_t fresh[2 * SG_REACHED_WORDS];
    sg_vis_ctx vis[NS];
    uint32_t *planes[NS]; /* color[0] ... color[3] */
    int x0, y0;           /* the bin's top-left pixel */
} msaa_bin;

/* The tiles of word `word` (sg_reached_word) that some sample's walk reached. */
static inline uint64_t reached_by_any(const msaa_bin *b, int word) {
    uint64_t reached = 0;
    for (int k = 0; k < NS; k++) reached |= sg_reached_word(b->reached[k], word);
    return reached;
}

/* Planes 1-3 of tile `base` (word, bit) filled in from plane 0, if they are not kept. */
static inline void expand(msaa_bin *b, int word, int bit, int base) {
    const uint64_t flag = (uint64_t)1 << bit;
    if (!(b->one_color[word] & flag)) return;
    b->one_color[word] &= ~flag;
    for (int k = 1; k < NS; k++)
        memcpy(b->color[k] + base, b->color[0] + base, SG_TILE_PIXELS * sizeof(uint32_t));
}

/* Shades the ids the samples hold: per tile, each triangle seen by some sample once, for the
 * pixels where one of its samples sees it, at the pixel centre, its colour then written to those
 * samples. The ids are taken as 0 from then on (fresh), the tiles as unreached. */
static void shade_ids(const sg_bin_pass *p, msaa_bin *b) {
    /* Tiles where every sample sees what sample 0 sees (inside the triangles, away from their
     * edges): shaded as a one-sample bin's, in plane 0, then copied to the other planes' covered
     * pixels. The others below, triangle by triangle. */
    uint64_t mixed[SG_REACHED_WORDS];
    _Alignas(64) uint8_t uniform[SG_REACHED_BYTES]; /* as sg_vis_ctx.reached */
    memset(uniform, 0, sizeof uniform);
    for (int word = 0; word < SG_REACHED_WORDS; word++) {
        const uint64_t reached = reached_by_any(b, word);
        const size_t at = (size_t)word * 64 * SG_TILE_PIXELS;
        const uint32_t *const ids[NS] = {b->ids[0] + at, b->ids[1] + at, b->ids[2] + at,
                                         b->ids[3] + at};
        const uint64_t alike = reached ? p->fb->alike_tiles(ids, reached) : 0;
        mixed[word] = reached & ~alike;
        for (uint64_t left = alike; left; left &= left - 1)
            uniform[word * 64 + __builtin_ctzll(left)] = 1;
    }
    sg_shade_bin_tiles(p, b->ids[0], uniform, b->x0, b->y0, b->color[0]);
    /* A mixed tile's triangles whose draw packs runs are shaded as runs, triangle by triangle. */
    sg_run_set run_buf, *runs = sg_runs_start(p, &run_buf);
    uint32_t *const *const planes = b->planes;
    const sg_run_target to = {b->shaded, planes, b->x0, b->y0};
    for (int word = 0; word < SG_REACHED_WORDS; word++) {
        const uint64_t uniform_word = sg_reached_word(uniform, word);
        /* A uniform tile's samples take the same colour where covered: a one-colour tile stays. */
        for (uint64_t left = uniform_word & ~b->one_color[word]; left; left &= left - 1) {
            const int base = (word * 64 + __builtin_ctzll(left)) * SG_TILE_PIXELS;
            const uint64_t covered = ~sg_tile_same_id(b->ids[0] + base, 0) & 0xffffu;
            p->fb->put_samples(planes, (size_t)base, b->color[0] + base,
                               covered << 16 | covered << 32 | covered << 48);
        }
        for (uint64_t reached = mixed[word]; reached; reached &= reached - 1) {
            const int tile = word * 64 + __builtin_ctzll(reached);
            const int px = b->x0 + ((tile % BIN_TILES) << SG_TILE_SHIFT);
            const int py = b->y0 + ((tile / BIN_TILES) << SG_TILE_SHIFT);
            const int base = tile * SG_TILE_PIXELS;
            expand(b, word, tile & 63, base);
            const uint32_t *const tids[NS] = {b->ids[0] + base, b->ids[1] + base, b->ids[2] + base,
                                              b->ids[3] + base};
            uint32_t ids[NS * SG_TILE_PIXELS];
            uint64_t samples[NS * SG_TILE_PIXELS];
            const int n = p->fb->split_ids(tids, ids, samples);
            for (int j = 0; j < n; j++) {
                const sg_tri *t = &p->binner->tris[ids[j] - 1];
                const sg_draw_state *d = &p->draws[t->draw];
                const uint64_t sj = samples[j]; /* its pixels: any sample's */
                const uint32_t u = (uint32_t)(sj | sj >> 16 | sj >> 32 | sj >> 48) & 0xffffu;
                if (runs && d->runs_fn) {
                    sg_runs_add(p, runs, ids[j], tile, u, samples[j], &to);
                    continue;
                }
                _Alignas(64) uint32_t src[SG_TILE_PIXELS];
                d->shade_fn(&d->ctx, t, px, py, u, src);
                p->fb->put_samples(planes, (size_t)base, src, samples[j]);
            }
        }
        /* The shaded tiles' ids are done with: taken as 0 from here (fresh). */
        b->fresh[word] |= uniform_word | mixed[word];
        for (int k = 0; k < NS; k++) memset(b->reached[k] + 64 * word, 0, 64);
    }
    if (runs && runs->n) sg_runs_flush(p, runs, &to);
}

/* in_place's shading of the n tiles of runs (their pixels with a passing sample) and samples
 * (each sample's passing pixels) and its writes. A fixed draw with a runs function shades its
 * tiles' pixels at once (b->shaded), else each tile is shaded on its own. */
static void shade_in_place(const sg_bin_pass *p, msaa_bin *b, const sg_tri *t, const sg_tri st[NS],
                           const sg_draw_state *d, const sg_run *runs,
                           const uint16_t (*samples)[NS], int n) {
    const bool shader = d->ctx.shader.fragment != NULL;
    /* Every tile at once: whole tiles as they are, partly covered ones packed. */
    const bool packs = !shader && d->runs_fn;
    if (packs && n) d->runs_fn(&d->ctx, t, b->x0, b->y0, runs, n, b->shaded);
    for (int r = 0; r < n; r++) {
        const int tile = runs[r].tile, word = tile >> 6;
        const int px = b->x0 + ((tile % BIN_TILES) << SG_TILE_SHIFT);
        const int py = b->y0 + ((tile / BIN_TILES) << SG_TILE_SHIFT);
        const int base = tile * SG_TILE_PIXELS;
        const uint32_t u = runs[r].mask;
        _Alignas(64) uint32_t own[SG_TILE_PIXELS];
        const uint32_t *src = packs ? b->shaded + base : own;
        uint32_t keep = u;
        if (shader)
            keep = sg_shader_fragments(&d->ctx, t, px, py, u, own);
        else if (!packs)
            d->shade_fn(&d->ctx, t, px, py, u, own);
        if (shader && d->writes_depth && b->vis[0].depth) {
            /* planes 1-3 may still be taken as plane 0's (the recording walk leaves them so) */
            sg_vis_samples_touch(b->vis, px, py);
            for (int k = 0; k < NS; k++) {
                const float ox = (float)(px - st[k].minx), oy = (float)(py - st[k].miny);
                for (uint32_t left = samples[r][k] & keep; left; left &= left - 1) {
                    int bit = __builtin_ctz(left);
                    b->depth[k][base + bit] =
                        sg_tri_depth(&st[k], ox + (float)(bit & 3), oy + (float)(bit >> 2));
                }
            }
        }
        /* Every sample of a one-colour tile's pixels written alike: it stays one colour. */
        bool alike = b->one_color[word] >> (tile & 63) & 1;
        for (int k = 0; k < NS; k++) alike &= samples[r][k] == u;
        if (alike) {
            if (!(u & keep)) continue;
            if (d->blend)
                p->fb->blend_masked(b->color[0] + base, src, u & keep);
            else
                p->fb->put_masked(b->color[0] + base, src, u & keep);
            continue;
        }
        expand(b, word, tile & 63, base);
        uint64_t mk = 0; /* each sample's passing pixels that keep a fragment */
        for (int k = 0; k < NS; k++) mk |= (uint64_t)(samples[r][k] & keep) << (16 * k);
        if (d->blend)
            p->fb->blend_samples(b->planes, (size_t)base, src, mk);
        else
            p->fb->put_samples(b->planes, (size_t)base, src, mk);
    }
}

/* sg_fb_ops.depth_range of the bin's samples: plane 0's whole, and planes 1-3's over the tiles
 * that keep their own (fresh: they are plane 0's), a run of such tiles a call. */
static bool samples_depth_range(const sg_bin_pass *p, const msaa_bin *b, float *lo, float *hi) {
    if (!p->fb->depth_range(b->depth[0], BIN_PIXELS, lo, hi)) return false;
    const uint64_t *fresh = b->fresh + SG_REACHED_WORDS;
    enum { TILES = BIN_TILES * BIN_TILES };
    for (int tile = 0; tile < TILES;) {
        if (fresh[tile >> 6] >> (tile & 63) & 1) {
            tile++;
            continue;
        }
        int end = tile + 1;
        while (end < TILES && !(fresh[end >> 6] >> (end & 63) & 1)) end++;
        for (int k = 1; k < NS; k++) {
            float l, h;
            if (!p->fb->depth_range(b->depth[k] + tile * SG_TILE_PIXELS,
                                    (size_t)(end - tile) * SG_TILE_PIXELS, &l, &h))
                return false;
            *lo = l < *lo ? l : *lo;
            *hi = h > *hi ? h : *hi;
        }
        tile = end;
    }
    return true;
}

/* Whether every sample of triangle t passes its depth compare at each of its pixels in the bin,
 * so that its walk without the test records the same: sg_depth_passes_all of the pixel centres'
 * plane against a range widened by how far a sample's depth may lie from its centre's (samples
 * are at most half a pixel away in x and in y), with a little more for that sum's rounding. */
static bool passes_bin(const sg_bin_pass *p, const msaa_bin *b, sg_depth_range *r, const sg_tri *t,
                       sgCompare op) {
    if (!r->known) {
        r->valid = samples_depth_range(p, b, &r->lo, &r->hi);
        r->known = true;
    }
    if (!r->valid) return false;
    const float off = 0.5f * (fabsf(t->z_dx) + fabsf(t->z_dy)) * (1.0f + 0x1p-16f);
    return sg_depth_passes_all(t, op, b->x0, b->y0, b->x0 + SG_BIN_SIZE - 1,
                               b->y0 + SG_BIN_SIZE - 1, r->lo - off, r->hi + off);
}

/* A triangle shaded in place (a blend, or a shader draw whose fragments may discard): each
 * sample's depth test, then the pixels with a passing sample shaded once, then each passing
 * sample's depth (when the draw writes it: by the test itself for a fixed draw) and colour,
 * blended or put, where the fragment was not discarded (shade_in_place). A set's recording walk
 * lists the passing pixels (sg_vis_record); elsewhere the walk's ids mark them and are read back:
 * the ids planes hold nothing else here (shade_ids ran before) and are taken as empty after it
 * (fresh). */
static void in_place(const sg_bin_pass *p, msaa_bin *b, const sg_tri *t, const sg_tri st[NS],
                     const sg_draw_state *d, uint32_t id, sg_depth_range *range) {
    for (int k = 0; k < NS; k++) {
        b->vis[k].id = id;
        b->vis[k].compare = d->compare;
    }
    const bool shader = d->ctx.shader.fragment != NULL;
    /* The tiles with a passing sample: their pixels (runs) and each sample's. */
    sg_run runs[BIN_TILES * BIN_TILES];
    uint16_t samples[BIN_TILES * BIN_TILES][NS];
    int n = 0;
    sg_raster_samples_fn record = shader ? d->test_record_fn : d->vis_record_fn;
    if (record && d->record_pass_fn && passes_bin(p, b, range, t, d->compare))
        record = d->record_pass_fn;
    if (record) { /* the walk lists them */
        sg_vis_record rec;
        rec.n = 0;
        b->vis[0].record = &rec;
        record(st, b->x0, b->y0, b->x0 + SG_BIN_SIZE, b->y0 + SG_BIN_SIZE, b->vis);
        b->vis[0].record = NULL;
        for (; n < rec.n; n++) {
            uint32_t u = 0;
            for (int k = 0; k < NS; k++) u |= samples[n][k] = rec.mask[n][k];
            runs[n] = (sg_run){rec.tile[n], (uint16_t)u};
        }
        shade_in_place(p, b, t, st, d, runs, samples, n);
        return;
    }
    (shader ? d->test_fn : d->vis_fn)(st, b->x0, b->y0, b->x0 + SG_BIN_SIZE, b->y0 + SG_BIN_SIZE,
                                      b->vis);
    /* Only the words of the tile rows the triangle's bounds cross can hold reached tiles (a small
     * triangle's: one or two of the four). */
    const int row0 = t->miny > b->y0 ? (t->miny - b->y0) >> SG_TILE_SHIFT : 0;
    const int row1 =
        t->maxy < b->y0 + SG_BIN_SIZE - 1 ? (t->maxy - b->y0) >> SG_TILE_SHIFT : BIN_TILES - 1;
    for (int word = row0 * BIN_TILES / 64; word <= row1 * BIN_TILES / 64; word++) {
        const uint64_t reached_word = reached_by_any(b, word);
        for (uint64_t reached = reached_word; reached; reached &= reached - 1) {
            const int tile = word * 64 + __builtin_ctzll(reached);
            uint32_t u = 0;
            for (int k = 0; k < NS; k++) {
                const uint32_t m = sg_tile_same_id(b->ids[k] + tile * SG_TILE_PIXELS, id);
                samples[n][k] = (uint16_t)m;
                u |= m;
            }
            if (u) runs[n++] = (sg_run){(uint16_t)tile, (uint16_t)u};
        }
        b->fresh[word] |= reached_word; /* their ids are done with */
        for (int k = 0; k < NS; k++) memset(b->reached[k] + 64 * word, 0, 64);
    }
    shade_in_place(p, b, t, st, d, runs, samples, n);
}

/* Whether plane 0 holds every sample of the tiles in t's bounds: their colour is one colour a
 * pixel (one_color) and, with a depth target, their planes 1-3 of depth are plane 0's (fresh). An
 * opaque line covers its pixels' four samples alike, at one depth, so there it can be drawn in
 * place into plane 0 alone and the tiles stay so. */
static bool plane0_holds(const msaa_bin *b, const sg_tri *t, const bool depth) {
    const int c0 = (t->minx > b->x0 ? t->minx - b->x0 : 0) >> SG_TILE_SHIFT;
    const int c1 =
        (t->maxx < b->x0 + SG_BIN_SIZE - 1 ? t->maxx - b->x0 : SG_BIN_SIZE - 1) >> SG_TILE_SHIFT;
    const int r0 = (t->miny > b->y0 ? t->miny - b->y0 : 0) >> SG_TILE_SHIFT;
    const int r1 =
        (t->maxy < b->y0 + SG_BIN_SIZE - 1 ? t->maxy - b->y0 : SG_BIN_SIZE - 1) >> SG_TILE_SHIFT;
    if (c0 > c1) return true;
    const uint64_t cols = (((uint64_t)2 << (c1 - c0)) - 1) << c0;
    for (int r = r0; r <= r1; r++) {
        const int word = r * BIN_TILES / 64;
        const uint64_t m = cols << (r * BIN_TILES % 64);
        if ((b->one_color[word] & m) != m) return false;
        if (depth && (b->fresh[SG_REACHED_WORDS + word] & m) != m) return false;
    }
    return true;
}

/* An opaque line drawn in place into plane 0 (plane0_holds): the draw's put function, as a
 * one-sample bin draws it. */
static void put_line(msaa_bin *b, const sg_tri *t, const sg_draw_state *d, uint32_t id) {
    sg_vis_ctx v = b->vis[0];
    v.id = id;
    v.compare = d->compare;
    v.color = b->color[0];
    v.shade = d->shade_fn;
    v.shade_ctx = &d->ctx;
    v.pending = NULL;
    v.fresh = NULL;
    d->raster_fn(t, b->x0, b->y0, b->x0 + SG_BIN_SIZE, b->y0 + SG_BIN_SIZE, &v);
}

/* Where a bin's pixels are in the target images. */
typedef sg_bin_view bin_view;

/* The bin's samples from the pass's load or clear, or from the sample buffers after a flush. */
static void start_bin(const sg_bin_pass *p, const bin_view *v, msaa_bin *b, int index) {
    const size_t at = (size_t)index * SG_MSAA_BIN_SAMPLES;
    /* Cleared or loaded, every tile is one colour: plane 0 alone is filled. And the ids and the
     * other planes of depth are set tile by tile as the walks first touch them (fresh), but for
     * samples that come back from a flush. */
    memset(b->one_color, v->color && !p->msaa_load ? 0xff : 0, sizeof b->one_color);
    memset(b->fresh, 0xff, sizeof b->fresh / 2);
    memset(b->fresh + SG_REACHED_WORDS, p->msaa_load ? 0 : 0xff, sizeof b->fresh / 2);
    if (v->color) {
        if (p->msaa_load) {
            for (int k = 0; k < NS; k++)
                memcpy(b->color[k], p->msaa_color + at + (size_t)k * BIN_PIXELS,
                       BIN_PIXELS * sizeof(uint32_t));
        } else if (p->load_color) {
            sg_tile_from_linear_rgba8(b->color[0], v->color, v->pitch, v->w, v->h, BIN_TILES);
        } else {
            p->fb->fill_color(b->color[0], BIN_PIXELS, p->clear_color);
        }
    }
    if (v->depth) {
        if (p->msaa_load) {
            for (int k = 0; k < NS; k++)
                memcpy(b->depth[k], p->msaa_depth + at + (size_t)k * BIN_PIXELS,
                       BIN_PIXELS * sizeof(float));
        } else if (p->load_depth) {
            sg_tile_from_linear_f32(b->depth[0], v->depth, v->pitch, v->w, v->h, BIN_TILES);
        } else {
            p->fb->fill_depth(b->depth[0], BIN_PIXELS, p->clear_depth);
        }
    }
}

/* The bin's samples kept for the rest of the pass (a flush), or resolved into the targets: the
 * colour's average, sample 0's depth. */
static void end_bin(const sg_bin_pass *p, const bin_view *v, msaa_bin *b, int index) {
    const size_t at = (size_t)index * SG_MSAA_BIN_SAMPLES;
    if (p->msaa_store) {
        for (int tile = 0; tile < BIN_TILES * BIN_TILES; tile++) {
            expand(b, tile >> 6, tile & 63, tile * SG_TILE_PIXELS);
            sg_vis_samples_touch(b->vis, b->x0 + ((tile % BIN_TILES) << SG_TILE_SHIFT),
                                 b->y0 + ((tile / BIN_TILES) << SG_TILE_SHIFT));
        }
        for (int k = 0; k < NS; k++) {
            const size_t to = at + (size_t)k * BIN_PIXELS;
            if (v->color) memcpy(p->msaa_color + to, b->color[k], BIN_PIXELS * sizeof(uint32_t));
            if (v->depth) memcpy(p->msaa_depth + to, b->depth[k], BIN_PIXELS * sizeof(float));
        }
        return;
    }
    if (v->color) {
        /* A one-colour tile's average is plane 0's colour. */
        for (int word = 0; word < SG_REACHED_WORDS; word++)
            for (uint64_t left = ~b->one_color[word]; left; left &= left - 1) {
                const int base = (word * 64 + __builtin_ctzll(left)) * SG_TILE_PIXELS;
                p->fb->average4(b->color[0] + base, b->color[1] + base, b->color[2] + base,
                                b->color[3] + base, SG_TILE_PIXELS);
            }
        sg_tile_to_linear_rgba8(v->color, v->pitch, b->color[0], v->w, v->h, BIN_TILES);
    }
    if (v->depth && p->store_depth)
        sg_tile_to_linear_f32(v->depth, v->pitch, b->depth[0], v->w, v->h, BIN_TILES);
}

/* The bin's triangles in submission order; with shaders_in_place every shader draw is shaded in
 * place (a fragment was discarded: what visibility first found behind it is unknown). False:
 * a shader draw discarded while shaded visibility first, and the bin must be redone so. */
static bool render(const sg_bin_pass *p, const bin_view *v, msaa_bin *b, int index,
                   const bool shaders_in_place) {
    const sg_bin *bin = &p->binner->bins[index];
    const int discards = p->any_shader ? __atomic_load_n(p->shader_discards, __ATOMIC_RELAXED) : 0;
    memset(b->reached, 0, sizeof b->reached);
    for (int k = 0; k < NS; k++)
        b->vis[k] = (sg_vis_ctx){.depth = v->depth ? b->depth[k] : NULL,
                                 .ids = b->ids[k],
                                 .reached = b->reached[k],
                                 .bx0 = b->x0,
                                 .by0 = b->y0,
                                 .compare = SG_COMPARE_ALWAYS,
                                 .fresh = b->fresh};
    start_bin(p, v, b, index);
    const bool depth_only = v->color == NULL;
    bool pending = false; /* the ids hold triangles not shaded yet */
    /* Every value of the planes is taken: a loaded bin's pixels outside the target were never
     * written, so such bins have none (as in rast_bin.c). */
    sg_depth_range range = {.known = !v->depth || ((p->load_depth || p->msaa_load) &&
                                                   (v->w < SG_BIN_SIZE || v->h < SG_BIN_SIZE))};
    sg_tri st[NS];
    for (uint32_t i = 0; i < bin->count; i++) {
        const uint32_t ti = bin->tris[i];
        sg_prefetch_tri(p->binner, bin, i + SG_PREFETCH_AHEAD);
        const sg_tri *t = &p->binner->tris[ti];
        const sg_draw_state *d = &p->draws[t->draw];
        const bool shader = d->ctx.shader.fragment != NULL;
        if (d->in_place && !d->blend && !shader && t->line && !depth_only &&
            plane0_holds(b, t, v->depth != NULL)) {
            if (pending) shade_ids(p, b);
            pending = false;
            put_line(b, t, d, ti + 1);
            if (d->writes_depth) range.known = false;
            continue;
        }
        for (int k = 0; k < NS; k++) sg_msaa_sample_tri(t, k, &st[k]);
        if (!depth_only && (d->blend || (shader && (d->in_place || shaders_in_place)))) {
            if (pending) shade_ids(p, b);
            pending = false;
            in_place(p, b, t, st, d, ti + 1, &range);
            if (d->writes_depth) range.known = false;
            continue;
        }
        for (int k = 0; k < NS; k++) {
            b->vis[k].id = ti + 1;
            b->vis[k].compare = d->compare;
        }
        d->vis_fn(st, b->x0, b->y0, b->x0 + SG_BIN_SIZE, b->y0 + SG_BIN_SIZE, b->vis);
        pending = !depth_only;
        if (d->writes_depth) range.known = false;
    }
    if (pending) shade_ids(p, b);
    if (!shaders_in_place && p->any_shader &&
        __atomic_load_n(p->shader_discards, __ATOMIC_RELAXED) != discards)
        return false;
    end_bin(p, v, b, index);
    return true;
}

void sg_rast_bin_msaa(const sg_bin_pass *p, int index) {
    const sg_bin *bin = &p->binner->bins[index];
    const bin_view v = sg_bin_view_of(p, index);
    if (!bin->count && !p->msaa_load && !p->msaa_store) {
        /* Nothing drawn here: every sample holds the load or clear, and so does their average. */
        sg_bin_fill_empty(p, &v);
        return;
    }
    /* About 215 KB of samples, ids and shaded pixels: the same stack for every bin of the thread.
     */
    msaa_bin b;
    b.x0 = v.x0;
    b.y0 = v.y0;
    for (int k = 0; k < NS; k++) b.planes[k] = b.color[k];
    if (!render(p, &v, &b, index, false)) render(p, &v, &b, index, true);
}
