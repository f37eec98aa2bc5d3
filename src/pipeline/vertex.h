/* vertex.h - the vertex stage: every vertex of a geom is transformed once per draw. */
#ifndef SG_VERTEX_H
#define SG_VERTEX_H

#include <stdbool.h>
#include <stddef.h>
#include <string.h>
#include <stdint.h>

#include "pipeline/clip.h"
#include "pipeline/light.h"
#include "pipeline/setup.h"

/** clip[i] = mvp * positions[i] and outcodes[i] = its clip outcode, for i < count. */
void sg_vertex_transform(const float mvp[16], const float *positions, int count, float (*clip)[4],
                         uint32_t *outcodes, const sg_guard *guard);

/** One vertex's clip position, the same bits as sg_vertex_transform's. */
void sg_vertex_clip(const float mvp[16], const float position[4], float clip[4]);

/** sg_vertex_transform then sg_vertex_project, the same outcodes, screen records and flags, with
 *  no clip position stored: a draw that clips one recomputes it (sg_vertex_clip). */
void sg_vertex_transform_project(const float mvp[16], const float *positions, int count,
                                 uint32_t *outcodes, const sg_guard *guard,
                                 const sg_setup_params *p, sg_svert *screen, uint8_t *ok);

/** For every vertex inside all clip planes (outcode 0): its projection to the screen, and ok[i]
 *  = 1 when it fits the raster's range (else 0; also 0 for vertices outside some plane). */
void sg_vertex_project(const sg_setup_params *p, const float (*clip)[4], const uint32_t *outcodes,
                       int count, sg_svert *screen, uint8_t *ok);
/** Whether the attributes a draw reads of vertex i are all finite (colour: 4 floats a vertex,
 *  NULL for none; texcoords: 2 floats a vertex, read when nattr > 4). A NaN or infinity has all
 *  exponent bits set. */
static inline bool sg_vertex_attributes_finite(const float *colors, const float *texcoords,
                                               int nattr, size_t i) {
    uint32_t u[6] = {0, 0, 0, 0, 0, 0};
    if (colors) memcpy(u, colors + i * 4, 4 * sizeof(float));
    if (nattr > 4) memcpy(u + 4, texcoords + i * 2, 2 * sizeof(float));
    uint32_t bad = 0;
    for (int k = 0; k < 6; k++) bad |= (uint32_t)((u[k] & 0x7f800000u) == 0x7f800000u);
    return !bad;
}

struct sg_vertex_lit;

/* Gouraud lighting in one instruction set (the GOURAUD path of sg_vertex_lit_attributes, the same
 * bytes) of the vertices [first, first + done) of [first, first + count); returns done, a whole
 * number of vectors. */
typedef int (*sg_vertex_lit_fn)(const struct sg_vertex_lit *l, int first, int count, float *out,
                                uint8_t *ok);

/* What the vertex stage of a lit draw needs (light.h has the layout of what it makes). */
typedef struct sg_vertex_lit {
    sgLightingMode mode; /* FLAT, GOURAUD or PHONG; NONE: unlit, receiving a shadow map */
    const float *world_view, *normal_matrix;
    const float *positions, *normals, *colors, *texcoords, *tint; /* each may be NULL but
                                                                     positions */
    const sg_lights *lights;                                      /* GOURAUD */
    int stride;                                                   /* floats a vertex */
    /* GOURAUD receiving a shadow map: 1 + the light it hides, whose part of the colours is kept
     * apart (the split colours of light.h, SG_LIT_SPLIT_*); 0: none. */
    int split;
    sg_vertex_lit_fn gouraud; /* GOURAUD in the device's instruction set; NULL: scalar */
} sg_vertex_lit;

/** The lit attributes of vertices [first, first + count) into out (stride floats each): base
 *  colour, texcoords, view position (FLAT, NONE); and normal (PHONG); or the lit colours
 *  (GOURAUD; split, with the view position, when it receives a shadow map). A
 *  vertex any of whose attributes is NaN or infinite gets ok[i] = 0. */
void sg_vertex_lit_attributes(const sg_vertex_lit *l, int first, int count, float *out,
                              uint8_t *ok);

/** The vector Gouraud lighting of AVX2, AVX-512 and NEON; NULL where the build has none. */
sg_vertex_lit_fn sg_vertex_gouraud_avx2(void);
sg_vertex_lit_fn sg_vertex_gouraud_avx512(void);
sg_vertex_lit_fn sg_vertex_gouraud_neon(void);

/** Clears ok[i] of the vertices with a NaN or infinite attribute the draw reads (colour: 4 floats
 *  a vertex, NULL for none; texcoords: 2 floats a vertex, read when nattr > 4). */
void sg_vertex_check_attributes(const float *colors, const float *texcoords, int nattr, int count,
                                uint8_t *ok);

#endif
