/* rast_tile.h - half-space rasterisation of set-up triangles, one 4x4 tile at a time. */
#ifndef SG_RAST_TILE_H
#define SG_RAST_TILE_H

#include <stdint.h>

#include "pipeline/setup.h"

/* Called once per touched tile with its top-left pixel and a 16-bit mask of covered pixels
 * (bit y * 4 + x). */
typedef void (*sg_tile_fn)(const void *ctx, const sg_tri *tri, int x0, int y0, uint32_t mask);

/** Walks the tiles of the triangle's bounds, rejecting or accepting whole tiles by their corners,
 *  testing pixels only in tiles the triangle's edges cross. */
void sg_rast_triangle(const sg_tri *tri, sg_tile_fn fn, const void *ctx);
/** The same, restricted to the tiles of the rectangle [x0, x1) x [y0, y1) (multiples of 4): the
 *  part of a triangle that falls in one screen bin. */
void sg_rast_triangle_in(const sg_tri *tri, int x0, int y0, int x1, int y1, sg_tile_fn fn,
                         const void *ctx);

#endif
