/* shade_phong.c - per-pixel lighting (SG_LIGHTING_PHONG): the scalar reference and the choice of
 * variant. Per pixel: the base colour (flat, or interpolated), the view-space position and the
 * normal interpolated perspective-correct, the lighting equation of light.h (the normal
 * renormalised there), then clamp(primary x texel + secondary). The AVX2 and AVX-512 variants
 * (shade_phong_avx2.c, shade_phong_avx512.c) compute the same IEEE operations in the same order.
 */
#include "raster/framebuffer.h"
#include "raster/shade.h"

static inline __attribute__((always_inline)) void phong_rows(const sg_shade_ctx *c, const sg_tri *t,
                                                             const sg_tri_ext *ext, int x0, int y0,
                                                             uint32_t mask, uint32_t *dst,
                                                             const int textured, const int bilinear,
                                                             const int repeat, const int flat) {
    const float ox = (float)(x0 - t->minx), oy = (float)(y0 - t->miny);
    const int ep = SG_LIT_POS - SG_TRI_ATTRS, en = SG_LIT_NRM - SG_TRI_ATTRS;
    while (mask) {
        int bit = __builtin_ctz(mask);
        mask &= mask - 1;
        float dx = ox + (float)(bit & 3), dy = oy + (float)(bit >> 2);
        float w = 1.0f / (t->q + t->q_dx * dx + t->q_dy * dy);
        float base[4], P[3], n[3], prim[4], sec[3];
        for (int k = 0; k < 4; k++)
            base[k] = flat ? t->color[k] : (t->a[k] + t->a_dx[k] * dx + t->a_dy[k] * dy) * w;
        for (int k = 0; k < 3; k++) {
            P[k] = (ext->a[ep + k] + ext->a_dx[ep + k] * dx + ext->a_dy[ep + k] * dy) * w;
            n[k] = (ext->a[en + k] + ext->a_dx[en + k] * dx + ext->a_dy[en + k] * dy) * w;
        }
        sg_light_eval(&c->lights, P, n, base, prim, sec);
        if (textured) {
            float s = (t->a[4] + t->a_dx[4] * dx + t->a_dy[4] * dy) * w;
            float u = (t->a[5] + t->a_dx[5] * dx + t->a_dy[5] * dy) * w;
            sg_texel tx = bilinear ? sg_sample_bilinear(&c->tex, s, u, repeat)
                                   : sg_sample_nearest(&c->tex, s, u, repeat);
            for (int k = 0; k < 4; k++) prim[k] *= (float)tx.c[k] * (1.0f / 255.0f);
        }
        for (int k = 0; k < 3; k++) prim[k] += sec[k];
        dst[bit] = sg_pack_rgba8(sg_to_unorm8(prim[0]), sg_to_unorm8(prim[1]),
                                 sg_to_unorm8(prim[2]), sg_to_unorm8(prim[3]));
    }
}

#define SG_PHONG_VARIANT(tex, bil, rep)                                                            \
    static void phong_##tex##bil##rep(const sg_shade_ctx *c, const sg_tri *t, int x0, int y0,      \
                                      uint32_t m, uint32_t *dst) {                                 \
        const sg_tri_ext *ext = sg_shade_ext(c, t);                                                \
        if (t->flat != SG_FLAT_NONE)                                                               \
            phong_rows(c, t, ext, x0, y0, m, dst, tex, bil, rep, 1);                               \
        else                                                                                       \
            phong_rows(c, t, ext, x0, y0, m, dst, tex, bil, rep, 0);                               \
    }
SG_PHONG_VARIANT(0, 0, 0)
SG_PHONG_VARIANT(1, 0, 1)
SG_PHONG_VARIANT(1, 0, 0)
SG_PHONG_VARIANT(1, 1, 1)
SG_PHONG_VARIANT(1, 1, 0)
#undef SG_PHONG_VARIANT

sg_shade_fn sg_shade_phong_scalar(int variant) {
    static const sg_shade_fn table[SG_SHADE_VARIANTS] = {phong_000, phong_101, phong_100, phong_111,
                                                         phong_110};
    return table[variant];
}

sg_shade_fn sg_shade_phong_select(int variant, sg_isa isa) {
    sg_shade_fn fn = NULL;
    if (isa >= SG_ISA_AVX512) fn = sg_shade_phong_avx512(variant);
    if (!fn && isa >= SG_ISA_AVX2) fn = sg_shade_phong_avx2(variant);
    return fn ? fn : sg_shade_phong_scalar(variant);
}
