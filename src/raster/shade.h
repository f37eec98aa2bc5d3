/* shade.h - per-pixel work of a covered tile: depth test, perspective-correct interpolation,
 * texturing and the write to the tiled framebuffer.
 *
 * One function is compiled for each combination of state that changes the inner loop (vertex
 * colour or texture with its filter and wrap; no depth, LESS, or any other compare; depth write on
 * or off), and a pipeline picks its function once, at creation. A vertex-colour draw therefore
 * never runs texture code, and a draw without depth never touches the depth buffer.
 */
#ifndef SG_SHADE_H
#define SG_SHADE_H

#include <stdbool.h>
#include <stdint.h>

#include "raster/rast_tile.h"
#include "sgapi/sgapi.h"
#include "tex/sample.h"

typedef struct sg_shade_ctx {
    uint32_t *color; /* tiled colour of the open pass */
    float *depth;    /* tiled depth, NULL when the pass has none */
    int tiles_x;
    sg_texview tex; /* bound texture, when the pipeline samples one */
    sgCompare compare;
} sg_shade_ctx;

/** The tile function specialised for a resolved pipeline state (no DEFAULT values). */
sg_tile_fn sg_shade_select(sgShade shade, sgFilter filter, sgWrap wrap, sgCompare compare,
                           bool depth_write);
/** Attributes a shading mode interpolates: r g b a, plus s t when textured. */
int sg_shade_attr_count(sgShade shade);
/** Float colour channel to unorm8, round to nearest, clamped to [0, 1] (NaN gives 0). */
static inline uint32_t sg_to_unorm8(float v) {
    if (!(v > 0.0f)) return 0;
    if (v >= 1.0f) return 255;
    return (uint32_t)(v * 255.0f + 0.5f);
}

#endif
