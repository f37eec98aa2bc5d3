/* postprocess.c - two passes with programmable stages: a scene drawn into an image by a shader
 * pipeline, then that image post-processed by a second pipeline whose fragment stage samples it
 * as texture 0 on a full-screen quad (a 3 x 3 box blur and a vignette).
 *
 *   postprocess [OUT.ppm]      writes the post-processed image (a binary PPM), exit 0
 *   postprocess --check        computes the same filter directly in C from the first image,
 *                              read back, and exits 0 when every channel of every pixel is
 *                              within 1 of the second pass's (1 otherwise, naming the worst)
 *
 * It uses the public API alone: copy it, and build it against the installed library
 * (find_package(sgapi) and sgapi::sgapi_static, or pkg-config --cflags --libs sgapi).
 */
#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <sgapi/sgapi.h>

enum { W = 256, H = 192 };

/* ---- the scene's shader: vertex colour times a procedural checker ------------------------------
 * Varyings: 0..2 colour, 3..4 the object-space x, y (the checker's coordinates). */

static void scene_vertex(sgVertexBatch *b, const void *uniforms) {
    (void)uniforms;
    const float *m = b->world_view, *p = b->proj;
    for (int i = 0; i < SG_SHADER_LANES; i++) {
        float x = b->position[0][i], y = b->position[1][i], z = b->position[2][i],
              w = b->position[3][i];
        float v[4];
        for (int r = 0; r < 4; r++)
            v[r] = ((m[4 * r] * x + m[4 * r + 1] * y) + m[4 * r + 2] * z) + m[4 * r + 3] * w;
        for (int r = 0; r < 4; r++)
            b->clip[r][i] = ((p[4 * r] * v[0] + p[4 * r + 1] * v[1]) + p[4 * r + 2] * v[2]) +
                            p[4 * r + 3] * v[3];
        for (int k = 0; k < 3; k++) b->varying[k][i] = b->color[k][i];
        b->varying[3][i] = x;
        b->varying[4][i] = y;
    }
}

static void scene_fragment(sgFragmentBatch *b, const void *uniforms) {
    const float cells = *(const float *)uniforms; /* checker cells per object-space unit */
    for (int i = 0; i < SG_SHADER_LANES; i++) {
        float cx = floorf(b->varying[3][i] * cells), cy = floorf(b->varying[4][i] * cells);
        float odd = fabsf(fmodf(cx + cy, 2.0f));
        float k = odd > 0.5f ? 1.0f : 0.35f;
        for (int c = 0; c < 3; c++) b->color[c][i] = b->varying[c][i] * k;
        b->color[3][i] = 1.0f;
    }
}

/* ---- the post-process: blur and vignette --------------------------------------------------------
 * The vertex stage passes the full-screen quad through; the fragment stage reads the first image
 * (texture 0, nearest, clamped to the edge) at the centres of the 3 x 3 texels around its pixel,
 * averages them and darkens towards the corners: factor 1 - strength r^2, r the distance from
 * the centre in half-diagonals. */

typedef struct post_uniforms {
    float width, height; /* of the image read */
    float strength;      /* of the vignette, 0..1 */
} post_uniforms;

static void post_vertex(sgVertexBatch *b, const void *uniforms) {
    (void)uniforms;
    for (int k = 0; k < 4; k++)
        for (int i = 0; i < SG_SHADER_LANES; i++) b->clip[k][i] = b->position[k][i];
}

/* The vignette's factor at pixel (x, y) (rows from the top): shared with the direct filter. */
static float vignette(const post_uniforms *u, int x, int y) {
    float dx = ((float)x + 0.5f) / u->width - 0.5f, dy = ((float)y + 0.5f) / u->height - 0.5f;
    float r2 = (dx * dx + dy * dy) * 2.0f; /* 1 at the corners */
    return 1.0f - u->strength * r2;
}

static void post_fragment(sgFragmentBatch *b, const void *uniforms) {
    const post_uniforms *u = uniforms;
    float sum[4][SG_SHADER_LANES] = {{0}};
    for (int dy = -1; dy <= 1; dy++)
        for (int dx = -1; dx <= 1; dx++) {
            float s[SG_SHADER_LANES], t[SG_SHADER_LANES], texel[4][SG_SHADER_LANES];
            for (int i = 0; i < SG_SHADER_LANES; i++) {
                /* texel centres; t = 0 is the bottom row, pixel rows count from the top */
                s[i] = ((float)(b->x + i % 4 + dx) + 0.5f) / u->width;
                t[i] = 1.0f - ((float)(b->y + i / 4 + dy) + 0.5f) / u->height;
            }
            sgSample(b, 0, s, t, texel);
            for (int k = 0; k < 3; k++)
                for (int i = 0; i < SG_SHADER_LANES; i++) sum[k][i] += texel[k][i];
        }
    for (int i = 0; i < SG_SHADER_LANES; i++) {
        float f = vignette(u, b->x + i % 4, b->y + i / 4) / 9.0f;
        for (int k = 0; k < 3; k++) b->color[k][i] = sum[k][i] * f;
        b->color[3][i] = 1.0f;
    }
}

/* The same filter, directly on the first image's bytes (rows from the top). */
static void filter_direct(const post_uniforms *u, const uint8_t *in, uint8_t *out) {
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            float sum[3] = {0, 0, 0};
            for (int dy = -1; dy <= 1; dy++)
                for (int dx = -1; dx <= 1; dx++) {
                    int sx = x + dx < 0 ? 0 : x + dx >= W ? W - 1 : x + dx;
                    int sy = y + dy < 0 ? 0 : y + dy >= H ? H - 1 : y + dy;
                    for (int k = 0; k < 3; k++) sum[k] += in[4 * (sy * W + sx) + k] / 255.0f;
                }
            float f = vignette(u, x, y) / 9.0f;
            for (int k = 0; k < 3; k++) {
                float c = sum[k] * f;
                c = c < 0.0f ? 0.0f : c > 1.0f ? 1.0f : c;
                out[4 * (y * W + x) + k] = (uint8_t)lrintf(c * 255.0f);
            }
            out[4 * (y * W + x) + 3] = 255;
        }
}

#define CHECK(call)                                                                                \
    do {                                                                                           \
        sgResult r_ = (call);                                                                      \
        if (r_ != SG_OK) {                                                                         \
            fprintf(stderr, "postprocess: %s: %s (%s)\n", #call, sgResultName(r_),                 \
                    sgGetLastError(dev));                                                          \
            goto done;                                                                             \
        }                                                                                          \
    } while (0)

int main(int argc, char **argv) {
    const bool check = argc > 1 && strcmp(argv[1], "--check") == 0;
    const char *out_path = !check && argc > 1 ? argv[1] : "postprocess.ppm";
    int status = 1;
    sgDevice *dev = NULL;
    uint8_t *first = malloc(4 * W * H), *second = malloc(4 * W * H), *direct = malloc(4 * W * H);
    if (!first || !second || !direct) goto done;
    CHECK(sgCreateDevice(&(sgDeviceDesc){0}, &dev));

    /* The scene: two vertex-coloured quads, one turned, under a perspective. */
    static const float pos[] = {-1, -1, 0, 1, 1, -1, 0, 1, 1, 1, 0, 1, -1, 1, 0, 1};
    static const float col[] = {1,    0.2f, 0.2f, 1, 1,    1,    0.2f, 1,
                                0.2f, 0.6f, 1,    1, 0.8f, 0.3f, 1,    1};
    static const uint32_t quad_idx[] = {0, 1, 2, 0, 2, 3};
    sgGeom quad, screen;
    CHECK(sgCreateGeom(dev,
                       &(sgGeomDesc){.vertex_count = 4,
                                     .positions = pos,
                                     .colors = col,
                                     .index_count = 6,
                                     .indices = quad_idx},
                       &quad));
    CHECK(sgCreateGeom(
        dev,
        &(sgGeomDesc){.vertex_count = 4, .positions = pos, .index_count = 6, .indices = quad_idx},
        &screen));
    sgImage2D image, result, depth;
    CHECK(sgCreateImage2D(
        dev, &(sgImage2DDesc){.width = W, .height = H, .format = SG_FORMAT_RGBA8_UNORM}, &image));
    CHECK(sgCreateImage2D(
        dev, &(sgImage2DDesc){.width = W, .height = H, .format = SG_FORMAT_RGBA8_UNORM}, &result));
    CHECK(sgCreateImage2D(
        dev, &(sgImage2DDesc){.width = W, .height = H, .format = SG_FORMAT_D32_FLOAT}, &depth));

    sgPipelineStateObject scene_pso, post_pso;
    CHECK(sgCreatePipelineStateObject(
        dev,
        &(sgPipelineDesc){
            .depth = {.compare = SG_COMPARE_LESS, .write = true},
            .shader = {.vertex = scene_vertex, .fragment = scene_fragment, .varying_count = 5}},
        &scene_pso));
    CHECK(sgCreatePipelineStateObject(
        dev,
        &(sgPipelineDesc){
            .filter = SG_FILTER_NEAREST,
            .wrap = SG_WRAP_CLAMP_TO_EDGE,
            .shader = {.vertex = post_vertex, .fragment = post_fragment, .texture_count = 1}},
        &post_pso));

    /* Pass 1. */
    const float aspect = (float)W / (float)H, f = 1.0f / tanf(0.5f * 0.8f);
    sgDrawParams draw = {
        .proj = {f / aspect, 0, 0, 0, 0, f, 0, 0, 0, 0, -1.002f, -0.2002f, 0, 0, -1, 0}};
    const float cells = 4.0f;
    draw.uniforms = &cells;
    draw.uniform_size = sizeof cells;
    sgPassDesc pass1 = {.color = image,
                        .depth = depth,
                        .color_load = SG_LOAD_CLEAR,
                        .depth_load = SG_LOAD_CLEAR,
                        .clear_color = {0.1f, 0.1f, 0.15f, 1},
                        .clear_depth = 1.0f};
    CHECK(sgBeginRenderPass(dev, &pass1));
    const float wv1[16] = {1.2f, 0, 0, -0.7f, 0, 1.2f, 0, 0.1f, 0, 0, 1, -3.5f, 0, 0, 0, 1};
    const float wv2[16] = {0.8f, 0, 0.6f, 0.8f, 0, 1, 0, -0.2f, -0.6f, 0, 0.8f, -3, 0, 0, 0, 1};
    memcpy(draw.world_view, wv1, sizeof wv1);
    CHECK(sgDraw(dev, scene_pso, quad, &draw));
    memcpy(draw.world_view, wv2, sizeof wv2);
    CHECK(sgDraw(dev, scene_pso, quad, &draw));
    CHECK(sgEndRenderPass(dev, &pass1));

    /* Pass 2: the first image as texture 0 on a full-screen quad. */
    const post_uniforms pu = {(float)W, (float)H, 0.6f};
    sgDrawParams post = {.world_view = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1},
                         .proj = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1},
                         .uniforms = &pu,
                         .uniform_size = sizeof pu,
                         .textures = {image}};
    sgPassDesc pass2 = {.color = result, .color_load = SG_LOAD_CLEAR};
    CHECK(sgBeginRenderPass(dev, &pass2));
    CHECK(sgDraw(dev, post_pso, screen, &post));
    CHECK(sgEndRenderPass(dev, &pass2));

    CHECK(sgReadImage2D(dev, image, first, 0));
    CHECK(sgReadImage2D(dev, result, second, 0));
    if (check) {
        filter_direct(&pu, first, direct);
        int worst = 0, wx = 0, wy = 0;
        for (int i = 0; i < W * H; i++)
            for (int k = 0; k < 4; k++) {
                int d = abs((int)second[4 * i + k] - (int)direct[4 * i + k]);
                if (d > worst) worst = d, wx = i % W, wy = i / W;
            }
        printf("postprocess: largest difference from the direct filter: %d at (%d, %d)\n", worst,
               wx, wy);
        status = worst <= 1 ? 0 : 1;
    } else {
        FILE *fp = fopen(out_path, "wb");
        if (!fp) {
            fprintf(stderr, "postprocess: cannot write %s\n", out_path);
            goto done;
        }
        fprintf(fp, "P6\n%d %d\n255\n", W, H);
        for (int i = 0; i < W * H; i++) fwrite(second + 4 * i, 1, 3, fp);
        status = fclose(fp) == 0 ? 0 : 1;
    }
done:
    sgDestroyDevice(dev);
    free(first);
    free(second);
    free(direct);
    return status;
}
