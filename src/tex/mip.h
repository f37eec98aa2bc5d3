/* mip.h - mipmapped sampling: the level of detail of a 2 x 2 quad and the trilinear blend.
 *
 * The level of detail follows lavapipe (llvmpipe's sampler at its default settings), which the
 * Vulkan spec allows (docs/accuracy.md, "Mipmaps"): one LOD per 2 x 2 quad, from the differences
 * of the texture coordinates between the quad's top-left pixel and its right and lower
 * neighbours; rho^2 = max(|d(s,t)/dx|^2, |d(s,t)/dy|^2) in level-0 texels, exactly; the nearest
 * level is round(log2 rho) taken from rho^2's exponent (exact); the linear LOD is
 * 0.5 * log2(rho^2) with log2 approximated piecewise linearly between powers of two
 * (exponent - 1 + mantissa), its fraction taken to 8 bits by truncation, and the two levels
 * blended in 8-bit fixed point as c0 + floor((c1 - c0) * f / 256).
 */
#ifndef SG_MIP_H
#define SG_MIP_H

#include <math.h>
#include <stdint.h>
#include <string.h>

#include "tex/sample.h"

/* The levels a quad samples: level0 and level1 with level1's weight f (0 .. 255). */
typedef struct sg_mip_pick {
    int level0, level1, f;
} sg_mip_pick;

static inline int sg_float_exponent(float x) {
    uint32_t b;
    memcpy(&b, &x, sizeof b);
    return (int)((b >> 23) & 0xffu) - 127;
}

/** The level(s) of a quad whose texture coordinates change by (dsdx, dtdx) to the right and
 *  (dsdy, dtdy) downward, for a chain; linear: two levels and a weight, else one. */
static inline sg_mip_pick sg_mip_select(const sg_mip_chain *m, float dsdx, float dtdx, float dsdy,
                                        float dtdy, int linear) {
    const float w = (float)m->level[0].width, h = (float)m->level[0].height;
    const float ax = dsdx * w, bx = dtdx * h, ay = dsdy * w, by = dtdy * h;
    const float rx = ax * ax + bx * bx, ry = ay * ay + by * by;
    const float rho2 = rx > ry ? rx : ry;
    const int last = m->levels - 1;
    sg_mip_pick p = {0, 0, 0};
    if (!linear) {
        /* round(log2 rho) = (floor(log2 rho^2) + 1) >> 1, an arithmetic shift (floor). */
        const int e = sg_float_exponent(rho2) + 1;
        int l = e >= 0 ? e / 2 : -((-e + 1) / 2);
        l = l < 0 ? 0 : (l > last ? last : l);
        p.level0 = p.level1 = l;
        return p;
    }
    uint32_t b;
    memcpy(&b, &rho2, sizeof b);
    const uint32_t mb = (b & 0x007fffffu) | 0x3f800000u;
    float mant;
    memcpy(&mant, &mb, sizeof mant);
    const float lod = ((float)(sg_float_exponent(rho2) - 1) + mant) * 0.5f;
    const float fl = floorf(lod);
    int i = (int)fl;
    float frac = lod - fl;
    if (!(lod >= -1e9f && lod <= 1e9f)) { /* NaN derivatives: level 0 */
        i = 0;
        frac = 0.0f;
    }
    if (i < 0) {
        p.level0 = p.level1 = 0;
    } else if (i >= last) {
        p.level0 = p.level1 = last;
    } else {
        p.level0 = i;
        p.level1 = i + 1;
        p.f = (int)(frac * 256.0f);
    }
    return p;
}

/** One texel of a chain at (s, t) with the picked levels, each sampled with the filter. */
static inline sg_texel sg_sample_mip(const sg_mip_chain *m, sg_mip_pick p, float s, float t,
                                     int bilinear, int repeat) {
    const sg_texview *v0 = &m->level[p.level0];
    sg_texel a =
        bilinear ? sg_sample_bilinear(v0, s, t, repeat) : sg_sample_nearest(v0, s, t, repeat);
    if (p.f == 0) return a;
    const sg_texview *v1 = &m->level[p.level1];
    sg_texel b =
        bilinear ? sg_sample_bilinear(v1, s, t, repeat) : sg_sample_nearest(v1, s, t, repeat);
    for (int k = 0; k < 4; k++) a.c[k] += ((b.c[k] - a.c[k]) * p.f) >> 8;
    return a;
}

#endif
