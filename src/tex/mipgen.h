/* mipgen.h - the mipmap generator: one level from the one above it, RGBA8, top row first.
 *
 * Header-only so that the core (image.c) and the utility library (sgu_generate_mip_level, which
 * the lavapipe reference uploads) run the same code and give the same bytes.
 *
 * Level k + 1 is max(1, w / 2) x max(1, h / 2) (integer division, as Vulkan sizes levels). Its
 * texel (x, y) is the mean of the 2 x 2 block of texels (2x .. 2x+1, 2y .. 2y+1) of level k,
 * rounded to nearest (halves up): (sum + n / 2) / n. A side of 1 takes its one texel instead of
 * two; an odd side above 1 folds its last texel into the last block, which then spans three
 * (so n is 1, 2, 3, 4, 6 or 9), so that no texel of the level above is lost.
 */
#ifndef SG_MIPGEN_H
#define SG_MIPGEN_H

#include <stddef.h>
#include <stdint.h>

/** The side of the next level: max(1, n / 2). */
static inline int sg_mip_next_side(int n) {
    return n > 1 ? n / 2 : 1;
}

/** The number of levels of the full chain of a w x h image, down to 1 x 1. */
static inline int sg_mip_chain_length(int w, int h) {
    int n = 1;
    for (int m = w > h ? w : h; m > 1; m >>= 1) n++;
    return n;
}

/* The source indices of destination index d along a side of n texels: first and count. */
static inline void sg_mip_span(int d, int n, int *first, int *count) {
    *first = 2 * d;
    if (n == 1) {
        *first = 0;
        *count = 1;
    } else {
        *count = (n & 1) && d == n / 2 - 1 ? 3 : 2;
    }
}

/** Makes the level below src (sw x sh, tightly packed RGBA8) into dst (its size by
 *  sg_mip_next_side). */
static inline void sg_mip_generate(const uint8_t *src, int sw, int sh, uint8_t *dst) {
    const int dw = sg_mip_next_side(sw), dh = sg_mip_next_side(sh);
    for (int y = 0; y < dh; y++) {
        int y0, ny;
        sg_mip_span(y, sh, &y0, &ny);
        for (int x = 0; x < dw; x++) {
            int x0, nx;
            sg_mip_span(x, sw, &x0, &nx);
            const uint32_t n = (uint32_t)(nx * ny);
            uint32_t sum[4] = {0, 0, 0, 0};
            for (int j = 0; j < ny; j++) {
                const uint8_t *row = src + ((size_t)(y0 + j) * (size_t)sw + (size_t)x0) * 4;
                for (int i = 0; i < nx; i++)
                    for (int k = 0; k < 4; k++) sum[k] += row[i * 4 + k];
            }
            uint8_t *out = dst + ((size_t)y * (size_t)dw + (size_t)x) * 4;
            for (int k = 0; k < 4; k++) out[k] = (uint8_t)((sum[k] + n / 2) / n);
        }
    }
}

#endif
