/* blend_avx512.c - the raster functions of blended draws in AVX-512 (see blend.h): a whole tile
 * a vector, the pixels of partly covered tiles of a textured triangle packed sixteen to a vector;
 * the same depth (z, clamp, compare) as the scalar and SSE2 code, the shading body of
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

/* Sixteen packed RGBA8 fragments over sixteen packed RGBA8 pixels (sg_blend_rgba8). */
INLINE __m512i blend16(__m512i s, __m512i d) {
    const __m512i zero = _mm512_setzero_si512();
    __m512i lo = blend_lanes(_mm512_unpacklo_epi8(s, zero), _mm512_unpacklo_epi8(d, zero));
    __m512i hi = blend_lanes(_mm512_unpackhi_epi8(s, zero), _mm512_unpackhi_epi8(d, zero));
    return _mm512_packus_epi16(lo, hi);
}

/* Up to sixteen pixels of a triangle waiting to be shaded together (a partly covered tile fills
 * few lanes, and the shading costs the same for 1 pixel as for 16): their offsets from the
 * triangle's bounds and in the bin's colour, lanes 0 to n - 1. The tiles of one triangle share no
 * pixel, so blending a pixel later changes nothing, as long as it is done before the next
 * triangle. */
typedef struct queue {
    __m512 dx, dy;
    __m512i off;
    int n;
} queue;

typedef struct queued_ctx {
    const sg_vis_ctx *v;
    queue *q;
} queued_ctx;

/* Appends the pixels of mask of a tile (offsets dx, dy; colour at bin offset base) to q: packed,
 * then rotated to start at lane n. When that fills the queue, full gets the sixteen lanes to
 * shade and q keeps the rest; true then. */
INLINE bool enqueue(queue *q, __m512 dx, __m512 dy, int base, __mmask16 mask, queue *full) {
    const __m512i lane = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
    const int n = q->n, k = __builtin_popcount(mask);
    /* Lane j takes packed pixel (j - n) mod 16: the first 16 - n go after the queue's n, the ones
     * that do not fit into lanes 0 to n + k - 17. */
    __m512i from =
        _mm512_and_si512(_mm512_sub_epi32(lane, _mm512_set1_epi32(n)), _mm512_set1_epi32(15));
    __m512 rdx = _mm512_permutexvar_ps(from, _mm512_maskz_compress_ps(mask, dx));
    __m512 rdy = _mm512_permutexvar_ps(from, _mm512_maskz_compress_ps(mask, dy));
    __m512i roff = _mm512_permutexvar_epi32(
        from, _mm512_maskz_compress_epi32(mask, _mm512_add_epi32(_mm512_set1_epi32(base), lane)));
    const __mmask16 keep = (__mmask16)((1u << n) - 1u);
    queue merged = {_mm512_mask_mov_ps(rdx, keep, q->dx), _mm512_mask_mov_ps(rdy, keep, q->dy),
                    _mm512_mask_mov_epi32(roff, keep, q->off), n + k};
    if (n + k < 16) {
        *q = merged;
        return false;
    }
    *full = merged;
    *q = (queue){rdx, rdy, roff, n + k - 16};
    return true;
}

/* The fragments s of the pixels of q's lanes m blended into their pixels of the bin's colour
 * (every offset is a pixel of the bin, and no two lanes of m share one). */
INLINE void blend_scattered(const sg_vis_ctx *v, const queue *q, __m512i s, __mmask16 m) {
    __m512i d = _mm512_mask_i32gather_epi32(_mm512_setzero_si512(), m, q->off, v->color, 4);
    _mm512_mask_i32scatter_epi32(v->color, m, q->off, blend16(s, d), 4);
}

INLINE void blend_avx512(const void *vctx, const sg_tri *t, int x0, int y0, uint32_t mask,
                         const int ztest, const int zwrite, const int textured, const int bilinear,
                         const int repeat) {
    const queued_ctx *p = vctx;
    const sg_vis_ctx *v = p->v;
    const int base = sg_bin_tile_offset(x0 - v->bx0, y0 - v->by0);
    __m512 dx, dy;
    sg_tile_dxdy16(t, x0, y0, &dx, &dy);
    if (ztest || zwrite) {
        float *dp = v->depth + base;
        __m512 z = sg_z16(t, dx, dy);
        mask = sg_compare16(v->compare, (__mmask16)mask, z, _mm512_loadu_ps(dp));
        if (zwrite) _mm512_mask_storeu_ps(dp, (__mmask16)mask, z);
    }
    if (!mask) return;
    /* Whole tiles need no packing, and vertex colours cost less to shade than to queue. One
     * shading call site for both (each is a large body). */
    const bool in_place = mask == 0xffffu || !textured;
    queue job = {dx, dy, _mm512_setzero_si512(), 16};
    if (!in_place && !enqueue(p->q, dx, dy, base, (__mmask16)mask, &job)) return;
    __m512i s = shade(v, t, job.dx, job.dy, in_place ? mask : 0xffffu, textured, bilinear, repeat);
    if (in_place) {
        uint32_t *dst = v->color + base;
        _mm512_mask_storeu_epi32(dst, (__mmask16)mask, blend16(s, _mm512_load_si512(dst)));
    } else {
        blend_scattered(v, &job, s, 0xffff);
    }
}

/* One raster function per shading variant (vertex colour; texture nearest / bilinear, repeat /
 * clamp: tex, bil, rep) and depth state (test, write); the pixels left in the queue are shaded
 * at the end. */
#define SG_BLEND_QUEUED(tex, bil, rep, zt, zw)                                                     \
    static inline void blend_##tex##bil##rep##zt##zw##_tile(const void *c, const sg_tri *t,        \
                                                            int x0, int y0, uint32_t m) {          \
        blend_avx512(c, t, x0, y0, m, zt, zw, tex, bil, rep);                                      \
    }                                                                                              \
    static void blend_##tex##bil##rep##zt##zw(const sg_tri *t, int x0, int y0, int x1, int y1,     \
                                              const void *c) {                                     \
        queue q = {_mm512_setzero_ps(), _mm512_setzero_ps(), _mm512_setzero_si512(), 0};           \
        queued_ctx p = {c, &q};                                                                    \
        sg_rast_walk(t, x0, y0, x1, y1, blend_##tex##bil##rep##zt##zw##_tile, &p);                 \
        if (q.n) {                                                                                 \
            const __mmask16 m = (__mmask16)((1u << q.n) - 1u);                                     \
            blend_scattered(c, &q, shade(c, t, q.dx, q.dy, m, tex, bil, rep), m);                  \
        }                                                                                          \
    }
SG_BLEND_VARIANTS(SG_BLEND_QUEUED)

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
