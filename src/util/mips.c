/* mips.c - mipmap levels made outside the core, with the core's own generator (tex/mipgen.h), so
 * that a renderer given these levels samples the bytes sgapi samples. */
#include "sgapi/sgapi_util.h"

#include "tex/mipgen.h"

int sgu_mip_level_count(int width, int height) {
    if (width < 1 || height < 1) return -1;
    return sg_mip_chain_length(width, height);
}

int sgu_generate_mip_level(const uint8_t *src, int width, int height, uint8_t *dst, int *dst_width,
                           int *dst_height) {
    if (!src || !dst || width < 1 || height < 1) return -1;
    sg_mip_generate(src, width, height, dst);
    if (dst_width) *dst_width = sg_mip_next_side(width);
    if (dst_height) *dst_height = sg_mip_next_side(height);
    return 0;
}
