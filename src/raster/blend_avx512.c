/* blend_avx512.c - the raster functions of blended draws in AVX-512 (see blend.h): a whole tile
 * a vector; the same depth (z, clamp, compare) as the scalar and SSE2 code, the shading body of
 * shade_avx512.h inlined (a call per tile would spill every vector register of the walk), and
 * the same integer blend, so the same bytes. One function per shading variant and depth state. */
#include "raster/blend.h"

#include "raster/depth_simd.h"
#include "raster/blend_walk.h"
#include "raster/shade_avx512.h"

#if defined(SG_SHADE_AVX512)

/* x y / 255 as sg_mul_unorm8 rounds it, in 16-bit lanes. */
static inline __m512i mul_unorm8(__m512i x, __m512i y) {
    __m512i t = _mm512_mullo_epi16(x, y);
    t = _mm512_add_epi16(_mm512_add_epi16(t, _mm512_srli_epi16(t, 8)), _mm512_set1_epi16(128));
    return _mm512_srli_epi16(t, 8);
}

/* Pixels in 16-bit lanes (r g b a ...): src over dst by src's alpha. */
static inline __m512i blend_lanes(__m512i s, __m512i d) {
    __m512i a = _mm512_shufflehi_epi16(_mm512_shufflelo_epi16(s, 0xff), 0xff);
    __m512i ia = _mm512_sub_epi16(_mm512_set1_epi16(255), a);
    return _mm512_add_epi16(mul_unorm8(s, a), mul_unorm8(d, ia));
}

/* The pipeline's colours of lanes `mask` at offsets (dx, dy), flat colours split off per
 * triangle. */
INLINE __m512i shade(const sg_vis_ctx *v, const sg_tri *t, __m512 dx, __m512 dy, uint32_t mask,
                     const int textured, const int bilinear, const int repeat) {
    const sg_shade_ctx *c = v->shade_ctx;
    if (t->flat == SG_FLAT_WHITE)
        return sg_shade16_at(c, t, NULL, dx, dy, mask, textured, bilinear, repeat, SG_FLAT_WHITE,
                             0);
    if (t->flat == SG_FLAT_COLOR)
        return sg_shade16_at(c, t, NULL, dx, dy, mask, textured, bilinear, repeat, SG_FLAT_COLOR,
                             0);
    return sg_shade16_at(c, t, NULL, dx, dy, mask, textured, bilinear, repeat, SG_FLAT_NONE, 0);
}

/* Blends the fragments s of the pixels of mask into the tile's colour. */
INLINE void blend_store(uint32_t *dst, __m512i s, __mmask16 mask) {
    const __m512i zero = _mm512_setzero_si512();
    __m512i d = _mm512_load_si512(dst);
    __m512i lo = blend_lanes(_mm512_unpacklo_epi8(s, zero), _mm512_unpacklo_epi8(d, zero));
    __m512i hi = blend_lanes(_mm512_unpackhi_epi8(s, zero), _mm512_unpackhi_epi8(d, zero));
    _mm512_mask_storeu_epi32(dst, mask, _mm512_packus_epi16(lo, hi));
}

/* A triangle's raster state: its bin, and one tile of at most 8 visible pixels that waits for a
 * second such tile to share a shading call with (small triangles cover tiles sparsely; the
 * shading costs the same for 1 pixel as for 16). The tiles of one triangle share no pixel, so
 * blending a tile later changes nothing, as long as it is done before the next triangle. */
typedef struct pending {
    int x0, y0;
    uint32_t mask;
} pending;

typedef struct pairing {
    const sg_vis_ctx *v;
    pending *wait;
} pairing;

INLINE void shade_tile_alone(const sg_vis_ctx *v, const sg_tri *t, int x0, int y0, uint32_t mask,
                             const int textured, const int bilinear, const int repeat) {
    __m512 dx, dy;
    sg_tile_dxdy16(t, x0, y0, &dx, &dy);
    __m512i s = shade(v, t, dx, dy, mask, textured, bilinear, repeat);
    blend_store(v->color + sg_bin_tile_offset(x0 - v->bx0, y0 - v->by0), s, (__mmask16)mask);
}

/* One shading call for the pixels of two sparse tiles: A's pixels packed in the low lanes, B's
 * after them, and the results spread back to each tile's layout. */
INLINE void shade_pair(const sg_vis_ctx *v, const sg_tri *t, const pending *a, int x0, int y0,
                       uint32_t mask, const int textured, const int bilinear, const int repeat) {
    int k = __builtin_popcount(a->mask), n = __builtin_popcount(mask);
    __mmask16 am = (__mmask16)a->mask, bm = (__mmask16)mask;
    __mmask16 lanes_b = (__mmask16)(((1u << n) - 1u) << k);
    __m512 adx, ady, bdx, bdy;
    sg_tile_dxdy16(t, a->x0, a->y0, &adx, &ady);
    sg_tile_dxdy16(t, x0, y0, &bdx, &bdy);
    __m512 dx = _mm512_mask_expand_ps(_mm512_maskz_compress_ps(am, adx), lanes_b,
                                      _mm512_maskz_compress_ps(bm, bdx));
    __m512 dy = _mm512_mask_expand_ps(_mm512_maskz_compress_ps(am, ady), lanes_b,
                                      _mm512_maskz_compress_ps(bm, bdy));
    __m512i s = shade(v, t, dx, dy, (1u << (k + n)) - 1u, textured, bilinear, repeat);
    blend_store(v->color + sg_bin_tile_offset(a->x0 - v->bx0, a->y0 - v->by0),
                _mm512_maskz_expand_epi32(am, s), am);
    blend_store(v->color + sg_bin_tile_offset(x0 - v->bx0, y0 - v->by0),
                _mm512_maskz_expand_epi32(bm, _mm512_maskz_compress_epi32(lanes_b, s)), bm);
}

INLINE void blend_avx512(const void *vctx, const sg_tri *t, int x0, int y0, uint32_t mask,
                         const int ztest, const int zwrite, const int textured, const int bilinear,
                         const int repeat) {
    const pairing *p = vctx;
    const sg_vis_ctx *v = p->v;
    if (ztest || zwrite) {
        float *dp = v->depth + sg_bin_tile_offset(x0 - v->bx0, y0 - v->by0);
        __m512 dx, dy;
        sg_tile_dxdy16(t, x0, y0, &dx, &dy);
        __m512 z = sg_z16(t, dx, dy);
        mask = sg_compare16(v->compare, (__mmask16)mask, z, _mm512_loadu_ps(dp));
        if (zwrite) _mm512_mask_storeu_ps(dp, (__mmask16)mask, z);
    }
    if (!mask) return;
    /* A flat colour costs nothing to shade: no pairing. */
    if ((!textured && t->flat != SG_FLAT_NONE) || __builtin_popcount(mask) > 8) {
        shade_tile_alone(v, t, x0, y0, mask, textured, bilinear, repeat);
        return;
    }
    pending *w = p->wait;
    if (!w->mask) {
        *w = (pending){x0, y0, mask};
        return;
    }
    shade_pair(v, t, w, x0, y0, mask, textured, bilinear, repeat);
    w->mask = 0;
}

/* One raster function per shading variant (vertex colour; texture nearest / bilinear, repeat /
 * clamp: tex, bil, rep) and depth state (test, write); a tile left waiting for a partner is
 * shaded alone at the end. */
#define SG_BLEND_PAIRED(tex, bil, rep, zt, zw)                                                     \
    static inline void blend_##tex##bil##rep##zt##zw##_tile(const void *c, const sg_tri *t,        \
                                                            int x0, int y0, uint32_t m) {          \
        blend_avx512(c, t, x0, y0, m, zt, zw, tex, bil, rep);                                      \
    }                                                                                              \
    static void blend_##tex##bil##rep##zt##zw(const sg_tri *t, int x0, int y0, int x1, int y1,     \
                                              const void *c) {                                     \
        pending wait = {0, 0, 0};                                                                  \
        pairing p = {c, &wait};                                                                    \
        sg_rast_walk(t, x0, y0, x1, y1, blend_##tex##bil##rep##zt##zw##_tile, &p);                 \
        if (wait.mask) shade_tile_alone(c, t, wait.x0, wait.y0, wait.mask, tex, bil, rep);         \
    }
SG_BLEND_VARIANTS(SG_BLEND_PAIRED)

sg_raster_fn sg_blend_avx512(int variant, bool depth_test, bool depth_write) {
    static const sg_raster_fn fns[5][4] = SG_BLEND_TABLE; /* in sg_shade_variant order */
    return fns[variant][(depth_test ? 2 : 0) + (depth_write ? 1 : 0)];
}

#else

sg_raster_fn sg_blend_avx512(int variant, bool depth_test, bool depth_write) {
    (void)variant;
    (void)depth_test;
    (void)depth_write;
    return NULL;
}

#endif
