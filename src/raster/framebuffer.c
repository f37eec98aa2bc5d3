/* framebuffer.c - filling tiled and linear pixels and converting between the two layouts. */
#include "raster/framebuffer.h"

#include "raster/blend.h"
#include "raster/depth.h"

#include <string.h>

static int tiles_of(int n) {
    return (n + SG_TILE - 1) >> SG_TILE_SHIFT;
}

size_t sg_fb_tiled_pixels(int width, int height) {
    return (size_t)tiles_of(width) * (size_t)tiles_of(height) * SG_TILE_PIXELS;
}

void sg_fb_fill_color(uint32_t *tiles, size_t pixels, uint32_t value) {
    for (size_t i = 0; i < pixels; i++) tiles[i] = value;
}

void sg_fb_fill_depth(float *tiles, size_t pixels, float value) {
    for (size_t i = 0; i < pixels; i++) tiles[i] = value;
}

void sg_tile_from_linear_rgba8(uint32_t *tiles, const uint8_t *src, size_t pitch, int w, int h,
                               int tx) {
    for (int y = 0; y < h; y++) {
        const uint8_t *row = src + (size_t)y * pitch;
        for (int x = 0; x < w; x++) {
            const uint8_t *p = row + (size_t)x * 4;
            tiles[sg_fb_index(tx, x, y)] = sg_pack_rgba8(p[0], p[1], p[2], p[3]);
        }
    }
}

void sg_tile_to_linear_rgba8(uint8_t *dst, size_t pitch, const uint32_t *tiles, int w, int h,
                             int tx) {
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
    /* The packed pixel's bytes in memory already are R, G, B, A: a tile row is 16 bytes to copy. */
    int whole = w >> SG_TILE_SHIFT;
    for (int y = 0; y < h; y++) {
        uint8_t *row = dst + (size_t)y * pitch;
        const uint32_t *src = tiles + sg_fb_index(tx, 0, y);
        for (int t = 0; t < whole; t++)
            memcpy(row + (size_t)t * 16, src + (size_t)t * SG_TILE_PIXELS, 16);
        for (int x = whole << SG_TILE_SHIFT; x < w; x++)
            memcpy(row + (size_t)x * 4, &tiles[sg_fb_index(tx, x, y)], 4);
    }
    return;
#endif
    for (int y = 0; y < h; y++) {
        uint8_t *row = dst + (size_t)y * pitch;
        for (int x = 0; x < w; x++) {
            uint32_t v = tiles[sg_fb_index(tx, x, y)];
            uint8_t *p = row + (size_t)x * 4;
            p[0] = (uint8_t)v;
            p[1] = (uint8_t)(v >> 8);
            p[2] = (uint8_t)(v >> 16);
            p[3] = (uint8_t)(v >> 24);
        }
    }
}

void sg_tile_from_linear_f32(float *tiles, const float *src, size_t pitch, int w, int h, int tx) {
    for (int y = 0; y < h; y++) {
        const float *row = (const float *)(const void *)((const uint8_t *)src + (size_t)y * pitch);
        for (int x = 0; x < w; x++) tiles[sg_fb_index(tx, x, y)] = row[x];
    }
}

void sg_tile_to_linear_f32(float *dst, size_t pitch, const float *tiles, int w, int h, int tx) {
    int whole = w >> SG_TILE_SHIFT;
    for (int y = 0; y < h; y++) {
        float *row = (float *)(void *)((uint8_t *)dst + (size_t)y * pitch);
        const float *src = tiles + sg_fb_index(tx, 0, y);
        for (int t = 0; t < whole; t++)
            memcpy(row + (size_t)t * SG_TILE, src + (size_t)t * SG_TILE_PIXELS,
                   SG_TILE * sizeof(float));
        for (int x = whole << SG_TILE_SHIFT; x < w; x++) row[x] = tiles[sg_fb_index(tx, x, y)];
    }
}

void sg_fill_linear_u32(void *dst, size_t pitch, int w, int h, uint32_t value) {
    for (int y = 0; y < h; y++) {
        uint32_t *row = (uint32_t *)(void *)((uint8_t *)dst + (size_t)y * pitch);
        for (int x = 0; x < w; x++) row[x] = value;
    }
}

bool sg_fb_depth_range(const float *src, size_t n, float *lo, float *hi) {
    return sg_fb_depth_range_of(src, n, lo, hi);
}

void sg_fb_put_masked(uint32_t *dst, const uint32_t *src, uint32_t mask) {
    sg_fb_put_lanes(dst, src, mask);
}

void sg_fb_blend_masked(uint32_t *dst, const uint32_t *src, uint32_t mask) {
    _Alignas(64) uint32_t px[SG_TILE_PIXELS];
    sg_blend16_rgba8(src, dst, px);
    sg_fb_put_masked(dst, px, mask);
}

void sg_fb_average4_planes(uint32_t *p0, const uint32_t *p1, const uint32_t *p2, const uint32_t *p3,
                           size_t n) {
    for (size_t i = 0; i < n; i++) p0[i] = sg_fb_average4(p0[i], p1[i], p2[i], p3[i]);
}

static uint32_t same_portable(const void *vecs, int k, uint32_t id) {
    return sg_tile_same_id(((const uint32_t *const *)vecs)[k], id);
}

int sg_fb_split_ids(const uint32_t *const planes[4], uint32_t *ids, uint64_t *samples) {
    uint32_t left[4];
    for (int k = 0; k < 4; k++) left[k] = ~sg_tile_same_id(planes[k], 0) & 0xffffu;
    return sg_fb_split_ids_with(planes, planes, left, same_portable, ids, samples);
}

static inline bool tile_alike(const uint32_t *const planes[4], size_t base) {
#if defined(__SSE2__)
    __m128i diff = _mm_setzero_si128();
    for (int j = 0; j < SG_TILE_PIXELS; j += 4) {
        const __m128i first = _mm_load_si128((const __m128i *)(const void *)(planes[0] + base + j));
        for (int k = 1; k < 4; k++)
            diff = _mm_or_si128(
                diff,
                _mm_xor_si128(
                    first, _mm_load_si128((const __m128i *)(const void *)(planes[k] + base + j))));
    }
    return _mm_movemask_epi8(_mm_cmpeq_epi32(diff, _mm_setzero_si128())) == 0xffff;
#else
    uint32_t diff = 0;
    for (int k = 1; k < 4; k++)
        for (int i = 0; i < SG_TILE_PIXELS; i++) diff |= planes[k][base + i] ^ planes[0][base + i];
    return diff == 0;
#endif
}

uint64_t sg_fb_alike_tiles(const uint32_t *const planes[4], uint64_t tiles) {
    return sg_fb_alike_tiles_with(planes, tiles, tile_alike);
}

void sg_fb_put_samples(uint32_t *const planes[4], size_t base, const uint32_t *src,
                       uint64_t samples) {
    sg_fb_each_plane(sg_fb_put_masked, planes, base, src, samples);
}

void sg_fb_blend_samples(uint32_t *const planes[4], size_t base, const uint32_t *src,
                         uint64_t samples) {
    sg_fb_each_plane(sg_fb_blend_masked, planes, base, src, samples);
}

const sg_fb_ops sg_fb_ops_portable = {sg_fb_fill_color,   sg_fb_fill_depth,   sg_fb_depth_range,
                                      sg_fb_put_masked,   sg_fb_blend_masked, sg_fb_average4_planes,
                                      sg_fb_split_ids,    sg_fb_alike_tiles,  sg_fb_put_samples,
                                      sg_fb_blend_samples};
