/* blend_walk.h - what every instruction set's blend file shares: the table of its raster
 * functions, one per shading variant and depth state (the depth modes and the walk macro are
 * depth_walk.h's; a blended tile is Z_NONE or Z_ANY). Included only by blend*.c. */
#ifndef SG_RASTER_BLEND_WALK_H
#define SG_RASTER_BLEND_WALK_H

#include "raster/depth_walk.h"

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
