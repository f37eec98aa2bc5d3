/* shade.h - per-pixel colour of a covered tile: perspective-correct interpolation, texturing and
 * the conversion to RGBA8.
 *
 * Shading runs after visibility (depth.c) has decided, for every pixel of a screen bin, which
 * triangle is seen there, so each pixel is shaded once whatever the overdraw. One function is
 * compiled for each combination of state that changes the inner loop (vertex colour, or texture
 * with its filter and wrap), and for each instruction set (portable scalar, SSE2, AVX2, AVX-512,
 * NEON); a
 * pipeline picks its function once, at creation, so a vertex-colour draw never runs texture code.
 * Every instruction set computes the same IEEE operations in the same order, so all give the same
 * bytes as the scalar reference.
 */
#ifndef SG_SHADE_H
#define SG_SHADE_H

#include <stdbool.h>
#include <stdint.h>

#include "pipeline/light.h"
#include "pipeline/setup.h"
#include "raster/framebuffer.h"
#include "raster/shadow.h"
#include "sgapi/sgapi.h"
#include "tex/sample.h"
#include "tex/sample16.h"

/* A texture a shader draw binds (sgSample): RGBA8 texels, or a depth image's floats. */
typedef struct sg_shader_tex {
    const uint8_t *data; /* NULL: not bound */
    int width, height;
    bool depth;
    const sg_mip_chain *mips; /* its levels (RGBA8) */
    /* sgSample's lookup of level 0 made for the draw's filter and wrap, when there is one
     * (sg_sample16_unit_fn_of), else NULL. */
    sg_sample16_unit_fn unit;
} sg_shader_tex;

/* What a shader draw's fragment stage needs (shade_shader.c). */
typedef struct sg_shader_state {
    void (*fragment)(sgFragmentBatch *b, const void *uniforms); /* NULL: not a shader draw */
    const void *uniforms;  /* the draw's copy, set when the pass renders its bins (pass.c) */
    size_t uniform_offset; /* where that copy is in the device's uniform arena (SIZE_MAX: none) */
    int varying_count;
    bool konst; /* the stage reads its varyings alone: triangles may be shaded once (sg_tri) */
    bool bilinear, repeat;
    int sample16;    /* the copy of the 16-lane lookups sgSample takes (SG_SAMPLE16_*) */
    sgMipmap mipmap; /* the pipeline's, resolved (NONE, NEAREST or LINEAR) */
    sg_shader_tex textures[SG_MAX_DRAW_TEXTURES];
    uint32_t pso; /* the pipeline's handle: told when the draw discards (pass.c) */
    /* Set, atomically, by the bins when a fragment of the draw was discarded; and the pass's
     * count of such tiles, which tells a bin shaded visibility first that it must be redone. */
    int discarded;
    int *pass_discards;
} sg_shader_state;

typedef struct sg_shade_ctx {
    sg_texview tex;           /* bound texture, when the pipeline samples one */
    const sg_mip_chain *mips; /* its levels, when the pipeline is mipmapped (shade_mip.c) */
    sg_lights lights;         /* the draw's lights and material (SG_LIGHTING_PHONG) */
    sg_shadow_view shadow;    /* the shadow map the draw receives (shadow.h) */
    /* The pass's triangles and their extensions (NULL when it has none), set when the pass
     * ends: a lit triangle t's attributes beyond SG_TRI_ATTRS are at ext + (t - tris). */
    const sg_tri *tris;
    const sg_tri_ext *ext;
    sg_shader_state shader; /* shader pipelines (sgShaderDesc) */
    /* The AVX-512 lookups of mipmapped textures and of sgSample try the 8 x 8 texel window (row
     * loads and permutes) before gathering: the device's choice, sg_texel_window_detect. The
     * fixed shading without mipmaps and the AVX2 lookups always try theirs. Same texels. */
    bool texel_window;
} sg_shade_ctx;

/** The extension of triangle t (NULL when the pass has none). */
static inline const sg_tri_ext *sg_shade_ext(const sg_shade_ctx *c, const sg_tri *t) {
    return c->ext ? c->ext + (t - c->tris) : NULL;
}

/* Instruction sets with their own shading and visibility code. */
typedef enum sg_isa {
    SG_ISA_SCALAR,
    SG_ISA_SSE2,
    SG_ISA_AVX2,
    SG_ISA_AVX512, /* AVX-512 F, BW, VL and DQ */
    SG_ISA_NEON,   /* AArch64 Advanced SIMD: not above the x86 sets, beside them */
    SG_ISA_COUNT
} sg_isa;

/* Shades the pixels of `mask` (bit y * 4 + x) of the 4x4 tile whose top-left pixel is (x0, y0)
 * and writes them as RGBA8 to dst[y * 4 + x]; other pixels of dst are left as they are. */
typedef void (*sg_shade_fn)(const sg_shade_ctx *ctx, const sg_tri *t, int x0, int y0, uint32_t mask,
                            uint32_t *dst);

/* Shades two whole tiles of one triangle (top-left pixels (x0, y0) and (x1, y1)) into dst0 and
 * dst1: the same bytes as two calls of the variant's sg_shade_fn, in less time where the
 * instruction set can work on both at once. */
typedef void (*sg_shade2_fn)(const sg_shade_ctx *ctx, const sg_tri *t, int x0, int y0, int x1,
                             int y1, uint32_t *dst0, uint32_t *dst1);

/* Part of a tile that sees one triangle: the tile's index among a bin's tiles (row by row,
 * SG_BIN_SIZE / SG_TILE a row) and its pixels (bit y * 4 + x). */
typedef struct sg_run {
    uint16_t tile, mask;
} sg_run;

/* Shades n runs of one triangle in the bin whose top-left pixel is (bx0, by0) into the bin's
 * colour (tile after tile, SG_TILE_PIXELS each): the same bytes as the variant's sg_shade_fn on
 * each run, with the pixels of several runs packed into one vector (small triangles leave tiles
 * partly covered, and a vector pass costs the same for one pixel as for all). */
typedef void (*sg_shade_runs_fn)(const sg_shade_ctx *ctx, const sg_tri *t, int bx0, int by0,
                                 const sg_run *runs, int n, uint32_t *color);

/* The pixels of a 4x4 tile (top-left pixel (x0, y0)) that n >= 2 triangles of one draw share,
 * all of one flat kind: ts[j] covers the pixels of masks[j] (disjoint); their colours go to dst
 * as an sg_shade_fn writes them. */
typedef struct sg_mixed_tile {
    const sg_tri *ts[SG_TILE_PIXELS];
    uint32_t masks[SG_TILE_PIXELS];
    int n, x0, y0;
    uint32_t *dst;
} sg_mixed_tile;

/* Shades `count` (1 or 2) such tiles of one draw: the same bytes as the variant's sg_shade_fn on
 * each triangle's pixels, in one pass over a tile instead of one per triangle (the tiles of a
 * dense mesh), two tiles side by side where there are two. */
typedef void (*sg_shade_mixed_fn)(const sg_shade_ctx *ctx, const sg_mixed_tile *tiles, int count);

/** The index of a resolved shading state in the variant tables below: 0 vertex colour,
 *  1 + (bilinear ? 2 : 0) + (clamp ? 1 : 0) texture. */
int sg_shade_variant(sgShade shade, sgFilter filter, sgWrap wrap);
/* The tables hold those five variants, then the same five adding a secondary colour (flat and
 * Gouraud lighting with a specular material: clamp(primary x texel + secondary), the secondary
 * colour at SG_LIT_SEC). */
enum { SG_SHADE_VARIANTS = 5, SG_SHADE_SECONDARY = 5 };
/** The shading function of a table index (variant, + SG_SHADE_SECONDARY) and instruction set. */
sg_shade_fn sg_shade_select_variant(int index, sg_isa isa);
/* The shading that works from the view-space position of each pixel (shade_phong*.c): per-pixel
 * lighting (SG_LIGHTING_PHONG), the same receiving a shadow map, unlit shading receiving a
 * shadow map (darkened to half where the light is hidden), and flat and Gouraud lighting
 * receiving one (the split colours of light.h, the light's part scaled by the visibility). Their
 * tables hold the five variants of each, in that order. */
enum {
    SG_PIXEL_PHONG = 0,
    SG_PIXEL_PHONG_SHADOW = 5,
    SG_PIXEL_SHADOW = 10,
    SG_PIXEL_SPLIT_SHADOW = 15,
    SG_PIXEL_VARIANTS = 20
};
/** The function of a table index (one of the three bases + variant) and instruction set. */
sg_shade_fn sg_shade_phong_select(int index, sg_isa isa);
sg_shade_fn sg_shade_phong_scalar(int index);
sg_shade_fn sg_shade_phong_avx2(int index);
sg_shade_fn sg_shade_phong_avx512(int index);
sg_shade_fn sg_shade_phong_neon(int index);
/* The `textured` argument of the SIMD shading bodies: 0 untextured, 1 one level, or a mipmap chain
 * with the nearest level (SG_TEX_MIP) or two levels blended (SG_TEX_MIP_LINEAR). */
enum { SG_TEX_MIP = 2, SG_TEX_MIP_LINEAR = 3 };

/** The textured shading of a mipmapped pipeline (mipmap NEAREST or LINEAR; shade_mip.c), with
 *  the secondary colour of flat and Gouraud lighting when sec: AVX-512's or AVX2's, else the
 *  portable one, which is the reference. */
sg_shade_fn sg_shade_mip_select(sgMipmap mipmap, sgFilter filter, sgWrap wrap, bool sec,
                                sg_isa isa);
/** Its two-tile function, or NULL where the instruction set has none (all but AVX-512 and AVX2).
 */
sg_shade2_fn sg_shade2_mip_select(sgMipmap mipmap, sgFilter filter, sgWrap wrap, bool sec,
                                  sg_isa isa);
/** Its packed-runs function (the runs' 2 x 2 quads packed), or NULL where it has none (all but
 *  AVX-512 and AVX2). */
sg_shade_runs_fn sg_shade_runs_mip_select(sgMipmap mipmap, sgFilter filter, sgWrap wrap, bool sec,
                                          sg_isa isa);
/** The portable reference of sg_shade_mip_select, and AVX-512's and AVX2's tables (NULL where not
 *  built), by index: linear * 8 + bilinear * 4 + repeat * 2 + sec. */
sg_shade_fn sg_shade_mip_portable(int index);
sg_shade_fn sg_shade_mip_avx512(int index);
sg_shade2_fn sg_shade2_mip_avx512(int index);
sg_shade_fn sg_shade_mip_avx2(int index);
sg_shade2_fn sg_shade2_mip_avx2(int index);
sg_shade_runs_fn sg_shade_runs_mip_avx2(int index);
sg_shade_runs_fn sg_shade_runs_mip_avx512(int index);
/** The shading function for a resolved pipeline state (no DEFAULT values) and instruction set. */
sg_shade_fn sg_shade_select(sgShade shade, sgFilter filter, sgWrap wrap, sg_isa isa);
/** The scalar reference functions (the SSE2, AVX2 and AVX-512 tables are in shade_sse2.c,
 *  shade_avx2.c, shade_avx512.c, shade_neon.c; NULL where not built, and the SSE2 table has no
 *  secondary variants), by table index. */
sg_shade_fn sg_shade_scalar(int variant);
sg_shade_fn sg_shade_sse2(int variant);
sg_shade_fn sg_shade_avx2(int variant);
sg_shade_fn sg_shade_avx512(int variant);
/** The two-tile function of an unlit variant for the instruction set, or NULL where it has none
 *  (all but AVX2 and AVX-512); the callers then shade each tile alone. */
sg_shade2_fn sg_shade2_select_variant(int variant, sg_isa isa);
sg_shade2_fn sg_shade2_avx512(int variant);
sg_shade2_fn sg_shade2_avx2(int variant);
/** The packed-runs function of an unlit variant for the instruction set, or NULL where it has
 *  none; the callers then shade each run alone. */
sg_shade_runs_fn sg_shade_runs_select_variant(int variant, sg_isa isa);
sg_shade_runs_fn sg_shade_runs_avx2(int variant);
sg_shade_runs_fn sg_shade_runs_avx512(int variant);
/** The shared-tile function of an unlit variant (no secondary colour) for the instruction set,
 *  or NULL where it has none; the callers then shade each triangle's pixels alone. */
sg_shade_mixed_fn sg_shade_mixed_select_variant(int variant, sg_isa isa);
sg_shade_mixed_fn sg_shade_mixed_avx2(int variant);
sg_shade_mixed_fn sg_shade_mixed_avx512(int variant);
sg_shade_fn sg_shade_neon(int variant);
/** Attributes an unlit shading mode interpolates: r g b a, plus s t when textured. */
int sg_shade_attr_count(sgShade shade);
/** The best instruction set this CPU runs. */
sg_isa sg_isa_detect(void);
/** Whether this CPU (and build) runs `isa`: the scalar code everywhere, the x86 sets up to the
 *  best detected, NEON on AArch64 only. */
bool sg_isa_runs(sg_isa isa);
/** Whether the AVX-512 lookups should try the texel window before gathering on this CPU
 *  (sg_shade_ctx.texel_window): no where gathers are quick, yes elsewhere. */
bool sg_texel_window_detect(void);

/** Float colour channel to unorm8, round to nearest, clamped to [0, 1] (NaN gives 0). */
static inline uint32_t sg_to_unorm8(float v) {
    if (!(v > 0.0f)) return 0;
    if (v >= 1.0f) return 255;
    return (uint32_t)(v * 255.0f + 0.5f);
}

/** The one pixel of an untextured flat-coloured triangle: its colour (plus, with sec, the
 *  secondary colour in ext), converted once for all its pixels. */
static inline uint32_t sg_flat_pixel(const sg_tri *t, const sg_tri_ext *ext, int sec) {
    float f[4] = {t->color[0], t->color[1], t->color[2], t->color[3]};
    if (sec)
        for (int k = 0; k < 3; k++) f[k] += ext->a[SG_LIT_SEC - SG_TRI_ATTRS + k];
    return (sg_to_unorm8(f[0]) | sg_to_unorm8(f[1]) << 8 | sg_to_unorm8(f[2]) << 16 |
            sg_to_unorm8(f[3]) << 24);
}

#endif
