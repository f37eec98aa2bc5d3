/* blend_avx512.c - the raster functions of draws shaded in place in AVX-512 (see blend.h): a whole
 * tile a vector, the pixels of partly covered tiles of a textured triangle packed sixteen to a
 * vector; the same depth (z, clamp, compare) as the scalar and SSE2 code, the shading body of
 * shade_avx512.h inlined (a call per tile would spill every vector register of the walk; a
 * textured draw's tiles and full queues are collected during its triangles' walks and shaded
 * later in the bin, four at a time, by one function per texture variant: blend_walk.h), and the
 * same integer blend, so the same bytes. One function per shading variant and depth state;
 * opaque lines of vertex colours put their fragments in place, sixteen columns of the line a
 * vector (put_line). */
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

/* A fragment colour the same at every pixel (a triangle of one colour, untextured): its part of
 * the blend, s a / 255, and 255 - a, in 16-bit lanes (four pixels), worked out once a triangle.
 */
typedef struct flat_src {
    __m512i sa, ia;
} flat_src;

INLINE flat_src flat_src_of(uint32_t px) {
    const __m512i s = _mm512_unpacklo_epi8(_mm512_set1_epi32((int)px), _mm512_setzero_si512());
    const __m512i a = _mm512_shufflehi_epi16(_mm512_shufflelo_epi16(s, 0xff), 0xff);
    return (flat_src){mul_unorm8(s, a), _mm512_sub_epi16(_mm512_set1_epi16(255), a)};
}

/* blend16 of that colour over sixteen packed RGBA8 pixels: the same sums, half the products. */
INLINE __m512i blend16_flat(const flat_src *f, __m512i d) {
    const __m512i zero = _mm512_setzero_si512();
    __m512i lo = _mm512_add_epi16(f->sa, mul_unorm8(_mm512_unpacklo_epi8(d, zero), f->ia));
    __m512i hi = _mm512_add_epi16(f->sa, mul_unorm8(_mm512_unpackhi_epi8(d, zero), f->ia));
    return _mm512_packus_epi16(lo, hi);
}

/* Sixteen packed RGBA8 fragments over sixteen packed RGBA8 pixels (sg_blend_rgba8). */
INLINE __m512i blend16(__m512i s, __m512i d) {
    const __m512i zero = _mm512_setzero_si512();
    __m512i lo = blend_lanes(_mm512_unpacklo_epi8(s, zero), _mm512_unpacklo_epi8(d, zero));
    __m512i hi = blend_lanes(_mm512_unpackhi_epi8(s, zero), _mm512_unpackhi_epi8(d, zero));
    return _mm512_packus_epi16(lo, hi);
}

/* Sixteen pixels of a textured triangle ready to shade: a whole tile, blended in place at bin
 * offset base, or a full (or the triangle's last, partial) queue, blended through its offsets
 * (the queue, sg_queue16 in shade_avx512.h, holds pixels of one triangle). The walks collect them
 * in the bin's list (blend_walk.h); they are shaded later, four side by side (shade16_tiles): a
 * shading is a long chain of dependent steps, and several keep the vector units busy. */
typedef struct job {
    __m512 dx, dy;
    __m512i off;
    const sg_tri *t;
    int base; /* -1: scattered through off */
    uint32_t mask;
} job;

/* Jobs a triangle's walk collects before they are shaded, and how many are shaded side by side
 * (as in blend_avx2.c). */
enum { JOBS = 32, JOB_SETS = 4 };

typedef struct queued_ctx {
    const sg_vis_ctx *v;
    sg_queue16 *q;
    sg_quad_queue *quads;   /* mipmapped triangles' */
    sg_blend_pending *jobs; /* the bin's */
    const flat_src *flat;   /* untextured triangles of one colour */
} queued_ctx;

/* The fragments s of the pixels of q's lanes m blended into their pixels of the bin's colour
 * (every offset is a pixel of the bin, and no two lanes of m share one). */
INLINE void blend_scattered(const sg_vis_ctx *v, const sg_queue16 *q, __m512i s, __mmask16 m) {
    __m512i d = _mm512_mask_i32gather_epi32(_mm512_setzero_si512(), m, q->off, v->color, 4);
    _mm512_mask_i32scatter_epi32(v->color, m, q->off, blend16(s, d), 4);
}

/* The shaded fragments s of a job blended into the bin's colour. */
INLINE void finish(const sg_vis_ctx *v, const job *j, __m512i s) {
    if (j->base >= 0) { /* a tile: whole, or a mipmapped triangle's with every quad touched */
        uint32_t *dst = v->color + j->base;
        _mm512_mask_store_epi32(dst, (__mmask16)j->mask, blend16(s, _mm512_load_si512(dst)));
    } else {
        const sg_queue16 q = {j->dx, j->dy, j->off, 0};
        blend_scattered(v, &q, s, (__mmask16)j->mask);
    }
}

/* The lanes of `mask` (the tile at bin offset base, pixels at dx, dy) that pass the depth test,
 * their depth written when the pipeline writes depth; with neither, mask itself. */
INLINE uint32_t depth16(const sg_vis_ctx *v, const sg_tri *t, __m512 dx, __m512 dy, int base,
                        uint32_t mask, const int ztest, const int zwrite) {
    if (!ztest && !zwrite) return mask;
    float *dp = v->depth + base;
    __m512 z = sg_z16(t, dx, dy);
    if (ztest) mask = sg_compare16(v->compare, (__mmask16)mask, z, _mm512_loadu_ps(dp));
    if (zwrite) _mm512_mask_storeu_ps(dp, (__mmask16)mask, z);
    return mask;
}

/* n jobs (a constant) shaded side by side (shade16_tiles) and blended, in their order. */
INLINE void shade_some(const sg_vis_ctx *v, const job *j, const int n, const int textured,
                       const int bilinear, const int repeat, const int flat) {
    __m512 dx[JOB_SETS], dy[JOB_SETS];
    uint32_t mask[JOB_SETS];
    __m512i s[JOB_SETS];
    const sg_tri *ts[JOB_SETS];
    for (int i = 0; i < n; i++) {
        dx[i] = j[i].dx;
        dy[i] = j[i].dy;
        mask[i] = j[i].mask;
        ts[i] = j[i].t;
    }
    shade16_tiles(v->shade_ctx, ts[0], ts, NULL, n, dx, dy, mask, s, textured, bilinear, repeat,
                  flat, 0);
    for (int i = 0; i < n; i++) finish(v, &j[i], s[i]);
}

SG_JOB_LIST_FNS
SG_MIP_JOB_FNS
#define blend_jobs_000 NULL /* vertex colours: shaded in place, no jobs */

INLINE void blend_avx512(const void *vctx, const sg_tri *t, int x0, int y0, uint32_t mask,
                         const int ztest, const int zwrite, const int textured) {
    queued_ctx *p = (queued_ctx *)(uintptr_t)vctx; /* the walk's context, this function's own */
    const sg_vis_ctx *v = p->v;
    const int base = sg_bin_tile_offset(x0 - v->bx0, y0 - v->by0);
    __m512 dx, dy;
    sg_tile_dxdy16(t, x0, y0, &dx, &dy);
    mask = depth16(v, t, dx, dy, base, mask, ztest, zwrite);
    if (!mask) return;
    if (!textured && t->flat != SG_FLAT_NONE) {
        uint32_t *dst = v->color + base;
        _mm512_mask_storeu_epi32(dst, (__mmask16)mask,
                                 blend16_flat(p->flat, _mm512_load_si512(dst)));
        return;
    }
    if (!textured) { /* vertex colours cost less to shade than to queue */
        __m512i s = shade(v, t, dx, dy, mask, 0, 0, 0);
        uint32_t *dst = v->color + base;
        _mm512_mask_storeu_epi32(dst, (__mmask16)mask, blend16(s, _mm512_load_si512(dst)));
        return;
    }
    if (mask == 0xffffu || (textured >= SG_TEX_MIP && sg_every_quad(mask))) {
        /* a whole tile needs no packing, nor a tile whose every quad is shaded anyway */
        const job j = {dx, dy, _mm512_setzero_si512(), t, base, mask};
        submit(p, &j);
        return;
    }
    if (textured >= SG_TEX_MIP) {
        sg_quad_queue full;
        if (sg_enqueue_quads(p->quads, dx, dy, base, mask, &full)) {
            const job j = {full.dx, full.dy, full.off, t, -1, full.mask};
            submit(p, &j);
        }
        return;
    }
    sg_queue16 full;
    if (sg_enqueue16(p->q, dx, dy, base, (__mmask16)mask, &full)) {
        const job j = {full.dx, full.dy, full.off, t, -1, 0xffffu};
        submit(p, &j);
    }
}

/* The end of a triangle: its partial queue joins the jobs waiting. */
INLINE void drain(queued_ctx *p, const sg_tri *t, const int textured) {
    if (textured >= SG_TEX_MIP) {
        const sg_quad_queue *q = p->quads;
        if (q->n) submit(p, &(job){q->dx, q->dy, q->off, t, -1, q->mask});
        return;
    }
    const sg_queue16 *q = p->q;
    if (q->n) submit(p, &(job){q->dx, q->dy, q->off, t, -1, (1u << q->n) - 1u});
}

/* One raster function per shading variant (vertex colour; texture nearest / bilinear, repeat /
 * clamp: tex, bil, rep) and depth state (test, write); the pixels left in the queue join the
 * jobs waiting at the end. */
#define SG_BLEND_QUEUED(tex, bil, rep, zt, zw)                                                     \
    static inline void blend_##tex##bil##rep##zt##zw##_tile(const void *c, const sg_tri *t,        \
                                                            int x0, int y0, uint32_t m) {          \
        blend_avx512(c, t, x0, y0, m, zt, zw, tex);                                                \
    }                                                                                              \
    static void blend_##tex##bil##rep##zt##zw(const sg_tri *t, int x0, int y0, int x1, int y1,     \
                                              const void *c) {                                     \
        sg_queue16 q = {_mm512_setzero_ps(), _mm512_setzero_ps(), _mm512_setzero_si512(), 0};      \
        queued_ctx p;                                                                              \
        p.v = c;                                                                                   \
        p.q = &q;                                                                                  \
        p.jobs = p.v->pending;                                                                     \
        sg_quad_queue quads = {_mm512_setzero_ps(), _mm512_setzero_ps(), _mm512_setzero_si512(),   \
                               0, 0};                                                              \
        p.quads = tex >= SG_TEX_MIP ? &quads : NULL;                                               \
        const flat_src f =                                                                         \
            flat_src_of(!tex && t->flat != SG_FLAT_NONE ? sg_flat_pixel(t, NULL, 0) : 0u);         \
        p.flat = &f;                                                                               \
        if (tex) start_jobs(&p, t, blend_jobs_##tex##bil##rep);                                    \
        sg_rast_walk(t, x0, y0, x1, y1, blend_##tex##bil##rep##zt##zw##_tile, &p);                 \
        if (tex) drain(&p, t, tex); /* vertex colours were blended in place */                     \
    }
SG_BLEND_VARIANTS(SG_BLEND_QUEUED)
/* Mipmapped textures, unlit (textured SG_TEX_MIP, SG_TEX_MIP_LINEAR) */
SG_BLEND_MIP_VARIANTS(SG_BLEND_QUEUED)

sg_raster_fn sg_blend_avx512(int variant, bool depth_test, bool depth_write) {
    static const sg_raster_fn fns[5][4] = SG_BLEND_TABLE; /* in sg_shade_variant order */
    return fns[variant][(depth_test ? 2 : 0) + (depth_write ? 1 : 0)];
}

sg_raster_fn sg_blend_mip_avx512(int index, bool depth_test, bool depth_write) {
    static const sg_raster_fn fns[8][4] = SG_BLEND_MIP_TABLE;
    return fns[index][(depth_test ? 2 : 0) + (depth_write ? 1 : 0)];
}

/* An opaque vertex-coloured line's tile: the passing pixels shaded and put in place. */
INLINE void put_inline(const void *vctx, const sg_tri *t, int x0, int y0, uint32_t mask,
                       const int zmode, const int zwrite) {
    const sg_vis_ctx *v = vctx;
    const int base = sg_bin_tile_offset(x0 - v->bx0, y0 - v->by0);
    __m512 dx, dy;
    sg_tile_dxdy16(t, x0, y0, &dx, &dy);
    mask = depth16(v, t, dx, dy, base, mask, zmode != Z_NONE, zwrite);
    if (!mask) return;
    _mm512_mask_storeu_epi32(v->color + base, (__mmask16)mask, shade(v, t, dx, dy, mask, 0, 0, 0));
}

SG_IN_PLACE_SET(put, put_inline)

/* An opaque vertex-coloured line put along its major axis, sixteen columns a vector: a line has
 * one pixel a column, so a tile holds at most four of them, and the tile walk shades a vector of
 * sixteen lanes for one to four pixels. Here each lane is a pixel, its depth and colour gathered
 * and scattered through its offset in the bin. The pixels of a line are all different, so the
 * order of the stores changes nothing; each lane computes what put_inline computes for its
 * pixel, so the bytes are the same. */
INLINE void put_line(const sg_tri *t, int rx0, int ry0, int rx1, int ry1, const sg_vis_ctx *v,
                     const int zmode, const int zwrite) {
    sg_line_dda d;
    if (!sg_line_dda_start(t, rx0, ry0, rx1, ry1, &d)) return;
    const __m512i lane = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
    const __m512i three = _mm512_set1_epi32(3);
    for (int u = d.u0; u <= d.u1; u += 16) {
        _Alignas(64) int32_t vs[16];
        uint32_t bits = sg_line_dda_columns(&d, vs, 16, d.u1 - u < 15 ? d.u1 - u + 1 : 16);
        if (!bits) continue;
        const __m512i cu = _mm512_add_epi32(_mm512_set1_epi32(u), lane);
        const __m512i cv = _mm512_load_si512(vs);
        const __m512i x = d.xm ? cu : cv, y = d.xm ? cv : cu;
        const __m512 dx = _mm512_cvtepi32_ps(_mm512_sub_epi32(x, _mm512_set1_epi32(t->minx)));
        const __m512 dy = _mm512_cvtepi32_ps(_mm512_sub_epi32(y, _mm512_set1_epi32(t->miny)));
        /* The pixel's place in the bin: its tile's (sg_bin_tile_offset), then its row and column.
         */
        const __m512i bx = _mm512_sub_epi32(x, _mm512_set1_epi32(v->bx0));
        const __m512i by = _mm512_sub_epi32(y, _mm512_set1_epi32(v->by0));
        const __m512i off =
            _mm512_add_epi32(_mm512_add_epi32(_mm512_slli_epi32(_mm512_srli_epi32(by, 2), 8),
                                              _mm512_slli_epi32(_mm512_srli_epi32(bx, 2), 4)),
                             _mm512_add_epi32(_mm512_slli_epi32(_mm512_and_si512(by, three), 2),
                                              _mm512_and_si512(bx, three)));
        if (zmode != Z_NONE || zwrite) {
            const __m512 z = sg_z16(t, dx, dy);
            if (zmode != Z_NONE) {
                const __m512 dd = _mm512_mask_i32gather_ps(_mm512_setzero_ps(), (__mmask16)bits,
                                                           off, v->depth, 4);
                bits = sg_compare16(v->compare, (__mmask16)bits, z, dd);
                if (!bits) continue;
            }
            if (zwrite) _mm512_mask_i32scatter_ps(v->depth, (__mmask16)bits, off, z, 4);
        }
        _mm512_mask_i32scatter_epi32(v->color, (__mmask16)bits, off,
                                     shade(v, t, dx, dy, bits, 0, 0, 0), 4);
    }
}

SG_PUT_LINE_SET(put_line)

sg_raster_fn sg_put_avx512(bool depth_test, bool depth_write) {
    static const sg_raster_fn fns[2][2] = SG_IN_PLACE_TABLE(put_line);
    return fns[depth_test][depth_write];
}

/* Shader draws in place (shade_shader_walk.h): tile_depth and put_tile of shade_shader_tile.h a
 * whole tile a vector, in depth_simd.h's operations (the same as tile_depth's, so its bits). */
static inline uint32_t shader_tile_depth(const sg_tri *t, int x0, int y0, uint32_t mask,
                                         const float *dp, sgCompare op, float *z) {
    __m512 dx, dy;
    sg_tile_dxdy16(t, x0, y0, &dx, &dy);
    const __m512 zc = sg_z16(t, dx, dy);
    _mm512_store_ps(z, zc);
    return dp ? sg_compare16(op, (__mmask16)mask, zc, _mm512_loadu_ps(dp)) : mask;
}

static inline void shader_put_tile(uint32_t keep, const float *z, float *dp, const uint32_t *src,
                                   uint32_t *dst) {
    if (dp) _mm512_mask_storeu_ps(dp, (__mmask16)keep, _mm512_load_ps(z));
    _mm512_mask_storeu_epi32(dst, (__mmask16)keep, _mm512_load_si512(src));
}

#define SG_SHADER_TILE_DEPTH(v, t, x0, y0, mask, dp, op, z)                                        \
    shader_tile_depth(t, x0, y0, mask, dp, op, z)
#define SG_SHADER_PUT_TILE(v, keep, z, dp, src, dst) shader_put_tile(keep, z, dp, src, dst)
#include "raster/shade_shader_walk.h"

sg_raster_fn sg_shader_in_place_avx512(int kind, bool depth_test, bool depth_write) {
    return sg_shader_walks[kind][depth_test][depth_write];
}

#else

sg_raster_fn sg_shader_in_place_avx512(int kind, bool depth_test, bool depth_write) {
    (void)kind;
    (void)depth_test;
    (void)depth_write;
    return NULL;
}

sg_raster_fn sg_blend_avx512(int variant, bool depth_test, bool depth_write) {
    (void)variant;
    (void)depth_test;
    (void)depth_write;
    return NULL;
}

sg_raster_fn sg_blend_mip_avx512(int index, bool depth_test, bool depth_write) {
    (void)index;
    (void)depth_test;
    (void)depth_write;
    return NULL;
}

sg_raster_fn sg_put_avx512(bool depth_test, bool depth_write) {
    (void)depth_test;
    (void)depth_write;
    return NULL;
}

#endif
