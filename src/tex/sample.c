/* sample.c - out-of-line entry to the inline samplers of sample.h. */
#include "tex/sample.h"

sg_texel sg_sample(const sg_texview *tv, float s, float t, int bilinear, int repeat) {
    return bilinear ? sg_sample_bilinear(tv, s, t, repeat) : sg_sample_nearest(tv, s, t, repeat);
}
