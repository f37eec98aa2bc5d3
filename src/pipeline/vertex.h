/* vertex.h - the vertex stage: every vertex of a geom is transformed once per draw. */
#ifndef SG_VERTEX_H
#define SG_VERTEX_H

#include <stddef.h>
#include <stdint.h>

#include "pipeline/clip.h"
#include "pipeline/setup.h"

/** clip[i] = mvp * positions[i] and outcodes[i] = its clip outcode, for i < count. */
void sg_vertex_transform(const float mvp[16], const float *positions, int count, float (*clip)[4],
                         uint32_t *outcodes, const sg_guard *guard);

/** For every vertex inside all clip planes (outcode 0): its projection to the screen, and ok[i]
 *  = 1 when it fits the raster's range (else 0; also 0 for vertices outside some plane). */
void sg_vertex_project(const sg_setup_params *p, const float (*clip)[4], const uint32_t *outcodes,
                       int count, sg_svert *screen, uint8_t *ok);
/** Clears ok[i] of the vertices with a NaN or infinite attribute the draw reads (colour: 4 floats
 *  a vertex, NULL for none; texcoords: 2 floats a vertex, read when nattr > 4). */
void sg_vertex_check_attributes(const float *colors, const float *texcoords, int nattr, int count,
                                uint8_t *ok);

#endif
