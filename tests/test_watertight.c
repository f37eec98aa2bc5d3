/* test_watertight.c - randomized watertightness: random meshes whose triangles share edges are
 * sent through the real front end (vertex stage, assembly, clipping, setup) and the tile
 * rasteriser, and every pixel is counted. Inside a mesh every pixel must be hit exactly once,
 * outside never, and nowhere twice.
 *
 * Each mesh is a grid over a rectangle of the screen (partly off screen at times) with jittered
 * inner vertices, a random diagonal per cell, random winding per triangle, and a random w per
 * vertex (the same screen position reached through a perspective divide). The border vertices
 * are not jittered, so the mesh covers exactly its rectangle; inner vertices move by at most a
 * fifth of a cell, which keeps every cell convex (either diagonal then gives a valid mesh).
 *
 * The setup rectangle ends a little short of the screen, so that triangles are also cut to it.
 *
 * The seed is fixed. SG_WATERTIGHT_TRIANGLES sets how many triangles to draw (default 1000000);
 * set it higher for a longer run.
 */
#include "test_common.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pipeline/assemble.h"
#include "pipeline/vertex.h"
#include "raster/depth.h"
#include "raster/rast_tile.h"

#define W        256
#define H        256
#define MAX_GRID 48
/* The setup rectangle: pixels past it must never be hit. Its sides are not multiples of the 4x4
 * tile, so tiles on it hold pixels on both sides. */
#define RECT_W 253
#define RECT_H 255

typedef struct counter {
    uint8_t hits[H][W];
    int overflows;
    sg_walk_fn walk; /* the tile walk under test */
    sg_tri tri;      /* where assembly builds each triangle */
} counter;

static void count_tile(const void *ctx, const sg_tri *t, int x0, int y0, uint32_t mask) {
    (void)t;
    counter *c = (counter *)(uintptr_t)ctx;
    for (int b = 0; b < 16; b++)
        if (mask & (1u << b)) {
            uint8_t *h = &c->hits[y0 + (b >> 2)][x0 + (b & 3)];
            if (*h == 255)
                c->overflows++;
            else
                (*h)++;
        }
}

static sg_tri *slot(void *user, sg_tri_ext **ext) {
    (void)ext; /* unlit: no extension */
    return &((counter *)user)->tri;
}

static void emit(void *user) {
    const counter *c = user;
    c->walk(&c->tri, 0, 0, c->tri.maxx + 1, c->tri.maxy + 1, count_tile, user);
}

typedef struct rng {
    uint64_t s;
} rng;

static double uniform(rng *r) {
    r->s = r->s * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(r->s >> 11) * (1.0 / 9007199254740992.0);
}

/* One random mesh: returns the number of triangles drawn and checks every pixel. */
static long one_mesh(rng *r, counter *c, float (*pos)[4], float (*clip)[4], uint32_t *codes,
                     sg_svert *screen, uint8_t *ok, uint32_t *idx) {
    int nx = 2 + (int)(uniform(r) * (MAX_GRID - 1)), ny = 2 + (int)(uniform(r) * (MAX_GRID - 1));
    double x0 = -40 + uniform(r) * 200, y0 = -40 + uniform(r) * 200;
    double cw = 0.3 + uniform(r) * 6, ch = 0.3 + uniform(r) * 6;
    double x1 = x0 + nx * cw, y1 = y0 + ny * ch;
    for (int j = 0; j <= ny; j++)
        for (int i = 0; i <= nx; i++) {
            double jx = (i == 0 || i == nx) ? 0 : (uniform(r) - 0.5) * 0.4 * cw;
            double jy = (j == 0 || j == ny) ? 0 : (uniform(r) - 0.5) * 0.4 * ch;
            double px = x0 + i * cw + jx, py = y0 + j * ch + jy;
            double w = 0.25 + uniform(r) * 4;
            float *p = pos[j * (nx + 1) + i];
            p[0] = (float)((px / W * 2 - 1) * w);
            p[1] = (float)((1 - py / H * 2) * w);
            p[2] = (float)((uniform(r) - 0.5) * w);
            p[3] = (float)w;
        }
    int n = 0;
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) {
            uint32_t a = (uint32_t)(j * (nx + 1) + i), b = a + 1, d = a + (uint32_t)nx + 1,
                     e = d + 1;
            uint32_t t[2][3];
            if (uniform(r) < 0.5) {
                uint32_t u[2][3] = {{a, b, e}, {a, e, d}};
                memcpy(t, u, sizeof t);
            } else {
                uint32_t u[2][3] = {{a, b, d}, {b, e, d}};
                memcpy(t, u, sizeof t);
            }
            for (int k = 0; k < 2; k++) {
                int flip = uniform(r) < 0.5;
                idx[n++] = t[k][0];
                idx[n++] = t[k][flip ? 2 : 1];
                idx[n++] = t[k][flip ? 1 : 2];
            }
        }
    const float id[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    sg_assembly as;
    memset(&as, 0, sizeof as);
    as.guard = sg_guard_for_viewport(W, H);
    sg_vertex_transform(id, &pos[0][0], (nx + 1) * (ny + 1), clip, codes, &as.guard);
    as.indices = idx;
    as.index_count = n;
    as.clip = (const float(*)[4])clip;
    as.outcodes = codes;
    as.setup.width = W;
    as.setup.height = H;
    as.setup.rect_x1 = RECT_W;
    as.setup.rect_y1 = RECT_H;
    as.setup.cull = SG_CULL_NONE;
    as.setup.front_face = SG_FRONT_FACE_CCW;
    sg_vertex_project(&as.setup, (const float(*)[4])clip, codes, (nx + 1) * (ny + 1), screen, ok);
    sg_vertex_check_attributes(NULL, NULL, 0, (nx + 1) * (ny + 1), ok);
    as.screen = screen;
    as.screen_ok = ok;
    as.slot = slot;
    as.emit = emit;
    as.user = c;
    memset(c->hits, 0, sizeof c->hits);
    sg_assemble(&as);

    /* The rectangle is exact up to snapping (1/512 px) and float rounding: a margin of 1/256. */
    const double m = 1.0 / 256;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            double cx = x + 0.5, cy = y + 0.5;
            int hits = c->hits[y][x];
            if (hits > 1) fail_msg("pixel (%d, %d) hit %d times", x, y, hits);
            bool in_rect = x < RECT_W && y < RECT_H;
            bool inside = in_rect && cx > x0 + m && cx < x1 - m && cy > y0 + m && cy < y1 - m;
            bool outside = !in_rect || cx < x0 - m || cx > x1 + m || cy < y0 - m || cy > y1 + m;
            if (inside && hits != 1)
                fail_msg("pixel (%d, %d) inside the mesh [%g,%g]x[%g,%g] hit %d times", x, y, x0,
                         x1, y0, y1, hits);
            if (outside && hits != 0) fail_msg("pixel (%d, %d) outside the mesh hit", x, y);
        }
    return n / 3;
}

static void random_meshes_cover_each_pixel_once(void **state) {
    (void)state;
    long target = 1000000;
    const char *env = getenv("SG_WATERTIGHT_TRIANGLES");
    if (env && atol(env) > 0) target = atol(env);
    counter *c = calloc(1, sizeof *c);
    size_t nv = (MAX_GRID + 1) * (MAX_GRID + 1);
    float(*pos)[4] = calloc(nv, sizeof *pos);
    float(*clip)[4] = calloc(nv, sizeof *clip);
    uint32_t *codes = calloc(nv, sizeof *codes);
    sg_svert *screen = calloc(nv, sizeof *screen);
    uint8_t *ok = calloc(nv, sizeof *ok);
    uint32_t *idx = calloc((size_t)MAX_GRID * MAX_GRID * 6, sizeof *idx);
    assert_non_null(c);
    assert_non_null(idx);
    /* The walk as compiled for each instruction set this CPU runs (its edge tests differ). */
    const char *names[SG_ISA_COUNT] = {"scalar/SSE2/NEON", "SSE2", "AVX2", "AVX-512", "NEON"};
    for (sg_isa isa = SG_ISA_SCALAR; isa < SG_ISA_COUNT; isa++) {
        /* SSE2 and NEON: the baseline walk, already run as the scalar one */
        if (isa == SG_ISA_SSE2 || isa == SG_ISA_NEON || !sg_isa_runs(isa)) continue;
        c->walk = sg_walk_select(isa);
        c->overflows = 0;
        rng r = {20261121};
        long drawn = 0, meshes = 0;
        while (drawn < target) {
            drawn += one_mesh(&r, c, pos, clip, codes, screen, ok, idx);
            meshes++;
        }
        assert_int_equal(c->overflows, 0);
        printf("watertight (%s walk): %ld triangles in %ld meshes, every pixel covered exactly "
               "once\n",
               names[isa], drawn, meshes);
    }
    free(c);
    free(pos);
    free(clip);
    free(codes);
    free(screen);
    free(ok);
    free(idx);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(random_meshes_cover_each_pixel_once),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
