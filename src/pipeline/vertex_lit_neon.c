/* vertex_lit_neon.c - Gouraud lighting of vertices in NEON (AArch64, four vertices a vector):
 * vertex_lit_simd.h on the operations of light_neon.h; the same bytes as the scalar path of
 * vertex.c. */
#include "raster/light_neon.h"

#include "pipeline/vertex.h"

#if defined(SG_LIGHT_NEON)

#include "pipeline/vertex_lit_simd.h"

static int gouraud_neon(const sg_vertex_lit *l, int first, int count, float *out, uint8_t *ok) {
    return vl_gouraud(l, first, count, out, ok);
}

sg_vertex_lit_fn sg_vertex_gouraud_neon(void) {
    return gouraud_neon;
}

#else

sg_vertex_lit_fn sg_vertex_gouraud_neon(void) {
    return NULL;
}

#endif
