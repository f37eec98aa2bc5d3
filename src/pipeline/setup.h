/* setup.h - perspective divide, viewport, snapping, culling and triangle setup.
 *
 * Screen positions are snapped to 8 sub-pixel bits. Edge functions are evaluated exactly in 64-bit
 * integers at pixel centres (integer + 0.5), with the top-left rule folded into each edge's
 * constant, so coverage is decided without any rounding: two triangles sharing an edge never both
 * cover a pixel and never leave a gap. Depth, 1/w and attribute/w are float plane equations.
 */
#ifndef SG_SETUP_H
#define SG_SETUP_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "pipeline/clip.h"
#include "sgapi/sgapi.h"

#define SG_SUBPIXEL_BITS 8
#define SG_SUBPIXEL_ONE  (1 << SG_SUBPIXEL_BITS)

typedef struct sg_setup_params {
    int width, height;    /* viewport: the whole target */
    int rect_x0, rect_y0; /* pixels that may be touched: [x0, x1) x [y0, y1) */
    int rect_x1, rect_y1;
    sgCull cull;            /* resolved: NONE, BACK or FRONT */
    sgFrontFace front_face; /* resolved: CCW or CW */
    int nattr;              /* attributes to interpolate (0 .. SG_MAX_ATTRS) */
    int sec;                /* lit draws: index of a secondary colour (3 attributes), else 0 */
    /* End of the attributes from `sec` that are constant on a flat triangle and kept as they
     * are (0: sec + 3; the split colours of a shadow receiver, light.h, reach further). */
    int sec_end;
    /* Depth bias: every pixel's window depth moves by bias_constant + bias_slope * max(|dz/dx|,
     * |dz/dy|), before the clamp to [0, 1] (finite; 0: none). */
    float bias_constant, bias_slope;
    /* A shader pipeline's draw: its attributes are varyings (no flat colour is looked for), the
     * triangle's facing is kept (sg_tri.sh), and the varyings of flat_mask are kept as they are
     * (the value every vertex of the primitive carries: assembly copies the first vertex's). */
    int shader;
    uint32_t flat_mask;
    /* Samples a pixel of the pass (0 or 1: the centre; 4: the pixel bounds reach every pixel one
     * of whose samples may be covered, rast_msaa.h). */
    int samples;
} sg_setup_params;

/* Attributes an sg_tri holds; a draw that interpolates more keeps the rest in an sg_tri_ext (the
 * binner's array beside the triangles, same index), so unlit triangles stay small. */
#define SG_TRI_ATTRS 6

/* A triangle ready for the raster. Every "at origin" value is taken at the centre of pixel
 * (minx, miny); a step moves one pixel. Edge e covers a pixel when its value is >= 0. */
typedef struct sg_tri {
    int minx, miny, maxx, maxy; /* inclusive pixel bounds, inside the setup rectangle */
    int64_t edge[3];            /* edge values at origin, fill-rule bias included */
    int64_t edge_dx[3], edge_dy[3];
    float z, z_dx, z_dy;   /* window depth (0 near .. 1 far), linear in screen space */
    float q, q_dx, q_dy;   /* 1 / w */
    float a[SG_TRI_ATTRS]; /* attribute / w */
    float a_dx[SG_TRI_ATTRS], a_dy[SG_TRI_ATTRS];
    int nattr;
    /* The three vertex colours are equal: the colour is `color` everywhere, exactly (interpolating
     * it would only add rounding), and SG_FLAT_WHITE when that colour is opaque white. */
    int flat;
    /* The pixel bounds were cut to the setup rectangle. When not, the edge functions alone
     * exclude every pixel outside the bounds (none lies inside the triangle), so the raster
     * need not mask them. */
    int rect_cut;
    /* A line (line.h): 1 x-major, 2 y-major, 0 a triangle. The raster then walks along its major
     * axis instead of over its bounds. */
    int line;
    union {
        float color[4]; /* the flat colour (flat) */
        /* A shader draw's: what its fragment stage is told (sgFragmentBatch). */
        struct {
            int32_t primitive, instance, front_facing;
            uint32_t color; /* shader_const: the stage's colour everywhere, RGBA8 */
        } sh;
    };
    uint32_t draw; /* which draw of the pass it belongs to (set by the binner) */
    /* SG_CONST_COLOR: a shader triangle whose varyings are the same at its three vertices, of a
     * stage that reads its varyings alone (sgShaderDesc.varyings_only), shaded once in assembly:
     * its pixels all take sh.color. SG_CONST_NONE: shaded pixel by pixel. */
    uint16_t shader_const;
    /* A shader triangle's varyings that are the same, bit for bit, at its three vertices (flat
     * ones among them): bit k set, varying k is that value everywhere, kept as it is in a[k] (or
     * the extension's) with zero steps, as a flat varying is (interpolating it would only add
     * rounding). The high half of the 32 bits from shader_const on, as the shared tiles read it
     * (raster/shade_shader_tile.h). */
    uint16_t same;
} sg_tri;
_Static_assert(offsetof(sg_tri, same) == offsetof(sg_tri, shader_const) + 2,
               "sg_tri.same: the high half of the word at shader_const");

enum { SG_FLAT_NONE, SG_FLAT_COLOR, SG_FLAT_WHITE };
enum { SG_CONST_NONE, SG_CONST_COLOR };

/* Attributes SG_TRI_ATTRS.. of a triangle, as sg_tri's (attribute / w, at the origin, steps). A
 * flat triangle with a secondary colour keeps that colour (attributes sec .. sec_end - 1) as it is
 * in a[sec - SG_TRI_ATTRS ..] (steps zero). */
typedef struct sg_tri_ext {
    float a[SG_MAX_ATTRS - SG_TRI_ATTRS];
    float a_dx[SG_MAX_ATTRS - SG_TRI_ATTRS], a_dy[SG_MAX_ATTRS - SG_TRI_ATTRS];
} sg_tri_ext;

/** Divides, snaps, culls and sets up one clipped triangle (all w > 0); false: nothing to draw.
 *  ext receives attributes SG_TRI_ATTRS.. (NULL when p->nattr <= SG_TRI_ATTRS). */
bool sg_setup_triangle(const sg_setup_params *p, const sg_cvert *v0, const sg_cvert *v1,
                       const sg_cvert *v2, sg_tri *out, sg_tri_ext *ext);

/* Triangle setup in steps (setup.c), for assembly: a vertex is projected once however many
 * triangles share it, and a triangle is culled from its screen positions alone, before any of its
 * attributes is read. sg_setup_triangle is these three steps in a row, with the same results. */

/* A vertex after the perspective divide, the viewport transform and snapping. */
typedef struct sg_svert {
    int32_t x, y; /* snapped, 1/256 pixel */
    float z;      /* window depth */
    float q;      /* 1 / w */
} sg_svert;

/** Projects a clip-space position (w > 0); false: it does not fit the raster's range. */
bool sg_setup_project(const sg_setup_params *p, const float pos[4], sg_svert *s);
/** Twice the signed area of a projected triangle, in 1/256 pixel squared (exact); positive is
 *  clockwise on screen. Inline: assembly culls with it before anything else. */
static inline int64_t sg_setup_area(const sg_svert s[3]) {
    return (int64_t)(s[1].x - s[0].x) * (s[2].y - s[0].y) -
           (int64_t)(s[2].x - s[0].x) * (s[1].y - s[0].y);
}

/** Whether a triangle of that signed area is culled (zero area always is). */
static inline bool sg_setup_culled(const sg_setup_params *p, int64_t area) {
    if (area == 0) return true;
    bool ccw = area < 0; /* counter-clockwise as seen with y up */
    bool front = (p->front_face == SG_FRONT_FACE_CW) ? !ccw : ccw;
    return (p->cull == SG_CULL_BACK && !front) || (p->cull == SG_CULL_FRONT && front);
}
/* The pixels a triangle may cover: its bounds, clamped to the render rectangle. */
typedef struct sg_bounds {
    int minx, miny, maxx, maxy;
    bool rect_cut; /* the clamp cut them */
} sg_bounds;

/** Pixel bounds of a triangle of signed area `area` (sg_setup_area) that culling kept; no
 *  triangle written, so that assembly asks for a slot only for one that passes. Puts s[] (and
 *  attr[] alongside) in the order sg_setup_planes wants; false: no pixel centre to draw. Reads
 *  no attribute: attr[] may still be empty. */
bool sg_setup_bounds(const sg_setup_params *p, sg_svert s[3], int64_t area, const float *attr[3],
                     sg_bounds *out);
/** The bounds and edge functions into out, of a triangle that passed sg_setup_bounds with s[]. */
void sg_setup_edges(const sg_bounds *bounds, const sg_svert s[3], sg_tri *out);
/** Area, culling (sg_setup_culled), sg_setup_bounds, then sg_setup_edges. */
bool sg_setup_coverage(const sg_setup_params *p, sg_svert s[3], const float *attr[3], sg_tri *out);
/** Depth, 1/w and attribute plane equations and the flat colour of a triangle that passed
 *  sg_setup_coverage, with the s[] and attr[] it reordered (each attr[i] holds nattr values).
 *  Only the planes the shading reads are computed; the others are zero. */
void sg_setup_planes(const sg_setup_params *p, const sg_svert s[3], const float *const attr[3],
                     sg_tri *out);
/** The planes of attributes SG_TRI_ATTRS .. p->nattr - 1 of a triangle sg_setup_planes has set
 *  up (a lit draw's), into its extension. */
void sg_setup_planes_ext(const sg_setup_params *p, const sg_svert s[3], const float *const attr[3],
                         const sg_tri *t, sg_tri_ext *ext);

#endif
