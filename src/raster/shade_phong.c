/* shade_phong.c - shading from each pixel's view-space position: per-pixel lighting
 * (SG_LIGHTING_PHONG), with or without a shadow map, and unlit shading that receives a shadow map;
 * the scalar reference and the choice of variant. Per pixel: the base colour (flat, or
 * interpolated), the view-space position (and the normal, lit) interpolated perspective-correct;
 * the shadow map's visibility there (shadow.h); the lighting equation of light.h (the normal
 * renormalised there, the shadowing light attenuated by the visibility) or, unlit, the base
 * colour; times the texel; then + secondary (lit), or rgb x (1/2 + visibility / 2) (unlit).
 * Flat and Gouraud draws receiving a shadow map (lit = 2) interpolate the split colours of light.h
 * instead of a normal (constant on a flat triangle) and combine them with the visibility. The
 * AVX2 and AVX-512 variants (shade_phong_avx2.c, shade_phong_avx512.c) compute the same IEEE
 * operations in the same order.
 */
#include "raster/framebuffer.h"
#include "raster/shade.h"

#include <string.h>

static inline __attribute__((always_inline)) void
phong_rows(const sg_shade_ctx *c, const sg_tri *t, const sg_tri_ext *ext, int x0, int y0,
           uint32_t mask, uint32_t *dst, const int textured, const int bilinear, const int repeat,
           const int flat, const int lit, const int shadow) {
    const float ox = (float)(x0 - t->minx), oy = (float)(y0 - t->miny);
    const int ep = SG_LIT_POS - SG_TRI_ATTRS, en = SG_LIT_NRM - SG_TRI_ATTRS;
    const int ed = SG_LIT_SPLIT_D - SG_TRI_ATTRS;
    const int split_spec = lit == 2 && c->lights.has_specular;
    while (mask) {
        int bit = __builtin_ctz(mask);
        mask &= mask - 1;
        float dx = ox + (float)(bit & 3), dy = oy + (float)(bit >> 2);
        float w = 1.0f / (t->q + t->q_dx * dx + t->q_dy * dy);
        float base[4], P[3], n[3], prim[4], sec[3] = {0.0f, 0.0f, 0.0f};
        for (int k = 0; k < 4; k++)
            base[k] = flat ? t->color[k] : (t->a[k] + t->a_dx[k] * dx + t->a_dy[k] * dy) * w;
        for (int k = 0; k < 3; k++) {
            P[k] = (ext->a[ep + k] + ext->a_dx[ep + k] * dx + ext->a_dy[ep + k] * dy) * w;
            if (lit == 1)
                n[k] = (ext->a[en + k] + ext->a_dx[en + k] * dx + ext->a_dy[en + k] * dy) * w;
        }
        const float vis = shadow ? sg_shadow_visibility(&c->shadow, P) : 1.0f;
        if (lit == 1) {
            sg_light_eval_shadowed(&c->lights, P, n, base, shadow ? c->shadow.light : -1, vis, prim,
                                   sec);
        } else if (lit == 2) { /* split: base is the rest of the primary colour */
            float part[9];     /* the light's diffuse part, the rest and the light's secondary */
            for (int k = 0; k < (split_spec ? 9 : 3); k++)
                part[k] =
                    flat ? ext->a[ed + k]
                         : (ext->a[ed + k] + ext->a_dx[ed + k] * dx + ext->a_dy[ed + k] * dy) * w;
            sg_light_split_combine(base, part, vis, prim);
            if (split_spec)
                for (int k = 0; k < 3; k++) sec[k] = part[3 + k] + vis * part[6 + k];
        } else {
            memcpy(prim, base, sizeof prim);
        }
        if (textured) {
            float s = (t->a[4] + t->a_dx[4] * dx + t->a_dy[4] * dy) * w;
            float u = (t->a[5] + t->a_dx[5] * dx + t->a_dy[5] * dy) * w;
            sg_texel tx = bilinear ? sg_sample_bilinear(&c->tex, s, u, repeat)
                                   : sg_sample_nearest(&c->tex, s, u, repeat);
            for (int k = 0; k < 4; k++) prim[k] *= (float)tx.c[k] * (1.0f / 255.0f);
        }
        if (lit == 1 || split_spec) {
            for (int k = 0; k < 3; k++) prim[k] += sec[k];
        } else if (!lit) {
            const float dim = 0.5f + 0.5f * vis;
            for (int k = 0; k < 3; k++) prim[k] *= dim;
        }
        dst[bit] = sg_pack_rgba8(sg_to_unorm8(prim[0]), sg_to_unorm8(prim[1]),
                                 sg_to_unorm8(prim[2]), sg_to_unorm8(prim[3]));
    }
}

#define SG_PHONG_BODY  phong_rows
#define SG_PHONG_TABLE sg_shade_phong_scalar
#include "raster/shade_phong_variants.h"

sg_shade_fn sg_shade_phong_select(int index, sg_isa isa) {
    sg_shade_fn fn = NULL;
    if (isa == SG_ISA_NEON) fn = sg_shade_phong_neon(index);
    if (fn || isa == SG_ISA_NEON) return fn ? fn : sg_shade_phong_scalar(index);
    if (isa >= SG_ISA_AVX512) fn = sg_shade_phong_avx512(index);
    if (!fn && isa >= SG_ISA_AVX2) fn = sg_shade_phong_avx2(index);
    return fn ? fn : sg_shade_phong_scalar(index);
}
