/* rast_tile.c - tile traversal and coverage masks (see rast_tile.h). */
#include "raster/rast_tile.h"

#include "raster/framebuffer.h"

/* Mask of the pixels of a tile at (x0, y0) that lie inside the triangle's pixel bounds. */
static uint32_t bounds_mask(const sg_tri *t, int x0, int y0) {
    uint32_t mask = 0;
    for (int j = 0; j < SG_TILE; j++) {
        int y = y0 + j;
        if (y < t->miny || y > t->maxy) continue;
        for (int i = 0; i < SG_TILE; i++) {
            int x = x0 + i;
            if (x >= t->minx && x <= t->maxx) mask |= 1u << (j * SG_TILE + i);
        }
    }
    return mask;
}

void sg_rast_triangle(const sg_tri *t, sg_tile_fn fn, const void *ctx) {
    sg_rast_triangle_in(t, 0, 0, t->maxx + 1, t->maxy + 1, fn, ctx);
}

void sg_rast_triangle_in(const sg_tri *t, int rx0, int ry0, int rx1, int ry1, sg_tile_fn fn,
                         const void *ctx) {
    int tx0 = (t->minx > rx0 ? t->minx : rx0) >> SG_TILE_SHIFT;
    int ty0 = (t->miny > ry0 ? t->miny : ry0) >> SG_TILE_SHIFT;
    int tx1 = (t->maxx < rx1 - 1 ? t->maxx : rx1 - 1) >> SG_TILE_SHIFT;
    int ty1 = (t->maxy < ry1 - 1 ? t->maxy : ry1 - 1) >> SG_TILE_SHIFT;
    /* Offsets from a tile's first pixel centre to the corner where each edge is largest
     * (for rejection) and smallest (for acceptance). */
    int64_t hi[3], lo[3];
    for (int e = 0; e < 3; e++) {
        int64_t ax = 3 * t->edge_dx[e], ay = 3 * t->edge_dy[e];
        hi[e] = (ax > 0 ? ax : 0) + (ay > 0 ? ay : 0);
        lo[e] = (ax < 0 ? ax : 0) + (ay < 0 ? ay : 0);
    }
    for (int ty = ty0; ty <= ty1; ty++) {
        int y0 = ty << SG_TILE_SHIFT;
        bool y_inner = y0 >= t->miny && y0 + SG_TILE - 1 <= t->maxy;
        for (int tx = tx0; tx <= tx1; tx++) {
            int x0 = tx << SG_TILE_SHIFT;
            int64_t e0[3];
            bool reject = false, accept = true;
            for (int e = 0; e < 3; e++) {
                e0[e] = t->edge[e] + (int64_t)(x0 - t->minx) * t->edge_dx[e] +
                        (int64_t)(y0 - t->miny) * t->edge_dy[e];
                if (e0[e] + hi[e] < 0) reject = true;
                if (e0[e] + lo[e] < 0) accept = false;
            }
            if (reject) continue;
            bool inner = y_inner && x0 >= t->minx && x0 + SG_TILE - 1 <= t->maxx;
            uint32_t mask;
            if (accept) {
                mask = 0xffffu;
            } else {
                mask = 0;
                for (int j = 0; j < SG_TILE; j++)
                    for (int i = 0; i < SG_TILE; i++) {
                        int64_t ox = i, oy = j;
                        bool in = true;
                        for (int e = 0; e < 3; e++)
                            in &= e0[e] + ox * t->edge_dx[e] + oy * t->edge_dy[e] >= 0;
                        if (in) mask |= 1u << (j * SG_TILE + i);
                    }
            }
            /* Tiles on the bounds also hold pixels outside the target or scissor rectangle. */
            if (!inner) mask &= bounds_mask(t, x0, y0);
            if (mask) fn(ctx, t, x0, y0, mask);
        }
    }
}
