/* depth_avx2.c - the visibility tile functions in AVX2 (see depth.h), for every compare, with and
 * without depth write: two rows of a tile a vector, the same z = (z0 + z_dx * dx) + z_dy * dy and
 * clamp as the scalar and SSE2 ones. */
#include "raster/depth.h"

/* The sample walks' bodies (vis4_with) ready a fresh tile themselves. */
#define SG_VIS_BODY_TOUCHES 1

#include "raster/depth_simd.h"
#include "raster/depth_walk.h"

#if defined(__AVX2__)
#include <immintrin.h>

/* Half h of a tile (rows 2h and 2h + 1), the lanes of bits: the depth test of z against the
 * stored depth dp, then depth (when written) and the id where it passes (ids NULL: no id);
 * returns the passing lanes. Both halves are tested and written whatever their masks, no branch:
 * a lane that does not pass writes back what it read, and a small triangle's halves pass or fail
 * in no pattern a branch predictor follows (docs/performance.md, "Four shading chains"). */
static inline __attribute__((always_inline)) uint32_t
vis_half_avx2(const sg_vis_ctx *v, uint32_t *ids, float *dp, int h, uint32_t bits, __m256 z,
              const int zmode, const int zwrite) {
    const __m256i lanes = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
    __m256 pass = _mm256_castsi256_ps(
        _mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32((int)bits), lanes), lanes));
    if (zmode != Z_NONE || zwrite) {
        __m256 d = _mm256_load_ps(dp + 8 * h);
        if (zmode != Z_NONE)
            pass = _mm256_and_ps(pass,
                                 sg_compare8(zmode == Z_LESS ? SG_COMPARE_LESS : v->compare, z, d));
        if (zwrite) _mm256_store_ps(dp + 8 * h, _mm256_blendv_ps(d, z, pass));
    }
    if (ids) {
        __m256i *ip = (__m256i *)(void *)(ids + 8 * h);
        _mm256_store_si256(ip,
                           _mm256_blendv_epi8(_mm256_load_si256(ip), _mm256_set1_epi32((int)v->id),
                                              _mm256_castps_si256(pass)));
    }
    return (uint32_t)_mm256_movemask_ps(pass);
}

static inline __attribute__((always_inline)) void vis_avx2(const void *vctx, const sg_tri *t,
                                                           int x0, int y0, uint32_t mask,
                                                           const int zmode, const int zwrite) {
    const sg_vis_ctx *v = vctx;
    int base = sg_bin_tile_offset(x0 - v->bx0, y0 - v->by0);
    uint32_t *ids = sg_vis_tile_ids_of(v, base, mask); /* mask may be empty: SG_WALK_FN_EMPTY */
    const bool depth = zmode != Z_NONE || zwrite;
    float *dp = depth ? v->depth + base : NULL; /* NULL: the pass may have no depth target */
    const sg_zrows8 zr = depth ? sg_zrows8_at(t, x0, y0) : (sg_zrows8){0};
    for (int h = 0; h < 2; h++)
        vis_half_avx2(v, ids, dp, h, (mask >> (8 * h)) & 255u,
                      depth ? sg_zrows8_half(&zr, h) : _mm256_setzero_ps(), zmode, zwrite);
}

SG_VIS_SET_OF(SG_WALK_FN_EMPTY, vis_avx2, vis_avx2)

/* The four samples of a tile at once (the sample walk's body), as vis4_with in depth_avx512.c:
 * the samples' triangles differ only in their edges and z, so the products of the depth slopes
 * with the pixels' offsets are computed once, and each sample's z is its own z plus them, added
 * in sg_zrows8's order: the same bits as vis_avx2. With `rec` the passing pixels are recorded
 * (sg_vis_record) instead of written as ids. A fresh tile is readied by the stores themselves,
 * as depth_avx512.c's are: every plane's ids stored whole (0 where no sample passes) and planes
 * 1-3 of depth tested against plane 0 and stored whole; then no sample is skipped, even one that
 * covers nothing, since its stores make its planes. */
static inline __attribute__((always_inline)) void vis4_with(const sg_vis_samples *s, int x0, int y0,
                                                            const uint32_t *mk, const int zmode,
                                                            const int zwrite, const int rec) {
    const sg_tri *st = s->st;
    const sg_vis_ctx *v0 = &s->vis[0];
    const int base = sg_bin_tile_offset(x0 - v0->bx0, y0 - v0->by0);
    bool fresh_ids, fresh_depth;
    sg_vis_samples_take(s->vis, x0, y0, base, zwrite, rec, &fresh_ids, &fresh_depth);
    const bool depth = zmode != Z_NONE || zwrite;
    /* every plane must be stored: its ids, or its depth, are taken as plane 0's until then */
    const bool every = (!rec && fresh_ids) || (zwrite && fresh_depth);
    /* The products of sg_zrows8_at and sg_zrows8_half, without the sample's z. */
    __m256 zdx = _mm256_setzero_ps(), zdy[2] = {_mm256_setzero_ps(), _mm256_setzero_ps()};
    __m256 plane0[2] = {_mm256_setzero_ps(), _mm256_setzero_ps()}; /* before sample 0's writes */
    if (depth) {
        const __m256 dx =
            _mm256_add_ps(_mm256_set1_ps((float)(x0 - st[0].minx)),
                          _mm256_setr_ps(0.0f, 1.0f, 2.0f, 3.0f, 0.0f, 1.0f, 2.0f, 3.0f));
        zdx = _mm256_mul_ps(_mm256_set1_ps(st[0].z_dx), dx);
        const __m256 oy = _mm256_set1_ps((float)(y0 - st[0].miny));
        for (int h = 0; h < 2; h++) {
            const float r0 = (float)(2 * h), r1 = (float)(2 * h + 1); /* the two rows, exact */
            const __m256 dy = _mm256_add_ps(oy, _mm256_setr_ps(r0, r0, r0, r0, r1, r1, r1, r1));
            zdy[h] = _mm256_mul_ps(_mm256_set1_ps(st[0].z_dy), dy);
            if (fresh_depth) plane0[h] = _mm256_load_ps(v0->depth + base + 8 * h);
        }
    }
    const __m256i lanes[2] = {
        _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128),
        _mm256_setr_epi32(1 << 8, 1 << 9, 1 << 10, 1 << 11, 1 << 12, 1 << 13, 1 << 14, 1 << 15)};
    const __m256i id = _mm256_set1_epi32((int)v0->id);
    sg_vis_record *r = v0->record;
    uint32_t any = 0;
    for (int k = 0; k < SG_VIS_SAMPLES; k++) {
        uint32_t pass = 0;
        if (mk[k] || every) {
            const sg_vis_ctx *v = &s->vis[k];
            uint32_t *ids = rec ? NULL : sg_vis_tile_ids_of(v, base, mk[k]);
            const bool from0 = k > 0 && fresh_depth; /* this plane is taken as plane 0's */
            const __m256 zx = _mm256_add_ps(_mm256_set1_ps(st[k].z), zdx);
            const __m256i bits = _mm256_set1_epi32((int)mk[k]); /* both halves' from one */
            for (int h = 0; h < 2; h++) {
                const __m256i cover = _mm256_and_si256(bits, lanes[h]);
                __m256 ok = _mm256_castsi256_ps(_mm256_cmpeq_epi32(cover, lanes[h]));
                if (depth) {
                    float *dp = v->depth + base + 8 * h;
                    __m256 z = _mm256_add_ps(zx, zdy[h]);
                    z = _mm256_min_ps(_mm256_set1_ps(1.0f), _mm256_max_ps(_mm256_setzero_ps(), z));
                    const __m256 d = from0 ? plane0[h] : _mm256_load_ps(dp);
                    if (zmode == Z_LESS && zwrite) {
                        /* The lanes not covered made NaN: z < d is then the passing lanes, and
                         * min(z, d) is z where it passes and d elsewhere (min gives its second
                         * operand for a NaN and for two zeros): the depth to store, no blend. */
                        z = _mm256_or_ps(z, _mm256_castsi256_ps(
                                                _mm256_cmpeq_epi32(cover, _mm256_setzero_si256())));
                        ok = _mm256_cmp_ps(z, d, _CMP_LT_OQ);
                        _mm256_store_ps(dp, _mm256_min_ps(z, d));
                    } else {
                        if (zmode != Z_NONE)
                            ok = _mm256_and_ps(
                                ok,
                                sg_compare8(zmode == Z_LESS ? SG_COMPARE_LESS : v->compare, z, d));
                        if (zwrite) _mm256_store_ps(dp, _mm256_blendv_ps(d, z, ok));
                    }
                }
                if (ids) {
                    __m256i *ip = (__m256i *)(void *)(ids + 8 * h);
                    const __m256i pass8 = _mm256_castps_si256(ok);
                    if (fresh_ids) { /* whole, 0 where no sample passes */
                        _mm256_store_si256(ip, _mm256_and_si256(pass8, id));
                    } else {
                        _mm256_store_si256(ip,
                                           _mm256_blendv_epi8(_mm256_load_si256(ip), id, pass8));
                    }
                }
                pass |= (uint32_t)_mm256_movemask_ps(ok) << (8 * h);
            }
        }
        if (rec) {
            r->mask[r->n][k] = (uint16_t)pass;
            any |= pass;
        }
    }
    if (rec) {
        r->tile[r->n] = (uint16_t)(base >> 4);
        r->n += any != 0;
    }
}

SG_VIS4_SETS(vis_samples_avx2, rec_samples_avx2)

sg_vis_fns sg_depth_avx2(sgCompare compare, bool depth_write) {
    static const sg_raster_fn one[3][2] = SG_VIS_TABLE(vis_avx2);
    static const sg_raster_samples_fn samples[3][2] = SG_VIS_TABLE(vis_samples_avx2);
    static const sg_raster_samples_fn record[3][2] = SG_VIS_TABLE(rec_samples_avx2);
    return sg_vis_pick(one, samples, record, compare, depth_write);
}

static void walk_any(const sg_tri *t, int x0, int y0, int x1, int y1, sg_tile_fn fn,
                     const void *ctx) {
    sg_rast_walk(t, x0, y0, x1, y1, fn, ctx);
}

sg_walk_fn sg_walk_avx2(void) {
    return walk_any;
}

#else

sg_vis_fns sg_depth_avx2(sgCompare compare, bool depth_write) {
    (void)compare;
    (void)depth_write;
    return (sg_vis_fns){NULL, NULL, NULL};
}

sg_walk_fn sg_walk_avx2(void) {
    return NULL;
}

#endif
