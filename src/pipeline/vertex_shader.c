/* vertex_shader.c - a shader pipeline's vertex stage (see vertex_shader.h). Each vertex is shaded
 * once per instance, however many primitives share it, as the fixed vertex stage does. */
#include "pipeline/vertex_shader.h"

#include <float.h>
#include <string.h>

#include "pipeline/vertex.h"

/* n floats (a multiple of 4) of value c, with vector stores: a call of memset becomes a string
 * instruction here, whose start-up cost more than a batch's other filling. */
static inline void fill_floats(float *p, size_t n, float c) {
#if defined(__SSE2__)
    const __m128 v = _mm_set1_ps(c);
    for (size_t i = 0; i < n; i += 4) _mm_storeu_ps(p + i, v);
#else
    for (size_t i = 0; i < n; i++) p[i] = c;
#endif
}

/* One stream of `comps` floats a vertex (2 to 4) into dst[k][lane], lane i from vertex v[i]. */
static inline void fill_stream(float (*dst)[SG_SHADER_LANES], const float *src, int comps,
                               const size_t v[SG_SHADER_LANES]) {
#if defined(__SSE2__)
    /* A vertex a register, then four lanes' registers transposed: the loads read the vertex's
     * own floats alone (the last vertex may end the array). */
    for (int g = 0; g < SG_SHADER_LANES; g += 4) {
        __m128 r[4];
        for (int j = 0; j < 4; j++) {
            const float *p = src + v[g + j] * (size_t)comps;
            const __m128 xy = _mm_castpd_ps(_mm_load_sd((const double *)(const void *)p));
            r[j] = comps == 4   ? _mm_loadu_ps(p)
                   : comps == 3 ? _mm_movelh_ps(xy, _mm_load_ss(p + 2))
                                : xy;
        }
        _MM_TRANSPOSE4_PS(r[0], r[1], r[2], r[3]);
        for (int k = 0; k < comps; k++) _mm_storeu_ps(dst[k] + g, r[k]);
    }
#else
    for (int k = 0; k < comps; k++)
        for (int i = 0; i < SG_SHADER_LANES; i++) dst[k][i] = src[v[i] * (size_t)comps + (size_t)k];
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
        if (src)                                                                                   \
            fill_stream((dst), (src), (comps), v);                                                 \
        else                                                                                       \
            fill_floats(&(dst)[0][0], sizeof(dst) / sizeof(float), (absent));                      \
    } while (0)
    SG_FILL(b->position, r->positions, 4, 0.0f);
    SG_FILL(b->color, r->colors, 4, 1.0f);
    SG_FILL(b->normal, r->normals, 3, 0.0f);
    SG_FILL(b->texcoord, r->texcoords, 2, 0.0f);
    for (int a = 0; a < SG_MAX_ATTRIBUTES; a++) SG_FILL(b->attribute[a], r->attributes[a], 4, 0.0f);
#undef SG_FILL
}

#if !(defined(__SSE2__) && defined(__SSE_MATH__))
static bool finite(float v) {
    return v >= -FLT_MAX && v <= FLT_MAX;
}
#endif

void sg_vertex_shade(const sg_vertex_shader_run *r, int first, int count) {
    sgVertexBatch b;
    for (int at = first; at < first + count; at += SG_SHADER_LANES) {
        int n = first + count - at < SG_SHADER_LANES ? first + count - at : SG_SHADER_LANES;
        fill_batch(r, at, n, &b);
        /* The outputs start defined: a shader that leaves a varying unwritten gets 0 there. */
        fill_floats(&b.clip[0][0], 4 * SG_SHADER_LANES, 0.0f);
        fill_floats(&b.varying[0][0], (size_t)r->varying_count * SG_SHADER_LANES, 0.0f);
        r->vertex(&b, r->uniforms);
#if defined(__SSE2__) && defined(__SSE_MATH__)
        for (int g = 0; g < n; g += 4) { /* four lanes' positions transposed to four vertices */
            __m128 c0 = _mm_load_ps(b.clip[0] + g), c1 = _mm_load_ps(b.clip[1] + g),
                   c2 = _mm_load_ps(b.clip[2] + g), c3 = _mm_load_ps(b.clip[3] + g);
            _MM_TRANSPOSE4_PS(c0, c1, c2, c3);
            const __m128 c[4] = {c0, c1, c2, c3};
            for (int j = 0; j < 4 && g + j < n; j++) _mm_storeu_ps(r->clip[at + g + j], c[j]);
        }
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
            for (int k = 0; k < 4; k++) r->clip[at + i][k] = b.clip[k][i];
        for (int i = 0; i < n; i++)
            r->outcodes[at + i] = sg_clip_outcode(r->clip[at + i], r->guard);
#endif
        sg_vertex_project(r->setup, (const float(*)[4])r->clip + at, r->outcodes + at, n,
                          r->screen + at, r->screen_ok + at);
        uint32_t bad = 0; /* lane i: a varying not finite */
        for (int k = 0; k < r->varying_count; k++) {
#if defined(__SSE2__) && defined(__SSE_MATH__)
            const __m128 lo = _mm_set1_ps(-FLT_MAX), hi = _mm_set1_ps(FLT_MAX);
            for (int g = 0; g < SG_SHADER_LANES; g += 4) {
                const __m128 x = _mm_load_ps(b.varying[k] + g);
                const __m128 in = _mm_and_ps(_mm_cmpge_ps(x, lo), _mm_cmple_ps(x, hi));
                bad |= (uint32_t)(_mm_movemask_ps(in) ^ 15) << g;
            }
#else
            for (int i = 0; i < SG_SHADER_LANES; i++)
                bad |= (uint32_t)!finite(b.varying[k][i]) << i;
#endif
            float *out = r->varyings + (size_t)at * (size_t)r->varying_count + (size_t)k;
            for (int i = 0; i < n; i++) out[(size_t)i * (size_t)r->varying_count] = b.varying[k][i];
        }
        for (int i = 0; i < n; i++) r->screen_ok[at + i] &= !(bad >> i & 1);
    }
}
