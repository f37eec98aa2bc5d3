/* test_shader_lib.c - the shader registry of the apps (shader_lib.h): the built-in library, a
 * library built as a user builds it (tests/shader_lib/tint.c, with the documented command), and
 * every library a program must refuse, each with its own message; then the checks of a scene
 * file's shader draws against the known shaders.
 *
 *   test_shader_lib DIR    (DIR holds tint.so, tint_next_abi.so, tint_unlit.so and nosym.so)
 */
#define _POSIX_C_SOURCE 200809L

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "test_common.h"

#include "builtin.h"
#include "pipeline/mat4.h"
#include "scene.h"
#include "shader_lib.h"
#include "test_msg.h"

static const char *lib_dir;

/* DIR/name, in a buffer of the caller's. */
static const char *lib_path(char *buf, size_t size, const char *name) {
    snprintf(buf, size, "%s/%s", lib_dir, name);
    return buf;
}

static void assert_contains(const char *text, const char *want) {
    if (!strstr(text, want)) fail_msg("'%s' lacks '%s'", text, want);
}

static void builtin_library(void **state) {
    (void)state;
    int n = 0, again = 0;
    const sgShaderInfo *const *list = sg_builtin_shaders(SG_SIMD_DEFAULT, &n);
    assert_int_equal(n, 9);
    assert_string_equal(list[0]->name, "unlit");
    assert_ptr_equal(sg_builtin_shaders(SG_SIMD_DEFAULT, &again), list); /* the same every call */
    assert_int_equal(again, n);
    TEST_MSG(err);
    sc_shaders *s;
    assert_true(sc_shaders_open(&s, SG_SIMD_DEFAULT, &err));
    const sgShaderInfo *unlit = sc_shaders_find(s, "unlit");
    assert_non_null(unlit);
    assert_int_equal(unlit->uniform_count, 1);
    assert_int_equal(unlit->desc.varying_count, 6);
    assert_non_null(unlit->glsl_vertex);
    assert_non_null(unlit->glsl_fragment);
    assert_null(sc_shaders_find(s, "tint"));
    assert_null(sc_shaders_find(s, NULL));
    sc_shaders_close(s);
    sc_shaders_close(NULL);
}

/* unlit's vertex stage: clip = (proj * world_view) * p with the fixed path's bits, the colour as 4
 * varyings; its fragment stage writes them back. */
/* A zeroed batch on the heap, aligned as its type asks. */
static void *zeroed_batch(size_t size) {
    void *p = aligned_alloc(64, (size + 63) / 64 * 64);
    if (p) memset(p, 0, size);
    return p;
}

static void unlit_stages(void **state) {
    (void)state;
    /* Matrices and positions whose products round (a turned view, an odd projection). */
    const float wv[16] = {0.8f,  -0.6f, 0.1f, 0.5f,  0.6f, 0.8f, 0.3f, -0.7f,
                          -0.1f, 0.3f,  0.9f, -3.3f, 0,    0,    0,    1};
    const float proj[16] = {1.37f, 0, 0.01f,    0,         0, 1.83f, 0,  0,
                            0,     0, -1.0202f, -0.20202f, 0, 0,     -1, 0};
    sgVertexBatch *b = zeroed_batch(sizeof *b); /* the batches' arrays are 64-byte aligned */
    assert_non_null(b);
    b->count = 16;
    b->world_view = wv;
    b->proj = proj;
    for (int i = 0; i < 16; i++) {
        b->position[0][i] = (float)i * 0.37f - 2.1f;
        b->position[1][i] = 1.3f - (float)i * 0.11f;
        b->position[2][i] = (float)(i % 3) * 0.77f;
        b->position[3][i] = 1;
        for (int c = 0; c < 4; c++) b->color[c][i] = (float)(c + 1) / 8 + (float)i / 64;
    }
    sg_shader_unlit.desc.vertex(b, NULL);
    /* The same bits as sgapi's fixed path: its combined matrix, then its transform. */
    float mvp[16];
    sg_mat4_mul(mvp, proj, wv);
    for (int i = 0; i < 16; i++) {
        const float p[4] = {b->position[0][i], b->position[1][i], b->position[2][i],
                            b->position[3][i]};
        float want[4];
        sg_mat4_transform(want, mvp, p);
        for (int r = 0; r < 4; r++)
            if (memcmp(&b->clip[r][i], &want[r], sizeof want[r]) != 0)
                fail_msg("lane %d, clip[%d]: %.9g, the fixed path %.9g", i, r, b->clip[r][i],
                         want[r]);
        for (int c = 0; c < 4; c++) assert_float_equal(b->varying[c][i], b->color[c][i], 0);
    }
    sgFragmentBatch *fb = zeroed_batch(sizeof *fb);
    assert_non_null(fb);
    fb->mask = 0xffff;
    fb->discard = 0x5;
    for (int c = 0; c < 4; c++)
        for (int i = 0; i < 16; i++) fb->varying[c][i] = (float)(c * 16 + i) / 64;
    const float untextured[1] = {0};
    sg_shader_unlit.desc.fragment(fb, untextured);
    for (int c = 0; c < 4; c++)
        for (int i = 0; i < 16; i++) assert_float_equal(fb->color[c][i], fb->varying[c][i], 0);
    assert_int_equal(fb->discard, 0);
    free(b);
    free(fb);
}

/* A library built with the headers alone loads, and its shader runs. */
static void load_library(void **state) {
    (void)state;
    char path[1024];
    TEST_MSG(err);
    sc_shaders *s;
    assert_true(sc_shaders_open(&s, SG_SIMD_DEFAULT, &err));
    if (!sc_shaders_load(s, lib_path(path, sizeof path, "tint.so"), &err)) fail_msg("%s", MSG(err));
    const sgShaderInfo *tint = sc_shaders_find(s, "tint");
    assert_non_null(tint);
    assert_int_equal(tint->uniform_count, 3);
    assert_non_null(sc_shaders_find(s, "unlit"));
    sgFragmentBatch *fb = zeroed_batch(sizeof *fb);
    assert_non_null(fb);
    const float u[3] = {0.25f, 0.5f, 0.75f};
    fb->mask = 0xffff;
    tint->desc.fragment(fb, u);
    assert_float_equal(fb->color[1][7], 0.5f, 0);
    assert_float_equal(fb->color[3][15], 1.0f, 0);
    free(fb);

    /* The same library again: its shader's name is taken; the registry stays as it was. */
    assert_false(sc_shaders_load(s, path, &err));
    assert_contains(MSG(err), "tint.so': shader 'tint' is already defined by shader library '");
    assert_ptr_equal(sc_shaders_find(s, "tint"), tint);
    /* A library naming a built-in shader. */
    assert_false(sc_shaders_load(s, lib_path(path, sizeof path, "tint_unlit.so"), &err));
    assert_contains(MSG(err), "shader 'unlit' is already defined by the built-in library");
    sc_shaders_close(s);
}

/* Each library a program refuses, with the message that says why; nothing is added. */
static void refused_libraries(void **state) {
    (void)state;
    char path[1024];
    TEST_MSG(err);
    sc_shaders *s;
    assert_true(sc_shaders_open(&s, SG_SIMD_DEFAULT, &err));

    assert_false(sc_shaders_load(s, lib_path(path, sizeof path, "missing.so"), &err));
    assert_contains(MSG(err), "missing.so': No such file or directory");

    /* A text file. */
    const char *text = lib_path(path, sizeof path, "text.so");
    FILE *f = fopen(text, "w");
    assert_non_null(f);
    fputs("not a shared object\n", f);
    fclose(f);
    assert_false(sc_shaders_load(s, text, &err));
    assert_contains(MSG(err), "text.so' is not a shared object (no ELF header)");
    remove(text);

    /* A folder. */
    assert_false(sc_shaders_load(s, lib_dir, &err));
    assert_contains(MSG(err), "' is not a regular file");

    assert_false(sc_shaders_load(s, lib_path(path, sizeof path, "nosym.so"), &err));
    assert_contains(MSG(err), "nosym.so' has no function sgapi_shader_library");

    assert_false(sc_shaders_load(s, lib_path(path, sizeof path, "tint_next_abi.so"), &err));
    char want[160];
    snprintf(want, sizeof want, "is of shader ABI version %d, and this program takes version %d",
             SGAPI_SHADER_ABI_VERSION + 1, SGAPI_SHADER_ABI_VERSION);
    assert_contains(MSG(err), want);

    assert_null(sc_shaders_find(s, "tint"));
    sc_shaders_close(s);
}

/* A file of one scene with one draw of a cube whose other keys are `keys`. */
static bool parse_draw(const char *keys, sc_file *f, sc_msg *err) {
    char json[1024];
    snprintf(json, sizeof json,
             "{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"s\", \"draws\": ["
             "{\"mesh\": {\"shape\": \"cube\"}, \"worldView\": [1,0,0,0, 0,1,0,0, 0,0,1,0, "
             "0,0,0,1], \"proj\": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1], %s}]}]}",
             keys);
    return sc_parse("draw.json", json, strlen(json), f, err);
}

/* A scene's shader draws against the known shaders: an unknown name lists the known ones, a
 * wrong uniform count names the shader's. */
static void check_scene_shaders(void **state) {
    (void)state;
    char path[1024];
    TEST_MSG(err);
    sc_shaders *s;
    assert_true(sc_shaders_open(&s, SG_SIMD_DEFAULT, &err));
    if (!sc_shaders_load(s, lib_path(path, sizeof path, "tint.so"), &err)) fail_msg("%s", MSG(err));
    static const struct {
        const char *keys, *want; /* want NULL: the draw fits */
    } cases[] = {
        {"\"shader\": \"unlit\", \"uniforms\": [0]", NULL},
        {"\"shader\": \"tint\", \"uniforms\": [1, 0.5, 0]", NULL},
        {"\"depth_write\": true", NULL},
        {"\"shader\": \"tnit\"",
         "draw.json: scenes[0] ('s'), draws[0]: unknown shader 'tnit' (known: unlit, phong, toon, "
         "normal_map, marble, waves, dissolve, instanced, phong_lights, tint; "},
        {"\"shader\": \"tint\", \"uniforms\": [1, 0.5]",
         "draw.json: scenes[0] ('s'), draws[0]: shader 'tint' takes 3 uniforms, and 'uniforms' "
         "has 2"},
        {"\"shader\": \"tint\"", "shader 'tint' takes 3 uniforms, and 'uniforms' has 0"},
        {"\"shader\": \"unlit\", \"uniforms\": [1, 0]",
         "shader 'unlit' takes 1 uniform, and 'uniforms' has 2"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        sc_file f;
        if (!parse_draw(cases[i].keys, &f, &err)) fail_msg("%s: %s", cases[i].keys, MSG(err));
        bool fits = sc_shaders_check(s, &f, &err);
        if (!cases[i].want && !fits) fail_msg("%s: %s", cases[i].keys, MSG(err));
        if (cases[i].want) {
            if (fits) fail_msg("%s passed", cases[i].keys);
            assert_contains(MSG(err), cases[i].want);
        }
        sc_free(&f);
    }
    sc_shaders_close(s);
}

int main(int argc, char **argv) {
    if (argc != 2) {
        fprintf(stderr, "usage: test_shader_lib DIR\n");
        return 2;
    }
    lib_dir = argv[1];
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(builtin_library),     cmocka_unit_test(unlit_stages),
        cmocka_unit_test(load_library),        cmocka_unit_test(refused_libraries),
        cmocka_unit_test(check_scene_shaders),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
