/* vertex_shader.c - a shader pipeline's vertex stage (see vertex_shader.h). Each vertex is shaded
 * once per instance, however many primitives share it, as the fixed vertex stage does. */
#include "pipeline/vertex_shader.h"

#include <float.h>
#include <string.h>

#include "pipeline/vertex.h"

/* The inputs of lanes [0, n) from vertices first..first + n - 1; lanes past n copy lane 0. */
static void fill_batch(const sg_vertex_shader_run *r, int first, int n, sgVertexBatch *b) {
    b->count = n;
    b->instance = r->instance;
    b->world_view = r->world_view;
    b->proj = r->proj;
    for (int i = 0; i < SG_SHADER_LANES; i++) {
        const size_t v = (size_t)first + (size_t)(i < n ? i : 0);
        b->index[i] = (uint32_t)v;
        for (int k = 0; k < 4; k++) {
            b->position[k][i] = r->positions[v * 4 + (size_t)k];
            b->color[k][i] = r->colors ? r->colors[v * 4 + (size_t)k] : 1.0f;
        }
        for (int k = 0; k < 3; k++)
            b->normal[k][i] = r->normals ? r->normals[v * 3 + (size_t)k] : 0.0f;
        for (int k = 0; k < 2; k++)
            b->texcoord[k][i] = r->texcoords ? r->texcoords[v * 2 + (size_t)k] : 0.0f;
        for (int a = 0; a < SG_MAX_ATTRIBUTES; a++)
            for (int k = 0; k < 4; k++)
                b->attribute[a][k][i] =
                    r->attributes[a] ? r->attributes[a][v * 4 + (size_t)k] : 0.0f;
    }
}

static bool finite(float v) {
    return v >= -FLT_MAX && v <= FLT_MAX;
}

void sg_vertex_shade(const sg_vertex_shader_run *r, int first, int count) {
    sgVertexBatch b;
    for (int at = first; at < first + count; at += SG_SHADER_LANES) {
        int n = first + count - at < SG_SHADER_LANES ? first + count - at : SG_SHADER_LANES;
        fill_batch(r, at, n, &b);
        /* The outputs start defined: a shader that leaves a varying unwritten gets 0 there. */
        memset(b.clip, 0, sizeof b.clip);
        memset(b.varying, 0, sizeof b.varying);
        r->vertex(&b, r->uniforms);
        for (int i = 0; i < n; i++) {
            const int v = at + i;
            for (int k = 0; k < 4; k++) r->clip[v][k] = b.clip[k][i];
            r->outcodes[v] = sg_clip_outcode(r->clip[v], r->guard);
            bool ok = true;
            float *out = r->varyings + (size_t)v * (size_t)r->varying_count;
            for (int k = 0; k < r->varying_count; k++) {
                out[k] = b.varying[k][i];
                ok &= finite(out[k]);
            }
            r->screen_ok[v] =
                ok && r->outcodes[v] == 0 && sg_setup_project(r->setup, r->clip[v], &r->screen[v]);
        }
    }
}
