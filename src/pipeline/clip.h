/* clip.h - homogeneous clipping of triangles.
 *
 * Triangles are clipped in clip space against: the near and far planes (-w <= z <= w), a
 * minimum w (so no vertex with w <= 0 reaches the divide), and a guard band in x and y that is far
 * outside the viewport. The raster clips to the viewport for free by its bounding box, so the guard
 * band only cuts triangles whose screen coordinates would leave the fixed-point range.
 */
#ifndef SG_CLIP_H
#define SG_CLIP_H

#include <stdint.h>

#define SG_MAX_ATTRS 6 /* r, g, b, a, s, t */

/* Smallest w a clipped vertex keeps; far below any near plane a scene uses. */
#define SG_CLIP_W_MIN 1e-9f

/* Half-width of the guard band in pixels: 2^15, so snapped coordinates stay below 2^23 in
 * magnitude at 8 sub-pixel bits and edge functions below 2^49 (see docs/architecture.md). */
#define SG_GUARD_BAND_PIXELS 32768.0

typedef struct sg_cvert {
    float pos[4]; /* clip space x, y, z, w */
    float attr[SG_MAX_ATTRS];
} sg_cvert;

enum {
    SG_CLIP_NEAR = 1u << 0,
    SG_CLIP_FAR = 1u << 1,
    SG_CLIP_WMIN = 1u << 2,
    SG_CLIP_LEFT = 1u << 3,
    SG_CLIP_RIGHT = 1u << 4,
    SG_CLIP_BOTTOM = 1u << 5,
    SG_CLIP_TOP = 1u << 6,
    SG_CLIP_PLANE_COUNT = 7,
    /* Not a plane: a coordinate is NaN or infinite. Such a triangle is dropped whole. */
    SG_CLIP_NONFINITE = 1u << 7,
};

/* A clipped triangle has at most one more vertex per plane. */
#define SG_CLIP_MAX_VERTS (3 + SG_CLIP_PLANE_COUNT)

typedef struct sg_guard {
    float gx, gy; /* |x| <= gx * w and |y| <= gy * w keep a vertex inside the guard band */
} sg_guard;

/** Guard-band factors for a viewport of the given size. */
sg_guard sg_guard_for_viewport(int width, int height);
/** The set of planes a clip-space position is outside of (0: inside all); a non-finite
 *  position is outside all planes and also has SG_CLIP_NONFINITE. */
uint32_t sg_clip_outcode(const float pos[4], const sg_guard *guard);
/** Clips the polygon poly[0..n) against `planes`, in place; returns the new vertex count
 *  (0 when nothing is left). poly must hold SG_CLIP_MAX_VERTS vertices. */
int sg_clip_polygon(sg_cvert *poly, int n, uint32_t planes, int nattr, const sg_guard *guard);

#endif
