/* depth_avx512.c - the visibility tile functions in AVX-512 (see depth.h), for every compare, with
 * and without depth write: a whole tile a vector, z as depth_simd.h computes it; the coverage mask
 * is the compare and store mask. */
#include "raster/depth.h"

/* The sample walks' bodies (vis4_with) ready a fresh tile themselves. */
#define SG_VIS_BODY_TOUCHES 1

#include "raster/depth_simd.h"
#include "raster/depth_walk.h"

#if defined(__AVX512F__)
#include <immintrin.h>

static inline __attribute__((always_inline)) void vis_avx512(const void *vctx, const sg_tri *t,
                                                             int x0, int y0, uint32_t mask,
                                                             const int zmode, const int zwrite) {
    const sg_vis_ctx *v = vctx;
    int base = sg_bin_tile_offset(x0 - v->bx0, y0 - v->by0);
    uint32_t *ids = sg_vis_tile_ids_of(v, base, mask); /* mask may be empty: SG_WALK_FN_EMPTY */
    __mmask16 pass = (__mmask16)mask;
    if (zmode != Z_NONE || zwrite) {
        float *dp = v->depth + base;
        __m512 dx, dy;
        sg_tile_dxdy16(t, x0, y0, &dx, &dy);
        __m512 z = sg_z16(t, dx, dy);
        if (zmode != Z_NONE)
            pass = sg_compare16(zmode == Z_LESS ? SG_COMPARE_LESS : v->compare, pass, z,
                                _mm512_loadu_ps(dp));
        /* No test of an empty mask: the masked stores then write nothing, and a small
         * triangle's tiles pass or fail in no pattern a branch predictor follows. */
        if (zwrite) _mm512_mask_storeu_ps(dp, pass, z);
    }
    _mm512_mask_storeu_epi32(ids, pass, _mm512_set1_epi32((int)v->id));
}

SG_VIS_SET_OF(SG_WALK_FN_EMPTY, vis_avx512, vis_avx512)

/* The four samples of a tile at once (the sample walk's body): the samples' triangles differ only
 * in their edges and z (sg_msaa_sample_tri), so the pixels' offsets and the depth slopes' products
 * with them are computed once, and each sample's z is its own z plus those products, added in
 * vis_avx512's order: the same bits. With `rec` the passing pixels are recorded (sg_vis_record)
 * instead of written as ids.
 * A fresh tile (sg_vis_samples_touch) is readied by the stores themselves where they write every
 * plane (ids written, depth written): each sample's ids are stored whole, 0 where no sample
 * passes, and planes 1-3 of depth whole, plane 0's value where none passes, against which they
 * were tested; the bytes the touch then the masked stores would leave, without the touch's own
 * clearing and copying, which a tile's first triangle (a large one's most tiles) would redo. The
 * recording walk writes no ids, so it leaves their bit; it tests planes 1-3 of a fresh tile
 * against plane 0 and, without depth writes, leaves that bit too (a shader's in-place depth
 * writes touch the tile first). */
static inline __attribute__((always_inline)) void vis4_with(const sg_vis_samples *s, int x0, int y0,
                                                            const uint32_t *mk, const int zmode,
                                                            const int zwrite, const int rec) {
    const sg_tri *st = s->st;
    const sg_vis_ctx *v0 = &s->vis[0];
    const int base = sg_bin_tile_offset(x0 - v0->bx0, y0 - v0->by0);
    bool fresh_ids, fresh_depth;
    sg_vis_samples_take(s->vis, x0, y0, base, zwrite, rec, &fresh_ids, &fresh_depth);
    const bool depth = zmode != Z_NONE || zwrite; /* the depth target is read or written */
    __m512 dzx = _mm512_setzero_ps(), dzy = _mm512_setzero_ps();
    if (depth) {
        __m512 dx, dy;
        sg_tile_dxdy16(&st[0], x0, y0, &dx, &dy);
        dzx = _mm512_mul_ps(_mm512_set1_ps(st[0].z_dx), dx);
        dzy = _mm512_mul_ps(_mm512_set1_ps(st[0].z_dy), dy);
    }
    const __m512i id = _mm512_set1_epi32((int)v0->id);
    sg_vis_record *r = v0->record;
    uint32_t any = 0;
    /* Plane 0's depth before sample 0's writes: the others' where fresh (only where the target is
     * used: a pass without one has the bit set as well). */
    const __m512 plane0 =
        depth && fresh_depth ? _mm512_loadu_ps(v0->depth + base) : _mm512_setzero_ps();
    /* No branch on a sample's mask: an edge tile's samples are covered or not in no pattern a
     * predictor follows, and an empty one writes and marks nothing. */
    for (int k = 0; k < SG_VIS_SAMPLES; k++) {
        const sg_vis_ctx *v = &s->vis[k];
        __mmask16 pass = (__mmask16)mk[k];
        if (depth) {
            float *dp = v->depth + base;
            const bool from0 = k > 0 && fresh_depth; /* this plane is taken as plane 0's */
            const __m512 old = from0 ? plane0 : _mm512_loadu_ps(dp);
            __m512 z = _mm512_add_ps(_mm512_add_ps(_mm512_set1_ps(st[k].z), dzx), dzy);
            z = _mm512_min_ps(_mm512_set1_ps(1.0f), _mm512_max_ps(_mm512_setzero_ps(), z));
            if (zmode != Z_NONE)
                pass = sg_compare16(zmode == Z_LESS ? SG_COMPARE_LESS : v->compare, pass, z, old);
            if (from0 && zwrite)
                _mm512_storeu_ps(dp, _mm512_mask_mov_ps(old, pass, z));
            else if (zwrite)
                _mm512_mask_storeu_ps(dp, pass, z);
        }
        if (rec) {
            r->mask[r->n][k] = pass;
            any |= pass;
        } else if (fresh_ids) {
            _mm512_storeu_si512(sg_vis_tile_ids_of(v, base, mk[k]),
                                _mm512_maskz_mov_epi32(pass, id));
        } else {
            _mm512_mask_storeu_epi32(sg_vis_tile_ids_of(v, base, mk[k]), pass, id);
        }
    }
    if (rec) {
        r->tile[r->n] = (uint16_t)(base >> 4);
        r->n += any != 0;
    }
}

SG_VIS4_SETS(vis_samples_avx512, rec_samples_avx512)

sg_vis_fns sg_depth_avx512(sgCompare compare, bool depth_write) {
    static const sg_raster_fn one[3][2] = SG_VIS_TABLE(vis_avx512);
    static const sg_raster_samples_fn samples[3][2] = SG_VIS_TABLE(vis_samples_avx512);
    static const sg_raster_samples_fn record[3][2] = SG_VIS_TABLE(rec_samples_avx512);
    return sg_vis_pick(one, samples, record, compare, depth_write);
}

static void walk_any(const sg_tri *t, int x0, int y0, int x1, int y1, sg_tile_fn fn,
                     const void *ctx) {
    sg_rast_walk(t, x0, y0, x1, y1, fn, ctx);
}

sg_walk_fn sg_walk_avx512(void) {
    return walk_any;
}

#else

sg_vis_fns sg_depth_avx512(sgCompare compare, bool depth_write) {
    (void)compare;
    (void)depth_write;
    return (sg_vis_fns){NULL, NULL, NULL};
}

sg_walk_fn sg_walk_avx512(void) {
    return NULL;
}

#endif
