/* shade_variants.h - the shading variants of one instruction set, made from its row function.
 *
 * Included by shade.c, shade_sse2.c, shade_avx2.c and shade_avx512.c after each defines
 *   shade_rows(ctx, tri, ext, x0, y0, mask, dst, textured, bilinear, repeat, flat, sec)
 * (always inlined, its last five arguments constants; sec: add the secondary colour of ext) and
 * SG_SHADE_TABLE, the name of its sg_shade_fn (int index) lookup, and SG_SHADE_NO_SECONDARY when
 * it has no secondary variants. The per-triangle `flat` is split off once per tile, so each
 * variant holds three specialised loops. With SG_MIP_TABLES (the names of the mipmapped single
 * tiles' and pairs' lookups) also the mipmapped variants, whose shade_pair must come first.
 */
#ifndef SG_SHADE_TABLE
#error "define SG_SHADE_TABLE and shade_rows before including shade_variants.h"
#endif

static inline __attribute__((always_inline)) void shade_flat(const sg_shade_ctx *c, const sg_tri *t,
                                                             const sg_tri_ext *ext, int x0, int y0,
                                                             uint32_t mask, uint32_t *dst,
                                                             const int textured, const int bilinear,
                                                             const int repeat, const int sec) {
    /* With a secondary colour, white is a colour like any other: the texel is not the result. */
    if (t->flat == SG_FLAT_WHITE && !sec)
        shade_rows(c, t, ext, x0, y0, mask, dst, textured, bilinear, repeat, SG_FLAT_WHITE, sec);
    else if (t->flat != SG_FLAT_NONE)
        shade_rows(c, t, ext, x0, y0, mask, dst, textured, bilinear, repeat, SG_FLAT_COLOR, sec);
    else
        shade_rows(c, t, ext, x0, y0, mask, dst, textured, bilinear, repeat, SG_FLAT_NONE, sec);
}

#define SG_VARIANT(tex, bil, rep, sec)                                                             \
    static void shade_##tex##bil##rep##sec(const sg_shade_ctx *c, const sg_tri *t, int x0, int y0, \
                                           uint32_t m, uint32_t *dst) {                            \
        shade_flat(c, t, sec ? sg_shade_ext(c, t) : NULL, x0, y0, m, dst, tex, bil, rep, sec);     \
    }
SG_VARIANT(0, 0, 0, 0) /* vertex colour */
SG_VARIANT(1, 0, 1, 0) /* texture, nearest, repeat */
SG_VARIANT(1, 0, 0, 0) /* texture, nearest, clamp */
SG_VARIANT(1, 1, 1, 0) /* texture, bilinear, repeat */
SG_VARIANT(1, 1, 0, 0) /* texture, bilinear, clamp */
#if !defined(SG_SHADE_NO_SECONDARY)
SG_VARIANT(0, 0, 0, 1) /* the same five, plus the secondary colour */
SG_VARIANT(1, 0, 1, 1)
SG_VARIANT(1, 0, 0, 1)
SG_VARIANT(1, 1, 1, 1)
SG_VARIANT(1, 1, 0, 1)
#endif
#undef SG_VARIANT

/* pair_<tex><bil><rep><sec>: a two-tile function (sg_shade2_fn) of the file's
 *   shade_pair(ctx, tri, ext, x0, y0, x1, y1, dst0, dst1, textured, bilinear, repeat, flat, sec)
 * (always inlined), the flat kind split off as in shade_flat; for the files that shade two whole
 * tiles at once. */
#define SG_PAIR_VARIANT(tex, bil, rep, sec)                                                        \
    static void pair_##tex##bil##rep##sec(const sg_shade_ctx *c, const sg_tri *t, int x0, int y0,  \
                                          int x1, int y1, uint32_t *d0, uint32_t *d1) {            \
        const sg_tri_ext *ext = sec ? sg_shade_ext(c, t) : NULL;                                   \
        if (t->flat == SG_FLAT_WHITE && !sec)                                                      \
            shade_pair(c, t, ext, x0, y0, x1, y1, d0, d1, tex, bil, rep, SG_FLAT_WHITE, sec);      \
        else if (t->flat != SG_FLAT_NONE)                                                          \
            shade_pair(c, t, ext, x0, y0, x1, y1, d0, d1, tex, bil, rep, SG_FLAT_COLOR, sec);      \
        else                                                                                       \
            shade_pair(c, t, ext, x0, y0, x1, y1, d0, d1, tex, bil, rep, SG_FLAT_NONE, sec);       \
    }

sg_shade_fn SG_SHADE_TABLE(int index) {
#if defined(SG_SHADE_NO_SECONDARY)
    static const sg_shade_fn table[10] = {shade_0000, shade_1010, shade_1000, shade_1110,
                                          shade_1100};
#else
    static const sg_shade_fn table[10] = {shade_0000, shade_1010, shade_1000, shade_1110,
                                          shade_1100, shade_0001, shade_1011, shade_1001,
                                          shade_1111, shade_1101};
#endif
    return table[index];
}

#if defined(SG_MIP_TABLES)
/* Mipmapped textures (sgPipelineDesc.mipmap; shade_mip.c is the portable reference): single tiles
 * mip_<tex><bil><rep><sec> and pairs, textured SG_TEX_MIP or SG_TEX_MIP_LINEAR. */
#define SG_MIP_VARIANT(tex, bil, rep, sec)                                                         \
    static void mip_##tex##bil##rep##sec(const sg_shade_ctx *c, const sg_tri *t, int x0, int y0,   \
                                         uint32_t m, uint32_t *dst) {                              \
        shade_flat(c, t, sec ? sg_shade_ext(c, t) : NULL, x0, y0, m, dst, tex, bil, rep, sec);     \
    }                                                                                              \
    SG_PAIR_VARIANT(tex, bil, rep, sec)
/* fn(tex, bil, rep, sec) for the eight mipmapped variants of tex, in sg_shade_mip_select's index
 * order (left defined for the file's own mipmapped functions) */
#define SG_MIP_EACH(fn, tex)                                                                       \
    fn(tex, 0, 0, 0) fn(tex, 0, 0, 1) fn(tex, 0, 1, 0) fn(tex, 0, 1, 1) fn(tex, 1, 0, 0)           \
        fn(tex, 1, 0, 1) fn(tex, 1, 1, 0) fn(tex, 1, 1, 1)
SG_MIP_EACH(SG_MIP_VARIANT, 2) /* SG_TEX_MIP */
SG_MIP_EACH(SG_MIP_VARIANT, 3) /* SG_TEX_MIP_LINEAR */
#undef SG_MIP_VARIANT
_Static_assert(SG_TEX_MIP == 2 && SG_TEX_MIP_LINEAR == 3, "the variants' names");

/* The lookup fn of the variants prefix_<tex>..., by the index of sg_shade_mip_select (left defined
 * for the file's own mipmapped functions). */
#define SG_MIP_TABLE(type, fn, prefix)                                                             \
    type fn(int index) {                                                                           \
        static const type table[16] = {                                                            \
            prefix##_2000, prefix##_2001, prefix##_2010, prefix##_2011,                            \
            prefix##_2100, prefix##_2101, prefix##_2110, prefix##_2111,                            \
            prefix##_3000, prefix##_3001, prefix##_3010, prefix##_3011,                            \
            prefix##_3100, prefix##_3101, prefix##_3110, prefix##_3111};                           \
        return table[index];                                                                       \
    }
SG_MIP_TABLES(SG_MIP_TABLE)
#endif
