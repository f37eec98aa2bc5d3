/* sample.h - texture sampling: nearest and bilinear, repeat and clamp-to-edge, from RGBA8.
 *
 * Texels are stored top row first (as uploaded); t = 0 addresses the bottom row, as in OpenGL.
 * Bilinear filtering works in 8-bit fixed point: the texel-space coordinate minus half a texel is
 * taken to 1/256 texel, and the four texels are weighted by those 8-bit fractions, as lavapipe
 * does for unorm8 textures. The functions are inline so each specialised shader gets its own copy
 * with the filter and wrap mode folded in.
 */
#ifndef SG_SAMPLE_H
#define SG_SAMPLE_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>

#include "sgapi/sgapi.h"

/* A texture's sizes in the forms the vector lookups take them ([0] x, [1] y), made once with the
 * view: read from memory, each is one broadcast load, where forming them from the width and height
 * took conversions and register broadcasts on every tile, for each level a trilinear tile reads. */
typedef struct sg_texsizes {
    float scale[2][2]; /* [bilinear][axis]: the side, times 256 when bilinear */
    float hi[2][2];    /* [bilinear][axis]: side - 1, or 256 (side + 1) when bilinear */
    int32_t n[2], last[2];
} sg_texsizes;

typedef struct sg_texview {
    const uint8_t *texels; /* RGBA8, top row first */
    int width, height;
    sg_texsizes size; /* of width and height (sg_texview_of) */
} sg_texview;

/* A view of w x h texels, its sizes made. */
static inline sg_texview sg_texview_of(const uint8_t *texels, int w, int h) {
    sg_texview v = {.texels = texels, .width = w, .height = h};
    const int side[2] = {w, h};
    for (int a = 0; a < 2; a++) {
        v.size.scale[0][a] = (float)side[a];
        v.size.scale[1][a] = 256.0f * (float)side[a];
        v.size.hi[0][a] = (float)(side[a] - 1);
        v.size.hi[1][a] = 256.0f * (float)(side[a] + 1);
        v.size.n[a] = side[a];
        v.size.last[a] = side[a] - 1;
    }
    return v;
}

/* An image's mipmap levels (level 0 included): each RGBA8, top row first, 64-byte aligned, in one
 * block, level k max(1, width >> k) x max(1, height >> k). Held by the image; draws point at it,
 * which the open pass keeps alive and unchanged (an image a draw samples cannot be uploaded to
 * or destroyed before sgEndRenderPass). */
typedef struct sg_mip_chain {
    int levels; /* 1 .. SG_MAX_MIP_LEVELS */
    sg_texview level[SG_MAX_MIP_LEVELS];
} sg_mip_chain;

typedef struct sg_texel {
    int32_t c[4]; /* 0 .. 255 */
} sg_texel;

/* Coordinate in texels (scaled by `scale`, 1 or 256) with repeat: only the fraction of the
 * coordinate matters, which also keeps huge coordinates from overflowing. NaN gives 0. */
static inline float sg_texcoord_repeat(float s, float size_scaled) {
    float f = s - floorf(s); /* in [0, 1]; exactly 1 for tiny negative s */
    float x = f * size_scaled;
    return x >= 0.0f ? x : 0.0f;
}

/* Coordinate in texels (scaled) with clamp: limited first so the int conversion cannot overflow. */
static inline float sg_texcoord_clamp(float s, float size_scaled) {
    if (!(s >= -1.0f)) s = -1.0f; /* NaN lands here too */
    if (s > 2.0f) s = 2.0f;
    return s * size_scaled;
}

static inline int sg_wrap_index(int i, int n, int repeat) {
    if (repeat) {
        if (i < 0) i += n;
        if (i >= n) i -= n;
        return i;
    }
    return i < 0 ? 0 : (i >= n ? n - 1 : i);
}

/* Texel at column i, row j counted from the bottom. */
static inline const uint8_t *sg_texel_at(const sg_texview *tv, int i, int j) {
    return tv->texels + ((size_t)(tv->height - 1 - j) * (size_t)tv->width + (size_t)i) * 4;
}

static inline sg_texel sg_sample_nearest(const sg_texview *tv, float s, float t, int repeat) {
    float x =
        repeat ? sg_texcoord_repeat(s, (float)tv->width) : sg_texcoord_clamp(s, (float)tv->width);
    float y =
        repeat ? sg_texcoord_repeat(t, (float)tv->height) : sg_texcoord_clamp(t, (float)tv->height);
    int i = sg_wrap_index((int)floorf(x), tv->width, repeat);
    int j = sg_wrap_index((int)floorf(y), tv->height, repeat);
    const uint8_t *p = sg_texel_at(tv, i, j);
    sg_texel r = {{p[0], p[1], p[2], p[3]}};
    return r;
}

/* Integer texel index and 8-bit fraction of a coordinate scaled by 256, half a texel back. */
static inline void sg_bilinear_split(float x256, int *i0, int *frac) {
    int v = (int)floorf(x256) - 128 + 512; /* +512 keeps it positive for the shift */
    *i0 = (v >> 8) - 2;
    *frac = v & 255;
}

static inline sg_texel sg_sample_bilinear(const sg_texview *tv, float s, float t, int repeat) {
    float x = repeat ? sg_texcoord_repeat(s, 256.0f * (float)tv->width)
                     : sg_texcoord_clamp(s, 256.0f * (float)tv->width);
    float y = repeat ? sg_texcoord_repeat(t, 256.0f * (float)tv->height)
                     : sg_texcoord_clamp(t, 256.0f * (float)tv->height);
    if (!repeat) { /* beyond one texel outside, clamp-to-edge reads the edge texel anyway */
        float xmax = 256.0f * (float)(tv->width + 1), ymax = 256.0f * (float)(tv->height + 1);
        x = x < -256.0f ? -256.0f : (x > xmax ? xmax : x);
        y = y < -256.0f ? -256.0f : (y > ymax ? ymax : y);
    }
    int i0, j0, fx, fy;
    sg_bilinear_split(x, &i0, &fx);
    sg_bilinear_split(y, &j0, &fy);
    int i1 = sg_wrap_index(i0 + 1, tv->width, repeat),
        j1 = sg_wrap_index(j0 + 1, tv->height, repeat);
    i0 = sg_wrap_index(i0, tv->width, repeat);
    j0 = sg_wrap_index(j0, tv->height, repeat);
    const uint8_t *p00 = sg_texel_at(tv, i0, j0), *p10 = sg_texel_at(tv, i1, j0);
    const uint8_t *p01 = sg_texel_at(tv, i0, j1), *p11 = sg_texel_at(tv, i1, j1);
    int w00 = (256 - fx) * (256 - fy), w10 = fx * (256 - fy), w01 = (256 - fx) * fy, w11 = fx * fy;
    sg_texel r;
    for (int k = 0; k < 4; k++)
        r.c[k] = (p00[k] * w00 + p10[k] * w10 + p01[k] * w01 + p11[k] * w11 + 32768) >> 16;
    return r;
}

/** Out-of-line copies of the samplers, for tests and non-specialised callers. */
sg_texel sg_sample(const sg_texview *tv, float s, float t, int bilinear, int repeat);

#endif
