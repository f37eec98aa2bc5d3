/* blend_walk.h - what every instruction set's blend file shares: the two depth modes a blended
 * tile is specialised for, and the macro that binds a tile body to a mode and walks it over a
 * triangle's tiles (rast_walk.h). Included only by blend*.c. */
#ifndef SG_RASTER_BLEND_WALK_H
#define SG_RASTER_BLEND_WALK_H

#include "raster/rast_walk.h"

/* Z_NONE: no depth test (ALWAYS); Z_ANY: the draw's compare. */
enum { Z_NONE, Z_ANY };

/* name(): the raster function of body(ctx, t, x0, y0, mask, zmode, zwrite) with zmode and
 * zwrite constant, so each variant compiles without the branches it does not take. */
#define SG_BLEND_FN(name, body, zm, zw)                                                            \
    static inline void name##_tile(const void *c, const sg_tri *t, int x0, int y0, uint32_t m) {   \
        body(c, t, x0, y0, m, zm, zw);                                                             \
    }                                                                                              \
    static void name(const sg_tri *t, int x0, int y0, int x1, int y1, const void *c) {             \
        sg_rast_walk(t, x0, y0, x1, y1, name##_tile, c);                                           \
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

#endif
