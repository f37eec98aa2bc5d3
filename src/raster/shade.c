/* shade.c - the specialised per-tile shading functions (see shade.h). */
#include "raster/shade.h"

#include "raster/framebuffer.h"

enum { Z_NONE, Z_LESS, Z_ANY };

static inline bool depth_passes(sgCompare op, float z, float d) {
    switch (op) {
    case SG_COMPARE_NEVER:
        return false;
    case SG_COMPARE_LESS:
        return z < d;
    case SG_COMPARE_EQUAL:
        return z == d;
    case SG_COMPARE_LESS_EQUAL:
        return z <= d;
    case SG_COMPARE_GREATER:
        return z > d;
    case SG_COMPARE_NOT_EQUAL:
        return z != d;
    case SG_COMPARE_GREATER_EQUAL:
        return z >= d;
    default:
        return true;
    }
}

/* The one body every variant is made from; the constant arguments fold away per variant, and
 * `flat` (a per-triangle constant, see sg_tri) is split off at the top into its own loops. */
static inline __attribute__((always_inline)) void
shade_pixels(const sg_shade_ctx *c, const sg_tri *t, int x0, int y0, uint32_t mask,
             const int textured, const int bilinear, const int repeat, const int zmode,
             const int zwrite, const int flat) {
    size_t base = sg_fb_index(c->tiles_x, x0, y0);
    float ox = (float)(x0 - t->minx), oy = (float)(y0 - t->miny);
    while (mask) {
        int bit = __builtin_ctz(mask);
        mask &= mask - 1;
        float dx = ox + (float)(bit & 3), dy = oy + (float)(bit >> 2);
        if (zmode != Z_NONE || zwrite) {
            float z = t->z + t->z_dx * dx + t->z_dy * dy;
            z = z < 0.0f ? 0.0f : (z > 1.0f ? 1.0f : z); /* depth is clamped to the depth range */
            float *dp = &c->depth[base + (size_t)bit];
            if (zmode == Z_LESS && !(z < *dp)) continue;
            if (zmode == Z_ANY && !depth_passes(c->compare, z, *dp)) continue;
            if (zwrite) *dp = z;
        }
        float w = 0.0f;
        if (textured || flat == SG_FLAT_NONE) w = 1.0f / (t->q + t->q_dx * dx + t->q_dy * dy);
        float col[4];
        for (int k = 0; k < 4; k++)
            col[k] = flat != SG_FLAT_NONE ? t->color[k]
                                          : (t->a[k] + t->a_dx[k] * dx + t->a_dy[k] * dy) * w;
        if (textured) {
            float s = (t->a[4] + t->a_dx[4] * dx + t->a_dy[4] * dy) * w;
            float u = (t->a[5] + t->a_dx[5] * dx + t->a_dy[5] * dy) * w;
            sg_texel tx = bilinear ? sg_sample_bilinear(&c->tex, s, u, repeat)
                                   : sg_sample_nearest(&c->tex, s, u, repeat);
            if (flat == SG_FLAT_WHITE) { /* 1 * texel / 255, back to unorm8, is the texel */
                c->color[base + (size_t)bit] = sg_pack_rgba8((uint32_t)tx.c[0], (uint32_t)tx.c[1],
                                                             (uint32_t)tx.c[2], (uint32_t)tx.c[3]);
                continue;
            }
            for (int k = 0; k < 4; k++) col[k] *= (float)tx.c[k] * (1.0f / 255.0f);
        }
        c->color[base + (size_t)bit] = sg_pack_rgba8(sg_to_unorm8(col[0]), sg_to_unorm8(col[1]),
                                                     sg_to_unorm8(col[2]), sg_to_unorm8(col[3]));
    }
}

static inline __attribute__((always_inline)) void
shade_tile(const void *vctx, const sg_tri *t, int x0, int y0, uint32_t mask, const int textured,
           const int bilinear, const int repeat, const int zmode, const int zwrite) {
    const sg_shade_ctx *c = vctx;
    if (t->flat == SG_FLAT_WHITE)
        shade_pixels(c, t, x0, y0, mask, textured, bilinear, repeat, zmode, zwrite, SG_FLAT_WHITE);
    else if (t->flat == SG_FLAT_COLOR)
        shade_pixels(c, t, x0, y0, mask, textured, bilinear, repeat, zmode, zwrite, SG_FLAT_COLOR);
    else
        shade_pixels(c, t, x0, y0, mask, textured, bilinear, repeat, zmode, zwrite, SG_FLAT_NONE);
}

#define SG_VARIANT(tex, bil, rep, zm, zw)                                                          \
    static void shade_##tex##bil##rep##zm##zw(const void *c, const sg_tri *t, int x0, int y0,      \
                                              uint32_t m) {                                        \
        shade_tile(c, t, x0, y0, m, tex, bil, rep, zm, zw);                                        \
    }
#define SG_VARIANTS_Z(tex, bil, rep)                                                               \
    SG_VARIANT(tex, bil, rep, 0, 0)                                                                \
    SG_VARIANT(tex, bil, rep, 0, 1)                                                                \
    SG_VARIANT(tex, bil, rep, 1, 0)                                                                \
    SG_VARIANT(tex, bil, rep, 1, 1)                                                                \
    SG_VARIANT(tex, bil, rep, 2, 0)                                                                \
    SG_VARIANT(tex, bil, rep, 2, 1)
#define SG_ROW_Z(tex, bil, rep)                                                                    \
    {                                                                                              \
        {shade_##tex##bil##rep##00, shade_##tex##bil##rep##01},                                    \
            {shade_##tex##bil##rep##10, shade_##tex##bil##rep##11}, {                              \
            shade_##tex##bil##rep##20, shade_##tex##bil##rep##21                                   \
        }                                                                                          \
    }

SG_VARIANTS_Z(0, 0, 0) /* vertex colour */
SG_VARIANTS_Z(1, 0, 1) /* texture, nearest, repeat */
SG_VARIANTS_Z(1, 0, 0) /* texture, nearest, clamp */
SG_VARIANTS_Z(1, 1, 1) /* texture, bilinear, repeat */
SG_VARIANTS_Z(1, 1, 0) /* texture, bilinear, clamp */

sg_tile_fn sg_shade_select(sgShade shade, sgFilter filter, sgWrap wrap, sgCompare compare,
                           bool depth_write) {
    static const sg_tile_fn table[5][3][2] = {SG_ROW_Z(0, 0, 0), SG_ROW_Z(1, 0, 1),
                                              SG_ROW_Z(1, 0, 0), SG_ROW_Z(1, 1, 1),
                                              SG_ROW_Z(1, 1, 0)};
    int colour = 0;
    if (shade == SG_SHADE_TEXTURE_MODULATE)
        colour = 1 + (filter == SG_FILTER_BILINEAR ? 2 : 0) + (wrap == SG_WRAP_REPEAT ? 0 : 1);
    int zmode =
        compare == SG_COMPARE_ALWAYS ? Z_NONE : (compare == SG_COMPARE_LESS ? Z_LESS : Z_ANY);
    return table[colour][zmode][depth_write ? 1 : 0];
}

int sg_shade_attr_count(sgShade shade) {
    return shade == SG_SHADE_TEXTURE_MODULATE ? 6 : 4;
}
