/* test_raster.c - setup and tile rasterisation: the top-left fill rule and watertightness.
 *
 * Triangles go through sg_setup_triangle and sg_rast_triangle with a tile function that counts
 * how often each pixel is hit, so coverage is checked exactly, pixel by pixel.
 */
#include "test_common.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "pipeline/setup.h"
#include "raster/depth.h"
#include "raster/framebuffer.h"
#include "raster/rast_msaa.h"
#include "raster/rast_tile.h"
#include "raster/shade.h"
#include "test_setup.h"

#define W 64
#define H 64

typedef struct counter {
    int hits[H][W];
} counter;

static void count_tile(const void *ctx, const sg_tri *t, int x0, int y0, uint32_t mask) {
    (void)t;
    counter *c = (counter *)(uintptr_t)ctx;
    for (int b = 0; b < 16; b++)
        if (mask & (1u << b)) c->hits[y0 + (b >> 2)][x0 + (b & 3)]++;
}

/* A vertex at pixel position (px, py), y down, as clip space with w = 1. */
static sg_cvert at_pixel(double px, double py) {
    sg_cvert v;
    memset(&v, 0, sizeof v);
    v.pos[0] = (float)(px / W * 2.0 - 1.0);
    v.pos[1] = (float)(1.0 - py / H * 2.0);
    v.pos[3] = 1.0f;
    return v;
}

static void draw(counter *c, sg_cvert a, sg_cvert b, sg_cvert d) {
    sg_setup_params p = sg_test_params(W, H, 0);
    sg_tri t;
    if (sg_setup_triangle(&p, &a, &b, &d, &t, NULL)) sg_rast_triangle(&t, count_tile, c);
}

static void square_halves_cover_each_pixel_once(void **state) {
    (void)state;
    counter *c = calloc(1, sizeof *c);
    /* Corners on pixel centres and edges through pixel centres: every tie-break case. */
    const double x0 = 8.5, y0 = 8.5, x1 = 40.5, y1 = 40.5;
    draw(c, at_pixel(x0, y0), at_pixel(x1, y0), at_pixel(x1, y1));
    draw(c, at_pixel(x0, y0), at_pixel(x1, y1), at_pixel(x0, y1));
    int covered = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            assert_true(c->hits[y][x] <= 1);
            covered += c->hits[y][x];
            /* Top-left rule: the top row and left column on the edge are in, right and bottom out.
             */
            int inside = x >= 8 && x < 40 && y >= 8 && y < 40;
            assert_int_equal(c->hits[y][x], inside);
        }
    assert_int_equal(covered, 32 * 32);
    free(c);
}

static void fan_covers_disc_once(void **state) {
    (void)state;
    counter *c = calloc(1, sizeof *c);
    const double cx = 31.5, cy = 30.5, r = 25.0; /* centre exactly on a pixel centre */
    sg_cvert centre = at_pixel(cx, cy);
    for (int i = 0; i < 64; i++) {
        double a0 = 2 * M_PI * i / 64, a1 = 2 * M_PI * (i + 1) / 64;
        draw(c, centre, at_pixel(cx + r * cos(a0), cy + r * sin(a0)),
             at_pixel(cx + r * cos(a1), cy + r * sin(a1)));
    }
    int covered = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            assert_true(c->hits[y][x] <= 1);
            covered += c->hits[y][x];
            double dx = x + 0.5 - cx, dy = y + 0.5 - cy;
            if (dx * dx + dy * dy < (r - 1.5) * (r - 1.5)) assert_int_equal(c->hits[y][x], 1);
        }
    assert_int_equal(c->hits[30][31], 1); /* the shared centre pixel: exactly one triangle */
    assert_true(covered > 0);
    free(c);
    (void)covered;
}

static void random_meshes_are_watertight(void **state) {
    (void)state;
    /* A grid of jittered vertices, split into triangles both ways: every pixel inside the grid's
     * outer square is hit exactly once. */
    counter *c = calloc(1, sizeof *c);
    enum { N = 9 };
    double gx[N][N], gy[N][N];
    uint32_t seed = 12345;
    for (int j = 0; j < N; j++)
        for (int i = 0; i < N; i++) {
            seed = seed * 1664525u + 1013904223u;
            double jx = (i == 0 || i == N - 1) ? 0 : ((seed >> 8) % 1000) / 1000.0 - 0.5;
            seed = seed * 1664525u + 1013904223u;
            double jy = (j == 0 || j == N - 1) ? 0 : ((seed >> 8) % 1000) / 1000.0 - 0.5;
            gx[j][i] = 4.0 + i * 7.0 + jx * 5.0;
            gy[j][i] = 4.0 + j * 7.0 + jy * 5.0;
        }
    for (int j = 0; j + 1 < N; j++)
        for (int i = 0; i + 1 < N; i++) {
            sg_cvert a = at_pixel(gx[j][i], gy[j][i]), b = at_pixel(gx[j][i + 1], gy[j][i + 1]);
            sg_cvert d = at_pixel(gx[j + 1][i], gy[j + 1][i]);
            sg_cvert e = at_pixel(gx[j + 1][i + 1], gy[j + 1][i + 1]);
            if ((i + j) & 1) {
                draw(c, a, b, e);
                draw(c, a, e, d);
            } else {
                draw(c, a, b, d);
                draw(c, b, e, d);
            }
        }
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            int inside = x + 0.5 > 4.0 && x + 0.5 < 60.0 && y + 0.5 > 4.0 && y + 0.5 < 60.0;
            assert_int_equal(c->hits[y][x], inside);
        }
    free(c);
}

/* Every instruction set's tile walk (the AVX2 and AVX-512 ones test rows of tiles a tile a lane
 * and whole bins in one pass) hits exactly the pixels whose three edge values are >= 0, inside
 * the triangle's bounds and the walked bin, each once: random triangles from a pixel to wider
 * than a bin, in perspective, some cut by the setup rectangle, walked in one random 64 x 64 bin. */
enum { WALK_W = 256, WALK_H = 256, WALK_BIN = 64 };

typedef struct walk_hits {
    uint8_t hits[WALK_H][WALK_W];
    int stray; /* hits outside the walked bin */
    int rx0, ry0;
} walk_hits;

static void walk_tile(const void *ctx, const sg_tri *t, int x0, int y0, uint32_t mask) {
    (void)t;
    walk_hits *h = (walk_hits *)(uintptr_t)ctx;
    for (int b = 0; b < 16; b++)
        if (mask & (1u << b)) {
            int x = x0 + (b & 3), y = y0 + (b >> 2);
            if (x < h->rx0 || x >= h->rx0 + WALK_BIN || y < h->ry0 || y >= h->ry0 + WALK_BIN)
                h->stray++;
            else
                h->hits[y][x]++;
        }
}

static double walk_rand(uint32_t *seed) { /* [0, 1) */
    *seed = *seed * 1664525u + 1013904223u;
    return (double)(*seed >> 8) / 16777216.0;
}

static void walks_agree_with_edge_functions(void **state) {
    (void)state;
    walk_hits *h = calloc(1, sizeof *h);
    assert_non_null(h);
    uint32_t seed = 20261125;
    for (sg_isa isa = SG_ISA_SCALAR; isa <= sg_isa_detect(); isa++) {
        sg_walk_fn walk = sg_walk_select(isa);
        long checked = 0;
        for (int n = 0; n < 6000; n++) {
            /* A size from a pixel to 1.5 bins, most of them small, as a mesh's. */
            double size = 1.0 + pow(walk_rand(&seed), 3.0) * 96.0;
            double cx = walk_rand(&seed) * WALK_W, cy = walk_rand(&seed) * WALK_H;
            sg_cvert v[3];
            for (int k = 0; k < 3; k++) {
                double px = cx + (walk_rand(&seed) - 0.5) * size;
                double py = cy + (walk_rand(&seed) - 0.5) * size;
                float w = (float)(0.5 + 3.0 * walk_rand(&seed));
                memset(&v[k], 0, sizeof v[k]);
                v[k].pos[0] = (float)(px / WALK_W * 2.0 - 1.0) * w;
                v[k].pos[1] = (float)(1.0 - py / WALK_H * 2.0) * w;
                v[k].pos[3] = w;
            }
            sg_setup_params p = sg_test_params(WALK_W, WALK_H, 0);
            if (n % 3 == 0) { /* a setup rectangle that cuts tiles */
                p.rect_x0 = (int)(walk_rand(&seed) * 100);
                p.rect_y0 = (int)(walk_rand(&seed) * 100);
                p.rect_x1 = WALK_W - (int)(walk_rand(&seed) * 100);
                p.rect_y1 = WALK_H - (int)(walk_rand(&seed) * 100);
            }
            sg_tri t;
            if (!sg_setup_triangle(&p, &v[0], &v[1], &v[2], &t, NULL)) continue;
            /* The bin holding the triangle's centre, or one its bounds touch. */
            h->rx0 =
                (t.minx + (int)(walk_rand(&seed) * (t.maxx - t.minx + 1))) / WALK_BIN * WALK_BIN;
            h->ry0 =
                (t.miny + (int)(walk_rand(&seed) * (t.maxy - t.miny + 1))) / WALK_BIN * WALK_BIN;
            h->stray = 0;
            for (int y = h->ry0; y < h->ry0 + WALK_BIN; y++)
                memset(&h->hits[y][h->rx0], 0, WALK_BIN);
            walk(&t, h->rx0, h->ry0, h->rx0 + WALK_BIN, h->ry0 + WALK_BIN, walk_tile, h);
            assert_int_equal(h->stray, 0);
            for (int y = h->ry0; y < h->ry0 + WALK_BIN; y++)
                for (int x = h->rx0; x < h->rx0 + WALK_BIN; x++) {
                    int in = x >= t.minx && x <= t.maxx && y >= t.miny && y <= t.maxy;
                    for (int e = 0; in && e < 3; e++)
                        in = t.edge[e] + (int64_t)(x - t.minx) * t.edge_dx[e] +
                                 (int64_t)(y - t.miny) * t.edge_dy[e] >=
                             0;
                    if (h->hits[y][x] != in)
                        fail_msg("walk of instruction set %d, triangle %d: pixel (%d, %d) hit %d "
                                 "times, covered %d",
                                 (int)isa, n, x, y, h->hits[y][x], in);
                }
            checked++;
        }
        assert_true(checked > 3000);
    }
    free(h);
}

/* A multisampled pass's one walk for a triangle's four samples (sg_depth_samples_select) leaves
 * each sample's plane of ids, depth and reached tiles as the one-sample visibility function of
 * the same depth state does walking that sample's triangle: every instruction set, compares with
 * and without a test and a write, random triangles from a pixel to far past the target (edge
 * values past 32 bits), over random stored depths. Where the set has a recording walk
 * (sg_depth_record_select), it leaves the same depth, no id and no reached mark, and lists each
 * tile with a written id once, with exactly those pixels per sample. */
typedef struct sample_planes {
    _Alignas(64) float depth[SG_VIS_SAMPLES][WALK_BIN * WALK_BIN];
    _Alignas(64) uint32_t ids[SG_VIS_SAMPLES][WALK_BIN * WALK_BIN];
    uint8_t reached[SG_VIS_SAMPLES][SG_REACHED_BYTES];
} sample_planes;

/* Sample k's plane of p as a bin at (rx0, ry0) rasterising triangle `id` with compare op. */
static sg_vis_ctx plane_ctx(sample_planes *p, int k, int rx0, int ry0, uint32_t id, sgCompare op) {
    return (sg_vis_ctx){.depth = p->depth[k],
                        .ids = p->ids[k],
                        .reached = p->reached[k],
                        .bx0 = rx0,
                        .by0 = ry0,
                        .id = id,
                        .compare = op};
}

static void sample_walk_matches_walk_per_sample(void **state) {
    (void)state;
    /* Aligned as a bin's planes are: the vector sets load them whole. */
    sample_planes *a = aligned_alloc(64, sizeof *a), *b = aligned_alloc(64, sizeof *b);
    sample_planes *c = aligned_alloc(64, sizeof *c);
    assert_non_null(a);
    assert_non_null(b);
    assert_non_null(c);
    long recorded = 0;
    const sgCompare ops[] = {SG_COMPARE_ALWAYS, SG_COMPARE_LESS, SG_COMPARE_GREATER_EQUAL};
    uint32_t seed = 20261129;
    for (sg_isa isa = SG_ISA_SCALAR; isa <= sg_isa_detect(); isa++) {
        long checked = 0;
        for (int n = 0; n < 3000; n++) {
            const double size = n % 10 == 9 ? 2e5 : 1.0 + pow(walk_rand(&seed), 3.0) * 96.0;
            const double cx = walk_rand(&seed) * WALK_W, cy = walk_rand(&seed) * WALK_H;
            sg_cvert v[3];
            for (int k = 0; k < 3; k++) {
                const float w = (float)(0.5 + 3.0 * walk_rand(&seed));
                memset(&v[k], 0, sizeof v[k]);
                v[k].pos[0] =
                    (float)((cx + (walk_rand(&seed) - 0.5) * size) / WALK_W * 2.0 - 1.0) * w;
                v[k].pos[1] =
                    (float)(1.0 - (cy + (walk_rand(&seed) - 0.5) * size) / WALK_H * 2.0) * w;
                v[k].pos[2] = (float)(walk_rand(&seed) * 2.0 - 1.0) * w;
                v[k].pos[3] = w;
            }
            sg_setup_params p = sg_test_params(WALK_W, WALK_H, 0);
            sg_tri t, st[SG_VIS_SAMPLES];
            if (!sg_setup_triangle(&p, &v[0], &v[1], &v[2], &t, NULL)) continue;
            for (int k = 0; k < SG_VIS_SAMPLES; k++) sg_msaa_sample_tri(&t, k, &st[k]);
            const int rx0 =
                (t.minx + (int)(walk_rand(&seed) * (t.maxx - t.minx + 1))) / WALK_BIN * WALK_BIN;
            const int ry0 =
                (t.miny + (int)(walk_rand(&seed) * (t.maxy - t.miny + 1))) / WALK_BIN * WALK_BIN;
            const sgCompare op = ops[n % 3];
            const bool write = (n / 3) % 2;
            memset(a, 0, sizeof *a);
            for (int k = 0; k < SG_VIS_SAMPLES; k++)
                for (int i = 0; i < WALK_BIN * WALK_BIN; i++)
                    a->depth[k][i] = (float)walk_rand(&seed);
            memcpy(b, a, sizeof *a);
            memcpy(c, a, sizeof *a);
            sg_vis_ctx va[SG_VIS_SAMPLES], vb[SG_VIS_SAMPLES], vc[SG_VIS_SAMPLES];
            for (int k = 0; k < SG_VIS_SAMPLES; k++) {
                va[k] = plane_ctx(a, k, rx0, ry0, (uint32_t)n + 1, op);
                vb[k] = plane_ctx(b, k, rx0, ry0, (uint32_t)n + 1, op);
                vc[k] = plane_ctx(c, k, rx0, ry0, (uint32_t)n + 1, op);
                sg_depth_select(op, write, isa)(&st[k], rx0, ry0, rx0 + WALK_BIN, ry0 + WALK_BIN,
                                                &va[k]);
            }
            sg_depth_samples_select(op, write, isa)(st, rx0, ry0, rx0 + WALK_BIN, ry0 + WALK_BIN,
                                                    vb);
            /* Both may mark the spare byte (sg_vis_tile_ids_of): no tile. */
            for (int k = 0; k < SG_VIS_SAMPLES; k++)
                a->reached[k][SG_REACHED_SPARE] = b->reached[k][SG_REACHED_SPARE] = 0;
            if (memcmp(a, b, sizeof *a) != 0)
                fail_msg("instruction set %d, triangle %d: the sample walk differs", (int)isa, n);
            checked++;
            const sg_raster_samples_fn record = sg_depth_record_select(op, write, isa);
            if (!record) continue;
            sg_vis_record rec;
            rec.n = 0;
            vc[0].record = &rec;
            record(st, rx0, ry0, rx0 + WALK_BIN, ry0 + WALK_BIN, vc);
            for (int k = 0; k < SG_VIS_SAMPLES; k++) c->reached[k][SG_REACHED_SPARE] = 0;
            if (memcmp(c->depth, b->depth, sizeof c->depth) != 0)
                fail_msg("instruction set %d, triangle %d: the recording walk's depth differs",
                         (int)isa, n);
            uint8_t listed[WALK_BIN * WALK_BIN / SG_TILE_PIXELS] = {0};
            for (int r = 0; r < rec.n; r++) {
                const int tile = rec.tile[r];
                assert_true(tile < WALK_BIN * WALK_BIN / SG_TILE_PIXELS);
                if (tile >= WALK_BIN * WALK_BIN / SG_TILE_PIXELS) break;
                assert_false(listed[tile]);
                listed[tile] = 1;
            }
            for (int tile = 0; tile < WALK_BIN * WALK_BIN / SG_TILE_PIXELS; tile++) {
                uint32_t want[SG_VIS_SAMPLES], any = 0;
                for (int k = 0; k < SG_VIS_SAMPLES; k++) {
                    want[k] = sg_tile_same_id(b->ids[k] + tile * SG_TILE_PIXELS, (uint32_t)n + 1);
                    any |= want[k];
                }
                assert_int_equal(listed[tile], any != 0);
                for (int r = 0; r < rec.n; r++)
                    if (rec.tile[r] == tile)
                        for (int k = 0; k < SG_VIS_SAMPLES; k++)
                            assert_int_equal(rec.mask[r][k], want[k]);
            }
            for (int k = 0; k < SG_VIS_SAMPLES; k++)
                for (int i = 0; i < WALK_BIN * WALK_BIN; i++) assert_int_equal(c->ids[k][i], 0);
            for (int k = 0; k < SG_VIS_SAMPLES; k++)
                for (int i = 0; i < SG_REACHED_BYTES; i++) assert_int_equal(c->reached[k][i], 0);
            recorded++;
        }
        assert_true(checked > 2000);
    }
#if defined(__x86_64__)
    /* The recording walks of AVX2 and AVX-512, where this CPU runs them. */
    if (sg_isa_detect() >= SG_ISA_AVX2) assert_true(recorded > 0);
#else
    (void)recorded;
#endif
    free(a);
    free(b);
    free(c);
}

static void culling_and_zero_area(void **state) {
    (void)state;
    sg_setup_params p = sg_test_params(W, H, 0);
    sg_tri t;
    /* Counter-clockwise on screen (y up): (10,50) -> (50,50) -> (30,10) in y-down pixels. */
    sg_cvert a = at_pixel(10, 50), b = at_pixel(50, 50), d = at_pixel(30, 10);
    p.cull = SG_CULL_BACK;
    assert_true(sg_setup_triangle(&p, &a, &b, &d, &t, NULL));
    assert_false(sg_setup_triangle(&p, &a, &d, &b, &t, NULL));
    p.cull = SG_CULL_FRONT;
    assert_false(sg_setup_triangle(&p, &a, &b, &d, &t, NULL));
    assert_true(sg_setup_triangle(&p, &a, &d, &b, &t, NULL));
    p.front_face = SG_FRONT_FACE_CW;
    assert_true(sg_setup_triangle(&p, &a, &b, &d, &t, NULL));
    p.cull = SG_CULL_NONE;
    sg_cvert e = at_pixel(20, 30), f = at_pixel(40, 30); /* collinear with (30, 30) */
    sg_cvert g = at_pixel(30, 30);
    assert_false(sg_setup_triangle(&p, &e, &f, &g, &t, NULL));
}

static void huge_triangle_stays_exact(void **state) {
    (void)state;
    /* A triangle reaching the guard band on every side covers the whole target exactly once
     * together with its mirror image. */
    counter *c = calloc(1, sizeof *c);
    sg_cvert a = at_pixel(-30000, -30000), b = at_pixel(30000, -30000);
    sg_cvert d = at_pixel(30000, 30000), e = at_pixel(-30000, 30000);
    draw(c, a, b, d);
    draw(c, a, d, e);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) assert_int_equal(c->hits[y][x], 1);
    free(c);
}

static float uniform(uint32_t *seed, float lo, float hi) {
    *seed = *seed * 1664525u + 1013904223u;
    return lo + (hi - lo) * (float)(*seed >> 8) / 16777216.0f;
}

/* sg_depth_passes_all, against every pixel's own depth (sg_tri_depth, as every set computes it):
 * a range just past the triangle's largest (smallest) pixel depth never passes all for LESS and
 * LESS_EQUAL (GREATER and GREATER_EQUAL), so the margin covers the pixels' rounding; when it says
 * all pass, they do, at both ends of the range. Planes reach outside [0, 1] (clamped depths). */
static void depth_bound_holds_every_pixel(void **state) {
    (void)state;
    uint32_t seed = 12345;
    int passed = 0;
    for (int round = 0; round < 3000; round++) {
        sg_tri t;
        memset(&t, 0, sizeof t);
        t.minx = (int)uniform(&seed, 0, 40);
        t.miny = (int)uniform(&seed, 0, 40);
        t.maxx = t.minx + (int)uniform(&seed, 0, 30);
        t.maxy = t.miny + (int)uniform(&seed, 0, 30);
        t.z = uniform(&seed, -0.1f, 1.1f);
        const float slope = round % 3 ? 1e-3f : 0.05f;
        t.z_dx = uniform(&seed, -slope, slope);
        t.z_dy = uniform(&seed, -slope, slope);
        /* the rectangle the bound is asked for: part of the bounds, or beyond them */
        const int x0 = (int)uniform(&seed, 0, 48), y0 = (int)uniform(&seed, 0, 48);
        const int x1 = x0 + (int)uniform(&seed, 0, 32), y1 = y0 + (int)uniform(&seed, 0, 32);
        float zmin = INFINITY, zmax = -INFINITY;
        for (int y = t.miny > y0 ? t.miny : y0; y <= (t.maxy < y1 ? t.maxy : y1); y++)
            for (int x = t.minx > x0 ? t.minx : x0; x <= (t.maxx < x1 ? t.maxx : x1); x++) {
                float z = sg_tri_depth(&t, (float)(x - t.minx), (float)(y - t.miny));
                zmin = z < zmin ? z : zmin;
                zmax = z > zmax ? z : zmax;
            }
        if (zmin > zmax) { /* no pixel there: nothing to claim */
            assert_false(sg_depth_passes_all(&t, SG_COMPARE_LESS, x0, y0, x1, y1, 1.0f, 1.0f));
            continue;
        }
        assert_false(sg_depth_passes_all(&t, SG_COMPARE_LESS, x0, y0, x1, y1, zmax, 1.0f));
        assert_false(sg_depth_passes_all(&t, SG_COMPARE_LESS_EQUAL, x0, y0, x1, y1,
                                         nextafterf(zmax, 0.0f), 1.0f));
        assert_false(sg_depth_passes_all(&t, SG_COMPARE_GREATER, x0, y0, x1, y1, 0.0f, zmin));
        assert_false(sg_depth_passes_all(&t, SG_COMPARE_GREATER_EQUAL, x0, y0, x1, y1, 0.0f,
                                         nextafterf(zmin, 1.0f)));
        assert_false(sg_depth_passes_all(&t, SG_COMPARE_EQUAL, x0, y0, x1, y1, 1.0f, 1.0f));
        const sgCompare ops[] = {SG_COMPARE_LESS, SG_COMPARE_LESS_EQUAL, SG_COMPARE_GREATER,
                                 SG_COMPARE_GREATER_EQUAL};
        for (int k = 0; k < 4; k++) {
            const float lo = uniform(&seed, 0.0f, 1.0f), hi = uniform(&seed, lo, 1.0f);
            if (!sg_depth_passes_all(&t, ops[k], x0, y0, x1, y1, lo, hi)) continue;
            passed++;
            for (int y = t.miny > y0 ? t.miny : y0; y <= (t.maxy < y1 ? t.maxy : y1); y++)
                for (int x = t.minx > x0 ? t.minx : x0; x <= (t.maxx < x1 ? t.maxx : x1); x++) {
                    float z = sg_tri_depth(&t, (float)(x - t.minx), (float)(y - t.miny));
                    assert_true(sg_depth_passes(ops[k], z, lo) && sg_depth_passes(ops[k], z, hi));
                }
        }
    }
    assert_true(passed > 1000); /* the bound is not only safe but of use */
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(square_halves_cover_each_pixel_once),
        cmocka_unit_test(fan_covers_disc_once),
        cmocka_unit_test(random_meshes_are_watertight),
        cmocka_unit_test(walks_agree_with_edge_functions),
        cmocka_unit_test(sample_walk_matches_walk_per_sample),
        cmocka_unit_test(culling_and_zero_area),
        cmocka_unit_test(huge_triangle_stays_exact),
        cmocka_unit_test(depth_bound_holds_every_pixel),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
