/* test_loader_alloc.c - every allocation of the apps' loaders (scene file, OBJ, images), made to
 * fail one at a time: the load must fail with a message naming the file, never crash, and leave
 * nothing allocated (the sanitizer build's leak checker sees that).
 *
 * malloc, calloc and realloc are wrapped at link time (-Wl,--wrap=...), which reaches every call
 * of the loaders' static library, of sgapi_util, and of the image decoder, compiled in here for
 * that reason; cJSON, a shared library, is routed through the wrapper with cJSON_InitHooks.
 *
 * A probe the decoder can do without may fail and the load still succeed, with the same result.
 *
 * Usage: test_loader_alloc SOURCE_DIR WORK_DIR. Prints the allocation points of each load. */
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cJSON.h>
#include <stb_image_write.h>

#include "image_io.h"
#include "obj.h"
#include "scene.h"
#include "test_msg.h"

void *__real_malloc(size_t size);
void *__real_calloc(size_t n, size_t size);
void *__real_realloc(void *p, size_t size);
void *__wrap_malloc(size_t size);
void *__wrap_calloc(size_t n, size_t size);
void *__wrap_realloc(void *p, size_t size);

/* The count has to be global: malloc takes no context. Only this test has it. */
static long alloc_count, fail_at;
static size_t largest; /* the largest request seen */

/* Requests over this are refused and remembered: no file here needs them. */
#define HUGE_REQUEST ((size_t)1 << 28)

static bool fail_now(size_t size) {
    if (size > largest) largest = size;
    return ++alloc_count == fail_at || size > HUGE_REQUEST;
}

void *__wrap_malloc(size_t size) {
    return fail_now(size) ? NULL : __real_malloc(size);
}

void *__wrap_calloc(size_t n, size_t size) {
    return fail_now(n && size > SIZE_MAX / n ? SIZE_MAX : n * size) ? NULL : __real_calloc(n, size);
}

void *__wrap_realloc(void *p, size_t size) {
    return fail_now(size) ? NULL : __real_realloc(p, size);
}

static void write_text(const char *path, const char *text) {
    FILE *f = fopen(path, "wb");
    if (!f || fputs(text, f) == EOF || fclose(f) != 0) {
        fprintf(stderr, "cannot write %s\n", path);
        exit(1);
    }
}

/* A load, and a digest of what it loaded. */
typedef bool (*loader)(const char *path, sc_msg *err, uint64_t *digest);

static uint64_t fnv(uint64_t h, const void *p, size_t n) {
    const unsigned char *b = p;
    for (size_t i = 0; b && i < n; i++) h = (h ^ b[i]) * 1099511628211u;
    return h;
}

static uint64_t mesh_digest(uint64_t h, const sc_mesh *m) {
    h = fnv(h, m->positions, (size_t)m->vertex_count * 4 * sizeof(float));
    h = fnv(h, m->normals, m->normals ? (size_t)m->vertex_count * 3 * sizeof(float) : 0);
    h = fnv(h, m->texcoords, m->texcoords ? (size_t)m->vertex_count * 2 * sizeof(float) : 0);
    h = fnv(h, m->indices, (size_t)m->index_count * sizeof(uint32_t));
    return fnv(h, m->line_indices, (size_t)m->line_index_count * sizeof(uint32_t));
}

static uint64_t image_digest(uint64_t h, const sc_image *im) {
    h = fnv(h, &im->width, sizeof im->width);
    return fnv(h, im->pixels, (size_t)im->width * (size_t)im->height * 4);
}

static bool load_scene(const char *path, sc_msg *err, uint64_t *digest) {
    sc_file f;
    bool ok = sc_load(path, &f, err);
    uint64_t h = 1469598103934665603u;
    for (size_t i = 0; ok && i < f.mesh_count; i++) h = mesh_digest(h, &f.meshes[i]);
    for (size_t i = 0; ok && i < f.texture_count; i++) h = image_digest(h, &f.textures[i]);
    for (size_t i = 0; ok && i < f.scene_count; i++)
        h = fnv(h, f.scenes[i].draws, f.scenes[i].draw_count * sizeof *f.scenes[i].draws);
    h ^= ok ? f.warning_count : 0;
    *digest = h;
    sc_free(&f);
    return ok;
}

static bool load_obj(const char *path, sc_msg *err, uint64_t *digest) {
    sc_mesh m;
    bool ok = sc_obj_load(path, &m, err);
    if (ok) {
        *digest = mesh_digest(1469598103934665603u, &m);
        sc_mesh_free(&m);
    }
    return ok;
}

static bool load_image(const char *path, sc_msg *err, uint64_t *digest) {
    sc_image im;
    bool ok = sc_image_load(path, &im, err);
    if (ok) {
        *digest = image_digest(1469598103934665603u, &im);
        sc_image_free(&im);
    }
    return ok;
}

/* Runs load once unfailed, then once per allocation point with that allocation failing; returns
 * the number of broken promises. */
static int check(const char *what, loader load, const char *path) {
    TEST_MSG(err);
    alloc_count = 0;
    fail_at = 0;
    uint64_t want = 0, got = 0;
    if (!load(path, &err, &want)) {
        fprintf(stderr, "%s: the unfailed load failed: %s\n", what, MSG(err));
        return 1;
    }
    long total = alloc_count;
    int bad = 0;
    for (long n = 1; n <= total; n++) {
        alloc_count = 0;
        fail_at = n;
        sc_msg_free(&err);
        bool ok = load(path, &err, &got);
        if (alloc_count < n) continue; /* the run took another path and never got there */
        /* Success is right only when the allocation was a probe the decoder could do without
         * (it tries each image format in turn): the result must be the unfailed one. */
        if (ok) {
            if (got != want) {
                fprintf(stderr, "%s: allocation %ld failed and the load gave another result\n",
                        what, n);
                bad++;
            }
        } else if (!strstr(MSG(err), path) &&
                   !(alloc_count == n && !strcmp(MSG(err), SC_MSG_OUT_OF_MEMORY))) {
            /* The one message that cannot name the file: the failed allocation was the message's
             * own, the run's last. */
            fprintf(stderr, "%s: allocation %ld: the message does not name %s: \"%s\"\n", what, n,
                    path, MSG(err));
            bad++;
        }
    }
    fail_at = 0;
    printf("%s: %ld allocation points, %s\n", what, total, bad ? "FAILED" : "each a clean error");
    return bad;
}

/* A file the loader must refuse by its header alone (a GIF of 16163 x 17746 pixels in 44 bytes):
 * whichever allocation fails, the load fails without asking for the gigabytes decoding would
 * take. Before the header was required, a failure of the header's probe let decoding go ahead. */
static int check_refused(const char *what, const char *path) {
    TEST_MSG(err);
    uint64_t digest;
    int bad = 0;
    long total = 0;
    for (long n = 0; n == 0 || n <= total; n++) {
        alloc_count = 0;
        largest = 0;
        fail_at = n;
        bool ok = load_image(path, &err, &digest);
        if (n == 0) total = alloc_count;
        if (ok || largest > HUGE_REQUEST) {
            fprintf(stderr, "%s: allocation %ld failed: %s, largest request %zu bytes\n", what, n,
                    ok ? "loaded" : "refused", largest);
            bad++;
        }
    }
    fail_at = 0;
    printf("%s: %ld allocation points, %s\n", what, total,
           bad ? "FAILED" : "each refused without a huge request");
    return bad;
}

int main(int argc, char **argv) {
    if (argc != 3) {
        fprintf(stderr, "usage: test_loader_alloc SOURCE_DIR WORK_DIR\n");
        return 2;
    }
    cJSON_Hooks hooks = {__wrap_malloc, free};
    cJSON_InitHooks(&hooks);
    const char *src = argv[1], *work = argv[2];
    char obj[4096], scene[4096], png[4096], bmp[4096], jpg[4096];
    snprintf(obj, sizeof obj, "%s/mesh.obj", work);
    snprintf(scene, sizeof scene, "%s/scene.json", work);
    snprintf(png, sizeof png, "%s/scenes/assets/checker.png", src);
    snprintf(bmp, sizeof bmp, "%s/tex.bmp", work);
    snprintf(jpg, sizeof jpg, "%s/tex.jpg", work);
    /* A JPEG: the decoder probes for it first, with an allocation of its own. */
    unsigned char rgb[8 * 8 * 3];
    for (int i = 0; i < 8 * 8 * 3; i++) rgb[i] = (unsigned char)(i * 7);
    if (!stbi_write_jpg(jpg, 8, 8, 3, rgb, 90)) return 1;
    /* Faces with texcoords and normals, a quad to split, a polyline, and a vertex colour. */
    write_text(obj, "v 0 0 0 1 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 2 2\n"
                    "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\n"
                    "f 1/1/1 2/2/1 3/3/1 4/4/1\nf 1/1/1 3/3/1 5/1/1\nl 1 5 2\n");
    /* A 2 x 2 BMP, decoded by the same loader. */
    static const unsigned char bmp_bytes[] = {
        66, 77, 70, 0, 0,  0, 0, 0, 0,   0, 54,  0, 0, 0, 40,  0, 0, 0,   2,   0,   0, 0, 2, 0,
        0,  0,  1,  0, 24, 0, 0, 0, 0,   0, 16,  0, 0, 0, 0,   0, 0, 0,   0,   0,   0, 0, 0, 0,
        0,  0,  0,  0, 0,  0, 0, 0, 255, 0, 255, 0, 0, 0, 255, 0, 0, 255, 255, 255, 0, 0};
    FILE *f = fopen(bmp, "wb");
    if (!f || fwrite(bmp_bytes, 1, sizeof bmp_bytes, f) != sizeof bmp_bytes || fclose(f) != 0)
        return 1;
    char json[8192];
    snprintf(json, sizeof json,
             "{\"width\": 16, \"height\": 16, \"note\": 1,\n"
             " \"lights\": [{\"type\": \"directional\", \"direction\": [0, 0, -1],"
             " \"color\": [1, 1, 1]}],\n"
             " \"scenes\": [\n"
             "  {\"name\": \"a\", \"shadow\": {\"light\": 0, \"size\": 64}, \"draws\": [\n"
             "   {\"mesh\": \"mesh.obj\", \"texture\": \"%s\","
             " \"lightnig\": 1, \"worldView\": [1,0,0,0, 0,1,0,0, 0,0,1,-3, 0,0,0,1],"
             " \"proj\": [1,0,0,0, 0,1,0,0, 0,0,-1,-0.2, 0,0,-1,0]},\n"
             "   {\"mesh\": {\"heightmap\": \"tex.bmp\", \"height_scale\": 0.5},"
             " \"lighting\": \"phong\", \"specular\": [1, 1, 1], \"shininess\": 8,"
             " \"worldView\": [1,0,0,0, 0,1,0,0, 0,0,1,-4, 0,0,0,1],"
             " \"proj\": [1,0,0,0, 0,1,0,0, 0,0,-1,-0.2, 0,0,-1,0]}]},\n"
             "  {\"name\": \"b\", \"draws\": [{\"mesh\": \"mesh.obj\", \"texture\": \"tex.bmp\","
             " \"worldView\": [1,0,0,0, 0,1,0,0, 0,0,1,-3, 0,0,0,1],"
             " \"proj\": [1,0,0,0, 0,1,0,0, 0,0,-1,-0.2, 0,0,-1,0]}]}]}\n",
             png);
    write_text(scene, json);
    int bad = check("OBJ", load_obj, obj) + check("PNG", load_image, png) +
              check("BMP", load_image, bmp) + check("JPEG", load_image, jpg) +
              check("scene", load_scene, scene);
    char gif[4096];
    snprintf(gif, sizeof gif, "%s/tests/fuzz/regressions/image/gif-huge-declared-size", src);
    bad += check_refused("huge GIF", gif);
    return bad ? 1 : 0;
}
