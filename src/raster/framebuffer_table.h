/* framebuffer_table.h - the part of an instruction set's sg_fb_ops that only adapts its
 * fill_color or compiles the portable code for the set: the depth fill and range, then the table
 * itself. Included once, at the end of framebuffer_<set>.c, after that file defines fill_color,
 * put_masked, blend_masked and average4 and sets SG_FB_TABLE to the table's name. */
#include <string.h>

static void fill_depth(float *dst, size_t n, float value) {
    uint32_t bits;
    memcpy(&bits, &value, 4);
    fill_color((uint32_t *)(void *)dst, n, bits); /* stored by intrinsics, which may alias */
}

static bool depth_range(const float *src, size_t n, float *lo, float *hi) {
    return sg_fb_depth_range_of(src, n, lo, hi);
}

const sg_fb_ops SG_FB_TABLE = {fill_color, fill_depth,   depth_range,
                               put_masked, blend_masked, average4};
