/* shade_avx512.c - the shading functions of shade.h in AVX-512 (this file alone is compiled with
 * -mavx512f/bw/vl/dq; no FMA, which would round differently), made of the body in
 * shade_avx512.h. Without AVX-512 (or off x86) every variant is NULL and the AVX2, SSE2 or scalar
 * code is used.
 */
#include "raster/shade_avx512.h"

#include "raster/bin.h"

#if defined(SG_SHADE_AVX512)

/* The mask is the store mask: pixels outside it are not written. */
INLINE void shade_rows(const sg_shade_ctx *c, const sg_tri *t, const sg_tri_ext *ext, int x0,
                       int y0, uint32_t mask, uint32_t *dst, const int textured, const int bilinear,
                       const int repeat, const int flat, const int sec) {
    __m512i v = sg_shade16(c, t, ext, x0, y0, mask, textured, bilinear, repeat, flat, sec);
    _mm512_mask_storeu_epi32(dst, (__mmask16)mask, v);
}

/* Two whole tiles of a triangle at once (sg_shade2_fn), the flat kind split off as in
 * shade_flat. */
INLINE void shade_pair(const sg_shade_ctx *c, const sg_tri *t, const sg_tri_ext *ext, int x0,
                       int y0, int x1, int y1, uint32_t *dst0, uint32_t *dst1, const int textured,
                       const int bilinear, const int repeat, const int flat, const int sec) {
    __m512 dx[2], dy[2];
    sg_tile_dxdy16(t, x0, y0, &dx[0], &dy[0]);
    sg_tile_dxdy16(t, x1, y1, &dx[1], &dy[1]);
    const uint32_t mask[2] = {0xffffu, 0xffffu};
    __m512i v[2];
    shade16_tiles(c, t, NULL, ext, 2, dx, dy, mask, v, textured, bilinear, repeat, flat, sec);
    _mm512_storeu_si512(dst0, v[0]);
    _mm512_storeu_si512(dst1, v[1]);
}

#define SG_SHADE_TABLE sg_shade_avx512
#define SG_MIP_TABLES(table)                                                                       \
    table(sg_shade_fn, sg_shade_mip_avx512, mip) table(sg_shade2_fn, sg_shade2_mip_avx512, pair)
#include "raster/shade_variants.h"

/* Textured variants only: vertex-colour tiles measured no faster in pairs. */
SG_PAIR_VARIANT(1, 0, 1, 0)
SG_PAIR_VARIANT(1, 0, 0, 0)
SG_PAIR_VARIANT(1, 1, 1, 0)
SG_PAIR_VARIANT(1, 1, 0, 0)
SG_PAIR_VARIANT(1, 0, 1, 1)
SG_PAIR_VARIANT(1, 0, 0, 1)
SG_PAIR_VARIANT(1, 1, 1, 1)
SG_PAIR_VARIANT(1, 1, 0, 1)

sg_shade2_fn sg_shade2_avx512(int index) {
    static const sg_shade2_fn table[10] = {NULL, pair_1010, pair_1000, pair_1110, pair_1100,
                                           NULL, pair_1011, pair_1001, pair_1111, pair_1101};
    return table[index];
}

enum { ROW = SG_BIN_SIZE / SG_TILE };

/* shade_runs of a mipmapped triangle: the runs' quads that hold a covered pixel packed four to a
 * vector (sg_quad_queue), two full vectors shaded side by side, each covered lane's colour stored
 * at its own offset; a run whose every quad is touched is shaded as its tile. */
INLINE void shade_quad_runs(const sg_shade_ctx *c, const sg_tri *t, const sg_tri_ext *ext, int bx0,
                            int by0, const sg_run *runs, int n, uint32_t *color, const int textured,
                            const int bilinear, const int repeat, const int flat, const int sec) {
    sg_quad_queue q = {_mm512_setzero_ps(), _mm512_setzero_ps(), _mm512_setzero_si512(), 0, 0};
    sg_quad_queue full[2];
    int nfull = 0;
    for (int i = 0; i < n; i++) {
        const int tile = runs[i].tile;
        const uint32_t mask = runs[i].mask;
        __m512 dx, dy;
        sg_tile_dxdy16(t, bx0 + (tile % ROW) * SG_TILE, by0 + (tile / ROW) * SG_TILE, &dx, &dy);
        if (sg_every_quad(mask)) {
            __m512i v =
                sg_shade16_at(c, t, ext, dx, dy, mask, textured, bilinear, repeat, flat, sec);
            _mm512_mask_storeu_epi32(color + tile * SG_TILE_PIXELS, (__mmask16)mask, v);
            continue;
        }
        if (!sg_enqueue_quads(&q, dx, dy, tile * SG_TILE_PIXELS, mask, &full[nfull]) || ++nfull < 2)
            continue;
        const __m512 fdx[2] = {full[0].dx, full[1].dx}, fdy[2] = {full[0].dy, full[1].dy};
        const uint32_t masks[2] = {full[0].mask, full[1].mask};
        __m512i v[2];
        shade16_tiles(c, t, NULL, ext, 2, fdx, fdy, masks, v, textured, bilinear, repeat, flat,
                      sec);
        for (int k = 0; k < 2; k++)
            _mm512_mask_i32scatter_epi32(color, (__mmask16)masks[k], full[k].off, v[k], 4);
        nfull = 0;
    }
    /* a full vector left, then the queue's last quads */
    for (int k = 0; k < 2; k++) {
        const sg_quad_queue *f = k ? &q : &full[0];
        if (k ? !q.n : !nfull) continue;
        __m512i v =
            sg_shade16_at(c, t, ext, f->dx, f->dy, f->mask, textured, bilinear, repeat, flat, sec);
        _mm512_mask_i32scatter_epi32(color, (__mmask16)f->mask, f->off, v, 4);
    }
}

/* Runs of a triangle (sg_shade_runs_fn): their pixels packed sixteen to a vector (sg_queue16),
 * two full vectors shaded side by side, and each lane's colour stored at its own offset; whole
 * tiles two at a time, stored as they are. */
INLINE void shade_runs(const sg_shade_ctx *c, const sg_tri *t, const sg_tri_ext *ext, int bx0,
                       int by0, const sg_run *runs, int n, uint32_t *color, const int textured,
                       const int bilinear, const int repeat, const int flat, const int sec) {
    sg_queue16 q = {_mm512_setzero_ps(), _mm512_setzero_ps(), _mm512_setzero_si512(), 0};
    sg_queue16 full[2];
    int nfull = 0;
    __m512 whole_dx, whole_dy; /* a whole tile waiting for another */
    int whole = -1;
    for (int i = 0; i < n; i++) {
        const int tile = runs[i].tile;
        __m512 dx, dy;
        sg_tile_dxdy16(t, bx0 + (tile % ROW) * SG_TILE, by0 + (tile / ROW) * SG_TILE, &dx, &dy);
        if (runs[i].mask == 0xffffu) { /* whole tiles two at a time, stored as they are */
            if (whole < 0) {
                whole = tile;
                whole_dx = dx;
                whole_dy = dy;
                continue;
            }
            const __m512 wdx[2] = {whole_dx, dx}, wdy[2] = {whole_dy, dy};
            const uint32_t all[2] = {0xffffu, 0xffffu};
            __m512i v[2];
            shade16_tiles(c, t, NULL, ext, 2, wdx, wdy, all, v, textured, bilinear, repeat, flat,
                          sec);
            _mm512_storeu_si512(color + whole * SG_TILE_PIXELS, v[0]);
            _mm512_storeu_si512(color + tile * SG_TILE_PIXELS, v[1]);
            whole = -1;
            continue;
        }
        if (!sg_enqueue16(&q, dx, dy, tile * SG_TILE_PIXELS, runs[i].mask, &full[nfull]) ||
            ++nfull < 2)
            continue;
        const __m512 fdx[2] = {full[0].dx, full[1].dx}, fdy[2] = {full[0].dy, full[1].dy};
        const uint32_t all[2] = {0xffffu, 0xffffu};
        __m512i v[2];
        shade16_tiles(c, t, NULL, ext, 2, fdx, fdy, all, v, textured, bilinear, repeat, flat, sec);
        _mm512_i32scatter_epi32(color, full[0].off, v[0], 4);
        _mm512_i32scatter_epi32(color, full[1].off, v[1], 4);
        nfull = 0;
    }
    if (whole >= 0) {
        __m512i v = sg_shade16_at(c, t, ext, whole_dx, whole_dy, 0xffffu, textured, bilinear,
                                  repeat, flat, sec);
        _mm512_storeu_si512(color + whole * SG_TILE_PIXELS, v);
    }
    if (nfull) {
        __m512i v = sg_shade16_at(c, t, ext, full[0].dx, full[0].dy, 0xffffu, textured, bilinear,
                                  repeat, flat, sec);
        _mm512_i32scatter_epi32(color, full[0].off, v, 4);
    }
    if (q.n) {
        const __mmask16 m = (__mmask16)((1u << q.n) - 1u);
        __m512i v = sg_shade16_at(c, t, ext, q.dx, q.dy, m, textured, bilinear, repeat, flat, sec);
        _mm512_mask_i32scatter_epi32(color, m, q.off, v, 4);
    }
}

#define SG_RUNS_TABLE sg_shade_runs_avx512
#include "raster/shade_runs_variants.h"

/* The mipmapped runs (shade_quad_runs), by the index of sg_shade_mip_select. */
#define SG_MIP_RUNS(tex, bil, rep, sec) SG_RUNS_VARIANT(shade_quad_runs, tex, bil, rep, sec)
SG_MIP_EACH(SG_MIP_RUNS, 2)
SG_MIP_EACH(SG_MIP_RUNS, 3)
#undef SG_MIP_RUNS
#undef SG_MIP_EACH

SG_MIP_TABLE(sg_shade_runs_fn, sg_shade_runs_mip_avx512, runs)

/* `count` tiles that several triangles share (sg_shade_mixed_fn), their triangles all of the flat
 * kind `flat`: shaded side by side, each stored under its mask. */
INLINE void shade_mixed(const sg_shade_ctx *c, const sg_mixed_tile *tiles, const int count,
                        const int textured, const int bilinear, const int repeat, const int flat) {
    uint32_t all[2] = {0, 0};
    for (int i = 0; i < count; i++)
        for (int j = 0; j < tiles[i].n; j++) all[i] |= tiles[i].masks[j];
    __m512i v[2];
    sg_shade16_mixed(c, tiles, count, all, v, textured, bilinear, repeat, flat);
    for (int i = 0; i < count; i++) _mm512_mask_storeu_epi32(tiles[i].dst, (__mmask16)all[i], v[i]);
}

#define SG_MIXED_TABLE sg_shade_mixed_avx512
#include "raster/shade_mixed.h"

#else

sg_shade_fn sg_shade_avx512(int index) {
    (void)index;
    return NULL;
}

sg_shade2_fn sg_shade2_avx512(int index) {
    (void)index;
    return NULL;
}

sg_shade_runs_fn sg_shade_runs_avx512(int index) {
    (void)index;
    return NULL;
}

sg_shade_fn sg_shade_mip_avx512(int index) {
    (void)index;
    return NULL;
}

sg_shade2_fn sg_shade2_mip_avx512(int index) {
    (void)index;
    return NULL;
}

sg_shade_runs_fn sg_shade_runs_mip_avx512(int index) {
    (void)index;
    return NULL;
}

sg_shade_mixed_fn sg_shade_mixed_avx512(int index) {
    (void)index;
    return NULL;
}

#endif
