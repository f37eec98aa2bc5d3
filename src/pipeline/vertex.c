/* vertex.c - transforms positions to clip space and classifies them against the clip planes once,
 * so that primitive assembly only reads results, however many triangles share a vertex. */
#include "pipeline/vertex.h"

#include "pipeline/mat4.h"

void sg_vertex_transform(const float mvp[16], const float *positions, int count, float (*clip)[4],
                         uint32_t *outcodes, const sg_guard *guard) {
    for (int i = 0; i < count; i++) {
        sg_mat4_transform(clip[i], mvp, positions + (size_t)i * 4);
        outcodes[i] = sg_clip_outcode(clip[i], guard);
    }
}
