/* vertex_shader.c - a shader pipeline's vertex stage (see vertex_shader.h). Each vertex is shaded
 * once per instance, however many primitives share it, as the fixed vertex stage does. */
#include "pipeline/vertex_shader.h"

#include <float.h>
#include <string.h>

#include "pipeline/vertex.h"

/* Zeroes n floats (a multiple of 16) with vector stores: a call of memset becomes a string
 * instruction here, whose start-up cost more than a batch's other filling. */
static inline void zero_floats(float *p, size_t n) {
#if defined(__SSE2__)
    for (size_t i = 0; i < n; i += 16) {
        const __m128 z = _mm_setzero_ps();
        _mm_storeu_ps(p + i, z);
        _mm_storeu_ps(p + i + 4, z);
        _mm_storeu_ps(p + i + 8, z);
        _mm_storeu_ps(p + i + 12, z);
    }
#else
    memset(p, 0, n * sizeof *p);
#endif
}

/* The inputs of lanes [0, n) from vertices first..first + n - 1; lanes past n copy lane 0. Stream
 * by stream: a missing one is a constant fill, with no test per lane. */
static void fill_batch(const sg_vertex_shader_run *r, int first, int n, sgVertexBatch *b) {
    b->count = n;
    b->instance = r->instance;
    b->world_view = r->world_view;
    b->proj = r->proj;
    size_t v[SG_SHADER_LANES];
    for (int i = 0; i < SG_SHADER_LANES; i++) {
        v[i] = (size_t)first + (size_t)(i < n ? i : 0);
        b->index[i] = (uint32_t)v[i];
    }
#define SG_FILL(dst, src, comps, absent)                                                           \
    do {                                                                                           \
        for (int k = 0; k < (comps); k++)                                                          \
            for (int i = 0; i < SG_SHADER_LANES; i++)                                              \
                (dst)[k][i] = (src) ? (src)[v[i] * (comps) + (size_t)k] : (absent);                \
    } while (0)
    SG_FILL(b->position, r->positions, 4, 0.0f);
    SG_FILL(b->color, r->colors, 4, 1.0f);
    SG_FILL(b->normal, r->normals, 3, 0.0f);
    SG_FILL(b->texcoord, r->texcoords, 2, 0.0f);
    for (int a = 0; a < SG_MAX_ATTRIBUTES; a++) {
        if (r->attributes[a])
            SG_FILL(b->attribute[a], r->attributes[a], 4, 0.0f);
        else
            zero_floats(&b->attribute[a][0][0], 4 * SG_SHADER_LANES);
    }
#undef SG_FILL
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
        zero_floats(&b.clip[0][0], 4 * SG_SHADER_LANES);
        zero_floats(&b.varying[0][0], (size_t)r->varying_count * SG_SHADER_LANES);
        r->vertex(&b, r->uniforms);
        for (int i = 0; i < n; i++)
            for (int k = 0; k < 4; k++) r->clip[at + i][k] = b.clip[k][i];
#if defined(__SSE2__) && defined(__SSE_MATH__)
        /* The fixed vertex stage's outcodes and projection, four lanes at a time. */
        _Alignas(16) uint32_t oc[SG_SHADER_LANES];
        for (int g = 0; g < SG_SHADER_LANES; g += 4)
            _mm_store_si128((__m128i *)(void *)(oc + g),
                            sg_clip_outcode4(_mm_load_ps(b.clip[0] + g), _mm_load_ps(b.clip[1] + g),
                                             _mm_load_ps(b.clip[2] + g), _mm_load_ps(b.clip[3] + g),
                                             r->guard));
        memcpy(r->outcodes + at, oc, (size_t)n * sizeof *oc);
#else
        for (int i = 0; i < n; i++)
            r->outcodes[at + i] = sg_clip_outcode(r->clip[at + i], r->guard);
#endif
        sg_vertex_project(r->setup, (const float(*)[4])r->clip + at, r->outcodes + at, n,
                          r->screen + at, r->screen_ok + at);
        for (int i = 0; i < n; i++) {
            bool ok = true;
            float *out = r->varyings + (size_t)(at + i) * (size_t)r->varying_count;
            for (int k = 0; k < r->varying_count; k++) {
                out[k] = b.varying[k][i];
                ok &= finite(out[k]);
            }
            r->screen_ok[at + i] &= ok;
        }
    }
}
