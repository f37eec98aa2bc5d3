/* framebuffer.h - colour and depth stored in 4x4-pixel tiles, as each screen bin keeps them while
 * it is rendered.
 *
 * A 4x4 tile is 16 consecutive pixels, row by row; tiles follow each other left to right, then top
 * to bottom. The raster touches a whole tile at once, so the 16 pixels it needs share two cache
 * lines (colour, 64 bytes) and (depth, 64 bytes) instead of four rows far apart.
 */
#ifndef SG_FRAMEBUFFER_H
#define SG_FRAMEBUFFER_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#define SG_TILE        4
#define SG_TILE_SHIFT  2
#define SG_TILE_MASK   3
#define SG_TILE_PIXELS 16

/** Index of pixel (x, y) in the tiled arrays. */
static inline size_t sg_fb_index(int tiles_x, int x, int y) {
    return ((size_t)(y >> SG_TILE_SHIFT) * (size_t)tiles_x + (size_t)(x >> SG_TILE_SHIFT)) *
               SG_TILE_PIXELS +
           (size_t)((y & SG_TILE_MASK) * SG_TILE + (x & SG_TILE_MASK));
}

/** Packs four bytes in memory order R, G, B, A. */
static inline uint32_t sg_pack_rgba8(uint32_t r, uint32_t g, uint32_t b, uint32_t a) {
    return r | (g << 8) | (b << 16) | (a << 24);
}

/** Pixels of a tiled image of the given size (padding included). */
size_t sg_fb_tiled_pixels(int width, int height);
/** Fills every pixel (padding included) of the tiled colour array. */
void sg_fb_fill_color(uint32_t *tiles, size_t pixels, uint32_t value);
/** Fills every pixel (padding included) of the tiled depth array. */
void sg_fb_fill_depth(float *tiles, size_t pixels, float value);
/* The conversions copy w x h pixels between linear rows (top first, `pitch` bytes apart) and
 * tiles laid out `tx` tiles to a row of tiles (tx >= w / 4 rounded up). */

/** Linear RGBA8 rows -> tiles. */
void sg_tile_from_linear_rgba8(uint32_t *tiles, const uint8_t *src, size_t pitch, int w, int h,
                               int tx);
/** Tiles -> linear RGBA8 rows. */
void sg_tile_to_linear_rgba8(uint8_t *dst, size_t pitch, const uint32_t *tiles, int w, int h,
                             int tx);
/** Linear float rows -> tiles. */
void sg_tile_from_linear_f32(float *tiles, const float *src, size_t pitch, int w, int h, int tx);
/** Tiles -> linear float rows. */
void sg_tile_to_linear_f32(float *dst, size_t pitch, const float *tiles, int w, int h, int tx);
/** Fills w x h 32-bit pixels of linear rows `pitch` bytes apart. */
void sg_fill_linear_u32(void *dst, size_t pitch, int w, int h, uint32_t value);

/* The fills of a bin's own buffers, per instruction set: the same bytes, a whole cache line
 * (AVX-512) or half a line (AVX2) a store, faster than 16-byte ones into buffers in cache. The
 * writes into the target images (sg_tile_to_linear_*, sg_fill_linear_u32) are the portable ones
 * on every set: 16 bytes a store, which took up to half the time of wider ones into lines not in
 * cache (docs/performance.md, "Narrow stores into the targets"). */
typedef struct sg_fb_ops {
    /* Fills n 32-bit values of a bin buffer (n a multiple of 16, dst 64-byte aligned). */
    void (*fill_color)(uint32_t *dst, size_t n, uint32_t value);
    void (*fill_depth)(float *dst, size_t n, float value);
    /* sg_fb_depth_range, vectorised for the set */
    bool (*depth_range)(const float *src, size_t n, float *lo, float *hi);
    /* Multisampled bins (rast_msaa.c): src's pixels of `mask` into dst (a tile, 16 pixels, both
     * 64-byte aligned); and the average of four planes of n pixels into the first (n a multiple
     * of 16, every plane 64-byte aligned), as sg_fb_average4 computes it. */
    void (*put_masked)(uint32_t *dst, const uint32_t *src, uint32_t mask);
    /* src's fragments of `mask` blended over dst's pixels (sg_blend16_rgba8), the same tiles. */
    void (*blend_masked)(uint32_t *dst, const uint32_t *src, uint32_t mask);
    void (*average4)(uint32_t *p0, const uint32_t *p1, const uint32_t *p2, const uint32_t *p3,
                     size_t n);
    /* The triangles a tile's four sample planes of ids see (16 ids each, 64-byte aligned; 0 is
     * none), each once, in the order sg_fb_split_ids_with finds them: ids[j] and, in samples[j],
     * its pixels per sample (sample k's in bits 16 k .. 16 k + 15); returns how many (<= 64). */
    int (*split_ids)(const uint32_t *const planes[4], uint32_t *ids, uint64_t *samples);
    /* Of the tiles of `tiles` (bit i: tile i from planes[k], 16 ids a tile), those whose four
     * sample planes of ids are alike. */
    uint64_t (*alike_tiles)(const uint32_t *const planes[4], uint64_t tiles);
    /* put_masked of src into the tile at `base` of each plane k, with mask bits 16 k .. 16 k + 15
     * of samples (one load of src for the four). */
    void (*put_samples)(uint32_t *const planes[4], size_t base, const uint32_t *src,
                        uint64_t samples);
    /* blend_masked the same way: src's fragments over each plane's pixels of its mask (the
     * source's terms of the blend formed once for the four). */
    void (*blend_samples)(uint32_t *const planes[4], size_t base, const uint32_t *src,
                          uint64_t samples);
} sg_fb_ops;

/* fn (a put_masked or blend_masked) into each plane k's tile at `base` with bits 16 k .. 16 k + 15
 * of samples, where any. */
static inline void sg_fb_each_plane(void (*fn)(uint32_t *, const uint32_t *, uint32_t),
                                    uint32_t *const planes[4], size_t base, const uint32_t *src,
                                    uint64_t samples) {
    for (int k = 0; k < 4; k++) {
        const uint32_t m = (uint32_t)(samples >> (16 * k)) & 0xffffu;
        if (m) fn(planes[k] + base, src, m);
    }
}

/** The average of four packed RGBA8 values, each channel rounded to nearest (halves up). */
static inline uint32_t sg_fb_average4(uint32_t a, uint32_t b, uint32_t c, uint32_t d) {
    const uint32_t m = 0x00ff00ffu;
    uint32_t lo = (a & m) + (b & m) + (c & m) + (d & m) + 0x00020002u;
    uint32_t hi = (a >> 8 & m) + (b >> 8 & m) + (c >> 8 & m) + (d >> 8 & m) + 0x00020002u;
    return (lo >> 2 & m) | (hi >> 2 & m) << 8;
}

/** The pixels of `mask` of a tile's src into dst (lane i is pixel i), the others kept. */
static inline void sg_fb_put_lanes(uint32_t *dst, const uint32_t *src, uint32_t mask) {
    if (mask == 0xffffu) {
        memcpy(dst, src, SG_TILE_PIXELS * sizeof *dst);
        return;
    }
    for (; mask; mask &= mask - 1) dst[__builtin_ctz(mask)] = src[__builtin_ctz(mask)];
}

/* Whether a shader tile of pixels `mask` is converted straight into its pixels `direct` (not
 * NULL) instead of through a local array and sg_fb_put_lanes: the whole tile, no lane
 * discarded. */
static inline bool sg_shade_direct(const uint32_t *direct, uint32_t mask, uint32_t discard) {
    return direct && mask == 0xffffu && !(discard & 0xffffu);
}

/* split_ids's walk for a set: left[k], the pixels of plane k not 0; same(vecs, k, id), the
 * pixels of plane k that hold id (vecs: the set's copy of the planes). The first triangle is the
 * first plane's with pixels left, at its first such pixel. */
static inline __attribute__((always_inline)) int
sg_fb_split_ids_with(const uint32_t *const planes[4], const void *vecs, uint32_t left[4],
                     uint32_t (*same)(const void *vecs, int k, uint32_t id), uint32_t *ids,
                     uint64_t *samples) {
    uint32_t any = left[0] | left[1] | left[2] | left[3];
    int n = 0;
    while (any) {
        int first = 0;
        while (!left[first]) first++;
        const uint32_t id = planes[first][__builtin_ctz(left[first])];
        uint64_t s = 0;
        any = 0;
        for (int k = 0; k < 4; k++) {
            const uint32_t m = left[k] ? same(vecs, k, id) & left[k] : 0;
            s |= (uint64_t)m << (16 * k);
            any |= left[k] &= ~m;
        }
        ids[n] = id;
        samples[n++] = s;
    }
    return n;
}

/* alike_tiles's loop for a set: alike(planes, base), whether tile `base`'s four planes (16 ids
 * from base in each) are equal. */
static inline __attribute__((always_inline)) uint64_t
sg_fb_alike_tiles_with(const uint32_t *const planes[4], uint64_t tiles,
                       bool (*alike)(const uint32_t *const planes[4], size_t base)) {
    uint64_t out = 0;
    for (; tiles; tiles &= tiles - 1) {
        const int bit = __builtin_ctzll(tiles);
        out |= (uint64_t)alike(planes, (size_t)bit * SG_TILE_PIXELS) << bit;
    }
    return out;
}

/** The portable put_masked (sg_fb_put_lanes), blend_masked, average4, split_ids, alike_tiles,
 *  put_samples and blend_samples of sg_fb_ops. */
void sg_fb_put_masked(uint32_t *dst, const uint32_t *src, uint32_t mask);
void sg_fb_blend_masked(uint32_t *dst, const uint32_t *src, uint32_t mask);
void sg_fb_average4_planes(uint32_t *p0, const uint32_t *p1, const uint32_t *p2, const uint32_t *p3,
                           size_t n);
int sg_fb_split_ids(const uint32_t *const planes[4], uint32_t *ids, uint64_t *samples);
uint64_t sg_fb_alike_tiles(const uint32_t *const planes[4], uint64_t tiles);
void sg_fb_put_samples(uint32_t *const planes[4], size_t base, const uint32_t *src,
                       uint64_t samples);
void sg_fb_blend_samples(uint32_t *const planes[4], size_t base, const uint32_t *src,
                         uint64_t samples);

/* The body of every set's sg_fb_depth_range: floats in [+0, +inf] order as their bit patterns
 * do, and an integer min and max vectorise on every set; a negative value or -0 (below 0 as
 * int32) or a NaN (above +inf) gives up. */
static inline bool sg_fb_depth_range_of(const float *src, size_t n, float *lo, float *hi) {
    int32_t mn = INT32_MAX, mx = INT32_MIN;
    for (size_t i = 0; i < n; i++) {
        int32_t b;
        memcpy(&b, src + i, sizeof b);
        mn = b < mn ? b : mn;
        mx = b > mx ? b : mx;
    }
    if (mn < 0 || mx > 0x7f800000) return false;
    memcpy(lo, &mn, sizeof *lo);
    memcpy(hi, &mx, sizeof *hi);
    return true;
}

/** The smallest and largest of n depths of a bin buffer; false (nothing given) when one is
 *  negative, -0 or NaN. */
bool sg_fb_depth_range(const float *src, size_t n, float *lo, float *hi);

/** The portable functions (any byte order). */
extern const sg_fb_ops sg_fb_ops_portable;
/** AVX2 and AVX-512 (call only where the CPU runs the set; the portable functions in builds
 *  without them). */
extern const sg_fb_ops sg_fb_ops_avx2, sg_fb_ops_avx512;

#endif
