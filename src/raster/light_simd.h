/* light_simd.h - the lighting equation of light.h on vectors of pixels (Phong) or of vertices
 * (Gouraud), written once for every instruction set: light_avx2.h, light_avx512.h and light_neon.h
 * define the vector operations below for their set, then include this header. Every lane computes
 * the IEEE operations of sg_light_eval and sg_light_eval_split (and of sg_normalize3,
 * sg_log2_pos, sg_exp2_neg, sg_pow_unit) in their order; where the scalar code branches per point,
 * the vector code computes both sides and selects, which changes no lane's bits.
 *
 * Each defines:
 *   LV, LM, LI              float vector, lane mask, int32 vector
 *   lv_set1(f), li_set1(i)
 *   lv_add, lv_sub, lv_mul, lv_div, lv_sqrt, lv_floor (toward -inf), lv_neg (sign flipped)
 *   lm_gt, lm_ge, lm_le, lm_lt (ordered: false for NaN), lm_and
 *   lv_sel(m, a, b)         a where m, b elsewhere
 *   lv_bits(v), lv_of_bits(i), lv_of_int(i) (convert), li_of_float(v) (truncate)
 *   li_and, li_or, li_add, li_sub, li_mul (low 32 bits), li_srl(i, n), li_sll(i, n)
 *   lv_gather(p, i, m)      p[i] in the lanes of m (no other lane is read), 0 elsewhere
 */
#ifndef SG_LIGHT_SIMD_H
#define SG_LIGHT_SIMD_H

#include "pipeline/light.h"
#include "raster/shadow.h"

#define LS_INLINE static inline __attribute__((always_inline))

LS_INLINE LV lv_dot3(const LV a[3], const LV b[3]) {
    return lv_add(lv_add(lv_mul(a[0], b[0]), lv_mul(a[1], b[1])), lv_mul(a[2], b[2]));
}

/* sg_normalize3 */
LS_INLINE void lv_normalize3(const LV v[3], LV out[3]) {
    LV len2 = lv_dot3(v, v);
    LM ok = lm_and(lm_gt(len2, lv_set1(0.0f)), lm_le(len2, lv_set1(FLT_MAX)));
    LV inv = lv_sel(ok, lv_div(lv_set1(1.0f), lv_sqrt(len2)), lv_set1(0.0f));
    for (int k = 0; k < 3; k++) out[k] = lv_mul(v[k], inv);
}

/* sg_log2_pos, for the lanes where x is a normal positive float. */
LS_INLINE LV lv_log2_pos(LV x) {
    LI bits = lv_bits(x);
    LI e = li_sub(li_and(li_srl(bits, 23), li_set1(255)), li_set1(127));
    LV m = lv_of_bits(li_or(li_and(bits, li_set1(0x007fffff)), li_set1(0x3f800000)));
    LM big = lm_gt(m, lv_set1(1.41421356f));
    m = lv_sel(big, lv_mul(m, lv_set1(0.5f)), m);
    e = lv_bits(lv_sel(big, lv_of_bits(li_add(e, li_set1(1))), lv_of_bits(e)));
    LV t = lv_div(lv_sub(m, lv_set1(1.0f)), lv_add(m, lv_set1(1.0f))), t2 = lv_mul(t, t);
    LV p = lv_set1(1.0f / 11.0f);
    p = lv_add(lv_mul(p, t2), lv_set1(1.0f / 9.0f));
    p = lv_add(lv_mul(p, t2), lv_set1(1.0f / 7.0f));
    p = lv_add(lv_mul(p, t2), lv_set1(1.0f / 5.0f));
    p = lv_add(lv_mul(p, t2), lv_set1(1.0f / 3.0f));
    p = lv_add(lv_mul(p, t2), lv_set1(1.0f));
    return lv_add(lv_of_int(e), lv_mul(lv_mul(p, t), lv_set1(2.88539008f)));
}

/* sg_exp2_neg */
LS_INLINE LV lv_exp2_neg(LV z) {
    LM ok = lm_ge(z, lv_set1(-126.0f));
    LV n = lv_floor(lv_add(z, lv_set1(0.5f)));
    LV x = lv_mul(lv_sub(z, n), lv_set1(0.693147181f));
    LV p = lv_set1(1.0f / 5040.0f);
    p = lv_add(lv_mul(p, x), lv_set1(1.0f / 720.0f));
    p = lv_add(lv_mul(p, x), lv_set1(1.0f / 120.0f));
    p = lv_add(lv_mul(p, x), lv_set1(1.0f / 24.0f));
    p = lv_add(lv_mul(p, x), lv_set1(1.0f / 6.0f));
    p = lv_add(lv_mul(p, x), lv_set1(0.5f));
    p = lv_add(lv_mul(p, x), lv_set1(1.0f));
    p = lv_add(lv_mul(p, x), lv_set1(1.0f));
    LV scale = lv_of_bits(li_sll(li_add(li_of_float(n), li_set1(127)), 23));
    return lv_sel(ok, lv_mul(p, scale), lv_set1(0.0f));
}

/* sg_pow_unit */
LS_INLINE LV lv_pow_unit(LV x, float s) {
    if (s == 0.0f) return lv_set1(1.0f);
    LM ok = lm_ge(x, lv_set1(FLT_MIN));
    return lv_sel(ok, lv_exp2_neg(lv_mul(lv_set1(s), lv_log2_pos(x))), lv_set1(0.0f));
}

/* sg_shadow_texel, for the lanes of `ok`, whose texel index is fi, fj (integers as floats). */
LS_INLINE LV lv_shadow_texel(const sg_shadow_view *s, LV fi, LV fj, LV depth, LM ok) {
    const LV zero = lv_set1(0.0f), one = lv_set1(1.0f);
    LM in = lm_and(lm_and(ok, lm_and(lm_ge(fi, zero), lm_lt(fi, lv_set1((float)s->width)))),
                   lm_and(lm_ge(fj, zero), lm_lt(fj, lv_set1((float)s->height))));
    LI idx = li_add(li_mul(li_of_float(fj), li_set1(s->width)), li_of_float(fi));
    LV d = lv_gather(s->map, idx, in);
    return lv_sel(in, lv_sel(lm_le(depth, d), one, zero), one);
}

/* sg_shadow_visibility, for the lanes of `live` (the others: 1, and no texel read). */
LS_INLINE LV lv_shadow_visibility(const sg_shadow_view *s, const LV P[3], LM live) {
    const float *m = s->m;
    const LV half = lv_set1(0.5f), one = lv_set1(1.0f);
    LV c[4];
    for (int r = 0; r < 4; r++)
        c[r] = lv_add(
            lv_add(lv_add(lv_mul(lv_set1(m[r * 4]), P[0]), lv_mul(lv_set1(m[r * 4 + 1]), P[1])),
                   lv_mul(lv_set1(m[r * 4 + 2]), P[2])),
            lv_set1(m[r * 4 + 3]));
    const LV W = lv_set1((float)s->width), H = lv_set1((float)s->height);
    LV x = lv_mul(lv_add(lv_mul(lv_div(c[0], c[3]), half), half), W);
    LV y = lv_mul(lv_sub(half, lv_mul(lv_div(c[1], c[3]), half)), H);
    LV depth = lv_add(lv_mul(lv_div(c[2], c[3]), half), half);
    depth = lv_sel(lm_lt(depth, one), depth, one);
    if (s->pcf) {
        x = lv_sub(x, half);
        y = lv_sub(y, half);
    }
    const LV m1 = lv_set1(-1.0f);
    LM ok = lm_and(lm_and(live, lm_gt(c[3], lv_set1(0.0f))),
                   lm_and(lm_and(lm_ge(x, m1), lm_lt(x, W)), lm_and(lm_ge(y, m1), lm_lt(y, H))));
    LV fi = lv_floor(x), fj = lv_floor(y);
    if (!s->pcf) return lv_sel(ok, lv_shadow_texel(s, fi, fj, depth, ok), one);
    LV fi1 = lv_add(fi, one), fj1 = lv_add(fj, one);
    LV sum = lv_add(
        lv_add(lv_shadow_texel(s, fi, fj, depth, ok), lv_shadow_texel(s, fi1, fj, depth, ok)),
        lv_add(lv_shadow_texel(s, fi, fj1, depth, ok), lv_shadow_texel(s, fi1, fj1, depth, ok)));
    return lv_sel(ok, lv_mul(sum, lv_set1(0.25f)), one);
}

/* sg_light_vector: L and the attenuation of light i. */
LS_INLINE LV lv_light_vector(const sg_lights *ls, int i, const LV P[3], LV L[3]) {
    if (!ls->light[i].point) {
        for (int j = 0; j < 3; j++) L[j] = lv_set1(ls->light[i].v[j]);
        return lv_set1(1.0f);
    }
    const LV zero = lv_set1(0.0f);
    const float *lp = ls->light[i].v, *k = ls->light[i].att;
    LV v[3] = {lv_sub(lv_set1(lp[0]), P[0]), lv_sub(lv_set1(lp[1]), P[1]),
               lv_sub(lv_set1(lp[2]), P[2])};
    LV d2 = lv_dot3(v, v), d = lv_sqrt(d2);
    LM ok = lm_and(lm_gt(d, zero), lm_le(d, lv_set1(FLT_MAX)));
    LV inv = lv_sel(ok, lv_div(lv_set1(1.0f), d), zero);
    for (int j = 0; j < 3; j++) L[j] = lv_mul(v[j], inv);
    LV den = lv_add(lv_add(lv_set1(k[0]), lv_mul(lv_set1(k[1]), d)), lv_mul(lv_set1(k[2]), d2));
    den = lv_sel(lm_gt(den, lv_set1(FLT_MIN)), den, lv_set1(FLT_MIN));
    return lv_div(lv_set1(1.0f), den);
}

/* The diffuse and specular sums of light i with L, att (the loop body of sg_light_eval_shadowed
 * and sg_light_eval_split), in the lanes where N.L > 0. */
LS_INLINE void lv_light_add(const sg_lights *ls, int i, const LV N[3], const LV V[3], const LV L[3],
                            LV att, LV diff[3], LV spec[3]) {
    const LV zero = lv_set1(0.0f);
    const float *c = ls->light[i].color;
    LV ndotl = lv_dot3(N, L);
    LM lit = lm_gt(ndotl, zero);
    LV f = lv_mul(att, ndotl);
    for (int j = 0; j < 3; j++)
        diff[j] = lv_sel(lit, lv_add(diff[j], lv_mul(f, lv_set1(c[j]))), diff[j]);
    if (ls->has_specular) {
        LV h[3] = {lv_add(L[0], V[0]), lv_add(L[1], V[1]), lv_add(L[2], V[2])}, H[3];
        lv_normalize3(h, H);
        LV ndoth = lv_dot3(N, H);
        LV g = lv_mul(att, lv_pow_unit(lv_sel(lm_gt(ndoth, zero), ndoth, zero), ls->shininess));
        for (int j = 0; j < 3; j++)
            spec[j] = lv_sel(lit, lv_add(spec[j], lv_mul(g, lv_set1(c[j]))), spec[j]);
    }
}

/* sg_light_eval_shadowed */
LS_INLINE void lv_light_eval(const sg_lights *ls, const LV P[3], const LV n[3], const LV base[4],
                             int shadowed, LV vis, LV prim[4], LV sec[3]) {
    LV N[3], V[3], mp[3] = {lv_neg(P[0]), lv_neg(P[1]), lv_neg(P[2])};
    lv_normalize3(n, N);
    lv_normalize3(mp, V);
    const LV zero = lv_set1(0.0f);
    LV diff[3] = {zero, zero, zero}, spec[3] = {zero, zero, zero};
    for (int i = 0; i < ls->count; i++) {
        LV L[3], att = lv_light_vector(ls, i, P, L);
        if (i == shadowed) att = lv_mul(att, vis);
        lv_light_add(ls, i, N, V, L, att, diff, spec);
    }
    for (int k = 0; k < 3; k++) {
        const LV big = lv_set1(FLT_MAX);
        diff[k] = lv_sel(lm_gt(big, diff[k]), diff[k], big);
        spec[k] = lv_sel(lm_gt(big, spec[k]), spec[k], big);
        LV v = lv_add(lv_mul(base[k], lv_set1(ls->ambient[k])), lv_mul(base[k], diff[k]));
        prim[k] = lv_sel(lm_gt(v, zero), lv_sel(lm_gt(lv_set1(1.0f), v), v, lv_set1(1.0f)), zero);
        sec[k] = lv_mul(spec[k], lv_set1(ls->specular[k]));
    }
    prim[3] = base[3];
}

/* sg_split_bound */
LS_INLINE LV lv_split_bound(LV v) {
    const LV hi = lv_set1(SG_LIT_SPLIT_MAX), lo = lv_set1(-SG_LIT_SPLIT_MAX);
    v = lv_sel(lm_lt(v, hi), v, hi);
    return lv_sel(lm_gt(v, lo), v, lo);
}

/* sg_light_eval_split */
LS_INLINE void lv_light_eval_split(const sg_lights *ls, const LV P[3], const LV n[3],
                                   const LV base[4], int shadowed, LV rest[4], LV light[3],
                                   LV rest_sec[3], LV light_sec[3]) {
    LV N[3], V[3], mp[3] = {lv_neg(P[0]), lv_neg(P[1]), lv_neg(P[2])};
    lv_normalize3(n, N);
    lv_normalize3(mp, V);
    const LV zero = lv_set1(0.0f);
    LV diff[2][3] = {{zero, zero, zero}, {zero, zero, zero}};
    LV spec[2][3] = {{zero, zero, zero}, {zero, zero, zero}};
    for (int i = 0; i < ls->count; i++) {
        LV L[3], att = lv_light_vector(ls, i, P, L);
        const int j = i == shadowed;
        lv_light_add(ls, i, N, V, L, att, diff[j], spec[j]);
    }
    for (int k = 0; k < 3; k++) {
        const LV big = lv_set1(FLT_MAX);
        for (int j = 0; j < 2; j++) {
            diff[j][k] = lv_sel(lm_gt(big, diff[j][k]), diff[j][k], big);
            spec[j][k] = lv_sel(lm_gt(big, spec[j][k]), spec[j][k], big);
        }
        rest[k] = lv_split_bound(
            lv_add(lv_mul(base[k], lv_set1(ls->ambient[k])), lv_mul(base[k], diff[0][k])));
        light[k] = lv_split_bound(lv_mul(base[k], diff[1][k]));
        rest_sec[k] = lv_split_bound(lv_mul(spec[0][k], lv_set1(ls->specular[k])));
        light_sec[k] = lv_split_bound(lv_mul(spec[1][k], lv_set1(ls->specular[k])));
    }
    rest[3] = base[3];
}

/* sg_light_split_combine */
LS_INLINE void lv_split_combine(const LV rest[4], const LV light[3], LV vis, LV prim[4]) {
    const LV zero = lv_set1(0.0f), one = lv_set1(1.0f);
    for (int k = 0; k < 3; k++) {
        LV v = lv_add(rest[k], lv_mul(vis, light[k]));
        prim[k] = lv_sel(lm_gt(v, zero), lv_sel(lm_gt(one, v), v, one), zero);
    }
    prim[3] = rest[3];
}

#undef LS_INLINE
#endif
