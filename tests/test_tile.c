/* test_tile.c - the 4x4 tiled framebuffer layout and its conversion to and from linear images. */
#include "test_common.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "raster/blend.h"
#include "raster/framebuffer.h"
#include "raster/shade.h"

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

/* The instruction sets' fills of a bin's buffers (sg_fb_ops) give the portable functions' bytes. */
static void fb_ops_match_portable(void **state) {
    (void)state;
    enum { BIN = 64 };
    const struct {
        sg_isa isa;
        const sg_fb_ops *ops;
    } sets[] = {{SG_ISA_AVX2, &sg_fb_ops_avx2}, {SG_ISA_AVX512, &sg_fb_ops_avx512}};
    _Alignas(64) uint32_t a[BIN * BIN], b[BIN * BIN];
    for (size_t k = 0; k < sizeof sets / sizeof sets[0]; k++) {
        if (!sg_isa_runs(sets[k].isa)) continue;
        const sg_fb_ops *ops = sets[k].ops, *ref = &sg_fb_ops_portable;
        ops->fill_color(a, BIN * BIN, 0x01020304u);
        ref->fill_color(b, BIN * BIN, 0x01020304u);
        assert_memory_equal(a, b, sizeof a);
        ops->fill_depth((float *)(void *)a, BIN * BIN, 0.25f);
        ref->fill_depth((float *)(void *)b, BIN * BIN, 0.25f);
        assert_memory_equal(a, b, sizeof a);
    }
}

/* The multisampled bins' masked tile copy and blend, into one plane and into four, and four-plane
 * average (sg_fb_ops): every set gives the portable bytes, and the portable average is each
 * channel's (a + b + c + d + 2) / 4. */
static void fb_sample_ops_match_portable(void **state) {
    (void)state;
    enum { N = 256 };
    const sg_fb_ops *sets[] = {&sg_fb_ops_portable, &sg_fb_ops_avx2, &sg_fb_ops_avx512};
    const sg_isa isas[] = {SG_ISA_SCALAR, SG_ISA_AVX2, SG_ISA_AVX512};
    _Alignas(64) uint32_t planes[4][N], a[N], b[N];
    uint32_t seed = 7;
    for (int k = 0; k < 4; k++)
        for (int i = 0; i < N; i++) {
            seed = seed * 1664525u + 1013904223u;
            /* Every channel value, the extremes included, in some pixel. */
            planes[k][i] = i < 4 ? (k == i ? 0xffffffffu : 0u) : seed;
        }
    for (size_t s = 0; s < sizeof sets / sizeof sets[0]; s++) {
        if (!sg_isa_runs(isas[s])) continue;
        memcpy(a, planes[0], sizeof a);
        sets[s]->average4(a, planes[1], planes[2], planes[3], N);
        for (int i = 0; i < N; i++)
            for (int c = 0; c < 4; c++) {
                unsigned sum = 2;
                for (int k = 0; k < 4; k++) sum += planes[k][i] >> (8 * c) & 255u;
                assert_int_equal(a[i] >> (8 * c) & 255u, sum / 4);
            }
        for (uint32_t mask = 0; mask < 0x10000u; mask += 0x0ffbu) {
            memcpy(a, planes[0], 64);
            memcpy(b, planes[0], 64);
            sets[s]->put_masked(a, planes[1], mask | (mask == 0 ? 0 : 0x8000u));
            for (int i = 0; i < 16; i++)
                if ((mask | (mask == 0 ? 0 : 0x8000u)) >> i & 1) b[i] = planes[1][i];
            assert_memory_equal(a, b, 64);
        }
        memcpy(a, planes[0], 64);
        sets[s]->put_masked(a, planes[2], 0xffffu);
        assert_memory_equal(a, planes[2], 64);
        /* put_samples: put_masked into each of four planes with its own 16 bits of the mask. */
        uint64_t x = 99;
        for (int round = 0; round < 64; round++) {
            x = x * 6364136223846793005u + 1442695040888963407u;
            /* some planes' masks empty, some whole, the others random */
            uint64_t samples = x;
            for (int k = 0; k < 4; k++) {
                const int kind = (int)(x >> (60 - 2 * k)) & 3;
                if (kind == 0) samples &= ~((uint64_t)0xffffu << (16 * k));
                if (kind == 1) samples |= (uint64_t)0xffffu << (16 * k);
            }
            _Alignas(64) uint32_t got[4][32], want[4][32];
            uint32_t *const planes_got[4] = {got[0], got[1], got[2], got[3]};
            for (int k = 0; k < 4; k++) {
                memcpy(got[k], planes[k], sizeof got[k]);
                memcpy(want[k], planes[k], sizeof want[k]);
                for (int i = 0; i < 16; i++)
                    if (samples >> (16 * k + i) & 1) want[k][16 + i] = planes[3][i];
            }
            sets[s]->put_samples(planes_got, 16, planes[3], samples);
            assert_memory_equal(got, want, sizeof got);
            /* blend_samples: sg_blend_rgba8 of src over each plane's pixels of its bits. */
            for (int k = 0; k < 4; k++) {
                memcpy(got[k], planes[k], sizeof got[k]);
                memcpy(want[k], planes[k], sizeof want[k]);
                for (int i = 0; i < 16; i++)
                    if (samples >> (16 * k + i) & 1)
                        want[k][16 + i] = sg_blend_rgba8(planes[3][i], planes[k][16 + i]);
            }
            sets[s]->blend_samples(planes_got, 16, planes[3], samples);
            assert_memory_equal(got, want, sizeof got);
        }
        /* blend_masked: sg_blend_rgba8 of the selected pixels, the others kept. */
        for (int t = 0; t + 16 <= N; t += 16)
            for (uint32_t mask = 0; mask < 0x10000u; mask += 0x1ffdu) {
                memcpy(a, planes[3] + t, 64);
                sets[s]->blend_masked(a, planes[1] + t, mask);
                for (int i = 0; i < 16; i++)
                    assert_int_equal(a[i], mask >> i & 1
                                               ? sg_blend_rgba8(planes[1][t + i], planes[3][t + i])
                                               : planes[3][t + i]);
            }
    }
}

/* A tile's four sample planes of ids split into their triangles (sg_fb_ops.split_ids): each id
 * but 0 once, with exactly the pixels of each plane that hold it, in the same order on every set;
 * tiles of one id to 64 different ones. */
static void fb_split_ids_per_triangle(void **state) {
    (void)state;
    const sg_fb_ops *sets[] = {&sg_fb_ops_portable, &sg_fb_ops_avx2, &sg_fb_ops_avx512};
    const sg_isa isas[] = {SG_ISA_SCALAR, SG_ISA_AVX2, SG_ISA_AVX512};
    _Alignas(64) uint32_t planes[4][16];
    const uint32_t *const p[4] = {planes[0], planes[1], planes[2], planes[3]};
    uint32_t seed = 11;
    for (int round = 0; round < 400; round++) {
        const uint32_t kinds = 1u + (uint32_t)round % 70; /* ids 1 .. kinds, and 0 */
        for (int k = 0; k < 4; k++)
            for (int i = 0; i < 16; i++) {
                seed = seed * 1664525u + 1013904223u;
                planes[k][i] = (seed >> 8) % (kinds + 1);
            }
        uint32_t want_ids[64], ids[64];
        uint64_t want[64], got[64];
        const int n = sg_fb_ops_portable.split_ids(p, want_ids, want);
        uint64_t all = 0;
        for (int j = 0; j < n; j++) {
            assert_int_not_equal(want_ids[j], 0);
            assert_int_equal(all & want[j], 0); /* each sample's pixel once */
            all |= want[j];
            for (int k = 0; k < 4; k++)
                for (int i = 0; i < 16; i++)
                    assert_int_equal(want[j] >> (16 * k + i) & 1, planes[k][i] == want_ids[j]);
        }
        for (int k = 0; k < 4; k++)
            for (int i = 0; i < 16; i++)
                assert_int_equal(all >> (16 * k + i) & 1, planes[k][i] != 0);
        for (size_t s = 1; s < sizeof sets / sizeof sets[0]; s++) {
            if (!sg_isa_runs(isas[s])) continue;
            assert_int_equal(sets[s]->split_ids(p, ids, got), n);
            assert_memory_equal(ids, want_ids, (size_t)n * sizeof ids[0]);
            assert_memory_equal(got, want, (size_t)n * sizeof got[0]);
        }
    }
}

/* A word of 64 tiles' four sample planes of ids (sg_fb_ops.alike_tiles): a tile is alike when the
 * four planes are equal, and one different id in one pixel of one plane makes it not; every set
 * gives the tiles the bits say, and only those asked for. */
static void fb_alike_tiles_per_tile(void **state) {
    (void)state;
    enum { TILES = 64, N = TILES * 16 };
    const sg_fb_ops *sets[] = {&sg_fb_ops_portable, &sg_fb_ops_avx2, &sg_fb_ops_avx512};
    const sg_isa isas[] = {SG_ISA_SCALAR, SG_ISA_AVX2, SG_ISA_AVX512};
    _Alignas(64) static uint32_t planes[4][N];
    const uint32_t *const p[4] = {planes[0], planes[1], planes[2], planes[3]};
    uint32_t seed = 5;
    for (int round = 0; round < 50; round++) {
        uint64_t want = 0, asked = 0;
        for (int tile = 0; tile < TILES; tile++) {
            for (int i = 0; i < 16; i++) {
                seed = seed * 1664525u + 1013904223u;
                for (int k = 0; k < 4; k++) planes[k][tile * 16 + i] = (seed >> 8) % 5;
            }
            seed = seed * 1664525u + 1013904223u;
            const bool differ = seed >> 31, ask = seed >> 30 & 1;
            if (differ) { /* one pixel of one plane other than plane 0's */
                const int k = 1 + (int)(seed >> 8) % 3, i = (int)(seed >> 12) % 16;
                planes[k][tile * 16 + i] ^= 1u << (seed >> 16) % 32;
            }
            want |= (uint64_t)(!differ && ask) << tile;
            asked |= (uint64_t)ask << tile;
        }
        for (size_t s = 0; s < sizeof sets / sizeof sets[0]; s++) {
            if (!sg_isa_runs(isas[s])) continue;
            assert_int_equal(sets[s]->alike_tiles(p, asked), want);
            assert_int_equal(sets[s]->alike_tiles(p, 0), 0);
        }
    }
}

/* Every set's depth range of a bin buffer is its smallest and largest value, and none is given
 * when a value is negative, -0 or NaN (+inf is a value). */
static void depth_range_of_bin(void **state) {
    (void)state;
    enum { N = 64 * 64 };
    const sg_fb_ops *sets[] = {&sg_fb_ops_portable, &sg_fb_ops_avx2, &sg_fb_ops_avx512};
    const sg_isa isas[] = {SG_ISA_SCALAR, SG_ISA_AVX2, SG_ISA_AVX512};
    _Alignas(64) static float d[N];
    uint32_t seed = 7;
    for (size_t k = 0; k < sizeof sets / sizeof sets[0]; k++) {
        if (!sg_isa_runs(isas[k])) continue;
        for (int round = 0; round < 40; round++) {
            float want_lo = 2.0f, want_hi = -1.0f;
            for (int i = 0; i < N; i++) {
                seed = seed * 1664525u + 1013904223u;
                d[i] = (float)(seed >> 8) / 16777216.0f * (round % 2 ? 1.0f : 1e-30f);
                want_lo = d[i] < want_lo ? d[i] : want_lo;
                want_hi = d[i] > want_hi ? d[i] : want_hi;
            }
            float lo, hi;
            assert_true(sets[k]->depth_range(d, N, &lo, &hi));
            assert_true(lo == want_lo && hi == want_hi);
            const int at = (round * 977) % N;
            const float keep = d[at];
            const float odd[] = {-0.0f, -0.5f, NAN, -NAN, INFINITY};
            for (size_t j = 0; j < sizeof odd / sizeof odd[0]; j++) {
                d[at] = odd[j];
                const bool ok = sets[k]->depth_range(d, N, &lo, &hi);
                assert_int_equal(ok, odd[j] == INFINITY);
                if (ok) assert_true(hi == INFINITY);
            }
            d[at] = keep;
        }
    }
}

/* A bin's writes into a target (every set's) put each pixel of every size of a bin's part of an
 * image (edges included) where sg_fb_index says, into a target at any 4-byte offset in a line,
 * and touch nothing outside the w x h pixels. */
static void bin_writes_stay_in_place(void **state) {
    (void)state;
    enum { BIN = 64, PITCH = 80 * 4, GUARD = 0x5a };
    _Alignas(64) uint32_t tiles[BIN * BIN];
    uint8_t *want = malloc(PITCH * (BIN + 2)), *got = malloc(PITCH * (BIN + 2));
    for (int i = 0; i < BIN * BIN; i++) tiles[i] = (uint32_t)i * 2654435761u;
    for (int w = 1; w <= BIN; w++)
        for (int h = 1; h <= BIN; h += (h < 8 ? 1 : 7))
            for (int off = 0; off < 64; off += 20) {
                uint8_t *at = got + PITCH + off;
                memset(want, GUARD, PITCH * (BIN + 2));
                for (int y = 0; y < h; y++)
                    for (int x = 0; x < w; x++)
                        memcpy(want + PITCH + off + (size_t)y * PITCH + (size_t)x * 4,
                               &tiles[sg_fb_index(BIN / 4, x, y)], 4);
                memset(got, GUARD, PITCH * (BIN + 2));
                sg_tile_to_linear_rgba8(at, PITCH, tiles, w, h, BIN / 4);
                assert_memory_equal(want, got, PITCH * (BIN + 2));
                memset(got, GUARD, PITCH * (BIN + 2));
                sg_tile_to_linear_f32((float *)(void *)at, PITCH,
                                      (const float *)(const void *)tiles, w, h, BIN / 4);
                assert_memory_equal(want, got, PITCH * (BIN + 2));
                for (int y = 0; y < h; y++)
                    for (int x = 0; x < w; x++)
                        memcpy(want + PITCH + off + (size_t)y * PITCH + (size_t)x * 4,
                               &(uint32_t){0xdeadbeefu}, 4);
                sg_fill_linear_u32(at, PITCH, w, h, 0xdeadbeefu);
                assert_memory_equal(want, got, PITCH * (BIN + 2));
            }
    free(want);
    free(got);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(index_layout),
        cmocka_unit_test(round_trip_odd_sizes),
        cmocka_unit_test(fb_ops_match_portable),
        cmocka_unit_test(fb_sample_ops_match_portable),
        cmocka_unit_test(fb_split_ids_per_triangle),
        cmocka_unit_test(fb_alike_tiles_per_tile),
        cmocka_unit_test(depth_range_of_bin),
        cmocka_unit_test(bin_writes_stay_in_place),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
