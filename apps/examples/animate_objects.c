/* animate_objects.c - an animation that creates and destroys objects between its frames, and
 * checks that the device's memory stays flat while it does.
 *
 *   animate_objects [FRAMES [SIZE]]     (default 2000 frames of 128 x 128 pixels)
 *
 * Every frame makes a new mesh (a fan whose triangle count changes from frame to frame), a new
 * texture (of a changing size) and a new pipeline (of a changing state), draws them beside a mesh
 * that lives through the whole animation, and destroys what it made three frames earlier, so
 * objects of different ages are alive at once and their slots are reused. The device allocates
 * through a counting allocator (sgDeviceDesc.allocator): once a warm-up has let its working
 * memory reach its largest, the bytes it holds at the end of a frame must never be more than one
 * period of the animation before. Exit status 0 when they never are and sgDestroyDevice frees
 * every byte, 1 otherwise.
 *
 * It uses the public API alone: copy it, and build it against the installed library
 * (find_package(sgapi) and sgapi::sgapi_static, or pkg-config --cflags --libs sgapi).
 */
#include <math.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <sgapi/sgapi.h>

/* ---- a counting allocator ----------------------------------------------------------------------
 * Each block carries its size in a 16-byte header, so that free knows what it gives back and
 * the memory handed to the device stays 16-byte aligned. Atomic: a device may allocate on its
 * worker threads. */

typedef struct counter {
    atomic_size_t bytes;  /* held now */
    atomic_size_t blocks; /* held now */
    atomic_size_t total;  /* allocations ever made */
} counter;

static void *count_alloc(size_t size, void *user) {
    counter *c = user;
    if (size > SIZE_MAX - 16) return NULL;
    unsigned char *p = aligned_alloc(16, (size + 16 + 15) & ~(size_t)15);
    if (!p) return NULL;
    memcpy(p, &size, sizeof size);
    atomic_fetch_add(&c->bytes, size);
    atomic_fetch_add(&c->blocks, 1);
    atomic_fetch_add(&c->total, 1);
    return p + 16;
}

static void count_free(void *ptr, void *user) {
    counter *c = user;
    if (!ptr) return;
    unsigned char *p = (unsigned char *)ptr - 16;
    size_t size;
    memcpy(&size, p, sizeof size);
    atomic_fetch_sub(&c->bytes, size);
    atomic_fetch_sub(&c->blocks, 1);
    free(p);
}

/* ---- the animation ------------------------------------------------------------------------- */

/* The objects one frame makes; destroyed LIFETIME frames later. */
typedef struct frame_objects {
    sgGeom geom;
    sgImage2D texture;
    sgPipelineStateObject pso;
} frame_objects;

enum {
    LIFETIME = 3,   /* frames an object lives */
    PERIOD = 24,    /* the sizes and states repeat after this many frames */
    MAX_TRIS = 120, /* most triangles of a frame's fan */
};

/* The fan of frame f: a centre and n outer vertices on a circle, n changing with f; its colours
 * and texture coordinates follow the angle. */
static sgResult make_fan(sgDevice *dev, int f, sgGeom *out) {
    float pos[(MAX_TRIS + 2) * 4], col[(MAX_TRIS + 2) * 4], uv[(MAX_TRIS + 2) * 2];
    uint32_t idx[MAX_TRIS * 3];
    const int n = 6 + (f % PERIOD) * (MAX_TRIS - 6) / (PERIOD - 1);
    const float pi = 3.14159265f;
    for (int v = 0; v <= n + 1; v++) {
        float a = v == 0 ? 0.0f : 2.0f * pi * (float)(v - 1) / (float)n, r = v == 0 ? 0.0f : 1.0f;
        float *p = pos + v * 4, *c = col + v * 4;
        p[0] = r * cosf(a), p[1] = r * sinf(a), p[2] = 0.0f, p[3] = 1.0f;
        c[0] = 0.5f + 0.5f * cosf(a), c[1] = 0.5f + 0.5f * sinf(a), c[2] = 1.0f - r * 0.5f;
        c[3] = 1.0f;
        uv[v * 2] = 0.5f + 0.5f * p[0], uv[v * 2 + 1] = 0.5f + 0.5f * p[1];
    }
    for (int t = 0; t < n; t++) {
        idx[t * 3] = 0, idx[t * 3 + 1] = (uint32_t)t + 1, idx[t * 3 + 2] = (uint32_t)t + 2;
    }
    /* Copied: the arrays on this stack are gone when the function returns. */
    return sgCreateGeom(dev,
                        &(sgGeomDesc){.vertex_count = n + 2,
                                      .positions = pos,
                                      .colors = col,
                                      .texcoords = uv,
                                      .index_count = n * 3,
                                      .indices = idx,
                                      .storage = SG_STORAGE_COPY},
                        out);
}

/* A checkerboard of a size that changes with the frame. */
static sgResult make_texture(sgDevice *dev, int f, sgImage2D *out) {
    const int side = 2 + (f * 5) % PERIOD;
    uint8_t texels[(2 + PERIOD) * (2 + PERIOD) * 4];
    for (int y = 0; y < side; y++) {
        for (int x = 0; x < side; x++) {
            uint8_t *t = texels + (y * side + x) * 4;
            bool on = (x + y) % 2 == 0;
            t[0] = on ? 255 : (uint8_t)(f * 7);
            t[1] = on ? 255 : 40;
            t[2] = on ? (uint8_t)(f * 3) : 90;
            t[3] = 255;
        }
    }
    return sgCreateImage2D(
        dev,
        &(sgImage2DDesc){
            .width = side, .height = side, .format = SG_FORMAT_RGBA8_UNORM, .data = texels},
        out);
}

/* A pipeline whose state changes with the frame: culling, winding, filter, wrap and blending. */
static sgResult make_pipeline(sgDevice *dev, int f, sgPipelineStateObject *out) {
    const int k = f % PERIOD;
    sgPipelineDesc desc = {
        .shade = SG_SHADE_TEXTURE_MODULATE,
        .filter = k % 2 ? SG_FILTER_BILINEAR : SG_FILTER_NEAREST,
        .wrap = k % 3 ? SG_WRAP_REPEAT : SG_WRAP_CLAMP_TO_EDGE,
        .depth = {.compare = SG_COMPARE_LESS_EQUAL, .write = k % 4 != 0},
        .cull = k % 5 == 0 ? SG_CULL_BACK : SG_CULL_NONE,
        .blend = k % 6 == 0 ? SG_BLEND_ALPHA : SG_BLEND_OPAQUE,
    };
    return sgCreatePipelineStateObject(dev, &desc, out);
}

static void destroy_objects(sgDevice *dev, frame_objects *o) {
    if (o->geom.id) sgDestroyGeom(dev, o->geom);
    if (o->texture.id) sgDestroyImage2D(dev, o->texture);
    if (o->pso.id) sgDestroyPipelineStateObject(dev, o->pso);
    memset(o, 0, sizeof *o);
}

/* A world-view that turns about y by `turns` of a full turn and moves back by `back`, and an
 * OpenGL perspective projection of 60 degrees. */
static void matrices(float turns, float x, float back, float wv[16], float proj[16]) {
    const float a = turns * 2.0f * 3.14159265f, c = cosf(a), s = sinf(a);
    const float m[16] = {c, 0, s, x, 0, 1, 0, 0, -s, 0, c, -back, 0, 0, 0, 1};
    const float n = 0.1f, fa = 20.0f, t = 1.0f / tanf(3.14159265f / 6.0f);
    const float p[16] = {t, 0, 0,  0, 0, t, 0, 0, 0, 0, (fa + n) / (n - fa), 2 * fa * n / (n - fa),
                         0, 0, -1, 0};
    memcpy(wv, m, sizeof m);
    memcpy(proj, p, sizeof p);
}

/* Runs an sgapi call of frame f; on failure says which and why, and ends the animation. */
#define TRY(call, what)                                                                            \
    do {                                                                                           \
        sgResult r_ = (call);                                                                      \
        if (r_ != SG_OK) {                                                                         \
            fprintf(stderr, "animate_objects: frame %d: %s: %s: %s\n", f, what, sgResultName(r_),  \
                    sgGetLastError(dev));                                                          \
            goto done;                                                                             \
        }                                                                                          \
    } while (0)

/* Runs the animation; 0 when every frame's calls succeed and the memory stays flat. */
static int animate(sgDevice *dev, counter *mem, int frames, int size) {
    sgImage2D color = {0}, depth = {0};
    sgGeom quad = {0};
    sgPipelineStateObject quad_pso = {0};
    frame_objects live[LIFETIME];
    memset(live, 0, sizeof live);
    uint8_t *pixels = malloc((size_t)size * (size_t)size * 4);
    size_t *held = calloc((size_t)frames, sizeof *held);
    int status = 1, f = -1; /* f: the frame, -1 before the first */
    if (!pixels || !held) {
        fprintf(stderr, "animate_objects: out of memory\n");
        goto done;
    }
    /* What lives through the whole animation: the targets and a floor quad. */
    const float quad_pos[] = {-3, -1, -3, 1, 3, -1, -3, 1, 3, -1, 3, 1, -3, -1, 3, 1};
    const float quad_col[] = {0.3f, 0.3f, 0.3f, 1, 0.5f, 0.5f, 0.5f, 1,
                              0.7f, 0.7f, 0.7f, 1, 0.4f, 0.4f, 0.4f, 1};
    const uint32_t quad_idx[] = {0, 1, 2, 3};
    TRY(sgCreateImage2D(
            dev, &(sgImage2DDesc){.width = size, .height = size, .format = SG_FORMAT_RGBA8_UNORM},
            &color),
        "colour target");
    TRY(sgCreateImage2D(
            dev, &(sgImage2DDesc){.width = size, .height = size, .format = SG_FORMAT_D32_FLOAT},
            &depth),
        "depth target");
    TRY(sgCreateGeom(dev,
                     &(sgGeomDesc){.vertex_count = 4,
                                   .positions = quad_pos,
                                   .colors = quad_col,
                                   .index_count = 4,
                                   .indices = quad_idx,
                                   .primitive = SG_PRIMITIVE_QUADS},
                     &quad),
        "floor geom");
    TRY(sgCreatePipelineStateObject(
            dev, &(sgPipelineDesc){.depth = {.compare = SG_COMPARE_LESS, .write = true}},
            &quad_pso),
        "floor pipeline");
    const sgPassDesc pass = {
        .color = color,
        .depth = depth,
        .color_load = SG_LOAD_CLEAR,
        .clear_color = {0.1f, 0.1f, 0.15f, 1.0f},
        .depth_store = SG_STORE_DONT_CARE,
    };
    uint32_t checksum = 0;
    for (f = 0; f < frames; f++) {
        /* This frame's objects take the place of those made LIFETIME frames ago. */
        frame_objects *o = &live[f % LIFETIME];
        destroy_objects(dev, o);
        TRY(make_fan(dev, f, &o->geom), "sgCreateGeom");
        TRY(make_texture(dev, f, &o->texture), "sgCreateImage2D");
        TRY(make_pipeline(dev, f, &o->pso), "sgCreatePipelineStateObject");

        TRY(sgBeginRenderPass(dev, &pass), "sgBeginRenderPass");
        sgDrawParams floor = {0};
        matrices(0.0f, 0.0f, 6.0f, floor.world_view, floor.proj);
        TRY(sgDraw(dev, quad_pso, quad, &floor), "sgDraw");
        /* Every live fan, each turned by its own age. */
        for (int k = 0; k < LIFETIME; k++) {
            if (!live[k].geom.id) continue;
            const sgColor tint = {1.0f, 1.0f, 1.0f, 0.75f};
            sgDrawParams p = {.texture = live[k].texture, .color = &tint};
            matrices((float)f / 100.0f + (float)k / LIFETIME, (float)(k - 1) * 1.5f, 5.0f,
                     p.world_view, p.proj);
            TRY(sgDraw(dev, live[k].pso, live[k].geom, &p), "sgDraw");
        }
        TRY(sgEndRenderPass(dev, &pass), "sgEndRenderPass");
        TRY(sgReadImage2D(dev, color, pixels, 0), "sgReadImage2D");
        checksum = 2166136261u; /* FNV-1a of the last frame, to show the images are the same */
        for (size_t i = 0; i < (size_t)size * (size_t)size * 4; i++)
            checksum = (checksum ^ pixels[i]) * 16777619u;
        held[f] = atomic_load(&mem->bytes);
    }

    /* The warm-up: LIFETIME frames fill the set of live objects and one period lets the
     * device's working memory reach what the largest frame needs. From then on a frame may hold
     * no more than the frame one period before it, which held the same sizes. */
    const int warm_up = LIFETIME + PERIOD;
    size_t lo = SIZE_MAX, hi = 0;
    status = 0;
    for (f = warm_up; f < frames; f++) {
        if (held[f] < lo) lo = held[f];
        if (held[f] > hi) hi = held[f];
        if (f >= warm_up + PERIOD && held[f] > held[f - PERIOD] && status == 0) {
            fprintf(stderr,
                    "animate_objects: frame %d holds %zu bytes, frame %d held %zu: the device's "
                    "memory grows\n",
                    f, held[f], f - PERIOD, held[f - PERIOD]);
            status = 1;
        }
    }
    printf("%d frames of %dx%d, checksum of the last %08x\n", frames, size, size,
           (unsigned)checksum);
    if (frames > warm_up)
        printf("bytes the device holds at the end of a frame, after %d frames of warm-up: %zu to "
               "%zu\n",
               warm_up, lo, hi);
done:
    for (int k = 0; k < LIFETIME; k++) destroy_objects(dev, &live[k]);
    if (quad_pso.id) sgDestroyPipelineStateObject(dev, quad_pso);
    if (quad.id) sgDestroyGeom(dev, quad);
    if (depth.id) sgDestroyImage2D(dev, depth);
    if (color.id) sgDestroyImage2D(dev, color);
    free(pixels);
    free(held);
    return status;
}

int main(int argc, char **argv) {
    int frames = argc > 1 ? atoi(argv[1]) : 2000, size = argc > 2 ? atoi(argv[2]) : 128;
    if (argc > 3 || frames < 1 || size < 1 || size > SG_MAX_IMAGE_SIZE) {
        fprintf(stderr, "usage: animate_objects [FRAMES [SIZE]]  (FRAMES >= 1, SIZE 1..%d)\n",
                SG_MAX_IMAGE_SIZE);
        return 2;
    }
    counter mem = {0};
    sgDevice *dev;
    sgDeviceDesc desc = {
        .allocator = {.alloc = count_alloc, .free = count_free, .user_data = &mem}};
    sgResult r = sgCreateDevice(&desc, &dev);
    if (r != SG_OK) {
        fprintf(stderr, "animate_objects: sgCreateDevice: %s\n", sgResultName(r));
        return 1;
    }
    int status = animate(dev, &mem, frames, size);
    sgDestroyDevice(dev);
    size_t bytes = atomic_load(&mem.bytes), blocks = atomic_load(&mem.blocks);
    printf("allocations: %zu, still held after sgDestroyDevice: %zu bytes in %zu blocks\n",
           atomic_load(&mem.total), bytes, blocks);
    if (bytes != 0 || blocks != 0) {
        fprintf(stderr, "animate_objects: sgDestroyDevice left memory allocated\n");
        status = 1;
    }
    return status;
}
