/* shade_mip.c - the fixed textured shading of mipmapped pipelines (SG_SHADE_TEXTURE_MODULATE with
 * sgPipelineDesc.mipmap NEAREST or LINEAR), unlit or lit flat or Gouraud, opaque or blended.
 *
 * A pipeline without mipmaps never runs this file: its shading keeps the functions of shade.c and
 * its SIMD twins. Here the level of detail needs each 2 x 2 quad's texture coordinates at all four
 * pixels, covered or not (a GPU's helper pixels), so a tile is shaded quad by quad: the four
 * coordinates from the same planes and in the same IEEE operations as shade.c, the quad's levels
 * from their differences (tex/mip.h), then the covered pixels sampled and coloured as shade.c
 * colours them. One portable body serves every instruction set, so all give the same bytes.
 */
#include "raster/shade.h"

#include "raster/framebuffer.h"
#include "tex/mip.h"

static inline __attribute__((always_inline)) void
shade_mip(const sg_shade_ctx *c, const sg_tri *t, int x0, int y0, uint32_t mask, uint32_t *dst,
          const int linear, const int bilinear, const int repeat, const int sec) {
    const sg_tri_ext *ext = sec ? sg_shade_ext(c, t) : NULL;
    const sg_mip_chain *m = c->mips;
    const float ox = (float)(x0 - t->minx), oy = (float)(y0 - t->miny);
    const int e = SG_LIT_SEC - SG_TRI_ATTRS; /* the secondary colour in ext */
    const int flat = t->flat;
    for (int q = 0; q < 4; q++) {
        /* Quad q's pixels are bits base, base + 1, base + 4, base + 5 of the tile. */
        const int base = (q & 1) * 2 + (q >> 1) * 8;
        const uint32_t qmask = mask & (0x33u << base);
        if (!qmask) continue;
        float s[4], u[4], w[4];
        for (int i = 0; i < 4; i++) {
            const int bit = base + (i & 1) + (i >> 1) * 4;
            const float dx = ox + (float)(bit & 3), dy = oy + (float)(bit >> 2);
            w[i] = 1.0f / (t->q + t->q_dx * dx + t->q_dy * dy);
            s[i] = (t->a[4] + t->a_dx[4] * dx + t->a_dy[4] * dy) * w[i];
            u[i] = (t->a[5] + t->a_dx[5] * dx + t->a_dy[5] * dy) * w[i];
        }
        const sg_mip_pick p =
            sg_mip_select(m, s[1] - s[0], u[1] - u[0], s[2] - s[0], u[2] - u[0], linear);
        for (int i = 0; i < 4; i++) {
            const int bit = base + (i & 1) + (i >> 1) * 4;
            if (!(qmask >> bit & 1)) continue;
            const float dx = ox + (float)(bit & 3), dy = oy + (float)(bit >> 2);
            const sg_texel tx = sg_sample_mip(m, p, s[i], u[i], bilinear, repeat);
            if (flat == SG_FLAT_WHITE && !sec) { /* 1 * texel / 255, back to unorm8: the texel */
                dst[bit] = sg_pack_rgba8((uint32_t)tx.c[0], (uint32_t)tx.c[1], (uint32_t)tx.c[2],
                                         (uint32_t)tx.c[3]);
                continue;
            }
            float col[4];
            for (int k = 0; k < 4; k++)
                col[k] = flat != SG_FLAT_NONE
                             ? t->color[k]
                             : (t->a[k] + t->a_dx[k] * dx + t->a_dy[k] * dy) * w[i];
            for (int k = 0; k < 4; k++) col[k] *= (float)tx.c[k] * (1.0f / 255.0f);
            if (sec)
                for (int k = 0; k < 3; k++)
                    col[k] +=
                        flat != SG_FLAT_NONE
                            ? ext->a[e + k]
                            : (ext->a[e + k] + ext->a_dx[e + k] * dx + ext->a_dy[e + k] * dy) *
                                  w[i];
            dst[bit] = sg_pack_rgba8(sg_to_unorm8(col[0]), sg_to_unorm8(col[1]),
                                     sg_to_unorm8(col[2]), sg_to_unorm8(col[3]));
        }
    }
}

#define SG_MIP_VARIANT(lin, bil, rep, sec)                                                         \
    static void mip_##lin##bil##rep##sec(const sg_shade_ctx *c, const sg_tri *t, int x0, int y0,   \
                                         uint32_t m, uint32_t *dst) {                              \
        shade_mip(c, t, x0, y0, m, dst, lin, bil, rep, sec);                                       \
    }
SG_MIP_VARIANT(0, 0, 0, 0)
SG_MIP_VARIANT(0, 0, 0, 1)
SG_MIP_VARIANT(0, 0, 1, 0)
SG_MIP_VARIANT(0, 0, 1, 1)
SG_MIP_VARIANT(0, 1, 0, 0)
SG_MIP_VARIANT(0, 1, 0, 1)
SG_MIP_VARIANT(0, 1, 1, 0)
SG_MIP_VARIANT(0, 1, 1, 1)
SG_MIP_VARIANT(1, 0, 0, 0)
SG_MIP_VARIANT(1, 0, 0, 1)
SG_MIP_VARIANT(1, 0, 1, 0)
SG_MIP_VARIANT(1, 0, 1, 1)
SG_MIP_VARIANT(1, 1, 0, 0)
SG_MIP_VARIANT(1, 1, 0, 1)
SG_MIP_VARIANT(1, 1, 1, 0)
SG_MIP_VARIANT(1, 1, 1, 1)
#undef SG_MIP_VARIANT

sg_shade_fn sg_shade_mip_select(sgMipmap mipmap, sgFilter filter, sgWrap wrap, bool sec) {
    static const sg_shade_fn table[16] = {
        mip_0000, mip_0001, mip_0010, mip_0011, mip_0100, mip_0101, mip_0110, mip_0111,
        mip_1000, mip_1001, mip_1010, mip_1011, mip_1100, mip_1101, mip_1110, mip_1111};
    const int i = (mipmap == SG_MIPMAP_LINEAR) * 8 + (filter == SG_FILTER_BILINEAR) * 4 +
                  (wrap == SG_WRAP_REPEAT) * 2 + (int)sec;
    return table[i];
}
