/* vertex.c - transforms positions to clip space and classifies them against the clip planes once,
 * so that primitive assembly only reads results, however many triangles share a vertex. */
#include "pipeline/vertex.h"

#include "pipeline/mat4.h"
/* SSE lanes only where SSE also does scalar float maths: then they round as the scalar code. */
#if defined(__SSE_MATH__)
#include <xmmintrin.h>
#endif

void sg_vertex_transform(const float mvp[16], const float *positions, int count, float (*clip)[4],
                         uint32_t *outcodes, const sg_guard *guard) {
#if defined(__SSE_MATH__)
    /* The matrix columns in SSE lanes: lane r computes ((m[r][0] x + m[r][1] y) + m[r][2] z) +
     * m[r][3] w, the products and sums of sg_mat4_transform in its order, so the same bits. */
    const __m128 c0 = _mm_setr_ps(mvp[0], mvp[4], mvp[8], mvp[12]);
    const __m128 c1 = _mm_setr_ps(mvp[1], mvp[5], mvp[9], mvp[13]);
    const __m128 c2 = _mm_setr_ps(mvp[2], mvp[6], mvp[10], mvp[14]);
    const __m128 c3 = _mm_setr_ps(mvp[3], mvp[7], mvp[11], mvp[15]);
    for (int i = 0; i < count; i++) {
        __m128 v = _mm_loadu_ps(positions + (size_t)i * 4);
        __m128 r = _mm_mul_ps(c0, _mm_shuffle_ps(v, v, _MM_SHUFFLE(0, 0, 0, 0)));
        r = _mm_add_ps(r, _mm_mul_ps(c1, _mm_shuffle_ps(v, v, _MM_SHUFFLE(1, 1, 1, 1))));
        r = _mm_add_ps(r, _mm_mul_ps(c2, _mm_shuffle_ps(v, v, _MM_SHUFFLE(2, 2, 2, 2))));
        r = _mm_add_ps(r, _mm_mul_ps(c3, _mm_shuffle_ps(v, v, _MM_SHUFFLE(3, 3, 3, 3))));
        _mm_storeu_ps(clip[i], r);
        outcodes[i] = sg_clip_outcode(clip[i], guard);
    }
#else
    for (int i = 0; i < count; i++) {
        sg_mat4_transform(clip[i], mvp, positions + (size_t)i * 4);
        outcodes[i] = sg_clip_outcode(clip[i], guard);
    }
#endif
}
