/* line.h - line setup: 1-pixel lines by the diamond-exit rule.
 *
 * The rule (Vulkan's Bresenham lines, OpenGL's diamond exit): pixel (i, j) is drawn when the
 * segment pa -> pb, both end points moved by (-e, -e^2) for an infinitesimal e, meets the open
 * diamond |x - (i + 1/2)| + |y - (j + 1/2)| < 1/2 and pb's moved point is not inside it. The move
 * decides every tie; end points are snapped to 1/256 pixel like a triangle's, and the rule is
 * evaluated exactly in integers.
 *
 * Along a line at most 45 degrees from its major axis, every major-axis pixel (a column of an
 * x-major line) meets at most one diamond: the one whose centre lies within half a pixel of the
 * line there. So the drawn pixels are a band two parallel edges bound, between a first and a last
 * major pixel that an exact test decides at each end. Setup writes that as an sg_tri: the band's
 * two edges, a third edge always inside, and pixel bounds that are exact along the major axis
 * (rect_cut set, so the raster masks them). Every raster function then draws lines as they are.
 * Depth, 1/w and attribute/w planes vary along the major axis only.
 */
#ifndef SG_LINE_H
#define SG_LINE_H

#include <stdbool.h>

#include "pipeline/setup.h"

/** The pixels of segment s[0] -> s[1] (projected, snapped) within the setup rectangle: bounds and
 *  edges of `out`; false when it draws none. Planes are not set. */
bool sg_setup_line_coverage(const sg_setup_params *p, const sg_svert s[2], sg_tri *out);
/** Coverage, then depth, 1/w and attribute planes (attr[i]: p->nattr values at s[i]; ext receives
 *  those beyond SG_TRI_ATTRS); false when the line draws nothing. */
bool sg_setup_line(const sg_setup_params *p, const sg_svert s[2], const float *const attr[2],
                   sg_tri *out, sg_tri_ext *ext);

#endif
