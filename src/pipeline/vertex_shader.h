/* vertex_shader.h - the vertex stage of shader pipelines: a draw's vertices, 16 at a time, through
 * the pipeline's vertex function (sgVertexBatch), into the vertex stage's arenas. */
#ifndef SG_VERTEX_SHADER_H
#define SG_VERTEX_SHADER_H

#include <stdint.h>

#include "pipeline/clip.h"
#include "pipeline/setup.h"
#include "sgapi/sgapi.h"

typedef struct sg_vertex_shader_run {
    void (*vertex)(sgVertexBatch *b, const void *uniforms);
    const void *uniforms;
    const float *positions, *colors, *normals, *texcoords; /* the geom's; NULL: absent */
    const float *attributes[SG_MAX_ATTRIBUTES];
    const float *world_view, *proj;
    int instance;
    int varying_count; /* floats of varyings a vertex in `varyings` */
    /* out, indexed by vertex */
    float (*clip)[4];
    float *varyings;
    uint32_t *outcodes;
    sg_svert *screen;
    uint8_t *screen_ok; /* 1: inside every clip plane, projected, and its varyings finite */
    const sg_guard *guard;
    const sg_setup_params *setup;
} sg_vertex_shader_run;

/** Runs vertices [first, first + count) through the vertex function, in batches of 16. */
void sg_vertex_shade(const sg_vertex_shader_run *r, int first, int count);

#endif
