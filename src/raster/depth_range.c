/* depth_range.c - triangles that pass the depth test at every pixel of a bin, found before they
 * are walked: a blended triangle (depth tested, not written) in front of everything drawn so far
 * is then walked with its raster function without the test, which changes no byte and saves a
 * depth load and compare per tile (ordered_bin in rast_bin.c).
 *
 * The bin's depth range is its smallest and largest stored value (sg_fb_depth_range). A triangle's
 * depth over the part of its bounds in the bin is bounded from its plane at the corners (the plane
 * is linear) widened by a margin that covers the rounding of every pixel's float evaluation
 * (sg_tri_depth: two products and two sums, each within 2^-24 of the largest term) many times over,
 * then clamped as sg_tri_depth clamps. test_raster's depth_bound_holds_every_pixel checks the
 * bound against every pixel, and that a range at a pixel's own depth never passes.
 */
#include <math.h>

#include "raster/depth.h"

bool sg_depth_passes_all(const sg_tri *t, sgCompare op, int x0, int y0, int x1, int y1, float lo,
                         float hi) {
    if (!isfinite(t->z) || !isfinite(t->z_dx) || !isfinite(t->z_dy)) return false;
    /* dx and dy of the pixels the walk can visit: the bounds' part in the rectangle */
    const int ax = (t->minx > x0 ? t->minx : x0) - t->minx,
              bx = (t->maxx < x1 ? t->maxx : x1) - t->minx;
    const int ay = (t->miny > y0 ? t->miny : y0) - t->miny,
              by = (t->maxy < y1 ? t->maxy : y1) - t->miny;
    if (ax > bx || ay > by) return false;
    const double z = t->z, zx0 = (double)t->z_dx * ax, zx1 = (double)t->z_dx * bx;
    const double zy0 = (double)t->z_dy * ay, zy1 = (double)t->z_dy * by;
    const double margin = (fabs(z) + fabs(zx0) + fabs(zx1) + fabs(zy0) + fabs(zy1)) * 0x1p-20;
    const double top = z + (zx0 > zx1 ? zx0 : zx1) + (zy0 > zy1 ? zy0 : zy1) + margin;
    const double bottom = z + (zx0 < zx1 ? zx0 : zx1) + (zy0 < zy1 ? zy0 : zy1) - margin;
    switch (op) {
    case SG_COMPARE_LESS:
    case SG_COMPARE_LESS_EQUAL: /* every clamped z <= max(top, 0) < lo <= d */
        return top < lo && 0.0f < lo;
    case SG_COMPARE_GREATER:
    case SG_COMPARE_GREATER_EQUAL: /* every clamped z >= min(bottom, 1) > hi >= d */
        return bottom > hi && 1.0f > hi;
    default:
        return false;
    }
}
