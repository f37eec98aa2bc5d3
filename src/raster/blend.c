/* blend.c - the raster functions of draws shaded in place (see blend.h): per covered tile, the
 * depth test, then the pipeline's shading of the passing pixels, then each blended into the bin's
 * colour (or, for an opaque line, put there). Portable C (the reference) and SSE2, which computes
 * the same integer blend and the same float depth, so both give the same bytes. */
#include "raster/blend.h"

#include "raster/depth_simd.h"
#include "raster/blend_walk.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

/* Depth test of the covered pixels of a tile: the mask of those that pass (their depth written
 * when the pipeline writes depth). */
static inline __attribute__((always_inline)) uint32_t depth_scalar(const sg_vis_ctx *v,
                                                                   const sg_tri *t, int x0, int y0,
                                                                   uint32_t mask, int base,
                                                                   const int zwrite) {
    float *dp = v->depth + base;
    float ox = (float)(x0 - t->minx), oy = (float)(y0 - t->miny);
    uint32_t pass = 0;
    for (uint32_t left = mask; left; left &= left - 1) {
        int bit = __builtin_ctz(left);
        float z = sg_tri_depth(t, ox + (float)(bit & 3), oy + (float)(bit >> 2));
        if (!sg_depth_passes(v->compare, z, dp[bit])) continue;
        if (zwrite) dp[bit] = z;
        pass |= 1u << bit;
    }
    return pass;
}

/* put: the fragments replace the pixels (an opaque line), else they are blended over them. */
static inline __attribute__((always_inline)) void in_place_scalar(const void *vctx, const sg_tri *t,
                                                                  int x0, int y0, uint32_t mask,
                                                                  const int zmode, const int zwrite,
                                                                  const int put) {
    const sg_vis_ctx *v = vctx;
    int base = sg_bin_tile_offset(x0 - v->bx0, y0 - v->by0);
    if (zmode != Z_NONE || zwrite) mask = depth_scalar(v, t, x0, y0, mask, base, zwrite);
    if (!mask) return;
    uint32_t src[SG_TILE_PIXELS];
    v->shade(v->shade_ctx, t, x0, y0, mask, src);
    uint32_t *dst = v->color + base;
    for (; mask; mask &= mask - 1) {
        int bit = __builtin_ctz(mask);
        dst[bit] = put ? src[bit] : sg_blend_rgba8(src[bit], dst[bit]);
    }
}

SG_IN_PLACE_BODY(blend_scalar, in_place_scalar, 0)
SG_IN_PLACE_BODY(put_scalar, in_place_scalar, 1)
SG_IN_PLACE_SET(blend, blend_scalar)
SG_IN_PLACE_SET(put, put_scalar)

#if defined(__SSE2__)
/* x y / 255 as sg_mul_unorm8 rounds it, in 16-bit lanes (x, y <= 255, so no lane overflows). */
static inline __m128i mul_unorm8_sse2(__m128i x, __m128i y) {
    __m128i t = _mm_mullo_epi16(x, y);
    t = _mm_add_epi16(_mm_add_epi16(t, _mm_srli_epi16(t, 8)), _mm_set1_epi16(128));
    return _mm_srli_epi16(t, 8);
}

/* Two pixels in 16-bit lanes (r g b a r g b a): src over dst by src's alpha. */
static inline __m128i blend2_sse2(__m128i s, __m128i d) {
    __m128i a = _mm_shufflehi_epi16(_mm_shufflelo_epi16(s, 0xff), 0xff);
    __m128i ia = _mm_sub_epi16(_mm_set1_epi16(255), a);
    return _mm_add_epi16(mul_unorm8_sse2(s, a), mul_unorm8_sse2(d, ia));
}

/* Four packed RGBA8 pixels blended as sg_blend_rgba8 does. */
static inline __m128i blend4_sse2(__m128i s, __m128i d) {
    const __m128i zero = _mm_setzero_si128();
    __m128i lo = blend2_sse2(_mm_unpacklo_epi8(s, zero), _mm_unpacklo_epi8(d, zero));
    __m128i hi = blend2_sse2(_mm_unpackhi_epi8(s, zero), _mm_unpackhi_epi8(d, zero));
    return _mm_packus_epi16(lo, hi);
}

static inline __attribute__((always_inline)) void in_place_sse2(const void *vctx, const sg_tri *t,
                                                                int x0, int y0, uint32_t mask,
                                                                const int zmode, const int zwrite,
                                                                const int put) {
    const sg_vis_ctx *v = vctx;
    int base = sg_bin_tile_offset(x0 - v->bx0, y0 - v->by0);
    const __m128i lanes = _mm_setr_epi32(1, 2, 4, 8);
    if (zmode != Z_NONE || zwrite) {
        float *dp = v->depth + base;
        const sg_zrows4 zr = sg_zrows4_at(t, x0, y0);
        uint32_t pass = 0;
        for (int j = 0; j < 4; j++) {
            uint32_t bits = (mask >> (4 * j)) & 15u;
            if (!bits) continue;
            __m128 z = sg_zrow4(&zr, j);
            __m128 d = _mm_load_ps(dp + 4 * j);
            __m128i cov = _mm_cmpeq_epi32(_mm_and_si128(_mm_set1_epi32((int)bits), lanes), lanes);
            __m128i p = _mm_and_si128(cov, _mm_castps_si128(sg_compare4(v->compare, z, d)));
            if (zwrite)
                _mm_store_ps(dp + 4 * j, _mm_or_ps(_mm_and_ps(_mm_castsi128_ps(p), z),
                                                   _mm_andnot_ps(_mm_castsi128_ps(p), d)));
            pass |= (uint32_t)_mm_movemask_ps(_mm_castsi128_ps(p)) << (4 * j);
        }
        mask = pass;
    }
    if (!mask) return;
    _Alignas(16) uint32_t src[SG_TILE_PIXELS];
    v->shade(v->shade_ctx, t, x0, y0, mask, src);
    uint32_t *dst = v->color + base;
    for (int j = 0; j < 4; j++) {
        uint32_t bits = (mask >> (4 * j)) & 15u;
        if (!bits) continue;
        __m128i *pd = (__m128i *)(void *)(dst + 4 * j);
        __m128i d = _mm_load_si128(pd);
        __m128i s = _mm_load_si128((const __m128i *)(const void *)(src + 4 * j));
        __m128i out = put ? s : blend4_sse2(s, d);
        __m128i sel = _mm_cmpeq_epi32(_mm_and_si128(_mm_set1_epi32((int)bits), lanes), lanes);
        _mm_store_si128(pd, _mm_or_si128(_mm_and_si128(sel, out), _mm_andnot_si128(sel, d)));
    }
}

SG_IN_PLACE_BODY(blend_sse2, in_place_sse2, 0)
SG_IN_PLACE_BODY(put_sse2, in_place_sse2, 1)
SG_IN_PLACE_SET(blend_sse2, blend_sse2)
SG_IN_PLACE_SET(put_sse2, put_sse2)
#endif

/* The raster function that shades in place: with `put` an opaque line's (its fragments replace
 * the pixels), else a blend's. */
static sg_raster_fn in_place_select(const bool put, int variant, sgCompare compare,
                                    bool depth_write, sg_isa isa) {
    const bool test = compare != SG_COMPARE_ALWAYS; /* Z_ANY, else Z_NONE */
    const int write = depth_write ? 1 : 0;
    sg_raster_fn fn = NULL;
    if (isa == SG_ISA_NEON)
        fn = put ? sg_put_neon(test, depth_write) : sg_blend_neon(test, depth_write);
    if (fn) return fn;
    /* AVX-512 inlines the unlit shading of every blend and of vertex-coloured lines; AVX2 calls
     * the draw's shading function for a lit blend (a negative variant) and for textured lines. */
    if (isa >= SG_ISA_AVX512 && (put ? variant == 0 : variant >= 0))
        fn = put ? sg_put_avx512(test, depth_write) : sg_blend_avx512(variant, test, depth_write);
    if (!fn && isa >= SG_ISA_AVX2)
        fn = put ? sg_put_avx2(variant, test, depth_write)
                 : sg_blend_avx2(variant, test, depth_write);
    if (fn) return fn;
#if defined(__SSE2__)
    static const sg_raster_fn sse2[2][2][2] = {SG_IN_PLACE_TABLE(blend_sse2),
                                               SG_IN_PLACE_TABLE(put_sse2)};
    if (isa >= SG_ISA_SSE2) return sse2[put][test][write];
#else
    (void)isa;
#endif
    static const sg_raster_fn scalar[2][2][2] = {SG_IN_PLACE_TABLE(blend), SG_IN_PLACE_TABLE(put)};
    return scalar[put][test][write];
}

sg_raster_fn sg_blend_select(int shade_variant, sgCompare compare, bool depth_write, sg_isa isa) {
    return in_place_select(false, shade_variant, compare, depth_write, isa);
}

sg_raster_fn sg_blend_mip_select(sgMipmap mipmap, sgFilter filter, sgWrap wrap, sgCompare compare,
                                 bool depth_write, sg_isa isa) {
    const int index = (mipmap == SG_MIPMAP_LINEAR) * 4 + (filter == SG_FILTER_BILINEAR) * 2 +
                      (wrap == SG_WRAP_REPEAT);
    const bool test = compare != SG_COMPARE_ALWAYS;
    const sg_raster_fn fn = isa == SG_ISA_AVX512 ? sg_blend_mip_avx512(index, test, depth_write)
                            : isa == SG_ISA_AVX2 ? sg_blend_mip_avx2(index, test, depth_write)
                                                 : NULL;
    return fn ? fn : in_place_select(false, -1, compare, depth_write, isa);
}

sg_raster_fn sg_put_select(int shade_variant, sgCompare compare, bool depth_write, sg_isa isa) {
    return in_place_select(true, shade_variant, compare, depth_write, isa);
}
