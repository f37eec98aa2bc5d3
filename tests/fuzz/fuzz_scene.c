/* fuzz_scene.c - libFuzzer target: scene JSON through sc_parse, and the file it promises. */
#define _POSIX_C_SOURCE 200809L /* mkdtemp, rmdir */

#include "fuzz.h"
#include "../test_msg.h"

#include <stdbool.h>
#include <string.h>
#include <unistd.h>

#include "scene.h"

/* The scene's relative paths resolve in a scratch folder (made at the first call, removed at exit)
 * that holds a valid mesh and texture, so inputs reach loading and not only JSON errors. */
static char scratch[4096];
static char scene_path[4096 + 16];
static const char *const scratch_files[] = {"tri.obj", "tex.png"};

static bool scratch_file(const char *name, char *out, size_t outlen) {
    int n = snprintf(out, outlen, "%s/%s", scratch, name);
    return n > 0 && (size_t)n < outlen;
}

static void remove_scratch(void) {
    char path[sizeof scratch + 16];
    for (size_t i = 0; i < sizeof scratch_files / sizeof scratch_files[0]; i++)
        if (scratch_file(scratch_files[i], path, sizeof path)) remove(path);
    rmdir(scratch);
}

/* Named by the fuzz dictionary and the scene seeds: a textured, coloured triangle with a normal. */
static const char tri_obj[] = "v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 1\n"
                              "vt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\nf 1/1/1 2/2/1 3/3/1\n";

static void make_scratch(void) {
    const char *tmp = getenv("TMPDIR");
    int n = snprintf(scratch, sizeof scratch, "%s/sgapi-fuzz-scene-XXXXXX",
                     tmp && tmp[0] ? tmp : "/tmp");
    if (n <= 0 || (size_t)n >= sizeof scratch || !mkdtemp(scratch)) {
        perror("fuzz_scene: cannot make the scratch folder");
        abort();
    }
    atexit(remove_scratch);
    char path[sizeof scratch + 16];
    TEST_MSG(err);
    FILE *f = scratch_file("tri.obj", path, sizeof path) ? fopen(path, "wb") : NULL;
    bool ok = f && fwrite(tri_obj, 1, sizeof tri_obj - 1, f) == sizeof tri_obj - 1;
    if (f && fclose(f) != 0) ok = false;
    /* 2x2, so it serves as a heightmap too. */
    static const unsigned char px[16] = {255, 0, 0,   255, 0,   255, 0,   255,
                                         0,   0, 255, 255, 255, 255, 255, 128};
    ok = ok && scratch_file("tex.png", path, sizeof path) &&
         sc_image_write_png(path, 2, 2, px, &err);
    n = snprintf(scene_path, sizeof scene_path, "%s/fuzz.json", scratch);
    if (!ok || n <= 0 || (size_t)n >= sizeof scene_path) {
        fprintf(stderr, "fuzz_scene: cannot fill the scratch folder %s\n", scratch);
        abort();
    }
}

static void check_mesh(const sc_mesh *m) {
    FUZZ_CHECK(m->index_count % 3 == 0 && m->line_index_count % 2 == 0 && m->vertex_count >= 1);
    FUZZ_CHECK(m->index_count + (uint64_t)m->line_index_count > 0);
    for (uint32_t i = 0; i < m->index_count; i++) FUZZ_CHECK(m->indices[i] < m->vertex_count);
    for (uint32_t i = 0; i < m->line_index_count; i++)
        FUZZ_CHECK(m->line_indices[i] < m->vertex_count);
    fuzz_touch(m->positions, (size_t)m->vertex_count * 4 * sizeof(float));
    fuzz_touch(m->colors, (size_t)m->vertex_count * 4 * sizeof(float));
}

int fuzz_scene(const uint8_t *data, size_t size) {
    if (!scene_path[0]) make_scratch();
    TEST_MSG(err);
    sc_file f;
    if (!sc_parse(scene_path, (const char *)data, size, &f, &err)) {
        /* A failure says why and leaves nothing to free. */
        FUZZ_CHECK(MSG(err)[0] != '\0');
        FUZZ_CHECK(!f.scenes && !f.meshes && !f.textures && !f.path);
        return 0;
    }
    /* What scene.h promises: everything a renderer maps without checks of its own. */
    FUZZ_CHECK(f.scene_count >= 1 && f.path && strcmp(f.path, scene_path) == 0);
    for (size_t i = 0; i < f.mesh_count; i++) {
        check_mesh(&f.meshes[i]);
        FUZZ_CHECK(f.mesh_sources[i] != NULL);
    }
    for (size_t i = 0; i < f.texture_count; i++) {
        const sc_image *t = &f.textures[i];
        FUZZ_CHECK(t->width >= 1 && t->width <= SC_MAX_IMAGE_SIZE);
        FUZZ_CHECK(t->height >= 1 && t->height <= SC_MAX_IMAGE_SIZE);
        fuzz_touch(t->pixels, (size_t)t->width * (size_t)t->height * 4);
        FUZZ_CHECK(f.texture_sources[i] != NULL);
    }
    for (size_t s = 0; s < f.scene_count; s++) {
        const sc_scene *sc = &f.scenes[s];
        size_t len = sc->name ? strlen(sc->name) : 0;
        FUZZ_CHECK(len >= 1 && len <= SC_MAX_NAME_LENGTH);
        FUZZ_CHECK(strspn(sc->name, "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz"
                                    "0123456789_.-") == len);
        FUZZ_CHECK(sc->width >= 1 && sc->width <= SC_MAX_IMAGE_SIZE);
        FUZZ_CHECK(sc->height >= 1 && sc->height <= SC_MAX_IMAGE_SIZE);
        for (int c = 0; c < 4; c++)
            FUZZ_CHECK(sc->clear_color[c] >= 0.0f && sc->clear_color[c] <= 1.0f);
        for (size_t d = 0; d < sc->draw_count; d++) {
            const sc_draw *dr = &sc->draws[d];
            FUZZ_CHECK(dr->mesh >= 0 && (size_t)dr->mesh < f.mesh_count);
            FUZZ_CHECK(dr->texture >= -1 &&
                       (dr->texture < 0 || (size_t)dr->texture < f.texture_count));
            FUZZ_CHECK(dr->mode <= SC_MODE_TEXTURE && dr->filter <= SC_FILTER_NEAREST);
            FUZZ_CHECK(dr->wrap <= SC_WRAP_CLAMP && dr->cull <= SC_CULL_FRONT);
            FUZZ_CHECK(dr->front_face <= SC_FRONT_FACE_CW &&
                       dr->depth_compare <= SC_COMPARE_ALWAYS);
        }
    }
    sc_free(&f);
    return 0;
}

#ifndef FUZZ_REPLAY
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    return fuzz_scene(data, size);
}
#endif
