/* vertex.c - transforms positions to clip space and classifies them against the clip planes once,
 * so that primitive assembly only reads results, however many triangles share a vertex. */
#include "pipeline/vertex.h"

#include "pipeline/mat4.h"

#include <float.h>
#include <string.h>
/* SSE lanes only where SSE also does scalar float maths: then they round as the scalar code. */
#if defined(__SSE_MATH__)
#include <xmmintrin.h>
#endif
#if defined(__SSE2__) && defined(__SSE_MATH__)
#include <emmintrin.h>
#endif

#if defined(__SSE_MATH__)
/* The matrix columns in SSE lanes: lane r computes ((m[r][0] x + m[r][1] y) + m[r][2] z) +
 * m[r][3] w, the products and sums of sg_mat4_transform in its order, so the same bits. */
typedef struct mvp_cols {
    __m128 c0, c1, c2, c3;
} mvp_cols;

static inline mvp_cols cols_of(const float mvp[16]) {
    mvp_cols m = {_mm_setr_ps(mvp[0], mvp[4], mvp[8], mvp[12]),
                  _mm_setr_ps(mvp[1], mvp[5], mvp[9], mvp[13]),
                  _mm_setr_ps(mvp[2], mvp[6], mvp[10], mvp[14]),
                  _mm_setr_ps(mvp[3], mvp[7], mvp[11], mvp[15])};
    return m;
}

static inline __m128 transform1(const mvp_cols *m, const float *position) {
    __m128 v = _mm_loadu_ps(position);
    return _mm_add_ps(
        _mm_add_ps(_mm_add_ps(_mm_mul_ps(m->c0, _mm_shuffle_ps(v, v, _MM_SHUFFLE(0, 0, 0, 0))),
                              _mm_mul_ps(m->c1, _mm_shuffle_ps(v, v, _MM_SHUFFLE(1, 1, 1, 1)))),
                   _mm_mul_ps(m->c2, _mm_shuffle_ps(v, v, _MM_SHUFFLE(2, 2, 2, 2)))),
        _mm_mul_ps(m->c3, _mm_shuffle_ps(v, v, _MM_SHUFFLE(3, 3, 3, 3))));
}
#endif

void sg_vertex_clip(const float mvp[16], const float position[4], float clip[4]) {
#if defined(__SSE_MATH__)
    const mvp_cols m = cols_of(mvp);
    _mm_storeu_ps(clip, transform1(&m, position));
#else
    sg_mat4_transform(clip, mvp, position);
#endif
}

#if defined(__SSE2__) && defined(__SSE_MATH__)
/* What projection needs of the setup, in lanes. */
typedef struct project_consts {
    __m128 hw, hh, sub, half, lim, fmax, sign, one;
} project_consts;

static inline project_consts project_consts_of(const sg_setup_params *p) {
    project_consts c = {_mm_set1_ps(0.5f * (float)p->width),
                        _mm_set1_ps(0.5f * (float)p->height),
                        _mm_set1_ps((float)SG_SUBPIXEL_ONE),
                        _mm_set1_ps(0.5f),
                        _mm_set1_ps(2147483520.0f),
                        _mm_set1_ps(FLT_MAX),
                        _mm_set1_ps(-0.0f),
                        _mm_set1_ps(1.0f)};
    return c;
}

/* Four vertices' clip x, y, z, w (one vertex a lane) and outcodes to their screen records and ok
 * flags, lane for lane the operations of sg_setup_project in its order (a true division;
 * cvtps2dq rounds to nearest even as its cvtss2si does), so the same bits. */
static inline void project4(const project_consts *c, __m128 x, __m128 y, __m128 z, __m128 w,
                            __m128i outcodes, sg_svert *screen, uint8_t *ok) {
    __m128 q = _mm_div_ps(c->one, w);
    __m128 xn = _mm_mul_ps(x, q), yn = _mm_mul_ps(y, q), zn = _mm_mul_ps(z, q);
    __m128 xf = _mm_mul_ps(_mm_add_ps(_mm_mul_ps(xn, c->hw), c->hw), c->sub);
    __m128 yf = _mm_mul_ps(_mm_sub_ps(c->hh, _mm_mul_ps(yn, c->hh)), c->sub);
    __m128 fits = _mm_and_ps(_mm_and_ps(_mm_cmplt_ps(_mm_andnot_ps(c->sign, xf), c->lim),
                                        _mm_cmplt_ps(_mm_andnot_ps(c->sign, yf), c->lim)),
                             _mm_and_ps(_mm_cmple_ps(_mm_andnot_ps(c->sign, zn), c->fmax),
                                        _mm_cmple_ps(_mm_andnot_ps(c->sign, q), c->fmax)));
    __m128i inside = _mm_cmpeq_epi32(outcodes, _mm_setzero_si128());
    int good = _mm_movemask_ps(_mm_and_ps(fits, _mm_castsi128_ps(inside)));
    /* sg_svert is {int32 x, y; float z, q}: four lanes back to four records. */
    __m128 sx = _mm_castsi128_ps(_mm_cvtps_epi32(xf)), sy = _mm_castsi128_ps(_mm_cvtps_epi32(yf));
    __m128 sz = _mm_add_ps(_mm_mul_ps(zn, c->half), c->half), sq = q;
    _MM_TRANSPOSE4_PS(sx, sy, sz, sq);
    _mm_storeu_ps((float *)(void *)&screen[0], sx);
    _mm_storeu_ps((float *)(void *)&screen[1], sy);
    _mm_storeu_ps((float *)(void *)&screen[2], sz);
    _mm_storeu_ps((float *)(void *)&screen[3], sq);
    for (int k = 0; k < 4; k++) ok[k] = (uint8_t)((good >> k) & 1);
}
#endif

void sg_vertex_transform(const float mvp[16], const float *positions, int count, float (*clip)[4],
                         uint32_t *outcodes, const sg_guard *guard) {
    int i = 0;
#if defined(__SSE_MATH__)
    const mvp_cols m = cols_of(mvp);
#if defined(__SSE2__)
    for (; i + 4 <= count; i += 4) { /* four vertices, then their outcodes four lanes wide */
        __m128 r[4];
        for (int k = 0; k < 4; k++) {
            r[k] = transform1(&m, positions + (size_t)(i + k) * 4);
            _mm_storeu_ps(clip[i + k], r[k]);
        }
        _MM_TRANSPOSE4_PS(r[0], r[1], r[2], r[3]);
        _mm_storeu_si128((__m128i *)(void *)(outcodes + i),
                         sg_clip_outcode4(r[0], r[1], r[2], r[3], guard));
    }
#endif
    for (; i < count; i++) {
        _mm_storeu_ps(clip[i], transform1(&m, positions + (size_t)i * 4));
        outcodes[i] = sg_clip_outcode(clip[i], guard);
    }
#else
    for (; i < count; i++) {
        sg_mat4_transform(clip[i], mvp, positions + (size_t)i * 4);
        outcodes[i] = sg_clip_outcode(clip[i], guard);
    }
#endif
}

void sg_vertex_project(const sg_setup_params *p, const float (*clip)[4], const uint32_t *outcodes,
                       int count, sg_svert *screen, uint8_t *ok) {
    int i = 0;
#if defined(__SSE2__) && defined(__SSE_MATH__)
    const project_consts c = project_consts_of(p);
    for (; i + 4 <= count; i += 4) {
        __m128 x = _mm_loadu_ps(clip[i]), y = _mm_loadu_ps(clip[i + 1]);
        __m128 z = _mm_loadu_ps(clip[i + 2]), w = _mm_loadu_ps(clip[i + 3]);
        _MM_TRANSPOSE4_PS(x, y, z, w);
        project4(&c, x, y, z, w, _mm_loadu_si128((const __m128i *)(const void *)(outcodes + i)),
                 screen + i, ok + i);
    }
#endif
    for (; i < count; i++) ok[i] = outcodes[i] == 0 && sg_setup_project(p, clip[i], &screen[i]);
}

void sg_vertex_transform_project(const float mvp[16], const float *positions, int count,
                                 uint32_t *outcodes, const sg_guard *guard,
                                 const sg_setup_params *p, sg_svert *screen, uint8_t *ok) {
    int i = 0;
#if defined(__SSE2__) && defined(__SSE_MATH__)
    /* sg_vertex_transform's four vertices, projected from the lanes they are in. */
    const mvp_cols m = cols_of(mvp);
    const project_consts c = project_consts_of(p);
    for (; i + 4 <= count; i += 4) {
        __m128 r[4];
        for (int k = 0; k < 4; k++) r[k] = transform1(&m, positions + (size_t)(i + k) * 4);
        _MM_TRANSPOSE4_PS(r[0], r[1], r[2], r[3]);
        const __m128i codes = sg_clip_outcode4(r[0], r[1], r[2], r[3], guard);
        _mm_storeu_si128((__m128i *)(void *)(outcodes + i), codes);
        project4(&c, r[0], r[1], r[2], r[3], codes, screen + i, ok + i);
    }
#endif
    for (; i < count; i++) {
        float clip[4];
        sg_vertex_clip(mvp, positions + (size_t)i * 4, clip);
        outcodes[i] = sg_clip_outcode(clip, guard);
        ok[i] = outcodes[i] == 0 && sg_setup_project(p, clip, &screen[i]);
    }
}

void sg_vertex_check_attributes(const float *colors, const float *texcoords, int nattr, int count,
                                uint8_t *ok) {
#if defined(__SSE2__)
    /* Whole arrays at once, as in sg_vertex_attributes_finite: all exponent bits set is bad. */
    const __m128i exp = _mm_set1_epi32(0x7f800000);
    const bool tex = nattr > 4;
    if (colors || tex) {
        for (int i = 0; i < count; i++) {
            __m128i bad = _mm_setzero_si128();
            if (colors)
                bad = _mm_cmpeq_epi32(
                    _mm_and_si128(
                        _mm_loadu_si128((const __m128i *)(const void *)(colors + 4 * (size_t)i)),
                        exp),
                    exp);
            if (tex)
                bad = _mm_or_si128(
                    bad, _mm_cmpeq_epi32(
                             _mm_and_si128(
                                 _mm_loadl_epi64(
                                     (const __m128i *)(const void *)(texcoords + 2 * (size_t)i)),
                                 exp),
                             exp));
            ok[i] &= (uint8_t)(_mm_movemask_epi8(bad) == 0);
        }
    }
#else
    for (int i = 0; i < count; i++)
        if (ok[i])
            ok[i] = (uint8_t)sg_vertex_attributes_finite(colors, texcoords, nattr, (size_t)i);
#endif
}

void sg_vertex_lit_attributes(const sg_vertex_lit *l, int first, int count, float *out,
                              uint8_t *ok) {
    if (l->mode == SG_LIGHTING_GOURAUD && l->gouraud) { /* vectors, then the last few here */
        int done = l->gouraud(l, first, count, out, ok);
        first += done;
        count -= done;
    }
    static const float white[4] = {1.0f, 1.0f, 1.0f, 1.0f};
    const float *m = l->world_view, *nm = l->normal_matrix;
    for (int i = first; i < first + count; i++) {
        float *o = out + (size_t)i * (size_t)l->stride;
        float base[4], P[3], v[4];
        memcpy(base, l->colors ? l->colors + (size_t)i * 4 : white, sizeof base);
        if (l->tint)
            for (int k = 0; k < 4; k++) base[k] *= l->tint[k];
        sg_mat4_transform(v, m, l->positions + (size_t)i * 4);
        for (int k = 0; k < 3; k++) P[k] = v[3] != 1.0f ? v[k] / v[3] : v[k];
        if (l->stride > SG_LIT_ST) { /* an untextured Gouraud draw stores its colour alone */
            o[SG_LIT_ST] = l->texcoords ? l->texcoords[(size_t)i * 2] : 0.0f;
            o[SG_LIT_ST + 1] = l->texcoords ? l->texcoords[(size_t)i * 2 + 1] : 0.0f;
        }
        float n[3] = {0.0f, 0.0f, 0.0f};
        if (l->mode == SG_LIGHTING_GOURAUD || l->mode == SG_LIGHTING_PHONG) {
            const float *src = l->normals + (size_t)i * 3;
            for (int r = 0; r < 3; r++)
                n[r] = (nm[r * 3] * src[0] + nm[r * 3 + 1] * src[1]) + nm[r * 3 + 2] * src[2];
        }
        if (l->mode == SG_LIGHTING_GOURAUD && l->split) {
            float rest[4], part[9];
            sg_light_eval_split(l->lights, P, n, base, l->split - 1, rest, part, part + 3,
                                part + 6);
            memcpy(o + SG_LIT_COLOR, rest, sizeof rest);
            memcpy(o + SG_LIT_POS, P, sizeof P);
            memcpy(o + SG_LIT_SPLIT_D, part, (size_t)(l->stride - SG_LIT_SPLIT_D) * sizeof(float));
        } else if (l->mode == SG_LIGHTING_GOURAUD) {
            float prim[4], sec[3];
            sg_light_eval(l->lights, P, n, base, prim, sec);
            memcpy(o + SG_LIT_COLOR, prim, sizeof prim);
            if (l->stride > SG_LIT_SEC) memcpy(o + SG_LIT_SEC, sec, sizeof sec);
        } else {
            memcpy(o + SG_LIT_COLOR, base, sizeof base);
            memcpy(o + SG_LIT_POS, P, sizeof P);
            if (l->mode == SG_LIGHTING_PHONG) memcpy(o + SG_LIT_NRM, n, sizeof n);
        }
        uint32_t bad = 0;
        for (int k = 0; k < l->stride; k++) {
            uint32_t u;
            memcpy(&u, o + k, sizeof u);
            bad |= (uint32_t)((u & 0x7f800000u) == 0x7f800000u);
        }
        if (bad) ok[i] = 0;
    }
}
