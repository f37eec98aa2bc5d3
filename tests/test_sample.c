/* test_sample.c - texture sampling: bilinear weights, repeat and clamp at the edges, orientation.
 */
#include "test_common.h"

#include "tex/mip.h"
#include "tex/mipgen.h"
#include "tex/sample.h"
#include "raster/shade.h"
#include "tex/sample16.h"

#include <math.h>
#include <stdlib.h>

/* 2x2 texture, uploaded top row first: top row (10, 20), bottom row (30, 40) in red. */
static const uint8_t texels[16] = {10, 0, 0, 255, 20, 0, 0, 255, 30, 0, 0, 255, 40, 0, 0, 255};
static const sg_texview tv = {.texels = texels, .width = 2, .height = 2}; /* scalar sampling only */

static void t_zero_is_the_bottom_row(void **state) {
    (void)state;
    assert_int_equal(sg_sample(&tv, 0.25f, 0.25f, 0, 1).c[0], 30);
    assert_int_equal(sg_sample(&tv, 0.75f, 0.25f, 0, 1).c[0], 40);
    assert_int_equal(sg_sample(&tv, 0.25f, 0.75f, 0, 1).c[0], 10);
    assert_int_equal(sg_sample(&tv, 0.75f, 0.75f, 0, 1).c[3], 255);
}

static void bilinear_weights(void **state) {
    (void)state;
    /* Texel centres give texels exactly; the middle gives the mean of all four. */
    assert_int_equal(sg_sample(&tv, 0.25f, 0.25f, 1, 1).c[0], 30);
    assert_int_equal(sg_sample(&tv, 0.75f, 0.75f, 1, 0).c[0], 20);
    assert_int_equal(sg_sample(&tv, 0.5f, 0.5f, 1, 0).c[0], 25);
    /* A quarter of the way from the bottom-left centre to the right: 30 + (40 - 30) / 4. */
    assert_int_equal(sg_sample(&tv, 0.375f, 0.25f, 1, 0).c[0], 33); /* 32.5 rounds up */
}

static void repeat_wraps_across_the_edge(void **state) {
    (void)state;
    /* s = 0 sits between the last and the first column: half of each with repeat. */
    assert_int_equal(sg_sample(&tv, 0.0f, 0.25f, 1, 1).c[0], 35);
    assert_int_equal(sg_sample(&tv, 1.0f, 0.25f, 1, 1).c[0], 35);
    /* Clamp keeps the edge texel instead. */
    assert_int_equal(sg_sample(&tv, 0.0f, 0.25f, 1, 0).c[0], 30);
    assert_int_equal(sg_sample(&tv, -5.0f, 0.25f, 1, 0).c[0], 30);
    assert_int_equal(sg_sample(&tv, 7.0f, 0.25f, 0, 0).c[0], 40);
    /* Far from the origin, repeat gives the same texel as near it. */
    assert_int_equal(sg_sample(&tv, 1000.25f, 0.25f, 0, 1).c[0], 30);
    assert_int_equal(sg_sample(&tv, -999.25f, 0.25f, 0, 1).c[0], 40);
    assert_int_equal(sg_sample(&tv, 1000.375f, 0.25f, 1, 1).c[0],
                     sg_sample(&tv, 0.375f, 0.25f, 1, 1).c[0]);
}

static void nonfinite_coordinates_stay_in_bounds(void **state) {
    (void)state;
    const float bad[] = {NAN, INFINITY, -INFINITY, 1e30f, -1e30f};
    for (int i = 0; i < 5; i++)
        for (int f = 0; f < 2; f++)
            for (int r = 0; r < 2; r++) {
                sg_texel t = sg_sample(&tv, bad[i], bad[4 - i], f, r);
                assert_true(t.c[0] >= 10 && t.c[0] <= 40);
            }
}

/* The mean of the texels of level-above block (x0 .. x0 + nx - 1) x (y0 .. y0 + ny - 1), rounded
 * half up: the definition of docs/api.md, written out for each case of a side. */
static uint8_t box(const uint8_t *src, int sw, int x0, int nx, int y0, int ny, int k) {
    unsigned sum = 0;
    for (int y = y0; y < y0 + ny; y++)
        for (int x = x0; x < x0 + nx; x++) sum += src[(y * sw + x) * 4 + k];
    unsigned n = (unsigned)(nx * ny);
    return (uint8_t)((sum + n / 2) / n);
}

static void mip_generator_matches_the_formula(void **state) {
    (void)state;
    const int sizes[][2] = {{8, 8}, {7, 5}, {1, 9}, {6, 1}, {3, 3}, {2, 7}, {1, 1}, {13, 4}};
    srand(45);
    for (size_t c = 0; c < sizeof sizes / sizeof *sizes; c++) {
        const int sw = sizes[c][0], sh = sizes[c][1];
        uint8_t src[13 * 9 * 4], dst[7 * 5 * 4];
        for (int i = 0; i < sw * sh * 4; i++) src[i] = (uint8_t)(rand() & 255);
        sg_mip_generate(src, sw, sh, dst);
        const int dw = sw > 1 ? sw / 2 : 1, dh = sh > 1 ? sh / 2 : 1;
        for (int y = 0; y < dh; y++)
            for (int x = 0; x < dw; x++) {
                /* Columns 2x, 2x + 1; a side of 1 its one texel; an odd side's last block takes
                 * the left-over texel too. */
                int nx = sw == 1 ? 1 : (sw % 2 && x == dw - 1 ? 3 : 2);
                int ny = sh == 1 ? 1 : (sh % 2 && y == dh - 1 ? 3 : 2);
                for (int k = 0; k < 4; k++)
                    assert_int_equal(
                        dst[(y * dw + x) * 4 + k],
                        box(src, sw, sw == 1 ? 0 : 2 * x, nx, sh == 1 ? 0 : 2 * y, ny, k));
            }
    }
    /* Halves round up: (10 + 11 + 10 + 11) / 4 = 10.5 gives 11. */
    const uint8_t two[16] = {10, 0, 0, 0, 11, 0, 0, 0, 10, 0, 0, 0, 11, 0, 0, 0};
    uint8_t one[4];
    sg_mip_generate(two, 2, 2, one);
    assert_int_equal(one[0], 11);
    assert_int_equal(sg_mip_chain_length(256, 256), 9);
    assert_int_equal(sg_mip_chain_length(5, 1), 3);
    assert_int_equal(sg_mip_chain_length(16384, 1), 15);
}

static void mip_level_of_detail(void **state) {
    (void)state;
    sg_mip_chain m = {.levels = 5};
    m.level[0] = sg_texview_of(texels, 16, 16);
    /* rho = 4 texels a pixel: level 2 exactly; trilinear level 2 with weight 0. */
    sg_mip_pick p = sg_mip_select(&m, 4.0f / 16, 0, 0, 4.0f / 16, 0);
    assert_int_equal(p.level0, 2);
    p = sg_mip_select(&m, 4.0f / 16, 0, 0, 4.0f / 16, 1);
    assert_true(p.level0 == 2 && p.level1 == 3 && p.f == 0);
    /* Nearest rounds log2 rho at rho = sqrt 2 powers: 2.8 -> 1 (log2 1.49), 2.9 -> 2 (1.54). */
    assert_int_equal(sg_mip_select(&m, 2.8f / 16, 0, 0, 0, 0).level0, 1);
    assert_int_equal(sg_mip_select(&m, 2.9f / 16, 0, 0, 0, 0).level0, 2);
    /* Linear: lod = (exponent - 1 + mantissa) / 2 of rho^2 = 6: (2 - 1 + 1.5) / 2 = 1.25. */
    p = sg_mip_select(&m, 0, 0, sqrtf(6.0f) / 16, 0, 1);
    assert_true(p.level0 == 1 && p.level1 == 2 && p.f == 64);
    /* Magnification and beyond the chain clamp; the larger of the x and y steps counts. */
    assert_int_equal(sg_mip_select(&m, 0.1f / 16, 0, 0, 0.1f / 16, 1).level0, 0);
    p = sg_mip_select(&m, 1000.0f / 16, 0, 0, 0, 1);
    assert_true(p.level0 == 4 && p.level1 == 4 && p.f == 0);
    assert_int_equal(sg_mip_select(&m, 1.0f / 16, 0, 0, 8.0f / 16, 0).level0, 3);
}

/* A coordinate for the 16-lane test: mostly in and near [0, 1], sometimes far, huge, NaN or
 * infinite. */
static float any_coordinate(void) {
    const int r = rand() % 40;
    if (r == 0) return NAN;
    if (r == 1) return (rand() & 1) ? INFINITY : -INFINITY;
    if (r == 2) return (float)(rand() - RAND_MAX / 2) * 1e4f;
    if (r == 3) return 3e9f * ((rand() & 1) ? 1.0f : -1.0f);
    return (float)rand() / (float)RAND_MAX * 3.0f - 1.0f;
}

/* A chain of `levels` levels of random texels (each level stands for itself), level 0 w x h, in
 * storage of 2 w h texels. */
static sg_mip_chain random_chain(uint8_t *storage, int w0, int h0, int levels) {
    for (size_t i = 0; i < (size_t)(2 * w0 * h0 * 4); i++) storage[i] = (uint8_t)(rand() & 255);
    sg_mip_chain m = {.levels = levels};
    const uint8_t *at = storage;
    for (int l = 0; l < levels; l++) {
        const int w = w0 >> l > 1 ? w0 >> l : 1, h = h0 >> l > 1 ? h0 >> l : 1;
        m.level[l] = sg_texview_of(at, w, h);
        at += (size_t)w * (size_t)h * 4;
    }
    return m;
}

/* The copies of the 16-lane lookups this CPU runs (SG_SAMPLE16_*): the portable one first. */
static int copies_run(int simd[3]) {
    int n = 0;
    simd[n++] = SG_SAMPLE16_PORTABLE;
    if (sg_isa_runs(SG_ISA_AVX2)) simd[n++] = SG_SAMPLE16_AVX2;
    if (sg_isa_runs(SG_ISA_AVX512)) simd[n++] = SG_SAMPLE16_AVX512;
    return n;
}

/* sg_sample16 and sg_sample16_mip (the copy simd names) at (s, t) give each lane exactly what
 * sg_sample and sg_sample_mip give, with the texel window tried or not, the quads' levels
 * random. */
static void check_lanes(const sg_mip_chain *m, int simd, bool bilinear, bool repeat,
                        const float s[SG_SHADER_LANES], const float t[SG_SHADER_LANES]) {
    for (int window = 0; window < 2; window++) {
        int32_t got[4][SG_SHADER_LANES];
        sg_sample16(simd, &m->level[0], bilinear, repeat, window, s, t, got);
        for (int i = 0; i < SG_SHADER_LANES; i++) {
            const sg_texel want = sg_sample(&m->level[0], s[i], t[i], bilinear, repeat);
            for (int k = 0; k < 4; k++) assert_int_equal(got[k][i], want.c[k]);
        }
        float unit[4][SG_SHADER_LANES];
        sg_sample16_unit(simd, &m->level[0], bilinear, repeat, window, s, t, unit);
        for (int i = 0; i < SG_SHADER_LANES; i++)
            for (int k = 0; k < 4; k++) {
                const float want = (float)got[k][i] / 255.0f;
                assert_memory_equal(&unit[k][i], &want, sizeof want);
            }
        sg_mip_pick pick[4];
        for (int q = 0; q < 4; q++) {
            const int l0 = rand() % m->levels;
            const bool two = l0 + 1 < m->levels && rand() % 3;
            pick[q] = (sg_mip_pick){l0, two ? l0 + 1 : l0, two ? rand() % 256 : 0};
        }
        sg_sample16_mip(simd, m, pick, bilinear, repeat, window, s, t, got);
        for (int i = 0; i < SG_SHADER_LANES; i++) {
            const sg_mip_pick p = pick[(i >> 1 & 1) | (i >> 3) << 1];
            const sg_texel want = sg_sample_mip(m, p, s[i], t[i], bilinear, repeat);
            for (int k = 0; k < 4; k++) assert_int_equal(got[k][i], want.c[k]);
        }
    }
}

/* Every copy (the portable one, and the AVX2 and AVX-512 ones where this CPU runs them) agrees
 * with the scalar sampler at random coordinates. */
static void sixteen_lanes_match_the_scalar_sampler(void **state) {
    (void)state;
    static uint8_t chain[2 * 13 * 6 * 4];
    srand(16);
    const sg_mip_chain m = random_chain(chain, 13, 6, 4);
    int simd[3];
    const int copies = copies_run(simd);
    for (int round = 0; round < 4000 * copies; round++) {
        float s[SG_SHADER_LANES], t[SG_SHADER_LANES];
        for (int i = 0; i < SG_SHADER_LANES; i++) {
            s[i] = any_coordinate();
            t[i] = any_coordinate();
        }
        check_lanes(&m, simd[round / 4000], round & 1, round >> 1 & 1, s, t);
    }
}

/* The same on a larger chain with tile-shaped footprints (a 4 x 4 block of lanes a small step
 * apart, anywhere on the texture and past its edges): the AVX2 and AVX-512 copies then read from a
 * window of texels, or two neighbours in one load or gather, besides lane by lane. */
static void sixteen_lanes_match_on_tile_footprints(void **state) {
    (void)state;
    enum { W = 45, H = 27 };
    static uint8_t chain[2 * W * H * 4];
    srand(45);
    const sg_mip_chain m = random_chain(chain, W, H, 5);
    int simd[3];
    const int copies = copies_run(simd);
    for (int round = 0; round < 4000 * copies; round++) {
        /* A step of 1/8 to 3 texels a lane, from anywhere in [-0.2, 1.2). */
        const float s0 = (float)rand() / (float)RAND_MAX * 1.4f - 0.2f,
                    t0 = (float)rand() / (float)RAND_MAX * 1.4f - 0.2f;
        const float step = (0.125f + (float)(rand() % 24) * 0.125f) / (float)W;
        const float skew = (float)(rand() % 5 - 2) * 0.25f * step;
        float s[SG_SHADER_LANES], t[SG_SHADER_LANES];
        for (int i = 0; i < SG_SHADER_LANES; i++) {
            s[i] = s0 + (float)(i & 3) * step + (float)(i >> 2) * skew;
            t[i] = t0 - (float)(i >> 2) * step + (float)(i & 3) * skew;
        }
        check_lanes(&m, simd[round / 4000], round & 1, round >> 1 & 1, s, t);
    }
}

/* Every channel value 0 .. 255 to the float c / 255.0f, bit for bit, in every copy. */
static void texels_to_unit_divide_exactly(void **state) {
    (void)state;
    int simd[3];
    const int copies = copies_run(simd);
    for (int copy = 0; copy < copies; copy++)
        for (int c0 = 0; c0 < 256; c0 += SG_SHADER_LANES) {
            int32_t texel[4][SG_SHADER_LANES];
            float got[4][SG_SHADER_LANES];
            for (int k = 0; k < 4; k++)
                for (int i = 0; i < SG_SHADER_LANES; i++) texel[k][i] = (c0 + i + 64 * k) & 255;
            sg_texels_to_unit(simd[copy], texel, got);
            for (int k = 0; k < 4; k++)
                for (int i = 0; i < SG_SHADER_LANES; i++) {
                    const float want = (float)texel[k][i] / 255.0f;
                    assert_memory_equal(&got[k][i], &want, sizeof want);
                }
        }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(t_zero_is_the_bottom_row),
        cmocka_unit_test(bilinear_weights),
        cmocka_unit_test(repeat_wraps_across_the_edge),
        cmocka_unit_test(nonfinite_coordinates_stay_in_bounds),
        cmocka_unit_test(mip_generator_matches_the_formula),
        cmocka_unit_test(mip_level_of_detail),
        cmocka_unit_test(sixteen_lanes_match_the_scalar_sampler),
        cmocka_unit_test(sixteen_lanes_match_on_tile_footprints),
        cmocka_unit_test(texels_to_unit_divide_exactly),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
