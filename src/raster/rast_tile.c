/* rast_tile.c - tile traversal and coverage masks (see rast_tile.h).
 *
 * The walk is hierarchical: a triangle's bounds are covered by 16x16-pixel blocks, each rejected
 * or accepted whole by its corners, and only blocks an edge crosses descend to their 4x4 tiles,
 * which are again rejected or accepted whole; only tiles an edge crosses test pixels. Edge values
 * are exact 64-bit integers; inside a crossed tile they differ from the tile's first pixel by less
 * than 3 (|dx| + |dy|), so for every triangle whose steps keep that under 2^31 (edges shorter
 * than about 5000 pixels) the 16 pixel tests run in 32 bits, four at a time in SSE2. The result is
 * the same exact comparison in every path.
 */
#include "raster/rast_tile.h"

#include "raster/rast_walk.h"

void sg_rast_triangle(const sg_tri *t, sg_tile_fn fn, const void *ctx) {
    sg_rast_triangle_in(t, 0, 0, t->maxx + 1, t->maxy + 1, fn, ctx);
}

void sg_rast_triangle_in(const sg_tri *t, int rx0, int ry0, int rx1, int ry1, sg_tile_fn fn,
                         const void *ctx) {
    sg_rast_walk(t, rx0, ry0, rx1, ry1, fn, ctx);
}
