/* vertex_lit_avx2.c - Gouraud lighting of vertices in AVX2 (eight vertices a vector):
 * vertex_lit_simd.h on the operations of light_avx2.h; the same bytes as the scalar path of
 * vertex.c. */
#include "raster/light_avx2.h"

#include "pipeline/vertex.h"

#if defined(SG_LIGHT_AVX2)

#include "pipeline/vertex_lit_simd.h"

static int gouraud_avx2(const sg_vertex_lit *l, int first, int count, float *out, uint8_t *ok) {
    return vl_gouraud(l, first, count, out, ok);
}

sg_vertex_lit_fn sg_vertex_gouraud_avx2(void) {
    return gouraud_avx2;
}

#else

sg_vertex_lit_fn sg_vertex_gouraud_avx2(void) {
    return NULL;
}

#endif
