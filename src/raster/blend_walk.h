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
#define SG_BLEND_TABLE                                                                             \
    {                                                                                              \
        SG_BLEND_ROW(0, 0, 0), SG_BLEND_ROW(1, 0, 1), SG_BLEND_ROW(1, 0, 0),                       \
            SG_BLEND_ROW(1, 1, 1), SG_BLEND_ROW(1, 1, 0)                                           \
    }

/* A textured blended triangle's jobs (sets of pixels to shade) collected during its walk and
 * shaded after it: the functions every vector blend file shares, for a file that defines `job`,
 * `queued_ctx` (with v, jobs, njobs and flush: the variant's blend_jobs_<bil><rep>), JOBS,
 * JOB_SETS and shade_some(v, t, jobs, n, bilinear, repeat, flat), which shades n jobs (a constant)
 * side by side and blends them. Defines shade_jobs_flat, shade_jobs, submit and
 * blend_jobs_00 ... blend_jobs_11 (nearest / bilinear, clamp / repeat: one copy each, called at a
 * triangle's end and when JOBS are waiting, not one per place the walk visits a tile). The pixels
 * of one triangle are all different, so the order they are blended in does not matter. */
#define SG_JOB_LIST_FNS                                                                            \
    static inline __attribute__((always_inline)) void shade_jobs_flat(                             \
        queued_ctx *p, const sg_tri *t, const int bilinear, const int repeat, const int flat) {    \
        const job *j = p->jobs;                                                                    \
        int i = 0;                                                                                 \
        for (; i + JOB_SETS <= p->njobs; i += JOB_SETS)                                            \
            shade_some(p->v, t, j + i, JOB_SETS, bilinear, repeat, flat);                          \
        if (p->njobs - i >= 2) {                                                                   \
            shade_some(p->v, t, j + i, 2, bilinear, repeat, flat);                                 \
            i += 2;                                                                                \
        }                                                                                          \
        if (i < p->njobs) shade_some(p->v, t, j + i, 1, bilinear, repeat, flat);                   \
        p->njobs = 0;                                                                              \
    }                                                                                              \
    static inline __attribute__((always_inline)) void shade_jobs(                                  \
        queued_ctx *p, const sg_tri *t, const int bilinear, const int repeat) {                    \
        if (t->flat == SG_FLAT_WHITE)                                                              \
            shade_jobs_flat(p, t, bilinear, repeat, SG_FLAT_WHITE);                                \
        else if (t->flat == SG_FLAT_COLOR)                                                         \
            shade_jobs_flat(p, t, bilinear, repeat, SG_FLAT_COLOR);                                \
        else                                                                                       \
            shade_jobs_flat(p, t, bilinear, repeat, SG_FLAT_NONE);                                 \
    }                                                                                              \
    static inline __attribute__((always_inline)) void submit(queued_ctx *p, const sg_tri *t,       \
                                                             const job *j) {                       \
        p->jobs[p->njobs++] = *j;                                                                  \
        if (p->njobs == JOBS) p->flush(p, t);                                                      \
    }                                                                                              \
    SG_BLEND_JOBS(0, 0)                                                                            \
    SG_BLEND_JOBS(0, 1)                                                                            \
    SG_BLEND_JOBS(1, 0)                                                                            \
    SG_BLEND_JOBS(1, 1)
#define SG_BLEND_JOBS(bil, rep)                                                                    \
    static __attribute__((noinline)) void blend_jobs_##bil##rep(queued_ctx *p, const sg_tri *t) {  \
        shade_jobs(p, t, bil, rep);                                                                \
    }

#endif
