/* shade_mip.c - the fixed textured shading of mipmapped pipelines (SG_SHADE_TEXTURE_MODULATE with
 * sgPipelineDesc.mipmap NEAREST or LINEAR), unlit or lit flat or Gouraud, opaque or blended.
 *
 * A pipeline without mipmaps never runs this file: its shading keeps the functions of shade.c and
 * its SIMD twins. Here the level of detail needs each 2 x 2 quad's texture coordinates at all four
 * pixels, covered or not (a GPU's helper pixels), so a tile's 16 coordinates are made first, from
 * the same planes and in the same IEEE operations as shade.c, then each quad's levels from their
 * differences (tex/mip.h), then the 16 lookups at once (tex/sample16.c), and the covered pixels
 * are coloured as shade.c colours them. This portable body is the reference; AVX-512 and AVX2 have
 * their own copies of these steps in their shading (shade_avx512.h, shade_avx2.h, the same bytes).
 */
#include "raster/shade.h"

#include "raster/framebuffer.h"
#include "tex/lanes.h"
#include "tex/mip.h"
#include "tex/sample16.h"

static inline __attribute__((always_inline)) void
shade_mip(const sg_shade_ctx *c, const sg_tri *t, int x0, int y0, uint32_t mask, uint32_t *dst,
          const int linear, const int bilinear, const int repeat, const int sec) {
    const sg_tri_ext *ext = sec ? sg_shade_ext(c, t) : NULL;
    const sg_mip_chain *m = c->mips;
    const float ox = (float)(x0 - t->minx), oy = (float)(y0 - t->miny);
    const int e = SG_LIT_SEC - SG_TRI_ATTRS; /* the secondary colour in ext */
    const int flat = t->flat;
    float s[SG_SHADER_LANES], u[SG_SHADER_LANES], w[SG_SHADER_LANES];
    for (int i = 0; i < SG_SHADER_LANES; i++) {
        const float dx = ox + (float)(i & 3), dy = oy + (float)(i >> 2);
        w[i] = 1.0f / (t->q + t->q_dx * dx + t->q_dy * dy);
        s[i] = (t->a[4] + t->a_dx[4] * dx + t->a_dy[4] * dy) * w[i];
        u[i] = (t->a[5] + t->a_dx[5] * dx + t->a_dy[5] * dy) * w[i];
    }
    /* Quad q's pixels are bits base, base + 1, base + 4, base + 5 of the tile; a quad without a
     * covered pixel takes a covered one's levels, so that it adds no level to read. */
    sg_mip_pick pick[4];
    int covered = -1;
    for (int q = 0; q < 4; q++) {
        const int base = (q & 1) * 2 + (q >> 1) * 8;
        if (!(mask & (0x33u << base))) continue;
        pick[q] = sg_mip_select(m, s[base + 1] - s[base], u[base + 1] - u[base],
                                s[base + 4] - s[base], u[base + 4] - u[base], linear);
        covered = q;
    }
    if (covered < 0) return;
    for (int q = 0; q < 4; q++)
        if (!(mask & (0x33u << ((q & 1) * 2 + (q >> 1) * 8)))) pick[q] = pick[covered];
    int32_t tx[4][SG_SHADER_LANES];
    sg_sample16_mip_portable(m, pick, bilinear, repeat, false, s, u, tx);
    /* The colours of all 16 lanes on vectors, each step as shade.c takes it, then the covered
     * pixels written. */
    typedef uint32_t sg_vu __attribute__((vector_size(4 * SG_SHADER_LANES)));
    sg_vi texel[4];
    sg_vu px;
    for (int k = 0; k < 4; k++) memcpy(&texel[k], tx[k], sizeof texel[k]);
    if (flat == SG_FLAT_WHITE && !sec) { /* 1 * texel / 255, back to unorm8: the texel */
        px = (sg_vu)texel[0] | (sg_vu)texel[1] << 8 | (sg_vu)texel[2] << 16 | (sg_vu)texel[3] << 24;
    } else {
        const sg_vf zero = {0}, lane = {0, 1, 2, 3, 0, 1, 2, 3, 0, 1, 2, 3, 0, 1, 2, 3},
                    row = {0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2, 3, 3, 3, 3};
        const sg_vf dx = ox + lane, dy = oy + row;
        sg_vf wv;
        memcpy(&wv, w, sizeof wv);
        sg_vi ch[4];
        for (int k = 0; k < 4; k++) {
            sg_vf col = flat != SG_FLAT_NONE ? zero + t->color[k]
                                             : (t->a[k] + t->a_dx[k] * dx + t->a_dy[k] * dy) * wv;
            col *= __builtin_convertvector(texel[k], sg_vf) * (1.0f / 255.0f);
            if (sec && k < 3)
                col += flat != SG_FLAT_NONE
                           ? zero + ext->a[e + k]
                           : (ext->a[e + k] + ext->a_dx[e + k] * dx + ext->a_dy[e + k] * dy) * wv;
            /* sg_to_unorm8: NaN and 0 or less give 0, 1 or more 255 (limited first, so that
             * every lane converts in range) */
            col = SEL(col > 0.0f, col, zero);
            col = SEL(col >= 1.0f, zero + 1.0f, col);
            ch[k] = __builtin_convertvector(col * 255.0f + 0.5f, sg_vi);
        }
        px = (sg_vu)ch[0] | (sg_vu)ch[1] << 8 | (sg_vu)ch[2] << 16 | (sg_vu)ch[3] << 24;
    }
    if ((mask & 0xffffu) == 0xffffu) { /* one store (lane by lane, each waits for the vector) */
        memcpy(dst, &px, sizeof px);
        return;
    }
    _Alignas(64) uint32_t out[SG_SHADER_LANES];
    memcpy(out, &px, sizeof out);
    for (uint32_t left = mask & 0xffffu; left; left &= left - 1) {
        const int bit = __builtin_ctz(left);
        dst[bit] = out[bit];
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

static const sg_shade_fn mip_table[16] = {
    mip_0000, mip_0001, mip_0010, mip_0011, mip_0100, mip_0101, mip_0110, mip_0111,
    mip_1000, mip_1001, mip_1010, mip_1011, mip_1100, mip_1101, mip_1110, mip_1111};

static int mip_index(sgMipmap mipmap, sgFilter filter, sgWrap wrap, bool sec) {
    return (mipmap == SG_MIPMAP_LINEAR) * 8 + (filter == SG_FILTER_BILINEAR) * 4 +
           (wrap == SG_WRAP_REPEAT) * 2 + (int)sec;
}

sg_shade_fn sg_shade_mip_portable(int index) {
    return mip_table[index];
}

/* The instruction set's own function of table kind (shade, shade2, shade_runs) at index i, NULL
 * where it has none. */
#define SG_MIP_SIMD(kind, isa, i)                                                                  \
    ((isa) == SG_ISA_AVX512 ? sg_##kind##_mip_avx512(i)                                            \
     : (isa) == SG_ISA_AVX2 ? sg_##kind##_mip_avx2(i)                                              \
                            : NULL)

sg_shade_fn sg_shade_mip_select(sgMipmap mipmap, sgFilter filter, sgWrap wrap, bool sec,
                                sg_isa isa) {
    const int i = mip_index(mipmap, filter, wrap, sec);
    const sg_shade_fn fn = SG_MIP_SIMD(shade, isa, i);
    return fn ? fn : mip_table[i];
}

sg_shade2_fn sg_shade2_mip_select(sgMipmap mipmap, sgFilter filter, sgWrap wrap, bool sec,
                                  sg_isa isa) {
    return SG_MIP_SIMD(shade2, isa, mip_index(mipmap, filter, wrap, sec));
}

sg_shade_runs_fn sg_shade_runs_mip_select(sgMipmap mipmap, sgFilter filter, sgWrap wrap, bool sec,
                                          sg_isa isa) {
    return SG_MIP_SIMD(shade_runs, isa, mip_index(mipmap, filter, wrap, sec));
}
