/* shade_phong_neon.c - per-pixel lighting and shadow-map shading in NEON (AArch64; see
 * shade_phong.c): one row of a tile a vector, the equation of light_simd.h, the texture helpers of
 * shade_neon.h; the same bytes as the scalar reference. */
#include "raster/shade_neon.h"

#if defined(SG_SHADE_NEON)

#include "raster/light_neon.h"

INLINE void phong_rows(const sg_shade_ctx *c, const sg_tri *t, const sg_tri_ext *ext, int x0,
                       int y0, uint32_t mask, uint32_t *dst, const int textured, const int bilinear,
                       const int repeat, const int flat, const int lit, const int shadow) {
    const int ep = SG_LIT_POS - SG_TRI_ATTRS, en = SG_LIT_NRM - SG_TRI_ATTRS;
    const int ed = SG_LIT_SPLIT_D - SG_TRI_ATTRS;
    const int split_spec = lit == 2 && c->lights.has_specular;
    const float ox = (float)(x0 - t->minx), oy = (float)(y0 - t->miny);
    const float32x4_t dx = row_dx(ox);
    tex4n tx;
    if (textured) tx = tex4n_of(&c->tex, bilinear);
    for (int r = 0; r < 4; r++) {
        unsigned m = (mask >> (4 * r)) & 15u;
        if (!m) continue;
        const float32x4_t dy = vdupq_n_f32(oy + (float)r);
#define SG_PLANE(a, adx, ady)                                                                      \
    vaddq_f32(vaddq_f32(vdupq_n_f32(a), vmulq_f32(vdupq_n_f32(adx), dx)),                          \
              vmulq_f32(vdupq_n_f32(ady), dy))
        const float32x4_t w = vdivq_f32(vdupq_n_f32(1.0f), SG_PLANE(t->q, t->q_dx, t->q_dy));
        float32x4_t base[4], P[3], n[3], prim[4], sec[3];
        for (int k = 0; k < 4; k++)
            base[k] = flat ? vdupq_n_f32(t->color[k])
                           : vmulq_f32(SG_PLANE(t->a[k], t->a_dx[k], t->a_dy[k]), w);
        for (int k = 0; k < 3; k++) {
            P[k] = vmulq_f32(SG_PLANE(ext->a[ep + k], ext->a_dx[ep + k], ext->a_dy[ep + k]), w);
            if (lit == 1)
                n[k] = vmulq_f32(SG_PLANE(ext->a[en + k], ext->a_dx[en + k], ext->a_dy[en + k]), w);
        }
        float32x4_t vis = vdupq_n_f32(1.0f);
        if (shadow) {
            const uint32x4_t bits = {1, 2, 4, 8};
            vis = lv_shadow_visibility(&c->shadow, P, vtstq_u32(vdupq_n_u32(m), bits));
        }
        if (lit == 1) {
            lv_light_eval(&c->lights, P, n, base, shadow ? c->shadow.light : -1, vis, prim, sec);
        } else if (lit == 2) { /* split: base is the rest of the primary colour */
            float32x4_t part[9];
            for (int k = 0; k < (split_spec ? 9 : 3); k++)
                part[k] =
                    flat ? vdupq_n_f32(ext->a[ed + k])
                         : vmulq_f32(SG_PLANE(ext->a[ed + k], ext->a_dx[ed + k], ext->a_dy[ed + k]),
                                     w);
            lv_split_combine(base, part, vis, prim);
            if (split_spec)
                for (int k = 0; k < 3; k++)
                    sec[k] = vaddq_f32(part[3 + k], vmulq_f32(vis, part[6 + k]));
        } else {
            for (int k = 0; k < 4; k++) prim[k] = base[k];
        }
        if (textured) {
            float32x4_t s = vmulq_f32(SG_PLANE(t->a[4], t->a_dx[4], t->a_dy[4]), w);
            float32x4_t u = vmulq_f32(SG_PLANE(t->a[5], t->a_dx[5], t->a_dy[5]), w);
            uint32x4_t tc[4];
            if (bilinear)
                bilinear4(&tx, s, u, repeat, tc);
            else
                unpack_texels(nearest4(&tx, s, u, repeat), tc);
            for (int k = 0; k < 4; k++)
                prim[k] =
                    vmulq_f32(prim[k], vmulq_f32(vcvtq_f32_u32(tc[k]), vdupq_n_f32(1.0f / 255.0f)));
        }
#undef SG_PLANE
        if (lit == 1 || split_spec) {
            for (int k = 0; k < 3; k++) prim[k] = vaddq_f32(prim[k], sec[k]);
        } else if (!lit) {
            const float32x4_t dim = vaddq_f32(vdupq_n_f32(0.5f), vmulq_f32(vdupq_n_f32(0.5f), vis));
            for (int k = 0; k < 3; k++) prim[k] = vmulq_f32(prim[k], dim);
        }
        store_row(dst + 4 * r, pack_unorm8(prim), m);
    }
}

#define SG_PHONG_BODY  phong_rows
#define SG_PHONG_TABLE sg_shade_phong_neon
#include "raster/shade_phong_variants.h"

#else

sg_shade_fn sg_shade_phong_neon(int index) {
    (void)index;
    return NULL;
}

#endif
