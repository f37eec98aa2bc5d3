/* vertex_lit_simd.h - Gouraud lighting of vertices (the GOURAUD path of sg_vertex_lit_attributes)
 * on vectors of vertices, written once for every instruction set: a file includes light_avx2.h,
 * light_avx512.h or light_neon.h (the vector operations and the equation of light_simd.h), then
 * this header, and makes its function of vl_gouraud. Every lane computes the scalar path's IEEE
 * operations in their order (the transforms included), so the same bytes.
 */
#ifndef SG_VERTEX_LIT_SIMD_H
#define SG_VERTEX_LIT_SIMD_H

#include "pipeline/vertex.h"

#define VL_LANES ((int)(sizeof(LV) / sizeof(float)))

static inline __attribute__((always_inline)) LV vl_load(const float *p) {
    LV v;
    memcpy(&v, p, sizeof v);
    return v;
}

/* A group's attributes (stride of them, then a last row of 1 for finite, 0 for not) back to its
 * vertices; the usual strides are constants, so their copies unroll. */
static inline __attribute__((always_inline)) void
vl_store_as(const float (*res)[VL_LANES], float *out, uint8_t *ok, const int stride) {
    for (int j = 0; j < VL_LANES; j++) {
        for (int k = 0; k < stride; k++) out[j * stride + k] = res[k][j];
        if (res[stride][j] == 0.0f) ok[j] = 0;
    }
}

static inline __attribute__((always_inline)) void vl_store(const float (*res)[VL_LANES], float *out,
                                                           uint8_t *ok, int stride) {
    if (stride == SG_LIT_SEC)
        vl_store_as(res, out, ok, SG_LIT_SEC);
    else if (stride == SG_LIT_ST)
        vl_store_as(res, out, ok, SG_LIT_ST);
    else if (stride == SG_LIT_SEC + 3)
        vl_store_as(res, out, ok, SG_LIT_SEC + 3);
    else
        vl_store_as(res, out, ok, stride);
}

/* The vertices [first, first + n VL_LANES) of [first, first + count) into out (stride floats
 * each), VL_LANES at a time; returns how many (the scalar path does the rest). */
static inline __attribute__((always_inline)) int vl_gouraud(const sg_vertex_lit *l, int first,
                                                            int count, float *out, uint8_t *ok) {
    enum { W = VL_LANES };
    const float *m = l->world_view, *nm = l->normal_matrix;
    const int stride = l->stride, end = first + count / W * W;
    for (int i0 = first; i0 < end; i0 += W) {
        /* The inputs, one array a component (lane j: vertex i0 + j). */
        float pos[4][W], nrm[3][W], col[4][W], st[2][W];
        const float *ps = l->positions + (size_t)i0 * 4, *ns = l->normals + (size_t)i0 * 3;
        for (int j = 0; j < W; j++)
            for (int k = 0; k < 4; k++) pos[k][j] = ps[j * 4 + k];
        for (int j = 0; j < W; j++)
            for (int k = 0; k < 3; k++) nrm[k][j] = ns[j * 3 + k];
        LV x[4], v[4], P[3], n[3], src[3], base[4];
        if (l->colors) {
            const float *cs = l->colors + (size_t)i0 * 4;
            for (int j = 0; j < W; j++)
                for (int k = 0; k < 4; k++) col[k][j] = cs[j * 4 + k];
            for (int k = 0; k < 4; k++) base[k] = vl_load(col[k]);
        } else {
            for (int k = 0; k < 4; k++) base[k] = lv_set1(1.0f);
        }
        for (int k = 0; k < 4; k++) {
            x[k] = vl_load(pos[k]);
            if (l->tint) base[k] = lv_mul(base[k], lv_set1(l->tint[k]));
        }
        for (int r = 0; r < 4; r++) /* sg_mat4_transform */
            v[r] = lv_add(
                lv_add(lv_add(lv_mul(lv_set1(m[r * 4]), x[0]), lv_mul(lv_set1(m[r * 4 + 1]), x[1])),
                       lv_mul(lv_set1(m[r * 4 + 2]), x[2])),
                lv_mul(lv_set1(m[r * 4 + 3]), x[3]));
        const LM w1 = lm_and(lm_ge(v[3], lv_set1(1.0f)), lm_le(v[3], lv_set1(1.0f)));
        for (int k = 0; k < 3; k++) P[k] = lv_sel(w1, v[k], lv_div(v[k], v[3]));
        for (int k = 0; k < 3; k++) src[k] = vl_load(nrm[k]);
        for (int r = 0; r < 3; r++)
            n[r] = lv_add(
                lv_add(lv_mul(lv_set1(nm[r * 3]), src[0]), lv_mul(lv_set1(nm[r * 3 + 1]), src[1])),
                lv_mul(lv_set1(nm[r * 3 + 2]), src[2]));
        /* The attributes in the order of light.h's SG_LIT_*, at most SG_LIT_SPLIT_END. */
        LV a[SG_LIT_SPLIT_END];
        if (l->texcoords) {
            const float *ts = l->texcoords + (size_t)i0 * 2;
            for (int j = 0; j < W; j++)
                for (int k = 0; k < 2; k++) st[k][j] = ts[j * 2 + k];
            a[SG_LIT_ST] = vl_load(st[0]);
            a[SG_LIT_ST + 1] = vl_load(st[1]);
        } else {
            a[SG_LIT_ST] = a[SG_LIT_ST + 1] = lv_set1(0.0f);
        }
        if (l->split) {
            lv_light_eval_split(l->lights, P, n, base, l->split - 1, a + SG_LIT_COLOR,
                                a + SG_LIT_SPLIT_D, a + SG_LIT_SPLIT_SEC, a + SG_LIT_SPLIT_S);
            for (int k = 0; k < 3; k++) a[SG_LIT_POS + k] = P[k];
        } else {
            lv_light_eval(l->lights, P, n, base, -1, lv_set1(1.0f), a + SG_LIT_COLOR,
                          a + SG_LIT_SEC);
        }
        /* finite: neither NaN nor infinite, in every attribute the vertex stores */
        LM finite = lm_and(lm_le(a[0], lv_set1(FLT_MAX)), lm_ge(a[0], lv_set1(-FLT_MAX)));
        for (int k = 1; k < stride; k++)
            finite = lm_and(finite,
                            lm_and(lm_le(a[k], lv_set1(FLT_MAX)), lm_ge(a[k], lv_set1(-FLT_MAX))));
        float res[SG_LIT_SPLIT_END + 1][W];
        for (int k = 0; k < stride; k++) memcpy(res[k], &a[k], sizeof a[k]);
        LV fin = lv_sel(finite, lv_set1(1.0f), lv_set1(0.0f));
        memcpy(res[stride], &fin, sizeof fin);
        vl_store((const float(*)[W])res, out + (size_t)i0 * (size_t)stride, ok + i0, stride);
    }
    return end - first;
}

#endif
