/* shadow.h - the shadow map a draw receives: how much of the shadowing light reaches a point.
 *
 * The map holds, per texel, the depth of the nearest caster seen from the light (a depth-only
 * pass). A point P in view space goes to the light's clip space, s = M (P, 1); where s.w <= 0 it
 * is behind the light, and lit. Otherwise, in the map's pixels (top row first, like every
 * target):
 *
 *   x = (s.x / s.w * 0.5 + 0.5) * width,  y = (0.5 - s.y / s.w * 0.5) * height,
 *   depth = min(s.z / s.w * 0.5 + 0.5, 1)
 *
 * (a point beyond the light's far plane is shadowed by what the map holds, lit where it holds
 * nothing) and a texel (i, j) sees the light when depth <= map[j][i]; texels outside the map see
 * it. Without PCF the visibility is that of texel (floor x, floor y), 0 or 1; with PCF, the mean of
 * the 2 x 2 texels around (x, y): from (floor(x - 0.5), floor(y - 0.5)), 0, 1/4, 1/2, 3/4 or 1.
 * Depth bias belongs to the pass that renders the map (sgPipelineDesc.depth.bias_*). The SIMD
 * shading (light_simd.h) computes the same IEEE operations in the same order.
 */
#ifndef SG_SHADOW_H
#define SG_SHADOW_H

#include <stdbool.h>

typedef struct sg_shadow_view {
    const float *map; /* width x height depths, top row first; NULL: the draw receives none */
    int width, height;
    float m[16]; /* view space -> the light's clip space, row-major */
    int light;   /* lit draws: the index of the light the map hides */
    bool pcf;
} sg_shadow_view;

/* Texel (i, j) sees the light at `depth` (outside the map: it does). */
static inline float sg_shadow_texel(const sg_shadow_view *s, int i, int j, float depth) {
    if (i < 0 || j < 0 || i >= s->width || j >= s->height) return 1.0f;
    return depth <= s->map[(long)j * s->width + i] ? 1.0f : 0.0f;
}

/** The fraction of the point P (view space) the shadowing light reaches, 0 .. 1. */
static inline float sg_shadow_visibility(const sg_shadow_view *s, const float P[3]) {
    const float *m = s->m;
    float c[4];
    for (int r = 0; r < 4; r++)
        c[r] = ((m[r * 4] * P[0] + m[r * 4 + 1] * P[1]) + m[r * 4 + 2] * P[2]) + m[r * 4 + 3];
    if (!(c[3] > 0.0f)) return 1.0f;
    float x = (c[0] / c[3] * 0.5f + 0.5f) * (float)s->width;
    float y = (0.5f - c[1] / c[3] * 0.5f) * (float)s->height;
    float depth = c[2] / c[3] * 0.5f + 0.5f;
    depth = depth < 1.0f ? depth : 1.0f; /* beyond the far plane: as on it */
    if (s->pcf) {
        x = x - 0.5f;
        y = y - 0.5f;
    }
    /* Far outside the map (or NaN): lit, before any conversion to int could overflow. */
    if (!(x >= -1.0f && x < (float)s->width && y >= -1.0f && y < (float)s->height)) return 1.0f;
    int i = (int)floorf(x), j = (int)floorf(y);
    if (!s->pcf) return sg_shadow_texel(s, i, j, depth);
    float sum = (sg_shadow_texel(s, i, j, depth) + sg_shadow_texel(s, i + 1, j, depth)) +
                (sg_shadow_texel(s, i, j + 1, depth) + sg_shadow_texel(s, i + 1, j + 1, depth));
    return sum * 0.25f;
}

#endif
