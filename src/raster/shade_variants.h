/* shade_variants.h - the shading variants of one instruction set, made from its row function.
 *
 * Included by shade.c, shade_sse2.c and shade_avx2.c after each defines
 *   shade_rows(ctx, tri, x0, y0, mask, dst, textured, bilinear, repeat, flat)
 * (always inlined, its last four arguments constants) and SG_SHADE_TABLE, the name of its
 * sg_shade_fn (int variant) lookup. The per-triangle `flat` is split off once per tile, so each
 * of the five pipeline variants holds three specialised loops.
 */
#ifndef SG_SHADE_TABLE
#error "define SG_SHADE_TABLE and shade_rows before including shade_variants.h"
#endif

static inline __attribute__((always_inline)) void shade_flat(const sg_shade_ctx *c, const sg_tri *t,
                                                             int x0, int y0, uint32_t mask,
                                                             uint32_t *dst, const int textured,
                                                             const int bilinear, const int repeat) {
    if (t->flat == SG_FLAT_WHITE)
        shade_rows(c, t, x0, y0, mask, dst, textured, bilinear, repeat, SG_FLAT_WHITE);
    else if (t->flat == SG_FLAT_COLOR)
        shade_rows(c, t, x0, y0, mask, dst, textured, bilinear, repeat, SG_FLAT_COLOR);
    else
        shade_rows(c, t, x0, y0, mask, dst, textured, bilinear, repeat, SG_FLAT_NONE);
}

#define SG_VARIANT(tex, bil, rep)                                                                  \
    static void shade_##tex##bil##rep(const sg_shade_ctx *c, const sg_tri *t, int x0, int y0,      \
                                      uint32_t m, uint32_t *dst) {                                 \
        shade_flat(c, t, x0, y0, m, dst, tex, bil, rep);                                           \
    }
SG_VARIANT(0, 0, 0) /* vertex colour */
SG_VARIANT(1, 0, 1) /* texture, nearest, repeat */
SG_VARIANT(1, 0, 0) /* texture, nearest, clamp */
SG_VARIANT(1, 1, 1) /* texture, bilinear, repeat */
SG_VARIANT(1, 1, 0) /* texture, bilinear, clamp */
#undef SG_VARIANT

sg_shade_fn SG_SHADE_TABLE(int variant) {
    static const sg_shade_fn table[5] = {shade_000, shade_101, shade_100, shade_111, shade_110};
    return table[variant];
}
