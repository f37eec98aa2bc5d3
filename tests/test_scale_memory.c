/* test_scale_memory.c - peak memory of a 10 M-triangle frame.
 *
 * Five UV spheres of 1024 x 1024 segments and rings (2 M triangles each), Gouraud-lit, back faces
 * culled, side by side in one 1024 x 1024 pass, rendered four times at 2 threads: the first frame
 * bins 32 MiB before it flushes, the next ones up to the limit. The
 * process's peak resident set (getrusage) must stay within the geometry's own size (the geoms'
 * copies of their arrays; the program's are freed once copied) + the device's bin_memory_limit +
 * 64 MiB (targets, vertex arenas, code). Before the limit, the parallel front end's reservations
 * grew with the draws.
 *   test_scale_memory [BIN_MEMORY_LIMIT]   (0 or none: the default limit)
 * Prints the figures; exit 1 past the bound. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

#include <sgapi/sgapi.h>
#include <sgapi/sgapi_util.h>

#define SIZE    1024
#define SPHERES 5

static int fail(sgDevice *dev, sgResult r, const char *what) {
    fprintf(stderr, "%s: %s: %s\n", what, sgResultName(r), dev ? sgGetLastError(dev) : "");
    return 1;
}

/* Under AddressSanitizer the resident set holds its shadow memory and the quarantine of freed
 * blocks, which say nothing of sgapi's own. */
#if defined(__SANITIZE_ADDRESS__)
#define UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define UNDER_ASAN 1
#endif
#endif
#ifndef UNDER_ASAN
#define UNDER_ASAN 0
#endif

int main(int argc, char **argv) {
    size_t limit = argc > 1 ? (size_t)strtoull(argv[1], NULL, 10) : 0;
    sgDeviceDesc dd = {.thread_count = 2, .bin_memory_limit = limit};
    sgDevice *dev = NULL;
    sgResult r = sgCreateDevice(&dd, &dev);
    if (r != SG_OK) return fail(NULL, r, "sgCreateDevice");
    const size_t budget = limit ? limit : SG_DEFAULT_BIN_MEMORY_LIMIT;

    sguShapeDesc sd = {
        .shape = SGU_SHAPE_UV_SPHERE, .segments = 1024, .rings = 1024, .radius = 0.3f};
    int nv = 0, ni = 0;
    if (sgu_shape_counts(&sd, &nv, &ni) != 0) return fail(dev, SG_OK, "sgu_shape_counts");
    size_t geometry = 0;
    sgGeom geoms[SPHERES] = {{0}};
    for (int i = 0; i < SPHERES; i++) {
        float *pos = malloc((size_t)nv * 4 * sizeof *pos);
        float *nrm = malloc((size_t)nv * 3 * sizeof *nrm);
        float *st = malloc((size_t)nv * 2 * sizeof *st);
        uint32_t *idx = malloc((size_t)ni * sizeof *idx);
        if (!pos || !nrm || !st || !idx || sgu_shape_build(&sd, pos, nrm, st, idx) != 0)
            return fail(dev, SG_OK, "building a sphere");
        sgGeomDesc gd = {.vertex_count = nv,
                         .positions = pos,
                         .normals = nrm,
                         .index_count = ni,
                         .indices = idx,
                         .primitive = SG_PRIMITIVE_TRIANGLES,
                         .storage = SG_STORAGE_COPY};
        r = sgCreateGeom(dev, &gd, &geoms[i]);
        free(pos);
        free(nrm);
        free(st);
        free(idx);
        if (r != SG_OK) return fail(dev, r, "sgCreateGeom");
        geometry += (size_t)nv * 7 * sizeof(float) + (size_t)ni * sizeof(uint32_t);
    }

    sgImage2D color = {0}, depth = {0};
    sgImage2DDesc id = {.width = SIZE, .height = SIZE, .format = SG_FORMAT_RGBA8_UNORM};
    if ((r = sgCreateImage2D(dev, &id, &color)) != SG_OK) return fail(dev, r, "color target");
    id.format = SG_FORMAT_D32_FLOAT;
    if ((r = sgCreateImage2D(dev, &id, &depth)) != SG_OK) return fail(dev, r, "depth target");
    sgPipelineDesc pd = {.depth = {.compare = SG_COMPARE_LESS, .write = true},
                         .cull = SG_CULL_BACK,
                         .lighting = SG_LIGHTING_GOURAUD};
    sgPipelineStateObject pso = {0};
    if ((r = sgCreatePipelineStateObject(dev, &pd, &pso)) != SG_OK) return fail(dev, r, "pso");
    sgLighting lights = {.ambient = {0.2f, 0.2f, 0.2f}, .light_count = 1};
    lights.lights[0] = (sgLight){.type = SG_LIGHT_DIRECTIONAL,
                                 .direction = {-0.4f, -0.6f, -1},
                                 .color = {0.85f, 0.85f, 0.85f}};
    sgPassDesc pass = {.color = color,
                       .depth = depth,
                       .clear_color = {0.1f, 0.12f, 0.16f, 1},
                       .depth_store = SG_STORE_DONT_CARE};
    for (int frame = 0; frame < 4; frame++) {
        if ((r = sgBeginRenderPass(dev, &pass)) != SG_OK) return fail(dev, r, "begin");
        for (int i = 0; i < SPHERES; i++) {
            sgDrawParams dp = {.lighting = &lights};
            const float f = 1.8f;
            const float proj[16] = {f, 0, 0,          0,          0, f, 0,  0,
                                    0, 0, -1.020202f, -1.010101f, 0, 0, -1, 0};
            const float wv[16] = {1, 0, 0, -1.2f + 0.6f * (float)i, 0, 1, 0, 0, 0, 0, 1, -3, 0,
                                  0, 0, 1};
            memcpy(dp.proj, proj, sizeof proj);
            memcpy(dp.world_view, wv, sizeof wv);
            if ((r = sgDraw(dev, pso, geoms[i], &dp)) != SG_OK) return fail(dev, r, "sgDraw");
        }
        if ((r = sgEndRenderPass(dev, &pass)) != SG_OK) return fail(dev, r, "end");
    }
    /* The spheres must be there: the centre pixel is not the clear colour. */
    uint8_t *pixels = malloc((size_t)SIZE * SIZE * 4);
    if (!pixels || (r = sgReadImage2D(dev, color, pixels, 0)) != SG_OK)
        return fail(dev, r, "sgReadImage2D");
    const uint8_t *c = pixels + ((size_t)SIZE / 2 * SIZE + SIZE / 2) * 4;
    int drawn = !(c[0] == 26 && c[1] == 31 && c[2] == 41);
    free(pixels);
    sgDestroyDevice(dev);

    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    size_t peak = (size_t)ru.ru_maxrss * 1024; /* kilobytes on Linux */
    size_t bound = geometry + budget + ((size_t)64 << 20);
    printf("%d triangles; peak resident %.1f MiB; bound %.1f MiB = geometry %.1f + "
           "bin_memory_limit %.1f + 64\n",
           SPHERES * ni / 3, (double)peak / 1048576, (double)bound / 1048576,
           (double)geometry / 1048576, (double)budget / 1048576);
    if (!drawn) {
        fprintf(stderr, "the spheres were not drawn\n");
        return 1;
    }
    if (UNDER_ASAN) { /* the rendering is checked; the figure is AddressSanitizer's */
        printf("bound not checked: AddressSanitizer's shadow memory and quarantine are resident "
               "too (the plain build checks it)\n");
        return 0;
    }
    if (peak > bound) {
        fprintf(stderr, "peak resident set past the bound\n");
        return 1;
    }
    return 0;
}
