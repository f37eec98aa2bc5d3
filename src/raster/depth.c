/* depth.c - the visibility tile functions (see depth.h): depth test and id write of one covered
 * 4x4 tile, specialised for no test, LESS, or any other compare, with or without depth write, in
 * portable C and in SSE2 (AVX2 and AVX-512 in depth_avx2.c, depth_avx512.c). All compute
 * z = (z0 + z_dx * dx) + z_dy * dy, clamped to [0, 1] with NaN kept, so they decide every pixel
 * alike. */
#include "raster/depth.h"

#include "raster/depth_simd.h"
#include "raster/depth_walk.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

static inline __attribute__((always_inline)) void vis_scalar(const void *vctx, const sg_tri *t,
                                                             int x0, int y0, uint32_t mask,
                                                             const int zmode, const int zwrite) {
    const sg_vis_ctx *v = vctx;
    int base = sg_bin_tile_offset(x0 - v->bx0, y0 - v->by0);
    uint32_t *ids = sg_vis_tile_ids(v, base);
    if (zmode == Z_NONE && !zwrite) {
        while (mask) {
            ids[__builtin_ctz(mask)] = v->id;
            mask &= mask - 1;
        }
        return;
    }
    float *dp = v->depth + base;
    float ox = (float)(x0 - t->minx), oy = (float)(y0 - t->miny);
    while (mask) {
        int bit = __builtin_ctz(mask);
        mask &= mask - 1;
        float dx = ox + (float)(bit & 3), dy = oy + (float)(bit >> 2);
        float z = sg_tri_depth(t, dx, dy);
        if (zmode == Z_LESS && !(z < dp[bit])) continue;
        if (zmode == Z_ANY && !sg_depth_passes(v->compare, z, dp[bit])) continue;
        if (zwrite) dp[bit] = z;
        ids[bit] = v->id;
    }
}

SG_VIS_SET(vis, vis_scalar)
SG_VIS_SAMPLES_SET(vis_samples, vis_scalar)

#if defined(__SSE2__)
/* One row of 4 pixels at a time (z as depth_simd.h computes it). `lanes` has the bit of each
 * lane, to turn the 4 coverage bits of a row into a lane mask. */
static inline __attribute__((always_inline)) void vis_sse2(const void *vctx, const sg_tri *t,
                                                           int x0, int y0, uint32_t mask,
                                                           const int zmode, const int zwrite) {
    (void)zmode; /* LESS only */
    const sg_vis_ctx *v = vctx;
    int base = sg_bin_tile_offset(x0 - v->bx0, y0 - v->by0);
    uint32_t *ids = sg_vis_tile_ids(v, base);
    float *dp = v->depth + base;
    const __m128i lanes = _mm_setr_epi32(1, 2, 4, 8);
    const sg_zrows4 zr = sg_zrows4_at(t, x0, y0);
    __m128i id = _mm_set1_epi32((int)v->id);
    for (int j = 0; j < 4; j++) {
        uint32_t bits = (mask >> (4 * j)) & 15u;
        if (!bits) continue;
        __m128 z = sg_zrow4(&zr, j);
        __m128 d = _mm_load_ps(dp + 4 * j);
        __m128i cov = _mm_cmpeq_epi32(_mm_and_si128(_mm_set1_epi32((int)bits), lanes), lanes);
        __m128i pass = _mm_and_si128(cov, _mm_castps_si128(sg_compare4(SG_COMPARE_LESS, z, d)));
        if (!_mm_movemask_epi8(pass)) continue;
        if (zwrite)
            _mm_store_ps(dp + 4 * j, _mm_or_ps(_mm_and_ps(_mm_castsi128_ps(pass), z),
                                               _mm_andnot_ps(_mm_castsi128_ps(pass), d)));
        __m128i old = _mm_load_si128((const __m128i *)(const void *)(ids + 4 * j));
        _mm_store_si128((__m128i *)(void *)(ids + 4 * j),
                        _mm_or_si128(_mm_and_si128(pass, id), _mm_andnot_si128(pass, old)));
    }
}

SG_WALK_FN(vis_less_0_sse2, vis_sse2, Z_LESS, 0)
SG_WALK_FN(vis_less_1_sse2, vis_sse2, Z_LESS, 1)
SG_VIS_SAMPLES_FN(vis_samples_less_0_sse2, vis_sse2, Z_LESS, 0)
SG_VIS_SAMPLES_FN(vis_samples_less_1_sse2, vis_sse2, Z_LESS, 1)
#endif

/* The visibility functions of a depth state on `isa`: the best set the ISA allows that is built
 * (AVX-512, AVX2, SSE2 for LESS, scalar; on AArch64 NEON for LESS, else scalar). */
static sg_vis_fns vis_select(sgCompare compare, bool depth_write, sg_isa isa) {
    static const sg_raster_fn one[3][2] = SG_VIS_TABLE(vis);
    static const sg_raster_samples_fn samples[3][2] = SG_VIS_TABLE(vis_samples);
    const int zmode = sg_zmode(compare);
    sg_vis_fns f = {NULL, NULL, NULL};
    if (isa == SG_ISA_NEON) {
        if (zmode == Z_LESS) f = sg_depth_less_neon(depth_write);
    } else {
        if (isa >= SG_ISA_AVX512) f = sg_depth_avx512(compare, depth_write);
        if (!f.one && isa >= SG_ISA_AVX2) f = sg_depth_avx2(compare, depth_write);
#if defined(__SSE2__)
        if (!f.one && isa >= SG_ISA_SSE2 && zmode == Z_LESS)
            f = depth_write ? (sg_vis_fns){vis_less_1_sse2, vis_samples_less_1_sse2, NULL}
                            : (sg_vis_fns){vis_less_0_sse2, vis_samples_less_0_sse2, NULL};
#endif
    }
    return f.one ? f : sg_vis_pick(one, samples, NULL, compare, depth_write);
}

sg_raster_fn sg_depth_select(sgCompare compare, bool depth_write, sg_isa isa) {
    return vis_select(compare, depth_write, isa).one;
}

sg_raster_samples_fn sg_depth_samples_select(sgCompare compare, bool depth_write, sg_isa isa) {
    return vis_select(compare, depth_write, isa).samples;
}

sg_raster_samples_fn sg_depth_record_select(sgCompare compare, bool depth_write, sg_isa isa) {
    return vis_select(compare, depth_write, isa).record;
}

sg_walk_fn sg_walk_select(sg_isa isa) {
    sg_walk_fn fn = NULL;
    if (isa == SG_ISA_NEON) return sg_rast_triangle_in; /* NEON's walk is the AArch64 baseline */
    if (isa == SG_ISA_AVX512) fn = sg_walk_avx512();
    if (!fn && isa >= SG_ISA_AVX2) fn = sg_walk_avx2();
    return fn ? fn : sg_rast_triangle_in;
}
