/* shade_phong_avx2.c - per-pixel lighting in AVX2 (see shade_phong.c): two rows of a tile a
 * vector, the equation of light_simd.h, the texture helpers of shade_avx2.h; the same bytes as the
 * scalar reference. */
#include "raster/shade_avx2.h"

#if defined(SG_SHADE_AVX2)

#include "raster/light_avx2.h"

INLINE void phong_rows(const sg_shade_ctx *c, const sg_tri *t, const sg_tri_ext *ext, int x0,
                       int y0, uint32_t mask, uint32_t *dst, const int textured, const int bilinear,
                       const int repeat, const int flat, const int lit, const int shadow) {
    const int ep = SG_LIT_POS - SG_TRI_ATTRS, en = SG_LIT_NRM - SG_TRI_ATTRS;
    const int ed = SG_LIT_SPLIT_D - SG_TRI_ATTRS;
    const int split_spec = lit == 2 && c->lights.has_specular;
    const float ox = (float)(x0 - t->minx), oy = (float)(y0 - t->miny);
    const __m256 dx = _mm256_add_ps(_mm256_set1_ps(ox),
                                    _mm256_setr_ps(0.0f, 1.0f, 2.0f, 3.0f, 0.0f, 1.0f, 2.0f, 3.0f));
    tex8 tx;
    if (textured) tx = tex8_of(&c->tex, bilinear);
    for (int r = 0; r < 4; r += 2) {
        unsigned m = (mask >> (4 * r)) & 255u;
        if (!m) continue;
        /* dy of row r in the low half, of row r + 1 in the high half */
        const __m256 dy =
            _mm256_set_m128(_mm_set1_ps(oy + (float)(r + 1)), _mm_set1_ps(oy + (float)r));
#define SG_PLANE(a, adx, ady)                                                                      \
    _mm256_add_ps(_mm256_add_ps(_mm256_set1_ps(a), _mm256_mul_ps(_mm256_set1_ps(adx), dx)),        \
                  _mm256_mul_ps(_mm256_set1_ps(ady), dy))
        const __m256 w = _mm256_div_ps(_mm256_set1_ps(1.0f), SG_PLANE(t->q, t->q_dx, t->q_dy));
        __m256 base[4], P[3], n[3], prim[4], sec[3];
        for (int k = 0; k < 4; k++)
            base[k] = flat ? _mm256_set1_ps(t->color[k])
                           : _mm256_mul_ps(SG_PLANE(t->a[k], t->a_dx[k], t->a_dy[k]), w);
        for (int k = 0; k < 3; k++) {
            P[k] = _mm256_mul_ps(SG_PLANE(ext->a[ep + k], ext->a_dx[ep + k], ext->a_dy[ep + k]), w);
            if (lit == 1)
                n[k] = _mm256_mul_ps(SG_PLANE(ext->a[en + k], ext->a_dx[en + k], ext->a_dy[en + k]),
                                     w);
        }
        __m256 vis = _mm256_set1_ps(1.0f);
        if (shadow) {
            const __m256i bits = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
            const __m256 live = _mm256_castsi256_ps(
                _mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32((int)m), bits), bits));
            vis = lv_shadow_visibility(&c->shadow, P, live);
        }
        if (lit == 1) {
            lv_light_eval(&c->lights, P, n, base, shadow ? c->shadow.light : -1, vis, prim, sec);
        } else if (lit == 2) { /* split: base is the rest of the primary colour */
            __m256 part[9];
            for (int k = 0; k < (split_spec ? 9 : 3); k++)
                part[k] =
                    flat ? _mm256_set1_ps(ext->a[ed + k])
                         : _mm256_mul_ps(
                               SG_PLANE(ext->a[ed + k], ext->a_dx[ed + k], ext->a_dy[ed + k]), w);
            lv_split_combine(base, part, vis, prim);
            if (split_spec)
                for (int k = 0; k < 3; k++)
                    sec[k] = _mm256_add_ps(part[3 + k], _mm256_mul_ps(vis, part[6 + k]));
        } else {
            for (int k = 0; k < 4; k++) prim[k] = base[k];
        }
        if (textured) {
            __m256 s = _mm256_mul_ps(SG_PLANE(t->a[4], t->a_dx[4], t->a_dy[4]), w);
            __m256 u = _mm256_mul_ps(SG_PLANE(t->a[5], t->a_dx[5], t->a_dy[5]), w);
            __m256i tc[4];
            if (bilinear) {
                __m256i x[4];
                bilinear8(&tx, s, u, repeat, x);
                for (int k = 0; k < 4; k++) tc[k] = _mm256_srli_epi32(x[k], 16);
            } else {
                unpack_texels(nearest8(&tx, s, u, repeat), tc);
            }
            for (int k = 0; k < 4; k++)
                prim[k] = _mm256_mul_ps(prim[k], _mm256_mul_ps(_mm256_cvtepi32_ps(tc[k]),
                                                               _mm256_set1_ps(1.0f / 255.0f)));
        }
#undef SG_PLANE
        if (lit == 1 || split_spec) {
            for (int k = 0; k < 3; k++) prim[k] = _mm256_add_ps(prim[k], sec[k]);
        } else if (!lit) {
            const __m256 dim =
                _mm256_add_ps(_mm256_set1_ps(0.5f), _mm256_mul_ps(_mm256_set1_ps(0.5f), vis));
            for (int k = 0; k < 3; k++) prim[k] = _mm256_mul_ps(prim[k], dim);
        }
        store_rows(dst + 4 * r, pack_unorm8(prim), m);
    }
}

#define SG_PHONG_BODY  phong_rows
#define SG_PHONG_TABLE sg_shade_phong_avx2
#include "raster/shade_phong_variants.h"

#else

sg_shade_fn sg_shade_phong_avx2(int index) {
    (void)index;
    return NULL;
}

#endif
