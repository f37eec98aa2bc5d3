/* vertex.h - the vertex stage: every vertex of a geom is transformed once per draw. */
#ifndef SG_VERTEX_H
#define SG_VERTEX_H

#include <stddef.h>
#include <stdint.h>

#include "pipeline/clip.h"

/** clip[i] = mvp * positions[i] and outcodes[i] = its clip outcode, for i < count. */
void sg_vertex_transform(const float mvp[16], const float *positions, int count, float (*clip)[4],
                         uint32_t *outcodes, const sg_guard *guard);

#endif
