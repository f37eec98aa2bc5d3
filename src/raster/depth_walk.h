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

/* name(): a raster function (sg_raster_fn) that walks with body(ctx, t, x0, y0, mask, zmode,
 * zwrite) inlined per tile, zmode and zwrite constant, so each compiles without the branches it
 * does not take. */
#define SG_WALK_FN(name, body, zm, zw) SG_WALK_FN_AS(name, body, zm, zw, inline)
/* The same with the tile function declared `tile_attr` (inline, or always inlined where the
 * compiler would keep a large body out of the walk). */
#define SG_WALK_FN_AS(name, body, zm, zw, tile_attr)                                               \
    static tile_attr void name##_tile(const void *c, const sg_tri *t, int x0, int y0,              \
                                      uint32_t m) {                                                \
        body(c, t, x0, y0, m, zm, zw);                                                             \
    }                                                                                              \
    static void name(const sg_tri *t, int x0, int y0, int x1, int y1, const void *c) {             \
        sg_rast_walk(t, x0, y0, x1, y1, name##_tile, c);                                           \
    }

/* The six visibility functions of a tile body, prefix_none_0 ... prefix_any_1, and their
 * [zmode][depth write] table. */
#define SG_VIS_SET(prefix, body)                                                                   \
    SG_WALK_FN(prefix##_none_0, body, Z_NONE, 0)                                                   \
    SG_WALK_FN(prefix##_none_1, body, Z_NONE, 1)                                                   \
    SG_WALK_FN(prefix##_less_0, body, Z_LESS, 0)                                                   \
    SG_WALK_FN(prefix##_less_1, body, Z_LESS, 1)                                                   \
    SG_WALK_FN(prefix##_any_0, body, Z_ANY, 0)                                                     \
    SG_WALK_FN(prefix##_any_1, body, Z_ANY, 1)
#define SG_VIS_TABLE(prefix)                                                                       \
    {                                                                                              \
        {prefix##_none_0, prefix##_none_1}, {prefix##_less_0, prefix##_less_1}, {                  \
            prefix##_any_0, prefix##_any_1                                                         \
        }                                                                                          \
    }

#endif
