/* shade_avx2.c - the shading functions of shade.h in AVX2 (this file alone is compiled with
 * -mavx2; no FMA, which would round differently), made of the helpers of shade_avx2.h. A tile is
 * shaded two rows at a time, eight pixels per __m256 (row r in the low half, row r + 1 in the
 * high half) and a vector per channel: 1/q, the colours and the texture coordinates are the scalar
 * reference's float operations (shade.c, sample.h) in the same order, so the bytes are the same;
 * pixels are written with a masked store. Without AVX2 (or off x86) every variant is NULL and the
 * SSE2 or scalar code is used.
 */
#include "raster/shade_avx2.h"

#include "raster/bin.h"

#if defined(SG_SHADE_AVX2)

/* Rows r[i] and r[i] + 1 (masks m[i]) of a tile, n halves (n is 1 or 2, a constant): each step
 * done for every half before the next, so the two halves' long chains of dependent steps (1/q,
 * texel coordinates, fetch, filter, packing) run side by side (as shade16_tiles in
 * shade_avx512.h). ax, sx and qx are shade_rows's per-column parts. */
INLINE void rows_body(const sg_tri *t, const sg_tri_ext *ext, const tex8 *tx, const __m256 ax[6],
                      const __m256 sx[3], __m256 qx, float oy, const int r[2], const unsigned m[2],
                      const int n, uint32_t *dst, const int textured, const int bilinear,
                      const int repeat, const int flat, const int sec) {
    const int e = SG_LIT_SEC - SG_TRI_ATTRS; /* the secondary colour in ext */
    __m256 dy[2], w[2], col[2][4];
    for (int i = 0; i < n; i++) {
        /* dy of row r in the low half, of row r + 1 in the high half */
        dy[i] = _mm256_set_m128(_mm_set1_ps(oy + (float)(r[i] + 1)), _mm_set1_ps(oy + (float)r[i]));
        w[i] = _mm256_div_ps(_mm256_set1_ps(1.0f),
                             _mm256_add_ps(qx, _mm256_mul_ps(_mm256_set1_ps(t->q_dy), dy[i])));
    }
    for (int i = 0; i < n; i++)
        for (int k = 0; k < 4; k++)
            col[i][k] =
                flat != SG_FLAT_NONE
                    ? ax[k]
                    : _mm256_mul_ps(
                          _mm256_add_ps(ax[k], _mm256_mul_ps(_mm256_set1_ps(t->a_dy[k]), dy[i])),
                          w[i]);
    if (textured) {
        __m256 s[2], u[2];
        for (int i = 0; i < n; i++) {
            s[i] = _mm256_mul_ps(
                _mm256_add_ps(ax[4], _mm256_mul_ps(_mm256_set1_ps(t->a_dy[4]), dy[i])), w[i]);
            u[i] = _mm256_mul_ps(
                _mm256_add_ps(ax[5], _mm256_mul_ps(_mm256_set1_ps(t->a_dy[5]), dy[i])), w[i]);
        }
        __m256i tc[2][4];
        if (bilinear) {
            __m256i gx[2], gy[2], texels[2][4], x[2][4];
            for (int i = 0; i < n; i++) {
                gx[i] = bilinear_split(s[i], tx->scale_x, tx->hi_x, repeat);
                gy[i] = bilinear_split(u[i], tx->scale_y, tx->hi_y, repeat);
            }
            for (int i = 0; i < n; i++) bilinear_fetch8(tx, gx[i], gy[i], repeat, texels[i]);
            for (int i = 0; i < n; i++) bilinear_filter8(gx[i], gy[i], texels[i], x[i]);
            if (flat == SG_FLAT_WHITE && !sec) {
                for (int i = 0; i < n; i++) store_rows(dst + 4 * r[i], pack_hi8(x[i]), m[i]);
                return;
            }
            for (int i = 0; i < n; i++)
                for (int k = 0; k < 4; k++) tc[i][k] = _mm256_srli_epi32(x[i][k], 16);
        } else {
            __m256i texel[2];
            for (int i = 0; i < n; i++) texel[i] = nearest8(tx, s[i], u[i], repeat);
            if (flat == SG_FLAT_WHITE && !sec) { /* the texel is the colour, as in the reference */
                for (int i = 0; i < n; i++) store_rows(dst + 4 * r[i], texel[i], m[i]);
                return;
            }
            for (int i = 0; i < n; i++) unpack_texels(texel[i], tc[i]);
        }
        for (int i = 0; i < n; i++)
            for (int k = 0; k < 4; k++)
                col[i][k] = _mm256_mul_ps(col[i][k], _mm256_mul_ps(_mm256_cvtepi32_ps(tc[i][k]),
                                                                   _mm256_set1_ps(1.0f / 255.0f)));
    }
    for (int i = 0; i < n; i++)
        for (int k = 0; sec && k < 3; k++)
            col[i][k] = _mm256_add_ps(
                col[i][k],
                flat != SG_FLAT_NONE
                    ? sx[k]
                    : _mm256_mul_ps(
                          _mm256_add_ps(sx[k],
                                        _mm256_mul_ps(_mm256_set1_ps(ext->a_dy[e + k]), dy[i])),
                          w[i]));
    for (int i = 0; i < n; i++) store_rows(dst + 4 * r[i], pack_unorm8(col[i]), m[i]);
}

/* A mipmapped tile (textured SG_TEX_MIP*): its pairs of rows that hold a covered pixel, each a
 * set of shade8_sets with its two whole quads, side by side. */
INLINE void mip_rows(const sg_shade_ctx *c, const sg_tri *t, const sg_tri_ext *ext, int x0, int y0,
                     uint32_t mask, uint32_t *dst, const int textured, const int bilinear,
                     const int repeat, const int flat, const int sec) {
    __m256 dx[2], dy[2];
    unsigned m[2];
    int h[2], n = 0;
    for (int k = 0; k < 2; k++) {
        const unsigned bits = (mask >> (8 * k)) & 255u;
        if (!bits) continue;
        sg_rows_dxdy8(t, x0, y0, k, &dx[n], &dy[n]);
        m[n] = bits;
        h[n++] = k;
    }
    __m256i v[2];
    if (n == 2)
        shade8_sets(c, t, NULL, ext, 2, dx, dy, m, v, textured, bilinear, repeat, flat, sec);
    else if (n == 1)
        shade8_sets(c, t, NULL, ext, 1, dx, dy, m, v, textured, bilinear, repeat, flat, sec);
    for (int i = 0; i < n; i++) store_rows(dst + 8 * h[i], v[i], m[i]);
}

/* The body of every variant, as shade_pixels in shade.c; the constant arguments fold away. */
INLINE void shade_rows(const sg_shade_ctx *c, const sg_tri *t, const sg_tri_ext *ext, int x0,
                       int y0, uint32_t mask, uint32_t *dst, const int textured, const int bilinear,
                       const int repeat, const int flat, const int sec) {
    if (textured >= SG_TEX_MIP) {
        mip_rows(c, t, ext, x0, y0, mask, dst, textured, bilinear, repeat, flat, sec);
        return;
    }
    const int e = SG_LIT_SEC - SG_TRI_ATTRS; /* the secondary colour in ext */
    if (!textured && flat != SG_FLAT_NONE) { /* one colour, converted once */
        uint32_t px = sg_flat_pixel(t, ext, sec);
        for (int r = 0; r < 4; r += 2) {
            unsigned m = (mask >> (4 * r)) & 255u;
            if (m) store_rows(dst + 4 * r, _mm256_set1_epi32((int)px), m);
        }
        return;
    }
    const float ox = (float)(x0 - t->minx), oy = (float)(y0 - t->miny);
    const __m256 dx = _mm256_add_ps(_mm256_set1_ps(ox),
                                    _mm256_setr_ps(0.0f, 1.0f, 2.0f, 3.0f, 0.0f, 1.0f, 2.0f, 3.0f));
    /* Everything but the a_dy * dy terms is the same on every row: q + q_dx dx and a + a_dx dx. */
    const __m256 qx =
        _mm256_add_ps(_mm256_set1_ps(t->q), _mm256_mul_ps(_mm256_set1_ps(t->q_dx), dx));
    const int nattr = textured ? 6 : 4;
    __m256 ax[6];
    for (int k = 0; k < nattr; k++) {
        if (k < 4 && flat != SG_FLAT_NONE)
            ax[k] = _mm256_set1_ps(t->color[k]);
        else
            ax[k] = _mm256_add_ps(_mm256_set1_ps(t->a[k]),
                                  _mm256_mul_ps(_mm256_set1_ps(t->a_dx[k]), dx));
    }
    __m256 sx[3]; /* the secondary colour's a + a_dx dx, or the flat colour */
    for (int k = 0; sec && k < 3; k++)
        sx[k] = flat != SG_FLAT_NONE
                    ? _mm256_set1_ps(ext->a[e + k])
                    : _mm256_add_ps(_mm256_set1_ps(ext->a[e + k]),
                                    _mm256_mul_ps(_mm256_set1_ps(ext->a_dx[e + k]), dx));
    tex8 tx;
    if (textured) tx = tex8_of(&c->tex, bilinear);
    const unsigned m0 = mask & 255u, m1 = (mask >> 8) & 255u;
    if (textured && m0 && m1) { /* both halves, side by side (see rows_body) */
        rows_body(t, ext, &tx, ax, sx, qx, oy, (const int[2]){0, 2}, (const unsigned[2]){m0, m1}, 2,
                  dst, textured, bilinear, repeat, flat, sec);
        return;
    }
    for (int r = 0; r < 4; r += 2) {
        const unsigned m = r ? m1 : m0;
        if (m)
            rows_body(t, ext, &tx, ax, sx, qx, oy, (const int[2]){r, 0}, (const unsigned[2]){m, 0},
                      1, dst, textured, bilinear, repeat, flat, sec);
    }
}

/* Two whole tiles of a triangle at once (sg_shade2_fn): their four pairs of rows shaded side by
 * side, the flat kind split off as in shade_flat. */
INLINE void shade_pair(const sg_shade_ctx *c, const sg_tri *t, const sg_tri_ext *ext, int x0,
                       int y0, int x1, int y1, uint32_t *dst0, uint32_t *dst1, const int textured,
                       const int bilinear, const int repeat, const int flat, const int sec) {
    __m256 dx[4], dy[4];
    for (int h = 0; h < 2; h++) {
        sg_rows_dxdy8(t, x0, y0, h, &dx[h], &dy[h]);
        sg_rows_dxdy8(t, x1, y1, h, &dx[2 + h], &dy[2 + h]);
    }
    __m256i v[4];
    shade8_sets(c, t, NULL, ext, 4, dx, dy, NULL, v, textured, bilinear, repeat, flat, sec);
    _mm256_storeu_si256((__m256i *)(void *)dst0, v[0]);
    _mm256_storeu_si256((__m256i *)(void *)(dst0 + 8), v[1]);
    _mm256_storeu_si256((__m256i *)(void *)dst1, v[2]);
    _mm256_storeu_si256((__m256i *)(void *)(dst1 + 8), v[3]);
}

#define SG_SHADE_TABLE sg_shade_avx2
#define SG_MIP_TABLES(table)                                                                       \
    table(sg_shade_fn, sg_shade_mip_avx2, mip) table(sg_shade2_fn, sg_shade2_mip_avx2, pair)
#include "raster/shade_variants.h"

/* Bilinear variants only: a nearest texel is a short chain, and 04_textured_cube (nearest) was
 * slower in pairs. */
SG_PAIR_VARIANT(1, 1, 1, 0)
SG_PAIR_VARIANT(1, 1, 0, 0)
SG_PAIR_VARIANT(1, 1, 1, 1)
SG_PAIR_VARIANT(1, 1, 0, 1)

sg_shade2_fn sg_shade2_avx2(int index) {
    static const sg_shade2_fn table[10] = {NULL, NULL, NULL, pair_1110, pair_1100,
                                           NULL, NULL, NULL, pair_1111, pair_1101};
    return table[index];
}

/* Runs of a triangle (sg_shade_runs_fn): the pixels of each pair of rows packed eight to a vector
 * (sg_queue8), two full vectors shaded side by side, each lane stored at its own offset; a whole
 * tile's two pairs of rows side by side, stored as they are. A
 * mipmapped triangle's sets must hold whole 2 x 2 quads instead: a pair of rows whose two quads
 * both hold a covered pixel is a set as it is, lone quads are paired (sg_pair_quad8), and only the
 * covered lanes are stored. */
INLINE void shade_runs(const sg_shade_ctx *c, const sg_tri *t, const sg_tri_ext *ext, int bx0,
                       int by0, const sg_run *runs, int n, uint32_t *color, const int textured,
                       const int bilinear, const int repeat, const int flat, const int sec) {
    enum { ROW = SG_BIN_SIZE / SG_TILE };
    const int mip = textured >= SG_TEX_MIP;
    sg_queue8 q = {_mm256_setzero_ps(), _mm256_setzero_ps(), _mm256_setzero_si256(), 0};
    sg_set8 lone = {_mm256_setzero_ps(), _mm256_setzero_ps(), _mm256_setzero_si256(), 0};
    sg_set8 full[2];
    int nfull = 0;
    for (int i = 0; i < n; i++) {
        const int tile = runs[i].tile;
        const int x0 = bx0 + (tile % ROW) * SG_TILE, y0 = by0 + (tile / ROW) * SG_TILE;
        if (runs[i].mask == 0xffffu) { /* a whole tile: its two pairs of rows, stored as they are */
            __m256 wdx[2], wdy[2];
            sg_rows_dxdy8(t, x0, y0, 0, &wdx[0], &wdy[0]);
            sg_rows_dxdy8(t, x0, y0, 1, &wdx[1], &wdy[1]);
            const unsigned all[2] = {255u, 255u};
            __m256i v[2];
            shade8_sets(c, t, NULL, ext, 2, wdx, wdy, mip ? all : NULL, v, textured, bilinear,
                        repeat, flat, sec);
            _mm256_storeu_si256((__m256i *)(void *)(color + tile * SG_TILE_PIXELS), v[0]);
            _mm256_storeu_si256((__m256i *)(void *)(color + tile * SG_TILE_PIXELS + 8), v[1]);
            continue;
        }
        for (int h = 0; h < 2; h++) {
            const unsigned bits = (runs[i].mask >> (8 * h)) & 255u;
            if (!bits) continue;
            __m256 dx, dy;
            sg_rows_dxdy8(t, x0, y0, h, &dx, &dy);
            const int off = tile * SG_TILE_PIXELS + 8 * h;
            if (mip && sg_both_quads8(bits)) {
                full[nfull] = sg_set8_of(dx, dy, off, bits);
            } else if (mip) {
                if (!sg_pair_quad8(&lone, dx, dy, off, bits, &full[nfull])) continue;
            } else {
                sg_queue8 f;
                if (!sg_enqueue8(&q, dx, dy, off, bits, &f)) continue;
                full[nfull] = (sg_set8){f.dx, f.dy, f.off, 255u};
            }
            if (++nfull < 2) continue;
            const __m256 fdx[2] = {full[0].dx, full[1].dx}, fdy[2] = {full[0].dy, full[1].dy};
            const unsigned masks[2] = {full[0].mask, full[1].mask};
            __m256i v[2];
            shade8_sets(c, t, NULL, ext, 2, fdx, fdy, mip ? masks : NULL, v, textured, bilinear,
                        repeat, flat, sec);
            sg_scatter8(color, full[0].off, v[0], mip ? masks[0] : 255u);
            sg_scatter8(color, full[1].off, v[1], mip ? masks[1] : 255u);
            nfull = 0;
        }
    }
    /* a full set left, then the last pixels, or the waiting quad */
    if (!mip && q.n) full[nfull++] = (sg_set8){q.dx, q.dy, q.off, (1u << q.n) - 1u};
    if (mip && lone.mask) full[nfull++] = lone;
    for (int k = 0; k < nfull; k++) {
        __m256i v;
        shade8_sets(c, t, NULL, ext, 1, &full[k].dx, &full[k].dy, mip ? &full[k].mask : NULL, &v,
                    textured, bilinear, repeat, flat, sec);
        sg_scatter8(color, full[k].off, v, full[k].mask);
    }
}

#define SG_RUNS_TABLE sg_shade_runs_avx2
#include "raster/shade_runs_variants.h"

/* The mipmapped runs, by the index of sg_shade_mip_select. */
#define SG_MIP_RUNS(tex, bil, rep, sec) SG_RUNS_VARIANT(shade_runs, tex, bil, rep, sec)
SG_MIP_EACH(SG_MIP_RUNS, 2)
SG_MIP_EACH(SG_MIP_RUNS, 3)
#undef SG_MIP_RUNS
#undef SG_MIP_EACH
SG_MIP_TABLE(sg_shade_runs_fn, sg_shade_runs_mip_avx2, runs)

/* `count` tiles that several triangles share (sg_shade_mixed_fn), their triangles all of the flat
 * kind `flat`: two rows a vector, all rows of both tiles side by side, each pair of rows stored
 * under its mask. */
INLINE void shade_mixed(const sg_shade_ctx *c, const sg_mixed_tile *tiles, const int count,
                        const int textured, const int bilinear, const int repeat, const int flat) {
    __m256i v[4];
    sg_shade8_mixed(c, tiles, count, v, textured, bilinear, repeat, flat);
    for (int i = 0; i < count; i++) {
        uint32_t all = 0;
        for (int j = 0; j < tiles[i].n; j++) all |= tiles[i].masks[j];
        store_rows(tiles[i].dst, v[2 * i], all & 255u);
        store_rows(tiles[i].dst + 8, v[2 * i + 1], all >> 8);
    }
}

#define SG_MIXED_TABLE sg_shade_mixed_avx2
#include "raster/shade_mixed.h"

#else

sg_shade_fn sg_shade_avx2(int index) {
    (void)index;
    return NULL;
}

sg_shade2_fn sg_shade2_avx2(int index) {
    (void)index;
    return NULL;
}

sg_shade_runs_fn sg_shade_runs_avx2(int index) {
    (void)index;
    return NULL;
}

sg_shade_mixed_fn sg_shade_mixed_avx2(int index) {
    (void)index;
    return NULL;
}

sg_shade_fn sg_shade_mip_avx2(int index) {
    (void)index;
    return NULL;
}

sg_shade2_fn sg_shade2_mip_avx2(int index) {
    (void)index;
    return NULL;
}

sg_shade_runs_fn sg_shade_runs_mip_avx2(int index) {
    (void)index;
    return NULL;
}

#endif
