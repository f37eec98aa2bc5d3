/* shade_phong_avx512.c - per-pixel lighting in AVX-512 (see shade_phong.c). */
#include "raster/shade.h"

sg_shade_fn sg_shade_phong_avx512(int variant) {
    (void)variant;
    return NULL;
}
