/* framebuffer_table.h - the part of an instruction set's sg_fb_ops that only adapts its
 * fill_color or compiles the portable code for the set: the depth fill and range, then the table
 * itself. Included once, at the end of framebuffer_<set>.c, after that file defines fill_color,
 * put_masked, blend_masked, split_ids, alike_tiles and put_samples (and blend_samples, with
 * SG_FB_BLEND_SAMPLES defined), and sets SG_FB_VECTOR_BYTES to its vectors' width and SG_FB_TABLE
 * to the table's name. */
#include <string.h>

static void fill_depth(float *dst, size_t n, float value) {
    uint32_t bits;
    memcpy(&bits, &value, 4);
    fill_color((uint32_t *)(void *)dst, n, bits); /* stored by intrinsics, which may alias */
}

static bool depth_range(const float *src, size_t n, float *lo, float *hi) {
    return sg_fb_depth_range_of(src, n, lo, hi);
}

/* sg_fb_average4 on vectors of SG_FB_VECTOR_BYTES (the set's width): red and blue, then green
 * and alpha, each in the 16-bit halves of 32-bit lanes. */
static void average4(uint32_t *p0, const uint32_t *p1, const uint32_t *p2, const uint32_t *p3,
                     size_t n) {
    typedef uint32_t vu __attribute__((vector_size(SG_FB_VECTOR_BYTES)));
    const size_t lanes = SG_FB_VECTOR_BYTES / sizeof(uint32_t);
    const uint32_t m = 0x00ff00ffu, half = 0x00020002u;
    for (size_t i = 0; i < n; i += lanes) {
        vu a, b, c, d;
        memcpy(&a, p0 + i, sizeof a);
        memcpy(&b, p1 + i, sizeof b);
        memcpy(&c, p2 + i, sizeof c);
        memcpy(&d, p3 + i, sizeof d);
        const vu lo = (a & m) + (b & m) + (c & m) + (d & m) + half;
        const vu hi = (a >> 8 & m) + (b >> 8 & m) + (c >> 8 & m) + (d >> 8 & m) + half;
        const vu r = (lo >> 2 & m) | (hi >> 2 & m) << 8;
        memcpy(p0 + i, &r, sizeof r);
    }
}

#ifndef SG_FB_BLEND_SAMPLES
/* blend_masked into each plane (a set without its own blend_samples). */
static void blend_samples(uint32_t *const planes[4], size_t base, const uint32_t *src,
                          uint64_t samples) {
    sg_fb_each_plane(blend_masked, planes, base, src, samples);
}
#endif

const sg_fb_ops SG_FB_TABLE = {fill_color, fill_depth, depth_range, put_masked,  blend_masked,
                               average4,   split_ids,  alike_tiles, put_samples, blend_samples};
