/* blend_avx2.c - the raster functions of draws shaded in place in AVX2 (see blend.h): two rows of
 * a tile a vector; the same depth (z, clamp, compare) as the scalar and SSE2 code, the same
 * shading and the same integer blend, so the same bytes.
 *
 * Unlit draws inline the shading body of shade_avx2.h (one function per shading variant and depth
 * state, as in blend_avx512.c): no call per tile, no tile buffer. A pair of rows whose eight
 * pixels all pass is shaded and blended in place; the pixels of partly covered pairs of textured
 * draws are packed into a queue of eight lanes, shaded when it is full (small triangles and edges
 * cover tiles sparsely, and a shading pass costs the same for one pixel as for eight). The whole
 * pairs and full queues of a textured draw are collected as jobs during its triangles' walks and
 * shaded later in the bin, four side by side, in the order they came (blend_walk.h); a mipmapped
 * draw's sets hold whole 2 x 2 quads instead of packed pixels (sg_pair_quad8). Lit draws call the
 * draw's shading function per tile. Opaque lines put their fragments in place: vertex colours eight
 * columns of the line a vector (put_line), the others through the draw's function per tile.
 */
#include "raster/blend.h"

#include "raster/blend_walk.h"
#include "raster/depth_simd.h"
#include "raster/shade_avx2.h"

#if defined(SG_SHADE_AVX2)

/* x y / 255 as sg_mul_unorm8 rounds it, in 16-bit lanes. */
static inline __m256i mul_unorm8(__m256i x, __m256i y) {
    __m256i t = _mm256_mullo_epi16(x, y);
    t = _mm256_add_epi16(_mm256_add_epi16(t, _mm256_srli_epi16(t, 8)), _mm256_set1_epi16(128));
    return _mm256_srli_epi16(t, 8);
}

/* Pixels in 16-bit lanes (r g b a ...): src over dst by src's alpha. */
static inline __m256i blend_lanes(__m256i s, __m256i d) {
    __m256i a = _mm256_shufflehi_epi16(_mm256_shufflelo_epi16(s, 0xff), 0xff);
    __m256i ia = _mm256_sub_epi16(_mm256_set1_epi16(255), a);
    return _mm256_add_epi16(mul_unorm8(s, a), mul_unorm8(d, ia));
}

/* Eight packed RGBA8 fragments over eight packed RGBA8 pixels (sg_blend_rgba8). */
INLINE __m256i blend8(__m256i s, __m256i d) {
    const __m256i zero = _mm256_setzero_si256();
    __m256i lo = blend_lanes(_mm256_unpacklo_epi8(s, zero), _mm256_unpacklo_epi8(d, zero));
    __m256i hi = blend_lanes(_mm256_unpackhi_epi8(s, zero), _mm256_unpackhi_epi8(d, zero));
    return _mm256_packus_epi16(lo, hi);
}

/* A fragment colour the same at every pixel (a triangle of one colour, untextured): its part of
 * the blend, s a / 255, and 255 - a, in 16-bit lanes (two pixels), worked out once a triangle. */
typedef struct flat_src {
    __m256i sa, ia;
} flat_src;

INLINE flat_src flat_src_of(uint32_t px) {
    const __m256i s = _mm256_unpacklo_epi8(_mm256_set1_epi32((int)px), _mm256_setzero_si256());
    const __m256i a = _mm256_shufflehi_epi16(_mm256_shufflelo_epi16(s, 0xff), 0xff);
    return (flat_src){mul_unorm8(s, a), _mm256_sub_epi16(_mm256_set1_epi16(255), a)};
}

/* blend8 of that colour over eight packed RGBA8 pixels: the same sums, half the products. */
INLINE __m256i blend8_flat(const flat_src *f, __m256i d) {
    const __m256i zero = _mm256_setzero_si256();
    __m256i lo = _mm256_add_epi16(f->sa, mul_unorm8(_mm256_unpacklo_epi8(d, zero), f->ia));
    __m256i hi = _mm256_add_epi16(f->sa, mul_unorm8(_mm256_unpackhi_epi8(d, zero), f->ia));
    return _mm256_packus_epi16(lo, hi);
}

/* All ones in the lanes of the 8-bit mask bits. */
INLINE __m256i lanes_of(unsigned bits) {
    const __m256i lanes = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
    return _mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32((int)bits), lanes), lanes);
}

/* The fragments s of the pixels of bits (two rows of a tile) blended into dst, or with `put`
 * put there. */
INLINE void blend_rows(uint32_t *dst, __m256i s, unsigned bits, const int put) {
    __m256i *pd = (__m256i *)(void *)dst;
    if (put && bits == 255) {
        _mm256_store_si256(pd, s);
        return;
    }
    __m256i d = _mm256_load_si256(pd);
    __m256i out = put ? s : blend8(s, d);
    _mm256_store_si256(pd, bits == 255 ? out : _mm256_blendv_epi8(d, out, lanes_of(bits)));
}

/* The depth test of the covered pixels of a tile: the mask of those that pass (their depth
 * written when the pipeline writes depth). */
INLINE uint32_t depth_tile(const sg_vis_ctx *v, const sg_tri *t, int x0, int y0, uint32_t mask,
                           int base, const int zwrite) {
    float *dp = v->depth + base;
    const sg_zrows8 zr = sg_zrows8_at(t, x0, y0);
    uint32_t pass = 0;
    for (int h = 0; h < 2; h++) {
        uint32_t bits = (mask >> (8 * h)) & 255u;
        if (!bits) continue;
        __m256 z = sg_zrows8_half(&zr, h);
        __m256 d = _mm256_load_ps(dp + 8 * h);
        __m256 p =
            _mm256_and_ps(sg_compare8(v->compare, z, d), _mm256_castsi256_ps(lanes_of(bits)));
        if (zwrite) _mm256_store_ps(dp + 8 * h, _mm256_blendv_ps(d, z, p));
        pass |= (uint32_t)_mm256_movemask_ps(p) << (8 * h);
    }
    return pass;
}

/* Lit draws and textured lines: the draw's shading function into a tile buffer, then the blend
 * (or, with `put`, the fragments put in place). */
INLINE void in_place_call(const void *vctx, const sg_tri *t, int x0, int y0, uint32_t mask,
                          const int zmode, const int zwrite, const int put) {
    const sg_vis_ctx *v = vctx;
    int base = sg_bin_tile_offset(x0 - v->bx0, y0 - v->by0);
    if (zmode != Z_NONE || zwrite) mask = depth_tile(v, t, x0, y0, mask, base, zwrite);
    if (!mask) return;
    _Alignas(32) uint32_t src[SG_TILE_PIXELS];
    v->shade(v->shade_ctx, t, x0, y0, mask, src);
    for (int h = 0; h < 2; h++) {
        unsigned bits = (mask >> (8 * h)) & 255u;
        if (bits)
            blend_rows(v->color + base + 8 * h,
                       _mm256_load_si256((const __m256i *)(const void *)(src + 8 * h)), bits, put);
    }
}

SG_IN_PLACE_BODY(blend_call, in_place_call, 0)
SG_IN_PLACE_BODY(put_call, in_place_call, 1)
SG_IN_PLACE_SET(blend, blend_call)
SG_IN_PLACE_SET(put_call, put_call)

/* Eight pixels of a textured triangle ready to shade: two rows of a tile, blended in place at bin
 * offset base, or a full (or the last, partial) queue, blended through its offsets; the lanes of
 * mask are written (a mipmapped job: two whole 2 x 2 quads, their covered pixels). The walks
 * collect them in the bin's list (blend_walk.h); they are shaded later, four side by side
 * (shade8_sets): a shading is a long chain of dependent steps, several keep the vector units busy,
 * and out of the walk they do not share the registers with its state. */
typedef struct job {
    __m256 dx, dy;
    __m256i off;
    const sg_tri *t;
    int base; /* -1: scattered through off */
    unsigned mask;
} job;

/* Jobs waiting at most (the teapots' triangles give about ten a bin), and how many are shaded
 * side by side. */
enum { JOBS = 32, JOB_SETS = 4 };

typedef struct queued_ctx {
    const sg_vis_ctx *v;
    sg_queue8 *q;
    sg_set8 *quads;         /* a mipmapped draw's lone quad */
    sg_blend_pending *jobs; /* the bin's */
    const flat_src *flat;   /* untextured triangles of one colour */
} queued_ctx;

/* The pipeline's colours of n sets of eight pixels at (dx, dy), flat colours split off per
 * triangle. */
INLINE void shade(const sg_vis_ctx *v, const sg_tri *t, const int n, const __m256 dx[],
                  const __m256 dy[], __m256i out[], const int textured, const int bilinear,
                  const int repeat) {
    const sg_shade_ctx *c = v->shade_ctx;
    if (t->flat == SG_FLAT_WHITE)
        shade8_sets(c, t, NULL, NULL, n, dx, dy, NULL, out, textured, bilinear, repeat,
                    SG_FLAT_WHITE, 0);
    else if (t->flat == SG_FLAT_COLOR)
        shade8_sets(c, t, NULL, NULL, n, dx, dy, NULL, out, textured, bilinear, repeat,
                    SG_FLAT_COLOR, 0);
    else
        shade8_sets(c, t, NULL, NULL, n, dx, dy, NULL, out, textured, bilinear, repeat,
                    SG_FLAT_NONE, 0);
}

/* The fragments s of the lanes of bits at offsets qoff blended into their pixels of the bin's
 * colour. */
INLINE void blend_scattered(const sg_vis_ctx *v, __m256i qoff, __m256i s, unsigned bits) {
    /* Every lane's offset is a pixel of the bin, so the loads read only the bin. */
    __m256i d = sg_load8((const int *)(const void *)v->color, qoff);
    sg_scatter8(v->color, qoff, blend8(s, d), bits);
}

/* The shaded fragments s of a job blended into the bin's colour. */
INLINE void finish(const sg_vis_ctx *v, const job *j, __m256i s) {
    if (j->base >= 0)
        blend_rows(v->color + j->base, s, j->mask, 0);
    else
        blend_scattered(v, j->off, s, j->mask);
}

/* n jobs (a constant) shaded side by side and blended, in their order. */
INLINE void shade_some(const sg_vis_ctx *v, const job *j, const int n, const int textured,
                       const int bilinear, const int repeat, const int flat) {
    __m256 dx[JOB_SETS], dy[JOB_SETS];
    __m256i s[JOB_SETS];
    const sg_tri *ts[JOB_SETS];
    unsigned mask[JOB_SETS];
    for (int i = 0; i < n; i++) {
        dx[i] = j[i].dx;
        dy[i] = j[i].dy;
        ts[i] = j[i].t;
        mask[i] = j[i].mask;
    }
    /* One triangle's jobs (they come together): its planes' terms broadcast once for all. */
    if (ts[0] == ts[n - 1])
        shade8_sets(v->shade_ctx, ts[0], NULL, NULL, n, dx, dy, mask, s, textured, bilinear, repeat,
                    flat, 0);
    else
        shade8_sets(v->shade_ctx, ts[0], ts, NULL, n, dx, dy, mask, s, textured, bilinear, repeat,
                    flat, 0);
    for (int i = 0; i < n; i++) finish(v, &j[i], s[i]);
}

SG_JOB_LIST_FNS
SG_MIP_JOB_FNS
#define blend_jobs_000 NULL /* vertex colours: shaded in place, no jobs */

INLINE void blend_inline(const void *vctx, const sg_tri *t, int x0, int y0, uint32_t mask,
                         const int zmode, const int zwrite, const int textured) {
    queued_ctx *p = (queued_ctx *)(uintptr_t)vctx; /* the walk's context, this function's own */
    const sg_vis_ctx *v = p->v;
    int base = sg_bin_tile_offset(x0 - v->bx0, y0 - v->by0);
    if (zmode != Z_NONE || zwrite) mask = depth_tile(v, t, x0, y0, mask, base, zwrite);
    if (!mask) return;
    for (int h = 0; h < 2; h++) {
        unsigned bits = (mask >> (8 * h)) & 255u;
        if (!bits) continue;
        if (!textured && t->flat != SG_FLAT_NONE) { /* the colour's share worked out already */
            __m256i *pd = (__m256i *)(void *)(v->color + base + 8 * h), d = _mm256_load_si256(pd);
            __m256i out = blend8_flat(p->flat, d);
            _mm256_store_si256(pd, bits == 255 ? out : _mm256_blendv_epi8(d, out, lanes_of(bits)));
            continue;
        }
        __m256 dx, dy;
        sg_rows_dxdy8(t, x0, y0, h, &dx, &dy);
        if (!textured) { /* vertex colours cost less to shade than to queue (alpha_stack) */
            __m256i s;
            shade(v, t, 1, &dx, &dy, &s, 0, 0, 0);
            blend_rows(v->color + base + 8 * h, s, bits, 0);
            continue;
        }
        if (bits == 255 || (textured >= SG_TEX_MIP && sg_both_quads8(bits))) {
            /* full rows need no packing, nor rows whose both quads are shaded anyway */
            const job j = {dx, dy, _mm256_setzero_si256(), t, base + 8 * h, bits};
            submit(p, &j);
            continue;
        }
        if (textured >= SG_TEX_MIP) {
            sg_set8 full;
            if (sg_pair_quad8(p->quads, dx, dy, base + 8 * h, bits, &full)) {
                const job j = {full.dx, full.dy, full.off, t, -1, full.mask};
                submit(p, &j);
            }
            continue;
        }
        sg_queue8 full;
        if (sg_enqueue8(p->q, dx, dy, base + 8 * h, bits, &full)) {
            const job j = {full.dx, full.dy, full.off, t, -1, 255u};
            submit(p, &j);
        }
    }
}

/* The end of a triangle: its partial queue, or its lone quad, joins the jobs waiting. */
INLINE void drain(queued_ctx *p, const sg_tri *t, const int textured) {
    if (textured >= SG_TEX_MIP) {
        const sg_set8 *q = p->quads;
        if (q->mask) submit(p, &(job){q->dx, q->dy, q->off, t, -1, q->mask});
        return;
    }
    const sg_queue8 *q = p->q;
    if (q->n) submit(p, &(job){q->dx, q->dy, q->off, t, -1, (1u << q->n) - 1u});
}

/* One raster function per shading variant (vertex colour; texture nearest / bilinear, repeat /
 * clamp: tex, bil, rep) and depth state (test, write: 0 or 1); the pixels left in the queue join
 * the jobs waiting at the end. */
#define SG_BLEND_INLINE(tex, bil, rep, zt, zw)                                                     \
    INLINE void blend_##tex##bil##rep##zt##zw##_tile(const void *c, const sg_tri *t, int x0,       \
                                                     int y0, uint32_t m) {                         \
        blend_inline(c, t, x0, y0, m, zt ? Z_ANY : Z_NONE, zw, tex);                               \
    }                                                                                              \
    static void blend_##tex##bil##rep##zt##zw(const sg_tri *t, int x0, int y0, int x1, int y1,     \
                                              const void *c) {                                     \
        sg_queue8 q = {_mm256_setzero_ps(), _mm256_setzero_ps(), _mm256_setzero_si256(), 0};       \
        const flat_src f =                                                                         \
            flat_src_of(!tex && t->flat != SG_FLAT_NONE ? sg_flat_pixel(t, NULL, 0) : 0u);         \
        /* Field by field: an initializer would clear the context with a string store, whose start \
         * costs more than the stores of the fields (a call per triangle and bin). */              \
        queued_ctx p;                                                                              \
        p.v = c;                                                                                   \
        p.q = &q;                                                                                  \
        p.jobs = p.v->pending;                                                                     \
        p.flat = &f;                                                                               \
        sg_set8 quads = {_mm256_setzero_ps(), _mm256_setzero_ps(), _mm256_setzero_si256(), 0};     \
        p.quads = &quads;                                                                          \
        if (tex) start_jobs(&p, t, blend_jobs_##tex##bil##rep);                                    \
        sg_rast_walk(t, x0, y0, x1, y1, blend_##tex##bil##rep##zt##zw##_tile, &p);                 \
        if (tex) drain(&p, t, tex); /* vertex colours were blended in place */                     \
    }
SG_BLEND_VARIANTS(SG_BLEND_INLINE)
/* Mipmapped textures, unlit (textured SG_TEX_MIP, SG_TEX_MIP_LINEAR) */
SG_BLEND_MIP_VARIANTS(SG_BLEND_INLINE)

/* An opaque vertex-coloured line's tile: the passing pixels shaded and put in place. */
INLINE void put_inline(const void *vctx, const sg_tri *t, int x0, int y0, uint32_t mask,
                       const int zmode, const int zwrite) {
    const sg_vis_ctx *v = vctx;
    int base = sg_bin_tile_offset(x0 - v->bx0, y0 - v->by0);
    for (int h = 0; h < 2; h++) {
        unsigned bits = (mask >> (8 * h)) & 255u;
        if (!bits) continue;
        __m256 dx, dy;
        sg_rows_dxdy8(t, x0, y0, h, &dx, &dy);
        __m256i pass = lanes_of(bits);
        if (zmode != Z_NONE || zwrite) { /* z from the shading's own dx, dy */
            float *dp = v->depth + base + 8 * h;
            const __m256 z = sg_z8(t, dx, dy), d = _mm256_load_ps(dp);
            if (zmode != Z_NONE) {
                pass = _mm256_and_si256(pass, _mm256_castps_si256(sg_compare8(v->compare, z, d)));
                if (_mm256_testz_si256(pass, pass)) continue;
            }
            if (zwrite) _mm256_store_ps(dp, _mm256_blendv_ps(d, z, _mm256_castsi256_ps(pass)));
        }
        __m256i s;
        shade(v, t, 1, &dx, &dy, &s, 0, 0, 0);
        __m256i *pc = (__m256i *)(void *)(v->color + base + 8 * h);
        _mm256_store_si256(pc, _mm256_blendv_epi8(_mm256_load_si256(pc), s, pass));
    }
}

SG_IN_PLACE_SET(put, put_inline)

/* An opaque vertex-coloured line put along its major axis, eight columns a vector: a line has one
 * pixel a column, so a tile holds at most four of them, in one pair of rows or both, and the tile
 * walk shades a vector of eight lanes for one to four pixels. Here each lane is a pixel: its
 * depth is read and written, and its colour stored, through its offset in the bin. The pixels of
 * a line are all different, so the order of the stores changes nothing; each lane computes what
 * put_inline computes for its pixel, so the bytes are the same. */
INLINE void put_line(const sg_tri *t, int rx0, int ry0, int rx1, int ry1, const sg_vis_ctx *v,
                     const int zmode, const int zwrite) {
    sg_line_dda d;
    if (!sg_line_dda_start(t, rx0, ry0, rx1, ry1, &d)) return;
    const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7), three = _mm256_set1_epi32(3);
    for (int u = d.u0; u <= d.u1; u += 8) {
        _Alignas(32) int32_t vs[8];
        unsigned bits = sg_line_dda_columns(&d, vs, 8, d.u1 - u < 7 ? d.u1 - u + 1 : 8);
        if (!bits) continue;
        const __m256i cu = _mm256_add_epi32(_mm256_set1_epi32(u), lane);
        const __m256i cv = _mm256_load_si256((const __m256i *)(const void *)vs);
        const __m256i x = d.xm ? cu : cv, y = d.xm ? cv : cu;
        __m256 dx = _mm256_cvtepi32_ps(_mm256_sub_epi32(x, _mm256_set1_epi32(t->minx)));
        __m256 dy = _mm256_cvtepi32_ps(_mm256_sub_epi32(y, _mm256_set1_epi32(t->miny)));
        /* The pixel's place in the bin: its tile's (sg_bin_tile_offset), then its row and column.
         */
        const __m256i bx = _mm256_sub_epi32(x, _mm256_set1_epi32(v->bx0));
        const __m256i by = _mm256_sub_epi32(y, _mm256_set1_epi32(v->by0));
        const __m256i off =
            _mm256_add_epi32(_mm256_add_epi32(_mm256_slli_epi32(_mm256_srli_epi32(by, 2), 8),
                                              _mm256_slli_epi32(_mm256_srli_epi32(bx, 2), 4)),
                             _mm256_add_epi32(_mm256_slli_epi32(_mm256_and_si256(by, three), 2),
                                              _mm256_and_si256(bx, three)));
        if (zmode != Z_NONE || zwrite) {
            const __m256 z = sg_z8(t, dx, dy);
            if (zmode != Z_NONE) {
                const __m256 pass = _mm256_castsi256_ps(lanes_of(bits));
                const __m256 dd =
                    _mm256_mask_i32gather_ps(_mm256_setzero_ps(), v->depth, off, pass, 4);
                bits &= (unsigned)_mm256_movemask_ps(
                    _mm256_and_ps(pass, sg_compare8(v->compare, z, dd)));
                if (!bits) continue;
            }
            if (zwrite) sg_scatter8(v->depth, off, _mm256_castps_si256(z), bits);
        }
        __m256i s;
        shade(v, t, 1, &dx, &dy, &s, 0, 0, 0);
        sg_scatter8(v->color, off, s, bits);
    }
}

SG_PUT_LINE_SET(put_line)

sg_raster_fn sg_blend_avx2(int variant, bool depth_test, bool depth_write) {
    if (variant < 0) {
        static const sg_raster_fn call[2][2] = SG_IN_PLACE_TABLE(blend);
        return call[depth_test][depth_write];
    }
    static const sg_raster_fn fns[5][4] = SG_BLEND_TABLE; /* in sg_shade_variant order */
    return fns[variant][(depth_test ? 2 : 0) + (depth_write ? 1 : 0)];
}

sg_raster_fn sg_blend_mip_avx2(int index, bool depth_test, bool depth_write) {
    static const sg_raster_fn fns[8][4] = SG_BLEND_MIP_TABLE;
    return fns[index][(depth_test ? 2 : 0) + (depth_write ? 1 : 0)];
}

sg_raster_fn sg_put_avx2(int variant, bool depth_test, bool depth_write) {
    static const sg_raster_fn inlined[2][2] = SG_IN_PLACE_TABLE(put_line);
    static const sg_raster_fn call[2][2] = SG_IN_PLACE_TABLE(put_call);
    return (variant == 0 ? inlined : call)[depth_test][depth_write];
}

/* Shader draws in place (shade_shader_walk.h): tile_depth and put_tile of shade_shader_tile.h two
 * rows a vector, in depth_simd.h's operations (the same as tile_depth's, so its bits). */
static inline uint32_t shader_tile_depth(const sg_tri *t, int x0, int y0, uint32_t mask,
                                         const float *dp, sgCompare op, float *z) {
    const sg_zrows8 zr = sg_zrows8_at(t, x0, y0);
    uint32_t pass = 0;
    for (int h = 0; h < 2; h++) {
        const __m256 zc = sg_zrows8_half(&zr, h);
        _mm256_store_ps(z + 8 * h, zc);
        if (dp)
            pass |= (uint32_t)_mm256_movemask_ps(sg_compare8(op, zc, _mm256_loadu_ps(dp + 8 * h)))
                    << (8 * h);
    }
    return dp ? mask & pass : mask;
}

static inline void shader_put_tile(uint32_t keep, const float *z, float *dp, const uint32_t *src,
                                   uint32_t *dst) {
    for (int h = 0; h < 2; h++) {
        const __m256i m = lanes_of((keep >> (8 * h)) & 255u);
        if (dp) _mm256_maskstore_ps(dp + 8 * h, m, _mm256_load_ps(z + 8 * h));
        _mm256_maskstore_epi32((int *)(void *)(dst + 8 * h), m,
                               _mm256_load_si256((const __m256i *)(const void *)(src + 8 * h)));
    }
}

#define SG_SHADER_TILE_DEPTH(v, t, x0, y0, mask, dp, op, z)                                        \
    shader_tile_depth(t, x0, y0, mask, dp, op, z)
#define SG_SHADER_PUT_TILE(v, keep, z, dp, src, dst) shader_put_tile(keep, z, dp, src, dst)
#include "raster/shade_shader_walk.h"

sg_raster_fn sg_shader_in_place_avx2(int kind, bool depth_test, bool depth_write) {
    return sg_shader_walks[kind][depth_test][depth_write];
}

#else

sg_raster_fn sg_shader_in_place_avx2(int kind, bool depth_test, bool depth_write) {
    (void)kind;
    (void)depth_test;
    (void)depth_write;
    return NULL;
}

sg_raster_fn sg_blend_avx2(int variant, bool depth_test, bool depth_write) {
    (void)variant;
    (void)depth_test;
    (void)depth_write;
    return NULL;
}

sg_raster_fn sg_blend_mip_avx2(int index, bool depth_test, bool depth_write) {
    (void)index;
    (void)depth_test;
    (void)depth_write;
    return NULL;
}

sg_raster_fn sg_put_avx2(int variant, bool depth_test, bool depth_write) {
    (void)variant;
    (void)depth_test;
    (void)depth_write;
    return NULL;
}

#endif
