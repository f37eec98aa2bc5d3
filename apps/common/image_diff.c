/* image_diff.c - error figures between two images, and a heat map of where they differ. */
#include "image_diff.h"

#include <math.h>
#include <stdlib.h>

/* Heat map colour for a difference of d/255: black, then blue (1), red (8), yellow (32), white
 * (128 and above), so single steps and real errors are told apart at a glance. */
static void heat_colour(int d, unsigned char *p) {
    static const int stops[5][3] = {
        {0, 0, 0}, {0, 0, 255}, {255, 0, 0}, {255, 255, 0}, {255, 255, 255}};
    static const int at[5] = {0, 1, 8, 32, 128};
    p[3] = 255;
    if (d <= 0) {
        p[0] = p[1] = p[2] = 0;
        return;
    }
    int k = 0;
    while (k < 3 && d > at[k + 1]) k++;
    double t = d >= at[4] ? 1.0 : (double)(d - at[k]) / (at[k + 1] - at[k]);
    for (int c = 0; c < 3; c++)
        p[c] = (unsigned char)lround(stops[k][c] + t * (stops[k + 1][c] - stops[k][c]));
}

sc_diff sc_image_diff(const unsigned char *a, const unsigned char *b, int w, int h,
                      const unsigned char background[4], unsigned char *heat) {
    size_t pixels = (size_t)w * (size_t)h;
    double sq = 0, abs_sum = 0;
    size_t over[3] = {0, 0, 0};
    sc_diff r = {0};
    for (size_t i = 0; i < pixels; i++) {
        const unsigned char *pa = a + i * 4, *pb = b + i * 4;
        int m = 0, bga = 1, bgb = 1;
        for (int c = 0; c < 4; c++) {
            int d = abs((int)pa[c] - (int)pb[c]);
            if (c < 3) sq += (double)d * d;
            abs_sum += d;
            if (d > m) m = d;
            bga &= pa[c] == background[c];
            bgb &= pb[c] == background[c];
        }
        if (m > r.max_error) r.max_error = m;
        over[0] += m > 2;
        over[1] += m > 8;
        over[2] += m > 32;
        r.coverage_mismatch += bga != bgb;
        if (heat) heat_colour(m, heat + i * 4);
    }
    double mse = pixels ? sq / ((double)pixels * 3) : 0;
    r.psnr_db = mse > 0 ? 10.0 * log10(255.0 * 255.0 / mse) : INFINITY;
    r.mean_abs_error = pixels ? abs_sum / ((double)pixels * 4) : 0;
    for (int k = 0; k < 3; k++) r.pct_over[k] = pixels ? 100.0 * (double)over[k] / pixels : 0;
    r.pct_coverage = pixels ? 100.0 * (double)r.coverage_mismatch / pixels : 0;
    return r;
}
