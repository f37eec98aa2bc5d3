/* shade_mixed.h - what the AVX2 and AVX-512 shading of tiles that several triangles share
 * (sg_shade_mixed_fn) have in common: the values each lane takes from its own triangle, and the
 * functions made of an instruction set's body.
 *
 * Included by shade_avx2.h and shade_avx512.h for SG_MIXED_VALUES; shade_avx2.c and
 * shade_avx512.c then define
 *   shade_mixed(ctx, tiles, count, textured, bilinear, repeat, flat)
 * (always inlined, its last five arguments constants: shades and stores `count` tiles whose
 * triangles all have the flat kind `flat`) and SG_MIXED_TABLE, the name of their
 * sg_shade_mixed_fn (int index) lookup, and include it again with SG_MIXED_TABLE defined for the
 * functions: the count and the flat kind split off once a call.
 */
#ifndef SG_SHADE_MIXED_H
#define SG_SHADE_MIXED_H

#include "raster/shade.h"

/* The values a lane takes from its triangle, by index: the offsets from the tile's first pixel to
 * the triangle's bounds (x, y), then value, step in x and step in y of 1/w, of the four colour
 * channels (a flat triangle's colour alone, at the value's index) and of the two texture
 * coordinates. */
enum {
    SG_MIX_OX,
    SG_MIX_OY,
    SG_MIX_Q,
    SG_MIX_C = SG_MIX_Q + 3,
    SG_MIX_S = SG_MIX_C + 12,
    SG_MIX_VALUES = SG_MIX_S + 6
};

/* put(index, value) for each value of triangle t a lane of the tile whose first pixel is (x0, y0)
 * reads, in the order above; flat and textured are constants, and the values they leave unread are
 * skipped. */
#define SG_MIXED_VALUES(t, x0, y0, flat, textured, put)                                            \
    do {                                                                                           \
        put(SG_MIX_OX, (float)((x0) - (t)->minx));                                                 \
        put(SG_MIX_OY, (float)((y0) - (t)->miny));                                                 \
        put(SG_MIX_Q, (t)->q);                                                                     \
        put(SG_MIX_Q + 1, (t)->q_dx);                                                              \
        put(SG_MIX_Q + 2, (t)->q_dy);                                                              \
        for (int k_ = 0; k_ < 4; k_++) {                                                           \
            if ((flat) != SG_FLAT_NONE) {                                                          \
                put(SG_MIX_C + 3 * k_, (t)->color[k_]);                                            \
                continue;                                                                          \
            }                                                                                      \
            put(SG_MIX_C + 3 * k_, (t)->a[k_]);                                                    \
            put(SG_MIX_C + 3 * k_ + 1, (t)->a_dx[k_]);                                             \
            put(SG_MIX_C + 3 * k_ + 2, (t)->a_dy[k_]);                                             \
        }                                                                                          \
        for (int k_ = 0; (textured) && k_ < 2; k_++) {                                             \
            put(SG_MIX_S + 3 * k_, (t)->a[4 + k_]);                                                \
            put(SG_MIX_S + 3 * k_ + 1, (t)->a_dx[4 + k_]);                                         \
            put(SG_MIX_S + 3 * k_ + 2, (t)->a_dy[4 + k_]);                                         \
        }                                                                                          \
    } while (0)

/* The planes of a lane's values vv (SG_MIX_VALUES vectors) at offsets dx, dy: value + step in x
 * dx + step in y dy, as SG_PLANE of the per-triangle bodies, in the vector type's add and mul. */
#define SG_MIX_PLANE(add, mul, vv, f, dx, dy)                                                      \
    add(add((vv)[f], mul((vv)[(f) + 1], dx)), mul((vv)[(f) + 2], dy))

/* What `sets` vectors of lanes compute from their values v[i] (lane_x, lane_y: each lane's column
 * and row in its vector): the offsets dx, dy to their triangles' bounds, w = 1 / (1/w), the
 * colours col (a flat colour as it is, else colour / w times w) and, when textured, the texture
 * coordinates s, u. add, mul, div and set1 are the vector type's operations: each lane does what
 * the per-triangle bodies do for its pixel. flat and textured are constants. */
#define SG_MIXED_PLANES(add, mul, div, set1, sets, v, lane_x, lane_y, dx, dy, w, col, s, u, flat,  \
                        textured)                                                                  \
    do {                                                                                           \
        for (int i_ = 0; i_ < (sets); i_++) {                                                      \
            dx[i_] = add(v[i_][SG_MIX_OX], lane_x);                                                \
            dy[i_] = add(v[i_][SG_MIX_OY], lane_y);                                                \
            w[i_] = div(set1(1.0f), SG_MIX_PLANE(add, mul, v[i_], SG_MIX_Q, dx[i_], dy[i_]));      \
            for (int k_ = 0; k_ < 4; k_++)                                                         \
                col[i_][k_] =                                                                      \
                    (flat) != SG_FLAT_NONE                                                         \
                        ? v[i_][SG_MIX_C + 3 * k_]                                                 \
                        : mul(SG_MIX_PLANE(add, mul, v[i_], SG_MIX_C + 3 * k_, dx[i_], dy[i_]),    \
                              w[i_]);                                                              \
            if (!(textured)) continue;                                                             \
            s[i_] = mul(SG_MIX_PLANE(add, mul, v[i_], SG_MIX_S, dx[i_], dy[i_]), w[i_]);           \
            u[i_] = mul(SG_MIX_PLANE(add, mul, v[i_], SG_MIX_S + 3, dx[i_], dy[i_]), w[i_]);       \
        }                                                                                          \
    } while (0)

#endif

#if defined(SG_MIXED_TABLE)

static inline __attribute__((always_inline)) void mixed_flat(const sg_shade_ctx *c,
                                                             const sg_mixed_tile *tiles,
                                                             const int count, const int textured,
                                                             const int bilinear, const int repeat) {
    const int flat = tiles[0].ts[0]->flat;
    if (flat == SG_FLAT_WHITE)
        shade_mixed(c, tiles, count, textured, bilinear, repeat, SG_FLAT_WHITE);
    else if (flat != SG_FLAT_NONE)
        shade_mixed(c, tiles, count, textured, bilinear, repeat, SG_FLAT_COLOR);
    else
        shade_mixed(c, tiles, count, textured, bilinear, repeat, SG_FLAT_NONE);
}

#define SG_MIXED(tex, bil, rep)                                                                    \
    static void mixed_##tex##bil##rep(const sg_shade_ctx *c, const sg_mixed_tile *tiles,           \
                                      int count) {                                                 \
        if (count == 2)                                                                            \
            mixed_flat(c, tiles, 2, tex, bil, rep);                                                \
        else                                                                                       \
            mixed_flat(c, tiles, 1, tex, bil, rep);                                                \
    }
SG_MIXED(0, 0, 0) /* vertex colour */
SG_MIXED(1, 0, 1) /* texture, nearest, repeat */
SG_MIXED(1, 0, 0) /* texture, nearest, clamp */
SG_MIXED(1, 1, 1) /* texture, bilinear, repeat */
SG_MIXED(1, 1, 0) /* texture, bilinear, clamp */
#undef SG_MIXED

sg_shade_mixed_fn SG_MIXED_TABLE(int index) {
    static const sg_shade_mixed_fn table[SG_SHADE_VARIANTS] = {mixed_000, mixed_101, mixed_100,
                                                               mixed_111, mixed_110};
    return table[index];
}

#endif
