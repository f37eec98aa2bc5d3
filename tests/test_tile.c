/* test_tile.c - the 4x4 tiled framebuffer layout and its conversion to and from linear images. */
#include "test_common.h"

#include <stdlib.h>

#include "raster/framebuffer.h"

static void index_layout(void **state) {
    (void)state;
    /* 10 pixels wide is 3 tiles; pixel (5, 6) is in tile (1, 1), at row 2, column 1 of it. */
    assert_int_equal(sg_fb_index(3, 0, 0), 0);
    assert_int_equal(sg_fb_index(3, 3, 0), 3);
    assert_int_equal(sg_fb_index(3, 0, 1), 4);
    assert_int_equal(sg_fb_index(3, 4, 0), 16);
    assert_int_equal(sg_fb_index(3, 5, 6), (1 * 3 + 1) * 16 + 2 * 4 + 1);
    assert_int_equal(sg_fb_tiled_pixels(10, 7), 3 * 2 * 16);
}

static void round_trip_odd_sizes(void **state) {
    (void)state;
    const int w = 7, h = 5;
    uint8_t src[7 * 5 * 4], dst[7 * 5 * 4];
    for (int i = 0; i < w * h * 4; i++) src[i] = (uint8_t)(i * 7 + 3);
    uint32_t *tiles = calloc(sg_fb_tiled_pixels(w, h), 4);
    sg_tile_from_linear_rgba8(tiles, src, (size_t)w * 4, w, h, 2);
    /* Byte order in memory is R, G, B, A. */
    uint32_t p = tiles[sg_fb_index(2, 6, 4)];
    const uint8_t *s = src + (4 * w + 6) * 4;
    assert_int_equal(p, sg_pack_rgba8(s[0], s[1], s[2], s[3]));
    sg_tile_to_linear_rgba8(dst, (size_t)w * 4, tiles, w, h, 2);
    assert_memory_equal(src, dst, sizeof src);

    float fs[35], fd[35];
    for (int i = 0; i < 35; i++) fs[i] = (float)i * 0.25f;
    float *ft = calloc(sg_fb_tiled_pixels(w, h), 4);
    sg_tile_from_linear_f32(ft, fs, (size_t)w * 4, w, h, 2);
    sg_tile_to_linear_f32(fd, (size_t)w * 4, ft, w, h, 2);
    assert_memory_equal(fs, fd, sizeof fs);
    free(tiles);
    free(ft);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(index_layout),
        cmocka_unit_test(round_trip_odd_sizes),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
