/* test_line.c - lines by the diamond-exit rule: for random segments (and the hard ones: end points
 * on pixel centres, corners and edges, every axis and diagonal, a pixel long or crossing the
 * setup rectangle), the pixels line setup and the tile raster draw (every instruction set's walk)
 * equal those of a slow reference that evaluates the rule as it is written: clip the moved
 * segment to each pixel's diamond, in exact arithmetic, and drop the pixel whose diamond holds the
 * moved end point. Opaque lines, shaded as they are rasterised, keep the submission order among
 * the triangles of their pass (lines_in_submission_order).
 *
 * The seed is fixed. SG_LINE_SEGMENTS sets how many random segments to test (default 100000).
 */
#include "test_common.h"
#include "test_objects.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pipeline/line.h"
#include "raster/depth.h"
#include "raster/rast_tile.h"
#include "sgapi/sgapi.h"

enum { W = 48, H = 40, ONE = SG_SUBPIXEL_ONE };

/* ---- the reference: the rule as written ---- */

/* v + a e + b e^2, e > 0 infinitesimal: the end points move by (-e, -e^2). */
typedef struct num {
    int64_t v, a, b;
} num;

static int sign_of(num n) {
    if (n.v) return n.v > 0 ? 1 : -1;
    if (n.a) return n.a > 0 ? 1 : -1;
    return (n.b > 0) - (n.b < 0);
}

/* A bound t <> p / q on the segment parameter, q > 0; `open`: strict. */
typedef struct bound {
    num p;
    int64_t q;
    bool open;
} bound;

/* sign(x.p / x.q - y.p / y.q) */
static int compare(bound x, bound y) {
    num d = {x.p.v * y.q - y.p.v * x.q, x.p.a * y.q - y.p.a * x.q, x.p.b * y.q - y.p.b * x.q};
    return sign_of(d);
}

/* Whether the moved segment a' + t (b - a), t in [0, 1], meets the open diamond |x - cx| + |y -
 * cy| < ONE / 2: each of its four sides s . (p - c) < ONE / 2 bounds t, and the bounds must leave
 * some t. */
static bool meets(int64_t ax, int64_t ay, int64_t bx, int64_t by, int64_t cx, int64_t cy) {
    static const int side[4][2] = {{1, 1}, {1, -1}, {-1, 1}, {-1, -1}};
    bound lo = {{0, 0, 0}, 1, false}, hi = {{1, 0, 0}, 1, false};
    for (int k = 0; k < 4; k++) {
        int64_t sx = side[k][0], sy = side[k][1];
        /* s . (a' - c) = alpha, s . (b - a) = beta; alpha + t beta < ONE / 2 */
        num alpha = {sx * (ax - cx) + sy * (ay - cy), -sx, -sy};
        int64_t beta = sx * (bx - ax) + sy * (by - ay);
        num room = {ONE / 2 - alpha.v, -alpha.a, -alpha.b}; /* t beta < room */
        if (beta == 0) {
            if (sign_of(room) <= 0) return false;
        } else if (beta > 0) { /* t < room / beta */
            bound b = {room, beta, true};
            int c = compare(b, hi);
            if (c < 0 || (c == 0 && !hi.open)) hi = b;
        } else { /* t > room / beta = -room / -beta */
            bound b = {{-room.v, -room.a, -room.b}, -beta, true};
            int c = compare(b, lo);
            if (c > 0 || (c == 0 && !lo.open)) lo = b;
        }
    }
    int c = compare(lo, hi);
    return c < 0 || (c == 0 && !lo.open && !hi.open);
}

static bool holds_end(int64_t bx, int64_t by, int64_t cx, int64_t cy) {
    num dx = {bx - cx, -1, 0}, dy = {by - cy, 0, -1};
    if (sign_of(dx) < 0) dx = (num){-dx.v, -dx.a, -dx.b};
    if (sign_of(dy) < 0) dy = (num){-dy.v, -dy.a, -dy.b};
    return sign_of((num){dx.v + dy.v - ONE / 2, dx.a + dy.a, dx.b + dy.b}) < 0;
}

/* The pixels of a w x h image the rule draws for segment s[0] -> s[1], row by row. */
static void reference_sized(const sg_svert s[2], int w, int h, uint8_t *out) {
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) {
            int64_t cx = (int64_t)i * ONE + ONE / 2, cy = (int64_t)j * ONE + ONE / 2;
            out[j * w + i] =
                meets(s[0].x, s[0].y, s[1].x, s[1].y, cx, cy) && !holds_end(s[1].x, s[1].y, cx, cy);
        }
}

static void reference(const sg_svert s[2], uint8_t out[H][W]) {
    reference_sized(s, W, H, &out[0][0]);
}

/* ---- sgapi: line setup, then the tile raster ---- */

typedef struct canvas {
    uint8_t px[H][W];
} canvas;

static void mark(const void *ctx, const sg_tri *t, int x0, int y0, uint32_t mask) {
    (void)t;
    canvas *c = (canvas *)(uintptr_t)ctx;
    for (int k = 0; k < 16; k++)
        if (mask >> k & 1) {
            int x = x0 + (k & 3), y = y0 + (k >> 2);
            assert_true(x >= 0 && x < W && y >= 0 && y < H);
            c->px[y][x]++;
        }
}

static const sg_setup_params PARAMS = {W, H, 0, 0, W, H, SG_CULL_NONE, SG_FRONT_FACE_CCW, 0, 0,
                                       0, 0, 0, 0, 0, 0};

static void drawn(sg_walk_fn walk, const sg_svert s[2], uint8_t out[H][W]) {
    canvas c;
    memset(&c, 0, sizeof c);
    sg_tri t;
    memset(&t, 0, sizeof t);
    if (sg_setup_line_coverage(&PARAMS, s, &t))
        walk(&t, 0, 0, (W + 3) & ~3, (H + 3) & ~3, mark, &c);
    memcpy(out, c.px, sizeof c.px);
}

static long failures;

static void check(const sg_svert s[2]) {
    uint8_t ref[H][W], got[H][W];
    reference(s, ref);
    for (int isa = 0; isa < SG_ISA_COUNT; isa++) {
        /* NEON's walk is the AArch64 baseline, the scalar one: not run twice */
        if (!sg_isa_runs((sg_isa)isa) || isa == SG_ISA_NEON) continue;
        drawn(sg_walk_select((sg_isa)isa), s, got);
        if (memcmp(ref, got, sizeof ref) == 0) continue;
        if (failures++ < 5) {
            printf("segment (%d, %d) -> (%d, %d) /256, isa %d:\n", s[0].x, s[0].y, s[1].x, s[1].y,
                   isa);
            for (int j = 0; j < H; j++)
                for (int i = 0; i < W; i++)
                    if (ref[j][i] != got[j][i])
                        printf("  pixel (%d, %d): reference %d, sgapi %d\n", i, j, ref[j][i],
                               got[j][i]);
        }
    }
}

static uint64_t rng_state = 0x11e5u;

static uint64_t next(void) {
    uint64_t z = (rng_state += 0x9e3779b97f4a7c15u);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
    return z ^ (z >> 31);
}

static int32_t pick(int32_t lo, int32_t hi) {
    return lo + (int32_t)(next() % (uint64_t)(hi - lo + 1));
}

/* A coordinate around the canvas: anywhere in 1/256, or on a pixel centre, corner or edge. */
static int32_t coord(int32_t size) {
    int32_t px = pick(-3, size + 2);
    switch (next() % 4) {
    case 0:
        return px * ONE + ONE / 2; /* centre */
    case 1:
        return px * ONE; /* corner or edge */
    case 2:
        return px * ONE + pick(0, 3) * (ONE / 4);
    default:
        return px * ONE + pick(0, ONE - 1);
    }
}

static void random_segments(void **state) {
    (void)state;
    long n = 100000;
    const char *env = getenv("SG_LINE_SEGMENTS");
    if (env) n = atol(env);
    for (long k = 0; k < n; k++) {
        sg_svert s[2];
        memset(s, 0, sizeof s);
        s[0].x = coord(W);
        s[0].y = coord(H);
        switch (next() % 5) {
        case 0: /* short: within a few pixels */
            s[1].x = s[0].x + pick(-3 * ONE, 3 * ONE);
            s[1].y = s[0].y + pick(-3 * ONE, 3 * ONE);
            break;
        case 1: { /* axis-aligned or diagonal */
            int32_t d = pick(-20 * ONE, 20 * ONE);
            int dir = (int)(next() % 4);
            s[1].x = s[0].x + (dir == 1 ? 0 : d);
            s[1].y = s[0].y + (dir == 0 ? 0 : dir == 3 ? -d : d);
            break;
        }
        default:
            s[1].x = coord(W);
            s[1].y = coord(H);
            break;
        }
        check(s);
    }
    printf("%ld segments, %ld differ\n", n, failures);
    assert_int_equal(failures, 0);
}

/* Segments whose ends lie far outside the canvas (up to about 30000 pixels, the clipper's guard
 * band) and which cross it or pass near it: edge values far past 32 bits, long walks cut to the
 * canvas, lines of every slope. One end near the canvas and the other far, or both far on
 * either side of a point near it. */
static void far_segments(void **state) {
    (void)state;
    long n = 20000;
    const char *env = getenv("SG_LINE_SEGMENTS");
    if (env) n = atol(env) / 5;
    for (long k = 0; k < n; k++) {
        const int32_t px = coord(W), py = coord(H);
        const int32_t dx = pick(-30000 * ONE, 30000 * ONE), dy = pick(-30000 * ONE, 30000 * ONE);
        sg_svert s[2];
        memset(s, 0, sizeof s);
        if (next() % 2) { /* from far away to near the canvas, or back */
            s[0].x = px + dx;
            s[0].y = py + dy;
            s[1].x = px;
            s[1].y = py;
            if (next() % 2) {
                const sg_svert t = s[0];
                s[0] = s[1];
                s[1] = t;
            }
        } else { /* through a point near the canvas, both ends far */
            const int32_t f = pick(1, 4);
            s[0].x = px + dx;
            s[0].y = py + dy;
            s[1].x = px - dx / f;
            s[1].y = py - dy / f;
        }
        check(s);
    }
    printf("%ld far segments, %ld differ\n", n, failures);
    assert_int_equal(failures, 0);
}

/* Every direction through a pixel centre and through a pixel corner, a few pixels long, in both
 * directions: the rule's hard cases, every one of them decided by its ties. */
static void fans_through_centres_and_corners(void **state) {
    (void)state;
    failures = 0;
    const int32_t centres[2][2] = {{20 * ONE + ONE / 2, 20 * ONE + ONE / 2}, {20 * ONE, 20 * ONE}};
    for (int c = 0; c < 2; c++)
        for (int dx = -12; dx <= 12; dx++)
            for (int dy = -12; dy <= 12; dy++)
                for (int half = 1; half <= 2; half++) {
                    sg_svert s[2];
                    memset(s, 0, sizeof s);
                    s[0].x = centres[c][0];
                    s[0].y = centres[c][1];
                    s[1].x = s[0].x + dx * (ONE / half);
                    s[1].y = s[0].y + dy * (ONE / half);
                    check(s);
                    sg_svert r[2] = {s[1], s[0]};
                    check(r);
                }
    assert_int_equal(failures, 0);
}

/* Known pixels: a horizontal line on a row of centres draws from its first pixel up to, not
 * including, its last; one on a row edge draws the row above (the move is up, -e^2 in y down). */
static void known_lines(void **state) {
    (void)state;
    uint8_t got[H][W];
    sg_svert s[2];
    memset(s, 0, sizeof s);
    s[0].x = 2 * ONE + ONE / 2;
    s[0].y = 5 * ONE + ONE / 2;
    s[1].x = 9 * ONE + ONE / 2;
    s[1].y = s[0].y;
    drawn(sg_walk_select(SG_ISA_SCALAR), s, got);
    for (int i = 0; i < W; i++) assert_int_equal(got[5][i], i >= 2 && i < 9);
    s[0].y = s[1].y = 5 * ONE;
    drawn(sg_walk_select(SG_ISA_SCALAR), s, got);
    for (int i = 0; i < W; i++) assert_int_equal(got[4][i], i >= 2 && i < 9);
    for (int i = 0; i < W; i++) assert_int_equal(got[5][i], 0);
}

/* ---- through the API ---- */

typedef struct api {
    sgDevice *dev;
    sgImage2D color, depth;
} api;

static void api_open(api *a) {
    assert_int_equal(sgCreateDevice(NULL, &a->dev), SG_OK);
    a->color = test_image(a->dev, W, H, SG_FORMAT_RGBA8_UNORM);
    a->depth = test_image(a->dev, W, H, SG_FORMAT_D32_FLOAT);
}

/* The clip position whose window position is (x, y) / 256 pixels, at clip w `w` (identity
 * matrices: NDC = clip / w). */
static void clip_of(int32_t x, int32_t y, float w, float out[4]) {
    out[0] = ((float)x / (float)(ONE * W) * 2.0f - 1.0f) * w;
    out[1] = (1.0f - (float)y / (float)(ONE * H) * 2.0f) * w;
    out[2] = 0.0f;
    out[3] = w;
}

static const float IDENTITY[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

/* Draws `count` vertices with `indices` as `prim` with pipeline desc `pd`; returns the result of
 * sgDraw and the image (clear colour black, vertices white unless `colors`). */
static sgResult draw(api *a, const float *pos, const float *colors, int count,
                     const uint32_t *indices, int index_count, sgPrimitive prim, sgPipelineDesc pd,
                     uint8_t img[H][W][4]) {
    sgGeom g;
    assert_int_equal(sgCreateGeom(a->dev,
                                  &(sgGeomDesc){.vertex_count = count,
                                                .positions = pos,
                                                .colors = colors,
                                                .index_count = index_count,
                                                .indices = indices,
                                                .primitive = prim},
                                  &g),
                     SG_OK);
    sgPipelineStateObject p;
    assert_int_equal(sgCreatePipelineStateObject(a->dev, &pd, &p), SG_OK);
    sgDrawParams dp = {0};
    memcpy(dp.world_view, IDENTITY, sizeof IDENTITY);
    memcpy(dp.proj, IDENTITY, sizeof IDENTITY);
    sgPassDesc pass = {.color = a->color, .depth = a->depth};
    assert_int_equal(sgBeginRenderPass(a->dev, &pass), SG_OK);
    sgResult r = sgDraw(a->dev, p, g, &dp);
    assert_int_equal(sgEndRenderPass(a->dev, &pass), SG_OK);
    assert_int_equal(sgReadImage2D(a->dev, a->color, img, 0), SG_OK);
    sgDestroyGeom(a->dev, g);
    sgDestroyPipelineStateObject(a->dev, p);
    return r;
}

/* Random segments through the whole pipeline (vertex stage, assembly, setup, binning, raster,
 * shading), at w 1 and at other w (the same window positions), each drawn alone: the image's
 * lit pixels are the reference's. */
static void segments_through_the_api(void **state) {
    (void)state;
    api a;
    api_open(&a);
    failures = 0;
    for (int k = 0; k < 300; k++) {
        sg_svert s[2];
        memset(s, 0, sizeof s);
        for (int i = 0; i < 2; i++) {
            s[i].x = coord(W);
            s[i].y = coord(H);
        }
        float pos[8];
        float w = k % 3 == 0 ? 1.0f : k % 3 == 1 ? 0.5f : 4.0f;
        clip_of(s[0].x, s[0].y, w, pos);
        clip_of(s[1].x, s[1].y, w, pos + 4);
        const uint32_t idx[2] = {0, 1};
        uint8_t img[H][W][4], ref[H][W];
        assert_int_equal(
            draw(&a, pos, NULL, 2, idx, 2, SG_PRIMITIVE_LINES, (sgPipelineDesc){0}, img), SG_OK);
        reference(s, ref);
        for (int j = 0; j < H; j++)
            for (int i = 0; i < W; i++)
                if ((img[j][i][0] == 255) != (ref[j][i] == 1) && failures++ < 5)
                    printf("segment %d (%d, %d) -> (%d, %d): pixel (%d, %d) %d, reference %d\n", k,
                           s[0].x, s[0].y, s[1].x, s[1].y, i, j, img[j][i][0], ref[j][i]);
    }
    assert_int_equal(failures, 0);
    sgDestroyDevice(a.dev);
}

/* Long segments across several 64 x 64 screen bins of a larger image, drawn alone through the
 * API at one and two threads: each bin gets exactly the line's pixels (lines are binned along
 * their major axis, line.h). */
static void long_segments_across_bins(void **state) {
    (void)state;
    enum { BW = 200, BH = 150 };
    for (int threads = 1; threads <= 2; threads++) {
        sgDevice *dev;
        assert_int_equal(sgCreateDevice(&(sgDeviceDesc){.thread_count = threads}, &dev), SG_OK);
        sgImage2D color = test_image(dev, BW, BH, SG_FORMAT_RGBA8_UNORM);
        sgPipelineStateObject p = test_pso(dev, (sgPipelineDesc){0});
        static uint8_t img[BH][BW][4], ref[BH * BW];
        for (int k = 0; k < 60; k++) {
            sg_svert s[2];
            memset(s, 0, sizeof s);
            for (int i = 0; i < 2; i++) {
                s[i].x = coord(BW);
                s[i].y = coord(BH);
            }
            float pos[8];
            for (int i = 0; i < 2; i++) {
                pos[4 * i] = (float)s[i].x / (float)(ONE * BW) * 2.0f - 1.0f;
                pos[4 * i + 1] = 1.0f - (float)s[i].y / (float)(ONE * BH) * 2.0f;
                pos[4 * i + 2] = 0.0f;
                pos[4 * i + 3] = 1.0f;
            }
            const uint32_t idx[2] = {0, 1};
            sgGeom g;
            assert_int_equal(sgCreateGeom(dev,
                                          &(sgGeomDesc){.vertex_count = 2,
                                                        .positions = pos,
                                                        .index_count = 2,
                                                        .indices = idx,
                                                        .primitive = SG_PRIMITIVE_LINES},
                                          &g),
                             SG_OK);
            sgDrawParams dp = {0};
            memcpy(dp.world_view, IDENTITY, sizeof IDENTITY);
            memcpy(dp.proj, IDENTITY, sizeof IDENTITY);
            sgPassDesc pass = {.color = color};
            assert_int_equal(sgBeginRenderPass(dev, &pass), SG_OK);
            assert_int_equal(sgDraw(dev, p, g, &dp), SG_OK);
            assert_int_equal(sgEndRenderPass(dev, &pass), SG_OK);
            assert_int_equal(sgReadImage2D(dev, color, img, 0), SG_OK);
            sgDestroyGeom(dev, g);
            reference_sized(s, BW, BH, ref);
            for (int j = 0; j < BH; j++)
                for (int i = 0; i < BW; i++)
                    if ((img[j][i][0] == 255) != (ref[j * BW + i] == 1))
                        fail_msg("segment (%d, %d) -> (%d, %d), %d threads: pixel (%d, %d)", s[0].x,
                                 s[0].y, s[1].x, s[1].y, threads, i, j);
        }
        sgDestroyDevice(dev);
    }
}

/* Wireframe: a triangle's three edges, each by the rule; a back face culled; a
 * quad's four outer edges and not its diagonal. */
static void wireframe(void **state) {
    (void)state;
    api a;
    api_open(&a);
    const int32_t v[4][2] = {{4 * ONE + 100, 4 * ONE + 30},
                             {40 * ONE + 17, 6 * ONE + 200},
                             {38 * ONE + 128, 35 * ONE},
                             {5 * ONE + 60, 33 * ONE + 1}};
    float pos[16];
    for (int i = 0; i < 4; i++) clip_of(v[i][0], v[i][1], 1.0f, pos + 4 * i);
    uint8_t img[H][W][4], ref[H][W], all[H][W];
    /* v0 v1 v2 is clockwise on screen (y down): a back face with the default front face. */
    const uint32_t tri[3] = {0, 1, 2};
    assert_int_equal(draw(&a, pos, NULL, 4, tri, 3, SG_PRIMITIVE_TRIANGLES,
                          (sgPipelineDesc){.polygon_mode = SG_POLYGON_MODE_LINE}, img),
                     SG_OK);
    memset(all, 0, sizeof all);
    for (int e = 0; e < 3; e++) {
        sg_svert s[2];
        memset(s, 0, sizeof s);
        s[0].x = v[e][0], s[0].y = v[e][1];
        s[1].x = v[(e + 1) % 3][0], s[1].y = v[(e + 1) % 3][1];
        reference(s, ref);
        for (int j = 0; j < H; j++)
            for (int i = 0; i < W; i++) all[j][i] |= ref[j][i];
    }
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++) assert_int_equal(img[j][i][0] == 255, all[j][i]);
    assert_int_equal(
        draw(&a, pos, NULL, 4, tri, 3, SG_PRIMITIVE_TRIANGLES,
             (sgPipelineDesc){.polygon_mode = SG_POLYGON_MODE_LINE, .cull = SG_CULL_BACK}, img),
        SG_OK);
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++) assert_int_equal(img[j][i][0], 0);
    /* The quad v0 v1 v2 v3: its outline, no diagonal v0 - v2 (pixel (21, 19) lies on it, far
     * from the outline). */
    const uint32_t quad[4] = {0, 1, 2, 3};
    assert_int_equal(draw(&a, pos, NULL, 4, quad, 4, SG_PRIMITIVE_QUADS,
                          (sgPipelineDesc){.polygon_mode = SG_POLYGON_MODE_LINE}, img),
                     SG_OK);
    memset(all, 0, sizeof all);
    for (int e = 0; e < 4; e++) {
        sg_svert s[2];
        memset(s, 0, sizeof s);
        s[0].x = v[e][0], s[0].y = v[e][1];
        s[1].x = v[(e + 1) % 4][0], s[1].y = v[(e + 1) % 4][1];
        reference(s, ref);
        for (int j = 0; j < H; j++)
            for (int i = 0; i < W; i++) all[j][i] |= ref[j][i];
    }
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++) assert_int_equal(img[j][i][0] == 255, all[j][i]);
    sgDestroyDevice(a.dev);
}

/* A line from in front of the eye to behind it (w < 0 at one end) draws its visible part and
 * never divides by w <= 0; one reaching far past the guard band draws its part on screen, the
 * same pixels as the same line cut short inside the image. Colours interpolate along the line. */
static void clipped_lines(void **state) {
    (void)state;
    api a;
    api_open(&a);
    uint8_t img[H][W][4], ref[H][W];
    const uint32_t idx[2] = {0, 1};
    /* Through the eye: w from 1 to -1. */
    float through[8] = {-0.5f, 0.2f, 0.0f, 1.0f, 0.5f, 0.2f, 0.0f, -1.0f};
    assert_int_equal(
        draw(&a, through, NULL, 2, idx, 2, SG_PRIMITIVE_LINES, (sgPipelineDesc){0}, img), SG_OK);
    int lit = 0;
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++) lit += img[j][i][0] == 255;
    assert_true(lit > 0);
    /* Far past the guard band to the right, 45000 pixels away, slope 1/4: the same pixels as the
     * line from the same start to where it leaves the image. */
    float far[8];
    clip_of(3 * ONE + 128, 5 * ONE + 128, 1.0f, far);
    clip_of(3 * ONE + 128 + 45000 * ONE, 5 * ONE + 128 + 11250 * ONE, 1.0f, far + 4);
    assert_int_equal(draw(&a, far, NULL, 2, idx, 2, SG_PRIMITIVE_LINES, (sgPipelineDesc){0}, img),
                     SG_OK);
    sg_svert s[2];
    memset(s, 0, sizeof s);
    s[0].x = 3 * ONE + 128, s[0].y = 5 * ONE + 128;
    s[1].x = s[0].x + 200 * ONE, s[1].y = s[0].y + 50 * ONE;
    reference(s, ref);
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++) assert_int_equal(img[j][i][0] == 255, ref[j][i]);
    /* Colour from black to white along x: increasing along the row. */
    const float col[8] = {0, 0, 0, 1, 1, 1, 1, 1};
    float row[8];
    clip_of(2 * ONE + 128, 10 * ONE + 128, 1.0f, row);
    clip_of(42 * ONE + 128, 10 * ONE + 128, 1.0f, row + 4);
    assert_int_equal(draw(&a, row, col, 2, idx, 2, SG_PRIMITIVE_LINES, (sgPipelineDesc){0}, img),
                     SG_OK);
    for (int i = 2; i < 42; i++) {
        int want = (int)((float)(i - 2) / 40.0f * 255.0f + 0.5f);
        if (abs(img[10][i][0] - want) > 1)
            fail_msg("pixel %d: %d, want %d", i, img[10][i][0], want);
    }
    sgDestroyDevice(a.dev);
}

/* Flat lighting has no face on a line: refused, nothing drawn. */
static void flat_lit_lines_are_refused(void **state) {
    (void)state;
    api a;
    api_open(&a);
    float pos[8];
    clip_of(ONE, ONE, 1.0f, pos);
    clip_of(20 * ONE, 9 * ONE, 1.0f, pos + 4);
    const uint32_t idx[2] = {0, 1};
    uint8_t img[H][W][4];
    assert_int_equal(draw(&a, pos, NULL, 2, idx, 2, SG_PRIMITIVE_LINES,
                          (sgPipelineDesc){.lighting = SG_LIGHTING_FLAT}, img),
                     SG_ERROR_UNSUPPORTED);
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++) assert_int_equal(img[j][i][0], 0);
    sgDestroyDevice(a.dev);
}

/* ---- submission order ---- */

/* Opaque line draws are shaded as they are rasterised (blend.h), opaque triangles visibility
 * first: a pass that mixes them, with blended triangles, wireframes, textured lines and several
 * depth states, gives the bytes of drawing each primitive in a pass of its own that loads the
 * last one's colour and depth (the plain order), at 1, 2 and 3 threads, with every instruction
 * set this CPU runs. */
enum { OS = 150, NPRIM = 168, PER_DRAW = 8, KINDS = 7 };

typedef struct order_scene {
    float pos[NPRIM * 3 * 4], col[NPRIM * 3 * 4], uv[NPRIM * 3 * 2];
    uint32_t idx[NPRIM * 3];
    int kind_shift;    /* primitive p is of kind (p / PER_DRAW + kind_shift) % KINDS */
    int samples;       /* the pass's (0: one) */
    size_t bin_memory; /* the device's bin_memory_limit (0: the default) */
} order_scene;

/* Draw kinds, by draw index mod KINDS: the primitive, the pipeline. */
static bool kind_is_line(int kind) {
    return kind == 1 || kind == 2 || kind == 4 || kind == 6;
}

static sgPipelineDesc kind_pipeline(int kind) {
    switch (kind) {
    case 0:
        return (sgPipelineDesc){.depth = {.compare = SG_COMPARE_LESS_EQUAL, .write = true}};
    case 1:
        return (sgPipelineDesc){.depth = {.compare = SG_COMPARE_LESS, .write = true}};
    case 2:
        return (sgPipelineDesc){.shade = SG_SHADE_TEXTURE_MODULATE,
                                .depth = {.compare = SG_COMPARE_LESS_EQUAL}};
    case 3:
        return (sgPipelineDesc){.blend = SG_BLEND_ALPHA,
                                .depth = {.compare = SG_COMPARE_LESS_EQUAL}};
    case 4:
        return (sgPipelineDesc){.depth = {.compare = SG_COMPARE_ALWAYS, .write = true}};
    case 5:
        return (sgPipelineDesc){.polygon_mode = SG_POLYGON_MODE_LINE,
                                .depth = {.compare = SG_COMPARE_LESS, .write = true}};
    default:
        return (sgPipelineDesc){.depth = {.compare = SG_COMPARE_GREATER}};
    }
}

/* A number in [0, 1) from the state *x (a linear congruential step). */
static float unit(uint32_t *x) {
    *x = *x * 1664525u + 1013904223u;
    return (float)(*x >> 8) / 16777216.0f;
}

static int kind_of(const order_scene *s, int p) {
    return (p / PER_DRAW + s->kind_shift) % KINDS;
}

/* line_reach: how far a line's ends spread (2.4: across several bins). */
static void make_order_scene(order_scene *s, float line_reach) {
    uint32_t x = 4242;
    for (int p = 0; p < NPRIM; p++) {
        const bool line = kind_is_line(kind_of(s, p));
        float cx = unit(&x) * 2.2f - 1.1f, cy = unit(&x) * 2.2f - 1.1f, z = unit(&x) * 1.6f - 0.8f;
        const float reach = line ? line_reach : 1.0f;
        for (int v = 0; v < 3; v++) {
            float *q = s->pos + (p * 3 + v) * 4;
            q[0] = cx + (unit(&x) - 0.5f) * reach;
            q[1] = cy + (unit(&x) - 0.5f) * reach;
            q[2] = z + unit(&x) * 0.4f - 0.2f;
            q[3] = 1.0f;
            for (int k = 0; k < 4; k++) s->col[(p * 3 + v) * 4 + k] = 0.2f + 0.8f * unit(&x);
            s->uv[(p * 3 + v) * 2] = unit(&x) * 3.0f;
            s->uv[(p * 3 + v) * 2 + 1] = unit(&x) * 3.0f;
            s->idx[p * 3 + v] = (uint32_t)(p * 3 + v);
        }
    }
}

/* The scene in one pass, draws of PER_DRAW primitives; or (per_primitive) each primitive in a
 * pass of its own that loads the last one's colour and depth. */
static void render_order(const void *scene, int threads, sgSimd simd, bool per_primitive,
                         uint8_t *out) {
    const order_scene *s = scene;
    sgDevice *dev;
    assert_int_equal(sgCreateDevice(&(sgDeviceDesc){.thread_count = threads,
                                                    .simd = simd,
                                                    .bin_memory_limit = s->bin_memory},
                                    &dev),
                     SG_OK);
    sgImage2D color = test_image(dev, OS, OS, SG_FORMAT_RGBA8_UNORM);
    sgImage2D depth = test_image(dev, OS, OS, SG_FORMAT_D32_FLOAT);
    uint8_t texels[4 * 4 * 4];
    for (int i = 0; i < 16; i++)
        for (int k = 0; k < 4; k++) texels[i * 4 + k] = (uint8_t)(40 + 13 * i + 50 * k);
    sgImage2D tex;
    assert_int_equal(sgCreateImage2D(dev,
                                     &(sgImage2DDesc){.width = 4,
                                                      .height = 4,
                                                      .format = SG_FORMAT_RGBA8_UNORM,
                                                      .data = texels},
                                     &tex),
                     SG_OK);
    sgPipelineStateObject pso[KINDS];
    for (int k = 0; k < KINDS; k++) pso[k] = test_pso(dev, kind_pipeline(k));
    sgDrawParams params = {.texture = tex};
    memcpy(params.world_view, IDENTITY, sizeof IDENTITY);
    memcpy(params.proj, IDENTITY, sizeof IDENTITY);
    sgPassDesc pass = {.color = color,
                       .depth = depth,
                       .clear_color = {0.1f, 0.2f, 0.3f, 1.0f},
                       .clear_depth = 1.0f,
                       .samples = s->samples};
    const int per = per_primitive ? 1 : PER_DRAW;
    if (!per_primitive) assert_int_equal(sgBeginRenderPass(dev, &pass), SG_OK);
    for (int first = 0; first < NPRIM; first += per) {
        const int kind = kind_of(s, first), n = kind_is_line(kind) ? 2 : 3;
        uint32_t idx[PER_DRAW * 3];
        for (int p = 0; p < per; p++)
            for (int v = 0; v < n; v++) idx[p * n + v] = s->idx[(first + p) * 3 + v];
        sgGeom g;
        assert_int_equal(sgCreateGeom(dev,
                                      &(sgGeomDesc){.vertex_count = NPRIM * 3,
                                                    .positions = s->pos,
                                                    .colors = s->col,
                                                    .texcoords = s->uv,
                                                    .index_count = per * n,
                                                    .indices = idx,
                                                    .primitive = n == 2 ? SG_PRIMITIVE_LINES
                                                                        : SG_PRIMITIVE_TRIANGLES},
                                      &g),
                         SG_OK);
        if (per_primitive) assert_int_equal(sgBeginRenderPass(dev, &pass), SG_OK);
        assert_int_equal(sgDraw(dev, pso[kind], g, &params), SG_OK);
        if (per_primitive) {
            assert_int_equal(sgEndRenderPass(dev, &pass), SG_OK);
            pass.color_load = pass.depth_load = SG_LOAD_LOAD;
        }
        sgDestroyGeom(dev, g); /* the pass keeps what it binned */
    }
    if (!per_primitive) assert_int_equal(sgEndRenderPass(dev, &pass), SG_OK);
    assert_int_equal(sgReadImage2D(dev, color, out, 0), SG_OK);
    sgDestroyDevice(dev);
}

static void lines_in_submission_order(void **state) {
    (void)state;
    order_scene *s = calloc(1, sizeof *s);
    make_order_scene(s, 2.4f);
    uint8_t *want = malloc(OS * OS * 4), *got = malloc(OS * OS * 4);
    render_order(s, 1, SG_SIMD_SCALAR, true, want);
    /* The lines show: against the same scene with every line behind the eye (clipped away),
     * they change over 5 % of the pixels. */
    int changed = 0;
    {
        order_scene *t = calloc(1, sizeof *t);
        memcpy(t, s, sizeof *t);
        for (int p = 0; p < NPRIM; p++)
            if (kind_is_line(kind_of(t, p)))
                for (int v = 0; v < 3; v++) t->pos[(p * 3 + v) * 4 + 3] = -1.0f; /* behind */
        uint8_t *bare = malloc(OS * OS * 4);
        render_order(t, 1, SG_SIMD_SCALAR, true, bare);
        for (int i = 0; i < OS * OS; i++) changed += memcmp(want + 4 * i, bare + 4 * i, 4) != 0;
        free(bare);
        free(t);
    }
    assert_true(changed > OS * OS / 20);
    test_same_in_one_pass(render_order, s, want, got, OS * OS * 4);
    free(want);
    free(got);
    free(s);
}

/* With 4 samples a pixel, an opaque line over tiles that hold one colour and one depth a pixel is
 * drawn in place into their first sample (rast_msaa.c), and elsewhere visibility first, as after
 * a flush, when a bin's samples come back from the sample buffers: a pass that flushes after
 * every few primitives gives the bytes of one that never does, with every set and thread count.
 */
static void lines_in_submission_order_4_samples(void **state) {
    (void)state;
    order_scene *s = calloc(1, sizeof *s);
    s->kind_shift = 1; /* lines first, and short: most of them on tiles nothing else drew yet */
    make_order_scene(s, 0.5f);
    s->samples = 4;
    s->bin_memory = 16384;
    uint8_t *want = malloc(OS * OS * 4), *got = malloc(OS * OS * 4);
    render_order(s, 1, SG_SIMD_SCALAR, false, want);
    s->bin_memory = 0;
    test_same_in_one_pass(render_order, s, want, got, OS * OS * 4);
    free(want);
    free(got);
    free(s);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(known_lines),
        cmocka_unit_test(fans_through_centres_and_corners),
        cmocka_unit_test(random_segments),
        cmocka_unit_test(far_segments),
        cmocka_unit_test(segments_through_the_api),
        cmocka_unit_test(long_segments_across_bins),
        cmocka_unit_test(wireframe),
        cmocka_unit_test(clipped_lines),
        cmocka_unit_test(flat_lit_lines_are_refused),
        cmocka_unit_test(lines_in_submission_order),
        cmocka_unit_test(lines_in_submission_order_4_samples),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
