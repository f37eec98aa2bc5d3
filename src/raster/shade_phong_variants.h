/* shade_phong_variants.h - the shading functions from the view position of one instruction set
 * (per-pixel lighting, the same with a shadow map, unlit with a shadow map, flat and Gouraud with
 * a shadow map; five texture variants each), made from its body function, and their table in the
 * order of shade.h (SG_PIXEL_*).
 *
 * Included by shade_phong.c, shade_phong_avx2.c and shade_phong_avx512.c after each defines
 *   SG_PHONG_BODY(ctx, tri, ext, x0, y0, mask, dst, textured, bilinear, repeat, flat, lit, shadow)
 * (always inlined, its last six arguments constants; lit: 0 unlit, 1 Phong, 2 split colours) and
 * SG_PHONG_TABLE, the name of its sg_shade_fn (int index) lookup. The per-triangle `flat` is split
 * off once per tile.
 */
#if !defined(SG_PHONG_TABLE) || !defined(SG_PHONG_BODY)
#error "define SG_PHONG_TABLE and SG_PHONG_BODY before including shade_phong_variants.h"
#endif

#define SG_PHONG_VARIANT(name, lit, shadow, tex, bil, rep)                                         \
    static void name##_##tex##bil##rep(const sg_shade_ctx *c, const sg_tri *t, int x0, int y0,     \
                                       uint32_t m, uint32_t *dst) {                                \
        const sg_tri_ext *ext = sg_shade_ext(c, t);                                                \
        if (t->flat != SG_FLAT_NONE)                                                               \
            SG_PHONG_BODY(c, t, ext, x0, y0, m, dst, tex, bil, rep, 1, lit, shadow);               \
        else                                                                                       \
            SG_PHONG_BODY(c, t, ext, x0, y0, m, dst, tex, bil, rep, 0, lit, shadow);               \
    }
#define SG_PHONG_KIND(name, lit, shadow)                                                           \
    SG_PHONG_VARIANT(name, lit, shadow, 0, 0, 0)                                                   \
    SG_PHONG_VARIANT(name, lit, shadow, 1, 0, 1)                                                   \
    SG_PHONG_VARIANT(name, lit, shadow, 1, 0, 0)                                                   \
    SG_PHONG_VARIANT(name, lit, shadow, 1, 1, 1)                                                   \
    SG_PHONG_VARIANT(name, lit, shadow, 1, 1, 0)
SG_PHONG_KIND(phong, 1, 0)
SG_PHONG_KIND(phong_shadow, 1, 1)
SG_PHONG_KIND(unlit_shadow, 0, 1)
SG_PHONG_KIND(split_shadow, 2, 1)
#undef SG_PHONG_KIND
#undef SG_PHONG_VARIANT

/* A kind's five variants, in the order of sg_shade_variant. */
#define SG_PHONG_ROW(name) name##_000, name##_101, name##_100, name##_111, name##_110

sg_shade_fn SG_PHONG_TABLE(int index) {
    static const sg_shade_fn table[SG_PIXEL_VARIANTS] = {
        SG_PHONG_ROW(phong), SG_PHONG_ROW(phong_shadow), SG_PHONG_ROW(unlit_shadow),
        SG_PHONG_ROW(split_shadow)};
    return table[index];
}

#undef SG_PHONG_ROW
