/* shade_neon.c - the shading functions of shade.h in NEON (AArch64), made of the helpers of
 * shade_neon.h. A tile is shaded one row of four pixels at a time, a pixel per lane and a vector
 * per channel: 1/q, the colours, the texture coordinates and the secondary colour are the scalar
 * reference's float operations (shade.c, sample.h) in the same order, so the bytes are the same.
 * Off AArch64 every variant is NULL.
 */
#include "raster/shade_neon.h"

#if defined(SG_SHADE_NEON)

/* The body of every variant, as shade_rows in shade.c; the constant arguments fold away. */
INLINE void shade_rows(const sg_shade_ctx *c, const sg_tri *t, const sg_tri_ext *ext, int x0,
                       int y0, uint32_t mask, uint32_t *dst, const int textured, const int bilinear,
                       const int repeat, const int flat, const int sec) {
    const int e = SG_LIT_SEC - SG_TRI_ATTRS; /* the secondary colour in ext */
    if (!textured && flat != SG_FLAT_NONE) { /* one colour, converted once */
        uint32_t px = sg_flat_pixel(t, ext, sec);
        for (int r = 0; r < 4; r++) {
            unsigned m = (mask >> (4 * r)) & 15u;
            if (m) store_row(dst + 4 * r, vdupq_n_u32(px), m);
        }
        return;
    }
    const float ox = (float)(x0 - t->minx), oy = (float)(y0 - t->miny);
    const float32x4_t dx = row_dx(ox);
    /* Everything but the a_dy * dy terms is the same on every row: q + q_dx dx and a + a_dx dx. */
    const float32x4_t qx = vaddq_f32(vdupq_n_f32(t->q), vmulq_f32(vdupq_n_f32(t->q_dx), dx));
    const int nattr = textured ? 6 : 4;
    float32x4_t ax[6];
    for (int k = 0; k < nattr; k++) {
        if (k < 4 && flat != SG_FLAT_NONE)
            ax[k] = vdupq_n_f32(t->color[k]);
        else
            ax[k] = vaddq_f32(vdupq_n_f32(t->a[k]), vmulq_f32(vdupq_n_f32(t->a_dx[k]), dx));
    }
    float32x4_t sx[3]; /* the secondary colour's a + a_dx dx, or the flat colour */
    for (int k = 0; sec && k < 3; k++)
        sx[k] = flat != SG_FLAT_NONE ? vdupq_n_f32(ext->a[e + k])
                                     : vaddq_f32(vdupq_n_f32(ext->a[e + k]),
                                                 vmulq_f32(vdupq_n_f32(ext->a_dx[e + k]), dx));
    tex4n tx;
    if (textured) tx = tex4n_of(&c->tex, bilinear);
    for (int r = 0; r < 4; r++) {
        unsigned m = (mask >> (4 * r)) & 15u;
        if (!m) continue;
        const float dy = oy + (float)r;
        const float32x4_t w =
            vdivq_f32(vdupq_n_f32(1.0f), vaddq_f32(qx, vdupq_n_f32(t->q_dy * dy)));
        float32x4_t col[4];
        for (int k = 0; k < 4; k++)
            col[k] = flat != SG_FLAT_NONE
                         ? ax[k]
                         : vmulq_f32(vaddq_f32(ax[k], vdupq_n_f32(t->a_dy[k] * dy)), w);
        if (textured) {
            float32x4_t s = vmulq_f32(vaddq_f32(ax[4], vdupq_n_f32(t->a_dy[4] * dy)), w);
            float32x4_t u = vmulq_f32(vaddq_f32(ax[5], vdupq_n_f32(t->a_dy[5] * dy)), w);
            uint32x4_t tc[4];
            if (bilinear) {
                bilinear4(&tx, s, u, repeat, tc);
                if (flat == SG_FLAT_WHITE && !sec) { /* the texel is the colour */
                    store_row(dst + 4 * r, pack4(tc), m);
                    continue;
                }
            } else {
                uint32x4_t texel = nearest4(&tx, s, u, repeat);
                if (flat == SG_FLAT_WHITE && !sec) {
                    store_row(dst + 4 * r, texel, m);
                    continue;
                }
                unpack_texels(texel, tc);
            }
            for (int k = 0; k < 4; k++)
                col[k] =
                    vmulq_f32(col[k], vmulq_f32(vcvtq_f32_u32(tc[k]), vdupq_n_f32(1.0f / 255.0f)));
        }
        for (int k = 0; sec && k < 3; k++)
            col[k] = vaddq_f32(
                col[k], flat != SG_FLAT_NONE
                            ? sx[k]
                            : vmulq_f32(vaddq_f32(sx[k], vdupq_n_f32(ext->a_dy[e + k] * dy)), w));
        store_row(dst + 4 * r, pack_unorm8(col), m);
    }
}

#define SG_SHADE_TABLE sg_shade_neon
#include "raster/shade_variants.h"

#else

sg_shade_fn sg_shade_neon(int index) {
    (void)index;
    return NULL;
}

#endif
