/* shade_phong_avx2.c - per-pixel lighting in AVX2 (see shade_phong.c). */
#include "raster/shade.h"

sg_shade_fn sg_shade_phong_avx2(int variant) {
    (void)variant;
    return NULL;
}
