/* framebuffer_table.h - the parts of an instruction set's sg_fb_ops that only adapt its
 * fill_color and to_linear: the depth fill and the two typed writes, then the table itself.
 * Included once, at the end of framebuffer_<set>.c, after that file defines fill_color,
 * to_linear and fill_linear and sets SG_FB_TABLE to the table's name. */
#include <string.h>

static void fill_depth(float *dst, size_t n, float value) {
    uint32_t bits;
    memcpy(&bits, &value, 4);
    fill_color((uint32_t *)(void *)dst, n, bits); /* stored by intrinsics, which may alias */
}

static void color_to_linear(uint8_t *dst, size_t pitch, const uint32_t *tiles, int w, int h,
                            int tx) {
    to_linear(dst, pitch, tiles, w, h, tx);
}

static void depth_to_linear(float *dst, size_t pitch, const float *tiles, int w, int h, int tx) {
    to_linear(dst, pitch, (const uint32_t *)(const void *)tiles, w, h, tx);
}

const sg_fb_ops SG_FB_TABLE = {fill_color, fill_depth, color_to_linear, depth_to_linear,
                               fill_linear};
