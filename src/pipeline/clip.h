/* clip.h - homogeneous clipping of triangles and lines.
 *
 * Triangles are clipped in clip space against: the near and far planes (-w <= z <= w), a
 * minimum w (so no vertex with w <= 0 reaches the divide), and a guard band in x and y that is far
 * outside the viewport. The raster clips to the viewport for free by its bounding box, so the guard
 * band only cuts triangles whose screen coordinates would leave the fixed-point range.
 */
#ifndef SG_CLIP_H
#define SG_CLIP_H

#include <stdbool.h>
#include <stdint.h>

/* Attributes a vertex may carry through clipping and setup: r g b a, s t, then up to twelve more
 * for lit draws (secondary colour; or view position and normal; or, receiving a shadow map, view
 * position and the split colours of light.h). */
#define SG_MAX_ATTRS 18

/* Smallest w a clipped vertex keeps; far below any near plane a scene uses. */
#define SG_CLIP_W_MIN 1e-9f

/* Half-width of the guard band in pixels: 2^15, so snapped coordinates stay below 2^23 in
 * magnitude at 8 sub-pixel bits and edge functions below 2^49 (see docs/architecture.md). */
#define SG_GUARD_BAND_PIXELS 32768.0

typedef struct sg_cvert {
    float pos[4]; /* clip space x, y, z, w */
    float attr[SG_MAX_ATTRS];
} sg_cvert;

enum {
    SG_CLIP_NEAR = 1u << 0,
    SG_CLIP_FAR = 1u << 1,
    SG_CLIP_WMIN = 1u << 2,
    SG_CLIP_LEFT = 1u << 3,
    SG_CLIP_RIGHT = 1u << 4,
    SG_CLIP_BOTTOM = 1u << 5,
    SG_CLIP_TOP = 1u << 6,
    SG_CLIP_PLANE_COUNT = 7,
    /* Not a plane: a coordinate is NaN or infinite. Such a triangle is dropped whole. */
    SG_CLIP_NONFINITE = 1u << 7,
};

/* A clipped triangle has at most one more vertex per plane. */
#define SG_CLIP_MAX_VERTS (3 + SG_CLIP_PLANE_COUNT)

typedef struct sg_guard {
    float gx, gy; /* |x| <= gx * w and |y| <= gy * w keep a vertex inside the guard band */
} sg_guard;

#if defined(__SSE2__) && defined(__SSE_MATH__)
#include <emmintrin.h>
#include <float.h>

/** sg_clip_outcode of four positions, one a lane (x, y, z, w each a vector): the plane distances
 *  of clip.c in their order (a - b is exactly a + (-b)), so the same codes. Outside is
 *  !(d >= 0), so NaN is outside. */
static inline __m128i sg_clip_outcode4(__m128 x, __m128 y, __m128 z, __m128 w,
                                       const sg_guard *guard) {
    const __m128 sign = _mm_set1_ps(-0.0f), fmax = _mm_set1_ps(FLT_MAX), zero = _mm_setzero_ps();
    __m128 finite = _mm_and_ps(_mm_and_ps(_mm_cmple_ps(_mm_andnot_ps(sign, x), fmax),
                                          _mm_cmple_ps(_mm_andnot_ps(sign, y), fmax)),
                               _mm_and_ps(_mm_cmple_ps(_mm_andnot_ps(sign, z), fmax),
                                          _mm_cmple_ps(_mm_andnot_ps(sign, w), fmax)));
    __m128 gxw = _mm_mul_ps(_mm_set1_ps(guard->gx), w), gyw = _mm_mul_ps(_mm_set1_ps(guard->gy), w);
    const __m128 d[SG_CLIP_PLANE_COUNT] = {
        _mm_add_ps(z, w),   _mm_sub_ps(w, z),   _mm_sub_ps(w, _mm_set1_ps(SG_CLIP_W_MIN)),
        _mm_add_ps(x, gxw), _mm_sub_ps(gxw, x), _mm_add_ps(y, gyw),
        _mm_sub_ps(gyw, y)};
    __m128i code = _mm_setzero_si128();
    for (int k = 0; k < SG_CLIP_PLANE_COUNT; k++)
        code = _mm_or_si128(code, _mm_and_si128(_mm_castps_si128(_mm_cmpnge_ps(d[k], zero)),
                                                _mm_set1_epi32(1 << k)));
    const __m128i all = _mm_set1_epi32(SG_CLIP_NONFINITE | ((1 << SG_CLIP_PLANE_COUNT) - 1));
    return _mm_or_si128(code, _mm_andnot_si128(_mm_castps_si128(finite), all));
}
#endif

/** Guard-band factors for a viewport of the given size. */
sg_guard sg_guard_for_viewport(int width, int height);
/** The set of planes a clip-space position is outside of (0: inside all); a non-finite
 *  position is outside all planes and also has SG_CLIP_NONFINITE. */
uint32_t sg_clip_outcode(const float pos[4], const sg_guard *guard);
/** Clips the polygon poly[0..n) against `planes`, in place; returns the new vertex count
 *  (0 when nothing is left). poly must hold SG_CLIP_MAX_VERTS vertices. */
int sg_clip_polygon(sg_cvert *poly, int n, uint32_t planes, int nattr, const sg_guard *guard);
/** Clips the segment v[0] -> v[1] against `planes`, in place, keeping its direction; false when
 *  nothing is left. */
bool sg_clip_line(sg_cvert v[2], uint32_t planes, int nattr, const sg_guard *guard);

#endif
