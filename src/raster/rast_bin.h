/* rast_bin.h - the back end of a render pass: one screen bin from start to finish.
 *
 * sgDraw only runs the front end and bins the pass's triangles; sgEndRenderPass renders every bin
 * on the device's threads. A bin keeps its colour, depth and triangle ids in 64 x 64-pixel
 * buffers that stay in the core's cache: it starts from the pass's clear values (or the loaded
 * images), finds the visible triangle of each pixel (depth.c), shades each pixel once (shade.c)
 * and writes its pixels to the target images, once. Bins share no pixels, so the images are the
 * same whichever thread renders which bin.
 */
#ifndef SG_RAST_BIN_H
#define SG_RAST_BIN_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "raster/bin.h"
#include "raster/depth.h"
#include "raster/framebuffer.h"
#include "raster/rast_tile.h"
#include "raster/shade.h"

/* What the back end needs of one draw: its pipeline's functions and its bound texture. */
typedef struct sg_draw_state {
    sg_raster_fn raster_fn; /* coverage and visibility (depth.h) */
    /* raster_fn without its depth test, for triangles that pass it at every pixel of a bin
     * (sg_depth_passes_all): blends that test depth and do not write it; else NULL. */
    sg_raster_fn raster_pass_fn;
    bool writes_depth;
    sg_shade_fn shade_fn;
    sg_shade2_fn shade2_fn;     /* two whole tiles of a triangle at once, or NULL */
    sg_shade_runs_fn runs_fn;   /* partly covered tiles of a triangle packed together, or NULL */
    sg_shade_mixed_fn mixed_fn; /* a tile several of the draw's triangles share, or NULL */
    sg_shade_ctx ctx;
    sgCompare compare;
    bool in_place; /* raster_fn shades into the colour as it goes: blends, lines (blend.h) */
    /* Shader draws: the raster function shading in place, for a bin redone because a fragment
     * was discarded (ctx.shader.fragment set). */
    sg_raster_fn shader_in_place;
    /* Multisampled passes only (rast_msaa.c): the plain visibility function of the draw's depth
     * state (ids and depth, per sample), the same without depth write (a depth test for the draws
     * shaded in place), and whether the draw blends. */
    sg_raster_samples_fn vis_fn, test_fn;
    /* The same recording (sg_vis_record; NULL where the set has none), for triangles shaded in
     * place. */
    sg_raster_samples_fn vis_record_fn, test_record_fn;
    /* vis_record_fn without the depth test, for a triangle that passes it everywhere in the bin
     * (as raster_pass_fn: blends that test depth and do not write it; else NULL). */
    sg_raster_samples_fn record_pass_fn;
    bool blend;
} sg_draw_state;

/* How many triangles ahead visibility and the ordered bins ask for the next: a triangle is four
 * cache lines, often not in cache (a big mesh's triangles outgrow it), and a small triangle's
 * visibility takes less time than a load from memory, so two ahead came too late (08_terrain 0.94
 * with twelve; docs/performance.md, "Triangles asked for twelve ahead"). */
enum { SG_PREFETCH_AHEAD = 12 };

/* Asks for the bin's i-th triangle, if any, and its extension when the pass has them: the
 * shading reads it after the bin's visibility, by which time a big mesh's extensions (the
 * attributes past SG_TRI_ATTRS of shader and lit draws) would have left the cache. */
static inline void sg_prefetch_tri(const sg_binner *b, const sg_bin *bin, uint32_t i) {
    if (i >= bin->count) return;
    const char *t = (const char *)&b->tris[bin->tris[i]];
    for (size_t off = 0; off < sizeof(sg_tri); off += 64) __builtin_prefetch(t + off);
    if (!b->use_ext) return;
    const char *e = (const char *)&b->ext[bin->tris[i]];
    for (size_t off = 0; off < sizeof(sg_tri_ext); off += 64) __builtin_prefetch(e + off);
    __builtin_prefetch(e + sizeof(sg_tri_ext) - 1);
}

/* Stages of a pass whose wall time a build with SGAPI_STAGE_TIMES adds up (stage_times.h). */
enum {
    SG_STAGE_FRONT,
    SG_STAGE_BIN_START,
    SG_STAGE_VISIBILITY,
    SG_STAGE_SHADE,
    SG_STAGE_BIN_WRITE,
    SG_STAGE_COUNT
};

typedef struct sg_bin_pass {
    const sg_binner *binner;
    const sg_draw_state *draws; /* indexed by sg_tri.draw */
    int width, height;
    uint8_t *color;              /* linear RGBA8 target, `width * 4` bytes a row */
    float *depth;                /* linear D32 target, or NULL */
    bool load_color, load_depth; /* else cleared to: */
    uint32_t clear_color;
    float clear_depth;
    bool store_depth;
    /* A byte a bin of the colour target (sg_image.cleared), or NULL: 1 where the target's pixels
     * there are all clear_color already, so that a bin nothing is drawn in leaves them as they
     * are; sg_rast_bin sets a bin's byte to 0 before anything else writes its pixels. */
    uint8_t *cleared;
    bool any_in_place;    /* some draw is shaded in place: bins take the ordered path */
    bool any_pair;        /* some draw shades two whole tiles at once (shade2_fn) */
    bool any_runs;        /* some draw packs partly covered tiles (runs_fn) */
    bool any_mixed;       /* some draw shades shared tiles in one pass (mixed_fn) */
    bool any_shader;      /* some draw has a fragment stage (sgShaderDesc) */
    bool any_konst;       /* some draw's triangles may be shaded once (sg_tri.shader_const) */
    int *shader_discards; /* tiles whose fragment stage discarded (shade_shader.h), all bins */
    const sg_fb_ops *fb;  /* the bin's fills, for the device's instruction set */
    /* Multisampled passes (samples 4, rast_msaa.h): the samples of every bin between flushes,
     * bin after bin (colour and depth, SG_MSAA_BIN_SAMPLES each; NULL until a flush needs them),
     * whether bins start from them (a flush came before) and whether they store into them (a
     * flush, which then leaves the targets alone). */
    int samples;
    uint32_t *msaa_color;
    float *msaa_depth;
    bool msaa_load, msaa_store;
    void *stage_times; /* sg_stage_times, in SGAPI_STAGE_TIMES builds */
} sg_bin_pass;

/** Renders bin `index` of the pass into its target images. */
void sg_rast_bin(const sg_bin_pass *pass, int index);

/* A bin's depth range (sg_fb_ops.depth_range), known or not yet, for the blends that pass their
 * depth test everywhere in it (raster_pass_fn, record_pass_fn); valid: known and given. */
typedef struct sg_depth_range {
    bool known, valid;
    float lo, hi;
} sg_depth_range;

/* Where bin `index` lies in the pass's targets. */
typedef struct sg_bin_view {
    int index;        /* the bin's */
    int x0, y0, w, h; /* its top-left pixel and size, cut at the targets' edges */
    size_t pitch;     /* of both targets: width * 4 bytes */
    uint8_t *color;   /* its first pixel in each target, NULL without that target */
    float *depth;
} sg_bin_view;

/** The view of bin `index` of the pass (one-sample and multisampled bins alike). */
sg_bin_view sg_bin_view_of(const sg_bin_pass *pass, int index);
/** A bin nothing was drawn in: its targets get the pass's clear where the pass does not load. */
void sg_bin_fill_empty(const sg_bin_pass *pass, const sg_bin_view *v);

/** Shades the visible ids of a bin's reached tiles (reached: a byte a tile, as the visibility
 *  functions set it) into its colour as a one-sample bin does, tiles in pairs and shared tiles
 *  in one pass; ids and reached are left as they are. The multisampled bins (rast_msaa.c) shade
 *  so the tiles whose samples all see what their pixel's first sample sees. */
void sg_shade_bin_tiles(const sg_bin_pass *p, uint32_t *ids, uint8_t *reached, int x0, int y0,
                        uint32_t *color);

#endif
