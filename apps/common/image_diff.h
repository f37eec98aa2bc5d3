/* image_diff.h - how far apart two RGBA8 images of the same size are. */
#ifndef SC_IMAGE_DIFF_H
#define SC_IMAGE_DIFF_H

#include <stddef.h>

typedef struct sc_diff {
    double psnr_db;           /* over R, G, B; INFINITY when identical */
    double mean_abs_error;    /* in 1/255 steps, over all four channels */
    int max_error;            /* largest channel difference, in 1/255 steps */
    double pct_over[3];       /* % of pixels whose largest channel difference exceeds 2, 8, 32 */
    size_t coverage_mismatch; /* pixels that are background in one image and not in the other */
    double pct_coverage;
} sc_diff;

/** Compares a and b (RGBA8, w x h); `background` is the clear colour (RGBA8). When heat is not
 *  NULL it receives an RGBA8 heat map of the largest channel difference per pixel. */
sc_diff sc_image_diff(const unsigned char *a, const unsigned char *b, int w, int h,
                      const unsigned char background[4], unsigned char *heat);

#endif
