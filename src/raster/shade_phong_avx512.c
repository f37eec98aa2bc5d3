/* shade_phong_avx512.c - per-pixel lighting in AVX-512 (see shade_phong.c): a whole tile a
 * vector, the equation of light_simd.h, the texture helpers of shade_avx512.h; the same bytes as
 * the scalar reference. */
#include "raster/shade_avx512.h"

#if defined(SG_SHADE_AVX512)

#include "raster/light_avx512.h"

INLINE void phong_tile(const sg_shade_ctx *c, const sg_tri *t, const sg_tri_ext *ext, int x0,
                       int y0, uint32_t mask, uint32_t *dst, const int textured, const int bilinear,
                       const int repeat, const int flat, const int lit, const int shadow) {
    const int ep = SG_LIT_POS - SG_TRI_ATTRS, en = SG_LIT_NRM - SG_TRI_ATTRS;
    const int ed = SG_LIT_SPLIT_D - SG_TRI_ATTRS;
    const int split_spec = lit == 2 && c->lights.has_specular;
    __m512 dx, dy;
    sg_tile_dxdy16(t, x0, y0, &dx, &dy);
#define SG_PLANE(a, adx, ady)                                                                      \
    _mm512_add_ps(_mm512_add_ps(_mm512_set1_ps(a), _mm512_mul_ps(_mm512_set1_ps(adx), dx)),        \
                  _mm512_mul_ps(_mm512_set1_ps(ady), dy))
    const __m512 w = _mm512_div_ps(_mm512_set1_ps(1.0f), SG_PLANE(t->q, t->q_dx, t->q_dy));
    __m512 base[4], P[3], n[3], prim[4], sec[3];
    for (int k = 0; k < 4; k++)
        base[k] = flat ? _mm512_set1_ps(t->color[k])
                       : _mm512_mul_ps(SG_PLANE(t->a[k], t->a_dx[k], t->a_dy[k]), w);
    for (int k = 0; k < 3; k++) {
        P[k] = _mm512_mul_ps(SG_PLANE(ext->a[ep + k], ext->a_dx[ep + k], ext->a_dy[ep + k]), w);
        if (lit == 1)
            n[k] = _mm512_mul_ps(SG_PLANE(ext->a[en + k], ext->a_dx[en + k], ext->a_dy[en + k]), w);
    }
    const __m512 vis =
        shadow ? lv_shadow_visibility(&c->shadow, P, (__mmask16)mask) : _mm512_set1_ps(1.0f);
    if (lit == 1) {
        lv_light_eval(&c->lights, P, n, base, shadow ? c->shadow.light : -1, vis, prim, sec);
    } else if (lit == 2) { /* split: base is the rest of the primary colour */
        __m512 part[9];
        for (int k = 0; k < (split_spec ? 9 : 3); k++)
            part[k] = flat ? _mm512_set1_ps(ext->a[ed + k])
                           : _mm512_mul_ps(
                                 SG_PLANE(ext->a[ed + k], ext->a_dx[ed + k], ext->a_dy[ed + k]), w);
        lv_split_combine(base, part, vis, prim);
        if (split_spec)
            for (int k = 0; k < 3; k++)
                sec[k] = _mm512_add_ps(part[3 + k], _mm512_mul_ps(vis, part[6 + k]));
    } else {
        for (int k = 0; k < 4; k++) prim[k] = base[k];
    }
    if (textured) {
        const tex16 tx = tex16_of(&c->tex, bilinear, true);
        __m512 s = _mm512_mul_ps(SG_PLANE(t->a[4], t->a_dx[4], t->a_dy[4]), w);
        __m512 u = _mm512_mul_ps(SG_PLANE(t->a[5], t->a_dx[5], t->a_dy[5]), w);
        __m512i tc[4];
        if (bilinear) {
            __m512i x[4];
            bilinear16(&tx, s, u, (__mmask16)mask, repeat, 0, x);
            for (int k = 0; k < 4; k++) tc[k] = _mm512_srli_epi32(x[k], 16);
        } else {
            unpack_texels(nearest16(&tx, s, u, (__mmask16)mask, repeat), tc);
        }
        for (int k = 0; k < 4; k++)
            prim[k] = _mm512_mul_ps(
                prim[k], _mm512_mul_ps(_mm512_cvtepi32_ps(tc[k]), _mm512_set1_ps(1.0f / 255.0f)));
    }
#undef SG_PLANE
    if (lit == 1 || split_spec) {
        for (int k = 0; k < 3; k++) prim[k] = _mm512_add_ps(prim[k], sec[k]);
    } else if (!lit) {
        const __m512 dim =
            _mm512_add_ps(_mm512_set1_ps(0.5f), _mm512_mul_ps(_mm512_set1_ps(0.5f), vis));
        for (int k = 0; k < 3; k++) prim[k] = _mm512_mul_ps(prim[k], dim);
    }
    _mm512_mask_storeu_epi32(dst, (__mmask16)mask, pack_unorm8(prim));
}

#define SG_PHONG_BODY  phong_tile
#define SG_PHONG_TABLE sg_shade_phong_avx512
#include "raster/shade_phong_variants.h"

#else

sg_shade_fn sg_shade_phong_avx512(int index) {
    (void)index;
    return NULL;
}

#endif
