/* The PNG files of compression level 0 (png_store.c): every file a strict reader accepts (each
 * chunk's CRC, the zlib stream's Adler-32, the data's length) and decodes to the image, whatever
 * mix of stored rows, repeated rows and runs it holds; and a file as stb_image reads it. */
#define _XOPEN_SOURCE 700 /* mkstemp */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>
#include <libdeflate.h>

#include "image_io.h"
#include "png_store.h"
#include "test_msg.h"

static uint32_t get_u32(const unsigned char *p) {
    return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

/* The file's pieces joined; its size in *len. */
static unsigned char *build(int w, int h, const unsigned char *rgba, size_t *len) {
    struct iovec *iov = malloc(sc_png_store_pieces(w, h) * sizeof *iov);
    unsigned char *heads = malloc(sc_png_store_heads(w, h));
    assert_non_null(iov);
    assert_non_null(heads);
    size_t n = sc_png_store_build(iov, heads, w, h, rgba);
    assert_true(n <= sc_png_store_pieces(w, h));
    size_t total = 0;
    for (size_t i = 0; i < n; i++) total += iov[i].iov_len;
    unsigned char *file = malloc(total);
    assert_non_null(file);
    size_t at = 0;
    for (size_t i = 0; i < n; i++) {
        memcpy(file + at, iov[i].iov_base, iov[i].iov_len);
        at += iov[i].iov_len;
    }
    /* every heads byte used lies inside the buffer asked for */
    for (size_t i = 0; i < n; i++) {
        const unsigned char *b = iov[i].iov_base;
        if (b >= heads && b < heads + sc_png_store_heads(w, h))
            assert_true(b + iov[i].iov_len <= heads + sc_png_store_heads(w, h));
    }
    free(iov);
    free(heads);
    *len = total;
    return file;
}

/* Reads the file as a strict decoder would and checks it holds the image. */
static void check_file(const unsigned char *f, size_t len, int w, int h,
                       const unsigned char *rgba) {
    static const unsigned char signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    assert_true(len > 8);
    assert_memory_equal(f, signature, 8);
    size_t p = 8, idat_at = 0, idat_len = 0;
    int chunks = 0;
    while (p < len) {
        assert_true(p + 12 <= len);
        uint32_t n = get_u32(f + p);
        assert_true(p + 12 + n <= len);
        assert_int_equal(get_u32(f + p + 8 + n), libdeflate_crc32(0, f + p + 4, n + 4));
        if (!memcmp(f + p + 4, "IHDR", 4)) {
            assert_int_equal(get_u32(f + p + 8), (uint32_t)w);
            assert_int_equal(get_u32(f + p + 12), (uint32_t)h);
        } else if (!memcmp(f + p + 4, "IDAT", 4)) {
            idat_at = p + 8;
            idat_len = n;
        }
        p += 12 + n;
        chunks++;
    }
    assert_int_equal(p, len);
    assert_int_equal(chunks, 3);
    const size_t row = (size_t)w * 4, raw_len = (size_t)h * (row + 1);
    unsigned char *raw = malloc(raw_len);
    assert_non_null(raw);
    struct libdeflate_decompressor *d = libdeflate_alloc_decompressor();
    size_t got = 0;
    assert_int_equal(libdeflate_zlib_decompress(d, f + idat_at, idat_len, raw, raw_len, &got),
                     LIBDEFLATE_SUCCESS);
    assert_int_equal(got, raw_len);
    for (int y = 0; y < h; y++) {
        assert_int_equal(raw[(size_t)y * (row + 1)], 0); /* filter None */
        assert_memory_equal(raw + (size_t)y * (row + 1) + 1, rgba + (size_t)y * row, row);
    }
    libdeflate_free_decompressor(d);
    free(raw);
}

static void round_trip(int w, int h, const unsigned char *rgba) {
    size_t len;
    unsigned char *f = build(w, h, rgba, &len);
    check_file(f, len, w, h, rgba);
    free(f);
}

static uint32_t next(uint32_t *s) {
    *s ^= *s << 13;
    *s ^= *s >> 17;
    *s ^= *s << 5;
    return *s;
}

/* Rows of every kind: noise, one colour, the row above again, runs of 31, 32 and 33 pixels and
 * longer ones at the start, middle and end of a row, a run broken by one pixel. */
static unsigned char *mixed(int w, int h, uint32_t seed) {
    uint32_t *px = malloc((size_t)w * (size_t)h * 4);
    assert_non_null(px);
    uint32_t s = seed;
    for (int y = 0; y < h; y++) {
        uint32_t *r = px + (size_t)y * (size_t)w;
        int kind = (int)(next(&s) % 6);
        for (int x = 0; x < w; x++) r[x] = next(&s);
        if (kind == 1) {
            for (int x = 0; x < w; x++) r[x] = 0xff102030u;
        } else if (kind == 2 && y) {
            memcpy(r, r - w, (size_t)w * 4);
        } else if (kind >= 3) {
            for (int k = 0; k < 4; k++) { /* runs at random places and of random lengths */
                int len = (int)(next(&s) % 3) + 31 + (kind == 5 ? (int)(next(&s) % 300) : 0);
                int at = (int)(next(&s) % (uint32_t)w);
                uint32_t c = next(&s) & 0xff0f0f0fu;
                for (int x = at; x < at + len && x < w; x++) r[x] = c;
            }
            if (kind == 4 && w > 40) r[w / 2] ^= 1u; /* a run broken in two */
        }
    }
    return (unsigned char *)px;
}

static void test_mixed_rows(void **state) {
    (void)state;
    const int sizes[][2] = {{1, 1},   {1, 7},   {2, 3},    {31, 5},    {32, 9},   {33, 9},
                            {64, 64}, {65, 40}, {257, 30}, {1024, 48}, {3000, 11}};
    for (size_t i = 0; i < sizeof sizes / sizeof sizes[0]; i++) {
        for (uint32_t seed = 1; seed <= 4; seed++) {
            unsigned char *img = mixed(sizes[i][0], sizes[i][1], seed * 2654435761u);
            round_trip(sizes[i][0], sizes[i][1], img);
            free(img);
        }
    }
}

/* One colour throughout, and noise throughout: all runs and repeats, all stored. */
static void test_flat_and_noise(void **state) {
    (void)state;
    const int w = 517, h = 33;
    uint32_t *px = malloc((size_t)w * h * 4);
    assert_non_null(px);
    for (int i = 0; i < w * h; i++) px[i] = 0x80ff00ffu;
    round_trip(w, h, (unsigned char *)px);
    size_t len;
    unsigned char *f = build(w, h, (unsigned char *)px, &len);
    assert_true(len < 2000); /* a few bytes a row, not its 2068 */
    free(f);
    uint32_t s = 7;
    for (int i = 0; i < w * h; i++) px[i] = next(&s);
    round_trip(w, h, (unsigned char *)px);
    free(px);
}

/* Rows at the limits of deflate: a repeat reaches back row + 1 bytes, at most 32768 (8191
 * pixels; 8192 cannot repeat), and a stored part of a 16384-pixel row (65536 bytes) takes two
 * blocks. */
static void test_wide_rows(void **state) {
    (void)state;
    const int widths[] = {8191, 8192, 16384};
    for (size_t i = 0; i < 3; i++) {
        const int w = widths[i], h = 4;
        uint32_t *px = malloc((size_t)w * h * 4);
        assert_non_null(px);
        uint32_t s = 99;
        for (int x = 0; x < w; x++) px[x] = next(&s);
        memcpy(px + w, px, (size_t)w * 4); /* row 1 repeats row 0 */
        for (int x = 0; x < w; x++) px[2 * w + x] = x < w / 2 ? 0xff000000u : next(&s);
        for (int x = 0; x < w; x++) px[3 * w + x] = next(&s);
        round_trip(w, h, (unsigned char *)px);
        free(px);
    }
}

/* Many small images of every size up to 200 x 12, each from its own seed: the pieces and heads
 * stay within their bounds (built under the sanitizers too) and every file reads back. */
static void test_random_images(void **state) {
    (void)state;
    uint32_t s = 2024;
    for (int i = 0; i < 600; i++) {
        int w = (int)(next(&s) % 200) + 1, h = (int)(next(&s) % 12) + 1;
        unsigned char *img = mixed(w, h, next(&s) | 1u);
        round_trip(w, h, img);
        free(img);
    }
}

/* The pixels need no alignment: an image one byte into its buffer gives the same file. */
static void test_unaligned_pixels(void **state) {
    (void)state;
    const int w = 97, h = 9;
    unsigned char *img = mixed(w, h, 77);
    unsigned char *moved = malloc((size_t)w * h * 4 + 1);
    assert_non_null(moved);
    memcpy(moved + 1, img, (size_t)w * h * 4);
    size_t len_a, len_b;
    unsigned char *a = build(w, h, img, &len_a), *b = build(w, h, moved + 1, &len_b);
    assert_int_equal(len_a, len_b);
    assert_memory_equal(a, b, len_a);
    round_trip(w, h, moved + 1);
    free(a);
    free(b);
    free(moved);
    free(img);
}

/* What the writer puts in a file is what stb_image reads back. */
static void test_file_reads_back(void **state) {
    (void)state;
    const int w = 300, h = 70;
    unsigned char *img = mixed(w, h, 12345);
    char path[] = "/tmp/sgapi-png-store-XXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    close(fd);
    TEST_MSG(err);
    sc_png_writer *writer = sc_png_writer_create(0);
    assert_non_null(writer);
    assert_true(sc_png_writer_write(writer, path, w, h, img, &err));
    sc_png_writer_destroy(writer);
    sc_image back;
    assert_true(sc_image_load(path, &back, &err));
    assert_int_equal(back.width, w);
    assert_int_equal(back.height, h);
    assert_memory_equal(back.pixels, img, (size_t)w * h * 4);
    sc_image_free(&back);
    remove(path);
    free(img);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_mixed_rows),       cmocka_unit_test(test_flat_and_noise),
        cmocka_unit_test(test_wide_rows),        cmocka_unit_test(test_random_images),
        cmocka_unit_test(test_unaligned_pixels), cmocka_unit_test(test_file_reads_back),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
