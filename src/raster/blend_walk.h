/* blend_walk.h - what every instruction set's blend file shares: the tables of its raster
 * functions, per depth state and per shading variant (the depth modes and the walk macro are
 * depth_walk.h's; a tile shaded in place is Z_NONE or Z_ANY). Included only by blend*.c. */
#ifndef SG_RASTER_BLEND_WALK_H
#define SG_RASTER_BLEND_WALK_H

#include "raster/depth_walk.h"

/* name(): a tile body that calls body(..., put) with `put` constant (1: the fragments replace the
 * pixels, an opaque line; 0: they are blended over them). */
#define SG_IN_PLACE_BODY(name, body, put)                                                          \
    static inline __attribute__((always_inline)) void name(const void *c, const sg_tri *t, int x0, \
                                                           int y0, uint32_t m, const int zmode,    \
                                                           const int zwrite) {                     \
        body(c, t, x0, y0, m, zmode, zwrite, put);                                                 \
    }

/* The four raster functions of a tile body, prefix_none_0 ... prefix_any_1 (depth test, depth
 * write), and their [test][write] table; their tile functions always inlined into the walk. */
#define SG_IN_PLACE_SET(prefix, body)                                                              \
    SG_WALK_FN_AS(prefix##_none_0, body, Z_NONE, 0, SG_IN_PLACE_TILE)                              \
    SG_WALK_FN_AS(prefix##_none_1, body, Z_NONE, 1, SG_IN_PLACE_TILE)                              \
    SG_WALK_FN_AS(prefix##_any_0, body, Z_ANY, 0, SG_IN_PLACE_TILE)                                \
    SG_WALK_FN_AS(prefix##_any_1, body, Z_ANY, 1, SG_IN_PLACE_TILE)
/* Their tile functions are inlined into the walk: a call per tile costs a line's tiles more
 * than the code's size does. */
#define SG_IN_PLACE_TILE inline __attribute__((always_inline))
#define SG_IN_PLACE_TABLE(prefix)                                                                  \
    {                                                                                              \
        {prefix##_none_0, prefix##_none_1}, {                                                      \
            prefix##_any_0, prefix##_any_1                                                         \
        }                                                                                          \
    }

/* The raster functions of opaque lines, put_line_none_0 ... put_line_any_1 and their table
 * (SG_IN_PLACE_TABLE(put_line)): line_fn(t, x0, y0, x1, y1, ctx, zmode, zwrite) for a line, and for
 * anything else the tile walk of SG_IN_PLACE_SET(put, ...). */
#define SG_PUT_LINE_SET(line_fn)                                                                   \
    SG_PUT_LINE_FN(line_fn, none_0, Z_NONE, 0)                                                     \
    SG_PUT_LINE_FN(line_fn, none_1, Z_NONE, 1)                                                     \
    SG_PUT_LINE_FN(line_fn, any_0, Z_ANY, 0)                                                       \
    SG_PUT_LINE_FN(line_fn, any_1, Z_ANY, 1)
#define SG_PUT_LINE_FN(line_fn, zname, zm, zw)                                                     \
    static void put_line_##zname(const sg_tri *t, int x0, int y0, int x1, int y1, const void *c) { \
        if (t->line)                                                                               \
            line_fn(t, x0, y0, x1, y1, c, zm, zw);                                                 \
        else                                                                                       \
            put_##zname(t, x0, y0, x1, y1, c);                                                     \
    }

/* The blend functions specialised per shading variant of the unlit table (vertex colour; texture
 * nearest / bilinear, repeat / clamp: tex, bil, rep) and depth state (test, write): fn(tex, bil,
 * rep, zt, zw) defines blend_<tex><bil><rep><zt><zw> once per combination, and SG_BLEND_TABLE is
 * their [variant][2 zt + zw] table, in sg_shade_variant order. */
#define SG_BLEND_DEPTHS(fn, tex, bil, rep)                                                         \
    fn(tex, bil, rep, 0, 0) fn(tex, bil, rep, 0, 1) fn(tex, bil, rep, 1, 0) fn(tex, bil, rep, 1, 1)
#define SG_BLEND_VARIANTS(fn)                                                                      \
    SG_BLEND_DEPTHS(fn, 0, 0, 0)                                                                   \
    SG_BLEND_DEPTHS(fn, 1, 0, 1)                                                                   \
    SG_BLEND_DEPTHS(fn, 1, 0, 0)                                                                   \
    SG_BLEND_DEPTHS(fn, 1, 1, 1)                                                                   \
    SG_BLEND_DEPTHS(fn, 1, 1, 0)
#define SG_BLEND_ROW(tex, bil, rep)                                                                \
    {                                                                                              \
        blend_##tex##bil##rep##00, blend_##tex##bil##rep##01, blend_##tex##bil##rep##10,           \
            blend_##tex##bil##rep##11                                                              \
    }
/* The mipmapped ones (textured SG_TEX_MIP and SG_TEX_MIP_LINEAR; bil, rep) and their table, by
 * index linear * 4 + bilinear * 2 + repeat (sg_blend_mip_select). */
#define SG_BLEND_MIP_VARIANTS(fn)                                                                  \
    SG_BLEND_DEPTHS(fn, 2, 0, 0)                                                                   \
    SG_BLEND_DEPTHS(fn, 2, 0, 1)                                                                   \
    SG_BLEND_DEPTHS(fn, 2, 1, 0)                                                                   \
    SG_BLEND_DEPTHS(fn, 2, 1, 1)                                                                   \
    SG_BLEND_DEPTHS(fn, 3, 0, 0)                                                                   \
    SG_BLEND_DEPTHS(fn, 3, 0, 1)                                                                   \
    SG_BLEND_DEPTHS(fn, 3, 1, 0)                                                                   \
    SG_BLEND_DEPTHS(fn, 3, 1, 1)
#define SG_BLEND_MIP_TABLE                                                                         \
    {                                                                                              \
        SG_BLEND_ROW(2, 0, 0), SG_BLEND_ROW(2, 0, 1), SG_BLEND_ROW(2, 1, 0),                       \
            SG_BLEND_ROW(2, 1, 1), SG_BLEND_ROW(3, 0, 0), SG_BLEND_ROW(3, 0, 1),                   \
            SG_BLEND_ROW(3, 1, 0), SG_BLEND_ROW(3, 1, 1)                                           \
    }
#define SG_BLEND_TABLE                                                                             \
    {                                                                                              \
        SG_BLEND_ROW(0, 0, 0), SG_BLEND_ROW(1, 0, 1), SG_BLEND_ROW(1, 0, 0),                       \
            SG_BLEND_ROW(1, 1, 1), SG_BLEND_ROW(1, 1, 0)                                           \
    }

/* A textured blended draw's jobs (sets of pixels to shade) collected during its triangles' walks
 * and shaded later, in the bin's sg_blend_pending (depth.h): the functions every vector blend
 * file shares, for a file that defines `job` (with t, its triangle), `queued_ctx` (with v and
 * jobs, the bin's sg_blend_pending), JOBS, JOB_SETS and shade_some(v, jobs, n, textured, bilinear,
 * repeat, flat), which shades n jobs (a constant) side by side and blends them in their order.
 * Defines shade_jobs_flat, shade_jobs, submit, start_jobs and blend_jobs_100 ... blend_jobs_111
 * (textured 1; nearest / bilinear, clamp / repeat: the flush, one copy each, not one per place the
 * walk visits a tile); SG_MIP_JOB_FNS adds those of mipmapped textures, blend_jobs_200 ...
 * blend_jobs_311 (textured SG_TEX_MIP and SG_TEX_MIP_LINEAR, shade.h).
 * Jobs are shaded in the order they came, and each is blended after the ones before it: a pixel
 * in two jobs (two triangles of the draw) is blended in the triangles' order. Jobs of several
 * triangles go side by side, so a triangle's last few do not go alone. */
#define SG_JOB_LIST_FNS                                                                            \
    static inline __attribute__((always_inline)) void shade_jobs_flat(                             \
        sg_blend_pending *w, const sg_vis_ctx *v, const int textured, const int bilinear,          \
        const int repeat, const int flat) {                                                        \
        const job *j = (const job *)(const void *)w->jobs;                                         \
        int i = 0;                                                                                 \
        for (; i + JOB_SETS <= w->n; i += JOB_SETS)                                                \
            shade_some(v, j + i, JOB_SETS, textured, bilinear, repeat, flat);                      \
        if (w->n - i >= 2) {                                                                       \
            shade_some(v, j + i, 2, textured, bilinear, repeat, flat);                             \
            i += 2;                                                                                \
        }                                                                                          \
        if (i < w->n) shade_some(v, j + i, 1, textured, bilinear, repeat, flat);                   \
        w->n = 0;                                                                                  \
    }                                                                                              \
    static inline __attribute__((always_inline)) void shade_jobs(                                  \
        sg_blend_pending *w, const sg_vis_ctx *v, const int textured, const int bilinear,          \
        const int repeat) {                                                                        \
        if (w->flat == SG_FLAT_WHITE)                                                              \
            shade_jobs_flat(w, v, textured, bilinear, repeat, SG_FLAT_WHITE);                      \
        else if (w->flat == SG_FLAT_COLOR)                                                         \
            shade_jobs_flat(w, v, textured, bilinear, repeat, SG_FLAT_COLOR);                      \
        else                                                                                       \
            shade_jobs_flat(w, v, textured, bilinear, repeat, SG_FLAT_NONE);                       \
    }                                                                                              \
    static inline __attribute__((always_inline)) void submit(queued_ctx *p, const job *j) {        \
        sg_blend_pending *w = p->jobs;                                                             \
        ((job *)(void *)w->jobs)[w->n++] = *j;                                                     \
        if (w->n == JOBS) w->flush(w, p->v);                                                       \
    }                                                                                              \
    /* A triangle's jobs join those waiting when its flat mode is theirs (same draw: same          \
     * texture and variant), else those go first. */                                               \
    static inline __attribute__((always_inline)) void start_jobs(                                  \
        queued_ctx *p, const sg_tri *t, void (*flush)(sg_blend_pending *, const sg_vis_ctx *)) {   \
        sg_blend_pending *w = p->jobs;                                                             \
        if (w->n && w->flat != (int)t->flat) w->flush(w, p->v);                                    \
        w->flush = flush;                                                                          \
        w->draw = t->draw;                                                                         \
        w->flat = (int)t->flat;                                                                    \
    }                                                                                              \
    SG_BLEND_JOBS(1, 0, 0)                                                                         \
    SG_BLEND_JOBS(1, 0, 1)                                                                         \
    SG_BLEND_JOBS(1, 1, 0)                                                                         \
    SG_BLEND_JOBS(1, 1, 1)                                                                         \
    _Static_assert(sizeof(job) * JOBS <= SG_PENDING_BYTES, "the bin's job buffer holds JOBS");
#define SG_BLEND_JOBS(tex, bil, rep)                                                               \
    static __attribute__((noinline)) void blend_jobs_##tex##bil##rep(sg_blend_pending *w,          \
                                                                     const sg_vis_ctx *v) {        \
        shade_jobs(w, v, tex, bil, rep);                                                           \
    }
#define SG_MIP_JOB_FNS                                                                             \
    SG_BLEND_JOBS(2, 0, 0)                                                                         \
    SG_BLEND_JOBS(2, 0, 1)                                                                         \
    SG_BLEND_JOBS(2, 1, 0)                                                                         \
    SG_BLEND_JOBS(2, 1, 1)                                                                         \
    SG_BLEND_JOBS(3, 0, 0)                                                                         \
    SG_BLEND_JOBS(3, 0, 1)                                                                         \
    SG_BLEND_JOBS(3, 1, 0)                                                                         \
    SG_BLEND_JOBS(3, 1, 1)

#endif
