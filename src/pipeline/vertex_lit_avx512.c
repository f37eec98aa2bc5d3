/* vertex_lit_avx512.c - Gouraud lighting of vertices in AVX-512 (sixteen vertices a vector):
 * vertex_lit_simd.h on the operations of light_avx512.h; the same bytes as the scalar path of
 * vertex.c. */
#include "raster/light_avx512.h"

#include "pipeline/vertex.h"

#if defined(SG_LIGHT_AVX512)

#include "pipeline/vertex_lit_simd.h"

static int gouraud_avx512(const sg_vertex_lit *l, int first, int count, float *out, uint8_t *ok) {
    return vl_gouraud(l, first, count, out, ok);
}

sg_vertex_lit_fn sg_vertex_gouraud_avx512(void) {
    return gouraud_avx512;
}

#else

sg_vertex_lit_fn sg_vertex_gouraud_avx512(void) {
    return NULL;
}

#endif
