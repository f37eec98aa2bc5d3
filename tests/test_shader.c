/* test_shader.c - programmable stages (sgShaderDesc): the batches the stages receive, varyings,
 * flat varyings, primitive and instance ids, facing, discard against depth (the bin redone in
 * place), batches several triangles share (independent lanes), blending, sgSample, the same bytes
 * at every thread count and instruction set, and the refusals of bad input. */
#include "test_objects.h"

#include <math.h>
#include <stdlib.h>

#include "raster/bin.h"

enum { W = 96, H = 80 };

typedef struct shade_uniforms {
    float offset_per_instance; /* x offset in NDC per instance */
    float threshold;           /* dissolve: discard where the varying's fraction < threshold */
} shade_uniforms;

/* clip = position + instance offset (identity matrices); varyings: colour r g b a, then a
 * value that is the vertex index (flat), then s. */
static void vs_basic(sgVertexBatch *b, const void *uniforms) {
    const shade_uniforms *u = uniforms;
    for (int i = 0; i < SG_SHADER_LANES; i++) {
        b->clip[0][i] =
            b->position[0][i] + (u ? u->offset_per_instance * (float)b->instance : 0.0f);
        b->clip[1][i] = b->position[1][i];
        b->clip[2][i] = b->position[2][i];
        b->clip[3][i] = b->position[3][i];
        for (int k = 0; k < 4; k++) b->varying[k][i] = b->color[k][i];
        b->varying[4][i] = (float)b->index[i];
        b->varying[5][i] = b->texcoord[0][i];
    }
}

static void fs_color(sgFragmentBatch *b, const void *uniforms) {
    (void)uniforms;
    for (int i = 0; i < SG_SHADER_LANES; i++)
        for (int k = 0; k < 4; k++) b->color[k][i] = b->varying[k][i];
}

/* Red from the primitive, green from the flat varying (vertex index of the first vertex), blue
 * from the instance and facing. */
static void fs_ids(sgFragmentBatch *b, const void *uniforms) {
    (void)uniforms;
    for (int i = 0; i < SG_SHADER_LANES; i++) {
        b->color[0][i] = (float)b->primitive / 255.0f;
        b->color[1][i] = b->varying[4][i] / 255.0f;
        b->color[2][i] = (float)(b->instance * 2 + (b->front_facing ? 1 : 0)) / 255.0f;
        b->color[3][i] = 1.0f;
    }
}

/* Discards the lanes of a checkerboard (by pixel), shades the others white. */
static void fs_checker(sgFragmentBatch *b, const void *uniforms) {
    (void)uniforms;
    for (int i = 0; i < SG_SHADER_LANES; i++) {
        int x = b->x + i % 4, y = b->y + i / 4;
        if ((x + y) & 1) b->discard |= 1u << i;
        for (int k = 0; k < 4; k++) b->color[k][i] = 1.0f;
    }
}

static void fs_sample(sgFragmentBatch *b, const void *uniforms) {
    (void)uniforms;
    float rgba[4][SG_SHADER_LANES];
    sgSample(b, 0, b->varying[5], b->varying[5], rgba);
    for (int i = 0; i < SG_SHADER_LANES; i++)
        for (int k = 0; k < 4; k++) b->color[k][i] = rgba[k][i];
}

static const float QUAD_POS[] = {-0.8f, -0.8f, 0.5f, 1, 0.8f,  -0.8f, 0.5f, 1,
                                 0.8f,  0.8f,  0.5f, 1, -0.8f, 0.8f,  0.5f, 1};
static const float QUAD_COL[] = {1, 0, 0, 1, 0, 1, 0, 1, 0, 0, 1, 1, 1, 1, 0, 1};
static const float QUAD_ST[] = {0, 0, 1, 0, 1, 1, 0, 1};
static const uint32_t QUAD_IDX[] = {0, 1, 2, 0, 2, 3};

static const float IDENTITY[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

typedef struct target {
    sgImage2D color, depth;
    sgPassDesc pass;
} target;

static target begin(sgDevice *dev) {
    target t;
    t.color = test_image(dev, W, H, SG_FORMAT_RGBA8_UNORM);
    t.depth = test_image(dev, W, H, SG_FORMAT_D32_FLOAT);
    t.pass = (sgPassDesc){.color = t.color, .depth = t.depth, .clear_color = {0, 0, 0, 1}};
    assert_int_equal(sgBeginRenderPass(dev, &t.pass), SG_OK);
    return t;
}

static void end(sgDevice *dev, target *t, uint8_t *out) {
    assert_int_equal(sgEndRenderPass(dev, &t->pass), SG_OK);
    assert_int_equal(sgReadImage2D(dev, t->color, out, 0), SG_OK);
    sgDestroyImage2D(dev, t->color);
    sgDestroyImage2D(dev, t->depth);
}

/* The quad at depth z, its x and y times `scale` (1: QUAD_POS). */
static sgGeom quad_scaled(sgDevice *dev, float z, float scale) {
    float pos[16];
    for (int i = 0; i < 16; i++) pos[i] = QUAD_POS[i] * (i % 4 < 2 ? scale : 1.0f);
    for (int i = 0; i < 4; i++) pos[i * 4 + 2] = z;
    sgGeom g;
    sgGeomDesc d = {.vertex_count = 4,
                    .positions = pos,
                    .colors = QUAD_COL,
                    .texcoords = QUAD_ST,
                    .index_count = 6,
                    .indices = QUAD_IDX};
    assert_int_equal(sgCreateGeom(dev, &d, &g), SG_OK);
    return g;
}

static sgGeom quad(sgDevice *dev, float z) {
    return quad_scaled(dev, z, 1.0f);
}

static sgDrawParams params(void) {
    sgDrawParams p = {0};
    memcpy(p.world_view, IDENTITY, sizeof IDENTITY);
    memcpy(p.proj, IDENTITY, sizeof IDENTITY);
    return p;
}

/* The unlit shader gives what the fixed vertex-colour shading gives, to one unit. */
static void test_matches_fixed(void **state) {
    (void)state;
    sgDevice *dev;
    assert_int_equal(sgCreateDevice(NULL, &dev), SG_OK);
    sgGeom g = quad(dev, 0.5f);
    sgDrawParams p = params();
    static uint8_t a[W * H * 4], b[W * H * 4];
    target t = begin(dev);
    assert_int_equal(sgDraw(dev, test_pso(dev, (sgPipelineDesc){0}), g, &p), SG_OK);
    end(dev, &t, a);
    t = begin(dev);
    sgPipelineDesc sd = {.shader = {vs_basic, fs_color, 6, 0, 0, false, false}};
    assert_int_equal(sgDraw(dev, test_pso(dev, sd), g, &p), SG_OK);
    end(dev, &t, b);
    int worst = 0, covered = 0;
    for (int i = 0; i < W * H * 4; i++) {
        int d = abs((int)a[i] - (int)b[i]);
        if (d > worst) worst = d;
        covered += (i % 4 == 3) && a[i - 3] + a[i - 2] + a[i - 1] > 0;
    }
    assert_true(covered > 1000);
    assert_true(worst <= 1);
    sgDestroyDevice(dev);
}

/* Primitive, flat varying (provoking vertex), instance and facing reach the fragment stage. */
static void test_ids(void **state) {
    (void)state;
    sgDevice *dev;
    assert_int_equal(sgCreateDevice(NULL, &dev), SG_OK);
    sgGeom g = quad(dev, 0.5f);
    sgDrawParams p = params();
    const shade_uniforms u = {0.0f, 0.0f};
    p.uniforms = &u;
    p.uniform_size = sizeof u;
    p.instance_count = 2; /* the second on top of the first: it wins where LESS_EQUAL passes */
    sgPipelineDesc sd = {.shader = {vs_basic, fs_ids, 6, 1u << 4, 0, false, false},
                         .depth = {.compare = SG_COMPARE_LESS_EQUAL, .write = true}};
    static uint8_t img[W * H * 4];
    target t = begin(dev);
    assert_int_equal(sgDraw(dev, test_pso(dev, sd), g, &p), SG_OK);
    end(dev, &t, img);
    /* A pixel in the lower right triangle (0 1 2: first vertex 0), one in the upper left (0 2 3:
     * first vertex 0): counter-clockwise, front facing, instance 1. */
    const uint8_t *lr = img + ((size_t)(H * 3 / 4) * W + W * 3 / 4) * 4;
    const uint8_t *ul = img + ((size_t)(H / 4) * W + W / 4) * 4;
    assert_int_equal(lr[0], 0);
    assert_int_equal(ul[0], 1);
    assert_int_equal(lr[1], 0);
    assert_int_equal(ul[1], 0);
    assert_int_equal(lr[2], 3);
    assert_int_equal(ul[2], 3);
    sgDestroyDevice(dev);
}

/* Clip x from the instance (u[0] + u[1] instance, NDC), y and z as given; varyings as vs_basic's,
 * then the instance in varying 6. */
static void vs_spread(sgVertexBatch *b, const void *uniforms) {
    const float *u = uniforms;
    vs_basic(b, NULL);
    for (int i = 0; i < SG_SHADER_LANES; i++) {
        b->clip[0][i] += u[0] + u[1] * (float)b->instance;
        b->varying[6][i] = (float)b->instance;
    }
}

/* The primitive, the instance the vertex stage was given (varying 6) and the fragment stage's, as
 * colours (the primitive modulo 251, not a divisor of a block's 256, the instances modulo 256);
 * alpha one half. */
static void fs_spread(sgFragmentBatch *b, const void *uniforms) {
    (void)uniforms;
    for (int i = 0; i < SG_SHADER_LANES; i++) {
        b->color[0][i] = (float)(b->primitive % 251) / 255.0f;
        b->color[1][i] = (float)((int)b->varying[6][i] % 256) / 255.0f;
        b->color[2][i] = (float)(b->instance % 256) / 255.0f;
        b->color[3][i] = 0.5f;
    }
}

/* A fan of `fan` triangles (at most 400), its centre behind the near plane (every triangle
 * clipped into more), drawn `instances` times side by side, overlapping; `quads`: as quads, half
 * as many. */
static void render_instances(int threads, size_t budget, sgPolygonMode mode, bool quads, int fan,
                             int instances, uint8_t *out) {
    sgDevice *dev;
    assert_int_equal(
        sgCreateDevice(&(sgDeviceDesc){.thread_count = threads, .bin_memory_limit = budget}, &dev),
        SG_OK);
    static float pos[401 * 4];
    static uint32_t idx[400 * 3];
    pos[0] = 0.0f, pos[1] = 0.0f, pos[2] = -1.5f, pos[3] = 1.0f;
    for (int i = 0; i < fan; i++) {
        const double a = 6.283185307179586 * i / fan;
        pos[4 + i * 4] = (float)(0.3 * cos(a));
        pos[5 + i * 4] = (float)(0.6 * sin(a));
        pos[6 + i * 4] = 0.5f - 0.5f * (float)i / (float)fan;
        pos[7 + i * 4] = 1.0f;
    }
    int n = 0;
    for (int i = 0; i < fan; i++) {
        if (quads && i % 2) continue;
        idx[n++] = 0;
        idx[n++] = 1 + (uint32_t)i;
        idx[n++] = 1 + (uint32_t)(i + 1) % (uint32_t)fan;
        if (quads) idx[n++] = 1 + (uint32_t)(i + 2) % (uint32_t)fan;
    }
    sgGeom g;
    sgGeomDesc gd = {.vertex_count = fan + 1,
                     .positions = pos,
                     .index_count = n,
                     .indices = idx,
                     .primitive = quads ? SG_PRIMITIVE_QUADS : SG_PRIMITIVE_TRIANGLES};
    assert_int_equal(sgCreateGeom(dev, &gd, &g), SG_OK);
    sgDrawParams p = params();
    const float u[2] = {-0.7f, 1.4f / (float)instances};
    p.uniforms = u;
    p.uniform_size = sizeof u;
    p.instance_count = instances;
    /* Blended, half opaque: every fragment of every triangle shows, in order. */
    sgPipelineDesc sd = {.shader = {vs_spread, fs_spread, 7, 1u << 4 | 1u << 6, 0, false, false},
                         .polygon_mode = mode,
                         .blend = SG_BLEND_ALPHA};
    target t = begin(dev);
    assert_int_equal(sgDraw(dev, test_pso(dev, sd), g, &p), SG_OK);
    end(dev, &t, out);
    sgDestroyDevice(dev);
}

/* Instanced draws of a small geom assemble rounds of instances on every thread (draw.c): the
 * image of one thread at every thread count, with runs overfilled by clipping (the calling
 * thread does the rest, from within an instance when it has more primitives than a block), as
 * wireframe, as quads, and with budgets that flush between rounds or leave no room for one. */
static void test_instance_rounds(void **state) {
    (void)state;
    static uint8_t want[W * H * 4], got[W * H * 4];
    /* Budgets: the default (one round of every instance); one whose rounds take part of the
     * instances, the rest one by one; one too small for a round. */
    static const size_t budgets[3] = {0, 12u << 20, 1u << 20};
    static const struct {
        int fan, instances;
        sgPolygonMode mode;
        bool quads;
        int budgets; /* how many of them */
    } cases[] = {{16, 600, SG_POLYGON_MODE_FILL, false, 3},
                 {16, 600, SG_POLYGON_MODE_FILL, true, 1},
                 {16, 600, SG_POLYGON_MODE_LINE, false, 1},
                 {400, 40, SG_POLYGON_MODE_FILL, false, 2}}; /* more primitives than a block */
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        render_instances(1, 0, cases[c].mode, cases[c].quads, cases[c].fan, cases[c].instances,
                         want);
        int drawn = 0;
        for (int i = 0; i < W * H; i++)
            drawn += (want[i * 4] | want[i * 4 + 1] | want[i * 4 + 2]) != 0;
        assert_true(drawn > W * H / 8);
        for (int k = 0; k < cases[c].budgets; k++) {
            const int threads = 2 + (int)(k + c + 1) % 2; /* 2 and 3 threads in turn */
            render_instances(threads, budgets[k], cases[c].mode, cases[c].quads, cases[c].fan,
                             cases[c].instances, got);
            if (memcmp(want, got, sizeof want) != 0)
                fail_msg("case %zu, %d threads, budget %zu: differs from one thread", c, threads,
                         budgets[k]);
        }
    }
}

/* The C library's allocator with resize, counting the resizes (user: a long). */
static void *plain_alloc(size_t size, void *user) {
    (void)user;
    return malloc(size);
}

static void plain_free(void *ptr, void *user) {
    (void)user;
    free(ptr);
}

static void *counted_resize(void *ptr, size_t size, void *user) {
    ++*(long *)user;
    return realloc(ptr, size);
}

/* The rounds' rest is stored past a small budget a triangle at a time (sg_binner_reserve past
 * memory_limit): the array grows an eighth at a time there, not by one triangle, which resized
 * (copied, under a sanitizer's allocator or a user's) the whole array once a triangle. */
static void test_rest_growth(void **state) {
    (void)state;
    long resizes = 0;
    sg_binner b = {.alloc = plain_alloc,
                   .free = plain_free,
                   .resize = counted_resize,
                   .user = &resizes,
                   .memory_limit = 1u << 20};
    const size_t n = 4 * (b.memory_limit / sg_binner_tri_bytes(&b));
    for (size_t i = 0; i < n; i++) {
        assert_non_null(sg_binner_reserve(&b, 1));
        b.tri_count++; /* stored; the rest is listed afterwards */
    }
    assert_true(b.tri_capacity >= n);
    assert_in_range(resizes, 1, 40);
    b.free(b.tris, b.user);
}

/* A discarding draw over a background: the background shows through the discarded pixels, and
 * the discarded pixels wrote no depth (a third draw behind the first two but in front of the
 * background's depth shows there). */
/* The discard tests' pipelines: fixed vertex colour and the checker shader, depth LESS, written. */
static void discard_psos(sgDevice *dev, sgPipelineStateObject *fixed,
                         sgPipelineStateObject *checker) {
    *fixed = test_pso(dev, (sgPipelineDesc){.depth = {.compare = SG_COMPARE_LESS, .write = true}});
    *checker =
        test_pso(dev, (sgPipelineDesc){.shader = {vs_basic, fs_checker, 6, 0, 0, false, false},
                                       .depth = {.compare = SG_COMPARE_LESS, .write = true}});
}

static void render_discard(int threads, sgSimd simd, bool with_front, uint8_t *out) {
    sgDevice *dev;
    assert_int_equal(sgCreateDevice(&(sgDeviceDesc){.thread_count = threads, .simd = simd}, &dev),
                     SG_OK);
    sgGeom back = quad(dev, 0.8f), front = quad(dev, 0.2f), middle = quad(dev, 0.5f);
    sgDrawParams p = params();
    sgPipelineStateObject fixed, checker;
    discard_psos(dev, &fixed, &checker);
    for (int frame = 0; frame < 2; frame++) { /* the second frame starts in place */
        target t = begin(dev);
        assert_int_equal(sgDraw(dev, fixed, back, &p), SG_OK);
        if (with_front) assert_int_equal(sgDraw(dev, checker, front, &p), SG_OK);
        static const sgColor grey = {0.5f, 0.5f, 0.5f, 1.0f};
        p.color = &grey;
        assert_int_equal(sgDraw(dev, fixed, middle, &p), SG_OK);
        p.color = NULL;
        end(dev, &t, out + (size_t)frame * W * H * 4);
    }
    sgDestroyDevice(dev);
}

static void test_discard(void **state) {
    (void)state;
    static uint8_t want[2 * W * H * 4], got[2 * W * H * 4], behind[2 * W * H * 4];
    render_discard(1, SG_SIMD_SCALAR, true, want);
    render_discard(1, SG_SIMD_SCALAR, false, behind);
    assert_memory_equal(want, want + W * H * 4, (size_t)W * H * 4);
    int white = 0, through = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            const size_t at = ((size_t)y * W + x) * 4;
            const uint8_t *px = want + at;
            if (px[0] == 255 && px[1] == 255 && px[2] == 255) {
                white++;
                assert_int_equal((x + y) & 1, 0);
            } else {
                /* what the draws behind leave, the middle one in front of the back one */
                assert_memory_equal(px, behind + at, 4);
                through += (x + y) & 1 && (px[0] | px[1] | px[2]);
            }
        }
    assert_true(white > 1000);
    assert_true(through > 1000 && abs(through - white) < W + H);
    for (int simd = SG_SIMD_SCALAR; simd <= SG_SIMD_NEON; simd++) {
        if (!test_simd_runs((sgSimd)simd)) continue;
        for (int threads = 1; threads <= 3; threads++) {
            render_discard(threads, (sgSimd)simd, true, got);
            if (memcmp(want, got, sizeof want) != 0)
                fail_msg("simd %d, %d threads: differs from the scalar one-thread image", simd,
                         threads);
        }
    }
}

/* A discarding draw that covers the whole target, in front of a fixed one: every tile is whole and
 * one triangle's (shaded two at a time), and a discard there must still send the bin in place.
 * Both frames: the checker's white on even pixels, the fixed draw alone's colours on the others. */
static void test_discard_whole_tiles(void **state) {
    (void)state;
    for (int threads = 1; threads <= 2; threads++) {
        sgDevice *dev;
        assert_int_equal(sgCreateDevice(&(sgDeviceDesc){.thread_count = threads}, &dev), SG_OK);
        /* 1.5 times the quad: wider than the target */
        const sgGeom geoms[2] = {quad_scaled(dev, 0.8f, 1.5f), quad_scaled(dev, 0.2f, 1.5f)};
        sgDrawParams p = params();
        sgPipelineStateObject fixed, checker;
        discard_psos(dev, &fixed, &checker);
        static uint8_t behind[W * H * 4], img[W * H * 4];
        for (int frame = -1; frame < 2; frame++) { /* -1: the fixed draw alone */
            target t = begin(dev);
            assert_int_equal(sgDraw(dev, fixed, geoms[0], &p), SG_OK);
            if (frame >= 0) assert_int_equal(sgDraw(dev, checker, geoms[1], &p), SG_OK);
            end(dev, &t, frame < 0 ? behind : img);
            if (frame < 0) continue;
            for (int y = 0; y < H; y++)
                for (int x = 0; x < W; x++) {
                    const size_t at = ((size_t)y * W + x) * 4;
                    static const uint8_t white[4] = {255, 255, 255, 255};
                    if (memcmp(img + at, (x + y) & 1 ? behind + at : white, 4) != 0)
                        fail_msg("%d threads, frame %d, pixel (%d, %d): %d %d %d %d", threads,
                                 frame, x, y, img[at], img[at + 1], img[at + 2], img[at + 3]);
                }
        }
        sgDestroyDevice(dev);
    }
}

/* Every depth compare of a draw shaded in place (a discarding one): a fixed draw at depth 0.5,
 * then the checker shader at 0.2, 0.5 and 0.8 with the compare under test: its white pixels show
 * exactly where the compare passes. */
static void test_in_place_compare(void **state) {
    (void)state;
    static const struct {
        sgCompare op;
        bool pass[3]; /* nearer, equal, farther */
    } cases[] = {{SG_COMPARE_NEVER, {false, false, false}},
                 {SG_COMPARE_LESS, {true, false, false}},
                 {SG_COMPARE_EQUAL, {false, true, false}},
                 {SG_COMPARE_LESS_EQUAL, {true, true, false}},
                 {SG_COMPARE_GREATER, {false, false, true}},
                 {SG_COMPARE_NOT_EQUAL, {true, false, true}},
                 {SG_COMPARE_GREATER_EQUAL, {false, true, true}},
                 {SG_COMPARE_ALWAYS, {true, true, true}}};
    static const float depths[3] = {0.2f, 0.5f, 0.8f};
    static uint8_t img[W * H * 4];
    for (int simd = SG_SIMD_SCALAR; simd <= SG_SIMD_NEON; simd++) {
        if (!test_simd_runs((sgSimd)simd)) continue;
        sgDevice *dev;
        assert_int_equal(
            sgCreateDevice(&(sgDeviceDesc){.thread_count = 1, .simd = (sgSimd)simd}, &dev), SG_OK);
        sgGeom mid = quad(dev, 0.5f);
        sgDrawParams p = params();
        sgPipelineStateObject fixed =
            test_pso(dev, (sgPipelineDesc){.depth = {.compare = SG_COMPARE_LESS, .write = true}});
        for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
            sgPipelineStateObject checker = test_pso(
                dev, (sgPipelineDesc){.shader = {vs_basic, fs_checker, 6, 0, 0, false, false},
                                      .depth = {.compare = cases[c].op, .write = true}});
            for (int k = 0; k < 3; k++) {
                sgGeom g = quad(dev, depths[k]);
                target t = begin(dev);
                static const sgColor grey = {0.5f, 0.5f, 0.5f, 1.0f};
                p.color = &grey;
                assert_int_equal(sgDraw(dev, fixed, mid, &p), SG_OK);
                p.color = NULL;
                assert_int_equal(sgDraw(dev, checker, g, &p), SG_OK);
                end(dev, &t, img);
                int white = 0; /* a quarter of the image when the compare passes */
                for (int i = 0; i < W * H; i++)
                    white += img[i * 4] == 255 && img[i * 4 + 1] == 255 && img[i * 4 + 2] == 255;
                if (cases[c].pass[k] ? white < W * H / 4 : white != 0)
                    fail_msg("simd %d, compare %d, depth %.1f: %d white pixels", simd,
                             (int)cases[c].op, (double)depths[k], white);
                sgDestroyGeom(dev, g);
            }
            sgDestroyPipelineStateObject(dev, checker);
        }
        sgDestroyDevice(dev);
    }
}

/* Each lane from its own inputs alone (independent lanes): the colour varyings, blue from the
 * facing; discards where red is below u[0] (with u[0] > 0). Counts its calls in *u[1]'s int. */
typedef struct lanes_uniforms {
    float discard_below;
    int *calls;
} lanes_uniforms;

static void fs_lanes(sgFragmentBatch *b, const void *uniforms) {
    const lanes_uniforms *u = uniforms;
    __atomic_fetch_add(u->calls, 1, __ATOMIC_RELAXED);
    for (int i = 0; i < SG_SHADER_LANES; i++) {
        b->color[0][i] = b->varying[0][i];
        b->color[1][i] = b->varying[1][i] * b->z[i];
        b->color[2][i] = b->front_facing ? 1.0f : 0.25f;
        b->color[3][i] = 1.0f;
        if (b->varying[0][i] < u->discard_below) b->discard |= 1u << i;
    }
}

typedef struct depth_state {
    sgCompare compare;
    bool write;
} depth_state;

/* The geom gd drawn with stage sh (uniforms: a lanes_uniforms of discard_below, counting the
 * fragment stage's calls) and depth state ds in front of a fixed-function quad (what discarded
 * pixels show) and before another that cuts through them, two frames (after a discard the second
 * starts in place) into out; destroys dev; returns the calls. */
static int frames_between(sgDevice *dev, const sgGeomDesc *gd, sgShaderDesc sh, depth_state ds,
                          float discard_below, uint8_t *out) {
    sgGeom g;
    assert_int_equal(sgCreateGeom(dev, gd, &g), SG_OK);
    int calls = 0;
    const lanes_uniforms u = {discard_below, &calls};
    sgDrawParams p = params();
    p.uniforms = &u;
    p.uniform_size = sizeof u;
    sgPipelineStateObject shaded = test_pso(
        dev, (sgPipelineDesc){.shader = sh, .depth = {.compare = ds.compare, .write = ds.write}});
    sgPipelineStateObject fixed =
        test_pso(dev, (sgPipelineDesc){.depth = {.compare = SG_COMPARE_LESS, .write = true}});
    sgGeom back = quad(dev, 0.9f), middle = quad(dev, 0.45f);
    sgDrawParams bp = params();
    for (int frame = 0; frame < 2; frame++) {
        target t = begin(dev);
        assert_int_equal(sgDraw(dev, fixed, back, &bp), SG_OK);
        assert_int_equal(sgDraw(dev, shaded, g, &p), SG_OK);
        assert_int_equal(sgDraw(dev, fixed, middle, &bp), SG_OK); /* after the waiting ones */
        end(dev, &t, out + (size_t)frame * W * H * 4);
    }
    sgDestroyDevice(dev);
    return calls;
}

/* Two 13 x 11 grids of quads over the target, two triangles each (every other quad wound the
 * other way: both facings in a tile), the second shifted by part of a quad and at depths that
 * cross the first's (a draw's own triangles overlap, in both orders), vertex colours from a hash,
 * drawn with fs_lanes and depth state `ds` in front of a fixed-function quad (what discarded
 * pixels show) and before another that cuts through them, two frames (after a discard the second
 * starts in place) into out; returns fs_lanes' calls. */
static int render_lanes(int threads, sgSimd simd, bool independent, float discard_below,
                        depth_state ds, uint8_t *out) {
    sgDevice *dev;
    sgResult r = sgCreateDevice(&(sgDeviceDesc){.thread_count = threads, .simd = simd}, &dev);
    if (r == SG_ERROR_UNSUPPORTED) return -1;
    assert_int_equal(r, SG_OK);
    enum { GX = 13, GY = 11, NV = (GX + 1) * (GY + 1) };
    static float pos[2 * NV * 4], col[2 * NV * 4];
    static uint32_t idx[2 * GX * GY * 6];
    int n = 0;
    for (int layer = 0; layer < 2; layer++) {
        const int v0 = layer * NV;
        for (int j = 0; j <= GY; j++)
            for (int i = 0; i <= GX; i++) {
                const int v = v0 + j * (GX + 1) + i;
                const uint32_t h = (uint32_t)v * 2654435761u;
                pos[v * 4] = -0.97f + 1.94f * ((float)i + 0.5f * (float)layer) / GX +
                             0.011f * (float)(h >> 28);
                pos[v * 4 + 1] = -0.95f + 1.9f * ((float)j + 0.3f * (float)layer) / GY +
                                 0.007f * (float)(h >> 24 & 15);
                pos[v * 4 + 2] = 0.3f - 0.05f * (float)layer + 0.02f * (float)(h >> 20 & 15);
                pos[v * 4 + 3] = 1.0f;
                for (int k = 0; k < 3; k++) col[v * 4 + k] = (float)(h >> (8 * k) & 255) / 255.0f;
                /* Green the same at the vertices of some triangles of a tile, not of others. */
                if (i % 3) col[v * 4 + 1] = 0.5f;
                col[v * 4 + 3] = 1.0f;
            }
        for (int j = 0; j < GY; j++)
            for (int i = 0; i < GX; i++) {
                const uint32_t a = (uint32_t)(v0 + j * (GX + 1) + i), b = a + 1, c = a + GX + 1,
                               d = c + 1;
                const bool flip = (i + j + layer) % 2;
                const uint32_t q[6] = {a, flip ? c : b, flip ? b : c,
                                       b, flip ? c : d, flip ? d : c};
                memcpy(idx + n, q, sizeof q);
                n += 6;
            }
    }
    const sgGeomDesc gd = {
        .vertex_count = 2 * NV, .positions = pos, .colors = col, .index_count = n, .indices = idx};
    return frames_between(dev, &gd,
                          (sgShaderDesc){.vertex = vs_basic,
                                         .fragment = fs_lanes,
                                         .varying_count = 6,
                                         .independent_lanes = independent},
                          ds, discard_below, out);
}

/* Independent lanes: the tiles that several triangles share are one batch a facing, fewer calls
 * for the same bytes at every thread count and instruction set; with discards (shaded in place,
 * the fragments of a tile waiting to be shaded together) too, under several depth states. */
static void test_independent_lanes(void **state) {
    (void)state;
    static uint8_t want[2 * W * H * 4], got[2 * W * H * 4];
    static const sgSimd sets[] = {SG_SIMD_SCALAR, SG_SIMD_AVX2, SG_SIMD_AVX512, SG_SIMD_NEON};
    static const depth_state depths[] = {
        {SG_COMPARE_LESS, true}, {SG_COMPARE_LESS_EQUAL, false}, {SG_COMPARE_ALWAYS, true}};
    for (size_t z = 0; z < sizeof depths / sizeof depths[0]; z++)
        for (int d = 0; d < 2; d++) {
            const float below = d ? 0.3f : 0.0f;
            const int one_each = render_lanes(1, SG_SIMD_SCALAR, false, below, depths[z], want);
            int drawn = 0, blue = 0;
            for (int i = 0; i < W * H; i++) {
                drawn += (want[i * 4] | want[i * 4 + 1]) != 0;
                blue += want[i * 4 + 2] == 255;
            }
            assert_true(drawn > W * H / 2);
            assert_true(blue > W * H / 10 && blue < W * H * 3 / 4); /* both facings show */
            const int shared = render_lanes(1, SG_SIMD_SCALAR, true, below, depths[z], got);
            if (memcmp(want, got, sizeof want) != 0)
                fail_msg("depth state %zu, discard below %g: differs", z, (double)below);
            assert_true(shared < one_each * 3 / 4);
            for (size_t k = 0; k < sizeof sets / sizeof sets[0]; k++)
                for (int threads = 1; threads <= 3; threads += 2)
                    for (int independent = 0; independent < 2; independent++) {
                        if (render_lanes(threads, sets[k], independent, below, depths[z], got) < 0)
                            continue;
                        if (memcmp(want, got, sizeof want) != 0)
                            fail_msg("depth state %zu, discard below %g, set %d, %d threads, "
                                     "independent %d: differs",
                                     z, (double)below, (int)sets[k], threads, independent);
                    }
        }
}

/* clip = position; varyings: the colour alone. */
static void vs_color(sgVertexBatch *b, const void *uniforms) {
    (void)uniforms;
    for (int i = 0; i < SG_SHADER_LANES; i++)
        for (int k = 0; k < 4; k++) {
            b->clip[k][i] = b->position[k][i];
            b->varying[k][i] = b->color[k][i];
        }
}

/* Red where varying 0 is exactly 0.3f, green where varying 1 is exactly 0.7f. */
static void fs_exact(sgFragmentBatch *b, const void *uniforms) {
    (void)uniforms;
    for (int i = 0; i < SG_SHADER_LANES; i++) {
        b->color[0][i] = b->varying[0][i] == 0.3f ? 1.0f : 0.0f;
        b->color[1][i] = b->varying[1][i] == 0.7f ? 1.0f : 0.0f;
        b->color[2][i] = 0.0f;
        b->color[3][i] = 1.0f;
    }
}

/* A varying the same at a triangle's three vertices is that value at every pixel, exactly, under
 * a perspective (w from 1 to 2.5 across the mesh) that an interpolation of value / w would round;
 * in batches of one triangle and of several, at every thread count and instruction set. */
static void test_same_varyings(void **state) {
    (void)state;
    enum { GX = 9, GY = 7, NV = (GX + 1) * (GY + 1) };
    static float pos[NV * 4], col[NV * 4];
    static uint32_t idx[GX * GY * 6];
    for (int j = 0; j <= GY; j++)
        for (int i = 0; i <= GX; i++) {
            const int v = j * (GX + 1) + i;
            const float w = 1.0f + 0.5f * (float)((uint32_t)v * 2654435761u >> 30);
            const float p[4] = {-0.9f + 1.8f * (float)i / GX, -0.9f + 1.8f * (float)j / GY, 0.5f,
                                1.0f};
            for (int k = 0; k < 4; k++) pos[v * 4 + k] = p[k] * w;
            const float c[4] = {0.3f, 0.7f, (float)v / NV, 1.0f};
            memcpy(col + v * 4, c, sizeof c);
        }
    int n = 0;
    for (int j = 0; j < GY; j++)
        for (int i = 0; i < GX; i++) {
            const uint32_t a = (uint32_t)(j * (GX + 1) + i), b = a + 1, c = a + GX + 1, d = c + 1;
            const uint32_t q[6] = {a, b, c, b, d, c};
            memcpy(idx + n, q, sizeof q);
            n += 6;
        }
    const sgGeomDesc gd = {
        .vertex_count = NV, .positions = pos, .colors = col, .index_count = n, .indices = idx};
    static const sgSimd sets[] = {SG_SIMD_SCALAR, SG_SIMD_AVX2, SG_SIMD_AVX512, SG_SIMD_NEON};
    static uint8_t out[W * H * 4];
    for (size_t k = 0; k < sizeof sets / sizeof sets[0]; k++)
        for (int threads = 1; threads <= 3; threads += 2)
            for (int independent = 0; independent < 2; independent++) {
                sgDevice *dev;
                const sgResult r =
                    sgCreateDevice(&(sgDeviceDesc){.thread_count = threads, .simd = sets[k]}, &dev);
                if (r == SG_ERROR_UNSUPPORTED) continue;
                assert_int_equal(r, SG_OK);
                sgGeom g;
                assert_int_equal(sgCreateGeom(dev, &gd, &g), SG_OK);
                sgPipelineStateObject pso =
                    test_pso(dev, (sgPipelineDesc){.shader = {.vertex = vs_color,
                                                              .fragment = fs_exact,
                                                              .varying_count = 4,
                                                              .independent_lanes = independent}});
                target t = begin(dev);
                sgDrawParams p = params();
                assert_int_equal(sgDraw(dev, pso, g, &p), SG_OK);
                end(dev, &t, out);
                sgDestroyDevice(dev);
                int covered = 0;
                for (int i = 0; i < W * H; i++) {
                    if (out[i * 4 + 3] == 255 && out[i * 4] == 0 && out[i * 4 + 1] == 0 &&
                        out[i * 4 + 2] == 0)
                        continue; /* the clear colour */
                    covered++;
                    if (out[i * 4] != 255 || out[i * 4 + 1] != 255)
                        fail_msg("set %d, %d threads, independent %d: pixel %d is %d %d",
                                 (int)sets[k], threads, independent, i, out[i * 4], out[i * 4 + 1]);
                }
                assert_true(covered > W * H / 2);
            }
}

/* A stage of its varyings alone (sgShaderDesc.varyings_only): the colour varyings, discarding
 * where red is below u[0]; counts its calls in *u[1]'s int. */
static void fs_pure(sgFragmentBatch *b, const void *uniforms) {
    const lanes_uniforms *u = uniforms;
    __atomic_fetch_add(u->calls, 1, __ATOMIC_RELAXED);
    for (int i = 0; i < SG_SHADER_LANES; i++) {
        for (int k = 0; k < 4; k++) b->color[k][i] = b->varying[k][i];
        if (b->varying[0][i] < u->discard_below) b->discard |= 1u << i;
    }
}

/* A 13 x 11 grid of quads of four vertices each over the target, every other quad of one colour
 * (k / 255 in each channel, so that a pixel's colour is exact either way), the others of a colour
 * a vertex, at depths that cross, drawn with fs_pure (varyings_only as given) between two
 * fixed-function quads, two frames, into out; returns fs_pure's calls. */
static int render_pure(int threads, sgSimd simd, bool varyings_only, float discard_below,
                       depth_state ds, uint8_t *out) {
    sgDevice *dev;
    sgResult r = sgCreateDevice(&(sgDeviceDesc){.thread_count = threads, .simd = simd}, &dev);
    if (r == SG_ERROR_UNSUPPORTED) return -1;
    assert_int_equal(r, SG_OK);
    enum { GX = 13, GY = 11, NV = GX * GY * 4 };
    static float pos[NV * 4], col[NV * 4];
    static uint32_t idx[GX * GY * 6];
    int n = 0, v = 0;
    for (int j = 0; j < GY; j++)
        for (int i = 0; i < GX; i++) {
            const uint32_t q = (uint32_t)(j * GX + i) * 2654435761u;
            const float x0 = -0.97f + 1.94f * (float)i / GX, y0 = -0.95f + 1.9f * (float)j / GY;
            const float x1 = x0 + 1.94f / GX * 1.1f, y1 = y0 + 1.9f / GY * 1.1f; /* overlapping */
            const float corner[4][2] = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
            for (int c = 0; c < 4; c++, v++) {
                const uint32_t h = (i + j) % 2 ? (uint32_t)v * 2246822519u : q;
                pos[v * 4] = corner[c][0];
                pos[v * 4 + 1] = corner[c][1];
                pos[v * 4 + 2] = 0.3f + 0.02f * (float)((q >> 20 & 15) + (uint32_t)c);
                pos[v * 4 + 3] = 1.0f;
                for (int k = 0; k < 3; k++) col[v * 4 + k] = (float)(h >> (8 * k) & 255) / 255.0f;
                /* Green the same at the vertices of some triangles of a tile, not of others. */
                if (i % 3) col[v * 4 + 1] = 0.5f;
                col[v * 4 + 3] = 1.0f;
            }
            const uint32_t a = (uint32_t)v - 4;
            const uint32_t t[6] = {a, a + 1, a + 2, a, a + 2, a + 3};
            memcpy(idx + n, t, sizeof t);
            n += 6;
        }
    const sgGeomDesc gd = {
        .vertex_count = NV, .positions = pos, .colors = col, .index_count = n, .indices = idx};
    return frames_between(dev, &gd,
                          (sgShaderDesc){.vertex = vs_color,
                                         .fragment = fs_pure,
                                         .varying_count = 4,
                                         .independent_lanes = true,
                                         .varyings_only = varyings_only},
                          ds, discard_below, out);
}

/* A stage of its varyings alone runs once for a triangle whose varyings agree, at assembly: a
 * quad of one colour is two calls, whatever it covers; with other triangles, fewer calls, the
 * same image as pixel by pixel (its colours exact either way), a triangle it discards dropped
 * whole (depth too), and the same bytes at every thread count and instruction set. */
static void test_varyings_only(void **state) {
    (void)state;
    {
        sgDevice *dev;
        assert_int_equal(sgCreateDevice(NULL, &dev), SG_OK);
        const float c[4] = {0.2f, 0.6f, 1.0f, 1.0f},
                    col[16] = {c[0], c[1], c[2], c[3], c[0], c[1], c[2], c[3],
                               c[0], c[1], c[2], c[3], c[0], c[1], c[2], c[3]};
        sgGeom g;
        sgGeomDesc gd = {.vertex_count = 4,
                         .positions = QUAD_POS,
                         .colors = col,
                         .index_count = 6,
                         .indices = QUAD_IDX};
        assert_int_equal(sgCreateGeom(dev, &gd, &g), SG_OK);
        int calls = 0;
        const lanes_uniforms u = {0.0f, &calls};
        sgDrawParams p = params();
        p.uniforms = &u;
        p.uniform_size = sizeof u;
        const sgPipelineStateObject pso =
            test_pso(dev, (sgPipelineDesc){.shader = {.vertex = vs_color,
                                                      .fragment = fs_pure,
                                                      .varying_count = 4,
                                                      .independent_lanes = true,
                                                      .varyings_only = true}});
        static uint8_t img[W * H * 4];
        target t = begin(dev);
        assert_int_equal(sgDraw(dev, pso, g, &p), SG_OK);
        end(dev, &t, img);
        assert_int_equal(calls, 2);
        const uint8_t want[4] = {51, 153, 255, 255};
        assert_memory_equal(img + ((H / 2) * W + W / 2) * 4, want, 4);
        int covered = 0;
        for (int i = 0; i < W * H; i++) covered += memcmp(img + i * 4, want, 4) == 0;
        assert_true(covered > W * H / 2);
        sgDestroyDevice(dev);
    }
    static uint8_t want[2 * W * H * 4], got[2 * W * H * 4];
    static const sgSimd sets[] = {SG_SIMD_SCALAR, SG_SIMD_SSE2, SG_SIMD_AVX2, SG_SIMD_AVX512,
                                  SG_SIMD_NEON};
    static const depth_state depths[] = {{SG_COMPARE_LESS, true}, {SG_COMPARE_ALWAYS, true}};
    for (size_t z = 0; z < sizeof depths / sizeof depths[0]; z++)
        for (int d = 0; d < 2; d++) {
            /* halfway between two units: no colour is near the threshold */
            const float below = d ? 0.3f + 0.5f / 255.0f : 0.0f;
            const int per_pixel = render_pure(1, SG_SIMD_SCALAR, false, below, depths[z], want);
            /* the discarding frames show something else where some quads were */
            static uint8_t kept[2 * W * H * 4];
            if (!d) memcpy(kept, want, sizeof kept);
            assert_true(d ? memcmp(kept, want, sizeof kept) != 0 : true);
            const int once = render_pure(1, SG_SIMD_SCALAR, true, below, depths[z], got);
            if (memcmp(want, got, sizeof want) != 0)
                fail_msg("depth state %zu, discard below %g: differs", z, (double)below);
            assert_true(once < per_pixel); /* tiles its two kinds of quad share still call it */
            for (size_t k = 0; k < sizeof sets / sizeof sets[0]; k++)
                for (int threads = 1; threads <= 3; threads += 2) {
                    if (render_pure(threads, sets[k], true, below, depths[z], got) < 0) continue;
                    if (memcmp(want, got, sizeof want) != 0)
                        fail_msg("depth state %zu, discard below %g, set %d, %d threads: differs",
                                 z, (double)below, (int)sets[k], threads);
                }
        }
}

/* sgSample reads the bound texture with the pipeline's filter; an empty slot gives (0, 0, 0, 1). */
static void test_sample(void **state) {
    (void)state;
    sgDevice *dev;
    assert_int_equal(sgCreateDevice(NULL, &dev), SG_OK);
    uint8_t texels[2 * 2 * 4] = {255, 0, 0,   255, 0,   255, 0,   255,
                                 0,   0, 255, 255, 255, 255, 255, 255};
    sgImage2D tex;
    assert_int_equal(sgCreateImage2D(dev,
                                     &(sgImage2DDesc){.width = 2,
                                                      .height = 2,
                                                      .format = SG_FORMAT_RGBA8_UNORM,
                                                      .data = texels},
                                     &tex),
                     SG_OK);
    sgGeom g = quad(dev, 0.5f);
    sgDrawParams p = params();
    p.textures[0] = tex;
    sgPipelineDesc sd = {.shader = {vs_basic, fs_sample, 6, 0, 1, false, false},
                         .wrap = SG_WRAP_CLAMP_TO_EDGE};
    static uint8_t img[W * H * 4];
    target t = begin(dev);
    assert_int_equal(sgDraw(dev, test_pso(dev, sd), g, &p), SG_OK);
    end(dev, &t, img);
    /* s = t along the diagonal: the bottom-left corner is texel (0, bottom row) = blue, the top
     * right texel (1, top row) = green. */
    const uint8_t *bl = img + ((size_t)(H * 85 / 100) * W + W * 15 / 100) * 4;
    const uint8_t *tr = img + ((size_t)(H * 15 / 100) * W + W * 85 / 100) * 4;
    assert_int_equal(bl[2], 255);
    assert_int_equal(bl[0], 0);
    assert_int_equal(tr[1], 255);
    assert_int_equal(tr[0], 0);
    /* Without the texture bound, the draw is refused: the shader samples one. */
    p.textures[0] = (sgImage2D){0};
    t = begin(dev);
    assert_int_equal(sgDraw(dev, test_pso(dev, sd), g, &p), SG_ERROR_MISSING_TEXTURE);
    end(dev, &t, img);
    sgDestroyDevice(dev);
}

/* Blended shader draws blend like fixed ones at every instruction set and depth state: the quad
 * drawn twice, the second time over the first (with LESS and depth written it fails there, else
 * it blends again). */
static void test_blend(void **state) {
    (void)state;
    static const depth_state depths[] = {
        {SG_COMPARE_ALWAYS, false}, {SG_COMPARE_LESS, true}, {SG_COMPARE_LESS_EQUAL, false}};
    float col[16];
    for (int i = 0; i < 16; i++) col[i] = (i % 4 == 3) ? 0.5f : 1.0f;
    static uint8_t a[W * H * 4], b[W * H * 4];
    for (int simd = SG_SIMD_SCALAR; simd <= SG_SIMD_NEON; simd++) {
        if (!test_simd_runs((sgSimd)simd)) continue;
        sgDevice *dev;
        assert_int_equal(
            sgCreateDevice(&(sgDeviceDesc){.thread_count = 1, .simd = (sgSimd)simd}, &dev), SG_OK);
        sgGeom g;
        sgGeomDesc d = {.vertex_count = 4,
                        .positions = QUAD_POS,
                        .colors = col,
                        .index_count = 6,
                        .indices = QUAD_IDX};
        assert_int_equal(sgCreateGeom(dev, &d, &g), SG_OK);
        sgDrawParams p = params();
        for (size_t z = 0; z < sizeof depths / sizeof depths[0]; z++) {
            sgPipelineDesc fixed = {.blend = SG_BLEND_ALPHA};
            fixed.depth.compare = depths[z].compare;
            fixed.depth.write = depths[z].write;
            sgPipelineDesc shader = fixed;
            shader.shader = (sgShaderDesc){vs_basic, fs_color, 6, 0, 0, false, false};
            const sgPipelineStateObject psos[2] = {test_pso(dev, fixed), test_pso(dev, shader)};
            for (int k = 0; k < 2; k++) {
                target t = begin(dev);
                for (int twice = 0; twice < 2; twice++)
                    assert_int_equal(sgDraw(dev, psos[k], g, &p), SG_OK);
                end(dev, &t, k ? b : a);
            }
            if (memcmp(a, b, sizeof a) != 0)
                fail_msg("simd %d, depth state %zu: the shader's blend differs", simd, z);
        }
        sgDestroyDevice(dev);
    }
}

/* Bad input: each a specific code, nothing drawn. */
static void test_refusals(void **state) {
    (void)state;
    sgDevice *dev;
    assert_int_equal(sgCreateDevice(NULL, &dev), SG_OK);
    sgPipelineStateObject pso;
    assert_int_equal(
        sgCreatePipelineStateObject(dev, &(sgPipelineDesc){.shader = {.vertex = vs_basic}}, &pso),
        SG_ERROR_NULL_POINTER);
    assert_non_null(strstr(sgGetLastError(dev), "shader.fragment"));
    assert_int_equal(sgCreatePipelineStateObject(
                         dev,
                         &(sgPipelineDesc){.shader = {vs_basic, fs_color, 6, 0, 0, false, false},
                                           .lighting = SG_LIGHTING_PHONG},
                         &pso),
                     SG_ERROR_INVALID_VALUE);
    assert_int_equal(
        sgCreatePipelineStateObject(
            dev, &(sgPipelineDesc){.shader = {vs_basic, fs_color, 17, 0, 0, false, false}}, &pso),
        SG_ERROR_INVALID_COUNT);
    assert_int_equal(
        sgCreatePipelineStateObject(
            dev, &(sgPipelineDesc){.shader = {vs_basic, fs_color, 2, 4u, 0, false, false}}, &pso),
        SG_ERROR_INVALID_VALUE);
    assert_int_equal(
        sgCreatePipelineStateObject(
            dev, &(sgPipelineDesc){.shader = {vs_basic, fs_color, 6, 0, 9, false, false}}, &pso),
        SG_ERROR_INVALID_COUNT);
    sgPipelineStateObject sh =
        test_pso(dev, (sgPipelineDesc){.shader = {vs_basic, fs_color, 6, 0, 0, false, false}});
    sgPipelineStateObject fixed = test_pso(dev, (sgPipelineDesc){0});
    sgGeom g = quad(dev, 0.5f);
    target t = begin(dev);
    sgDrawParams p = params();
    p.uniform_size = SG_MAX_UNIFORM_SIZE + 1;
    static float big[SG_MAX_UNIFORM_SIZE / 4 + 1];
    p.uniforms = big;
    assert_int_equal(sgDraw(dev, sh, g, &p), SG_ERROR_INVALID_SIZE);
    p.uniforms = NULL;
    p.uniform_size = 4;
    assert_int_equal(sgDraw(dev, sh, g, &p), SG_ERROR_NULL_POINTER);
    p = params();
    p.texture = t.color;
    assert_int_equal(sgDraw(dev, sh, g, &p), SG_ERROR_INVALID_VALUE);
    p = params();
    p.instance_count = 3;
    assert_int_equal(sgDraw(dev, fixed, g, &p), SG_ERROR_INVALID_VALUE);
    p.instance_count = -1;
    assert_int_equal(sgDraw(dev, sh, g, &p), SG_ERROR_INVALID_COUNT);
    static uint8_t img[W * H * 4];
    end(dev, &t, img);
    for (size_t i = 0; i < sizeof img; i += 4)
        assert_int_equal(img[i] | img[i + 1] | img[i + 2], 0);
    sgDestroyDevice(dev);
}

/* A non-finite clip position drops the triangle, and nothing else. */
static void vs_nan(sgVertexBatch *b, const void *uniforms) {
    vs_basic(b, uniforms);
    for (int i = 0; i < SG_SHADER_LANES; i++)
        if (b->index[i] == 3) b->clip[3][i] = NAN;
}

static void test_nan(void **state) {
    (void)state;
    sgDevice *dev;
    assert_int_equal(sgCreateDevice(NULL, &dev), SG_OK);
    sgGeom g = quad(dev, 0.5f);
    sgDrawParams p = params();
    static uint8_t img[W * H * 4];
    target t = begin(dev);
    assert_int_equal(
        sgDraw(dev,
               test_pso(dev, (sgPipelineDesc){.shader = {vs_nan, fs_color, 6, 0, 0, false, false}}),
               g, &p),
        SG_OK);
    end(dev, &t, img);
    const uint8_t *lr = img + ((size_t)(H * 3 / 4) * W + W * 3 / 4) * 4;
    const uint8_t *ul = img + ((size_t)(H / 4) * W + W / 4) * 4;
    assert_true(lr[0] + lr[1] + lr[2] > 0);
    assert_int_equal(ul[0] + ul[1] + ul[2], 0);
    sgDestroyDevice(dev);
}

/* A tile's colours: lane i's red conversion_values[i], its green the values in reverse: NaN,
 * infinities, zeros of both signs, values below 0, above 1 and between. With *uniforms not 0,
 * pixel (0, 0) is discarded, so that its bin is shaded in place. */
static const float conversion_values[SG_SHADER_LANES] = {
    NAN,   -NAN, -INFINITY, -1.0f,  -0.0f, 0.0f, 1e-30f,   0.0019f,
    0.25f, 0.5f, 0.75f,     0.998f, 1.0f,  1.5f, INFINITY, 0.001f};

static void fs_values(sgFragmentBatch *b, const void *uniforms) {
    const int *discard_origin = uniforms;
    for (int i = 0; i < SG_SHADER_LANES; i++) {
        b->color[0][i] = conversion_values[i];
        b->color[1][i] = conversion_values[SG_SHADER_LANES - 1 - i];
        b->color[2][i] = 0.5f;
        b->color[3][i] = 1.0f;
    }
    if (*discard_origin && b->x == 0 && b->y == 0) b->discard = 1;
}

/* The documented conversion: clamped to [0, 1], NaN written as 0, rounded to nearest. */
static uint8_t unorm8_of(float v) {
    return v > 0.0f ? (v < 1.0f ? (uint8_t)(v * 255.0f + 0.5f) : 255) : 0;
}

/* The fragment stage's colours reach the target clamped, NaN as 0, at every instruction set,
 * shaded visibility first (whole tiles in pairs) and in place. */
static void test_color_conversion(void **state) {
    (void)state;
    static uint8_t img[W * H * 4];
    for (int simd = SG_SIMD_SCALAR; simd <= SG_SIMD_NEON; simd++) {
        if (!test_simd_runs((sgSimd)simd)) continue;
        for (int discard_origin = 0; discard_origin < 2; discard_origin++) {
            sgDevice *dev;
            assert_int_equal(
                sgCreateDevice(&(sgDeviceDesc){.thread_count = 1, .simd = (sgSimd)simd}, &dev),
                SG_OK);
            sgGeom g = quad_scaled(dev, 0.5f, 1.5f);
            sgDrawParams p = params();
            p.uniforms = &discard_origin;
            p.uniform_size = sizeof discard_origin;
            sgPipelineStateObject pso = test_pso(
                dev, (sgPipelineDesc){.shader = {vs_basic, fs_values, 6, 0, 0, false, false}});
            for (int frame = 0; frame < 2; frame++) { /* after a discard, the second in place */
                target t = begin(dev);
                assert_int_equal(sgDraw(dev, pso, g, &p), SG_OK);
                end(dev, &t, img);
                for (int y = 0; y < H; y++)
                    for (int x = 0; x < W; x++) {
                        if (discard_origin && x == 0 && y == 0) continue;
                        const int lane = (x & 3) + (y & 3) * 4;
                        const uint8_t want[4] = {
                            unorm8_of(conversion_values[lane]),
                            unorm8_of(conversion_values[SG_SHADER_LANES - 1 - lane]), 128, 255};
                        const uint8_t *got = img + ((size_t)y * W + x) * 4;
                        if (memcmp(got, want, 4) != 0)
                            fail_msg("simd %d, discard %d, frame %d, pixel (%d, %d): %d %d %d %d",
                                     simd, discard_origin, frame, x, y, got[0], got[1], got[2],
                                     got[3]);
                    }
            }
            sgDestroyDevice(dev);
        }
    }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_matches_fixed),    cmocka_unit_test(test_ids),
        cmocka_unit_test(test_instance_rounds),  cmocka_unit_test(test_rest_growth),
        cmocka_unit_test(test_discard),          cmocka_unit_test(test_discard_whole_tiles),
        cmocka_unit_test(test_in_place_compare), cmocka_unit_test(test_independent_lanes),
        cmocka_unit_test(test_varyings_only),    cmocka_unit_test(test_same_varyings),
        cmocka_unit_test(test_sample),           cmocka_unit_test(test_blend),
        cmocka_unit_test(test_refusals),         cmocka_unit_test(test_nan),
        cmocka_unit_test(test_color_conversion),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
