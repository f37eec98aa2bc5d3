/* test_scene_loader.c - the API-neutral loaders: OBJ meshes, heightmap meshes and scene files; and
 * the back-to-front triangle order of the scene format.
 *
 * Every input file is written by the test itself into a fresh temporary folder.
 */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "test_common.h"

#include "depth_sort.h"
#include "image_io.h"
#include "obj.h"
#include "scene.h"
#include "scene_keys.h"
#include "shadow.h"
#include "test_msg.h"

/* ---- helpers --------------------------------------------------------------------------------- */

#define MAX_FILES 32

/* The temporary folder of the whole group and the files written into it. */
typedef struct tmp_dir {
    char path[512];
    char *files[MAX_FILES];
    int file_count;
} tmp_dir;

static int group_setup(void **state) {
    tmp_dir *t = calloc(1, sizeof *t);
    if (!t) return -1;
    const char *base = getenv("TMPDIR");
    snprintf(t->path, sizeof t->path, "%s/sgscene-test-XXXXXX", base && *base ? base : "/tmp");
    if (!mkdtemp(t->path)) {
        free(t);
        return -1;
    }
    *state = t;
    return 0;
}

static int group_teardown(void **state) {
    tmp_dir *t = *state;
    for (int i = 0; i < t->file_count; i++) {
        remove(t->files[i]);
        free(t->files[i]);
    }
    rmdir(t->path);
    free(t);
    return 0;
}

/* The full path of name in the temporary folder; remembered, so teardown removes the file. */
static char *tmp_path(tmp_dir *t, const char *name) {
    size_t n = strlen(t->path) + strlen(name) + 2;
    char *p = malloc(n);
    assert_non_null(p);
    snprintf(p, n, "%s/%s", t->path, name);
    for (int i = 0; i < t->file_count; i++) {
        if (!strcmp(t->files[i], p)) {
            free(p);
            return t->files[i];
        }
    }
    assert_true(t->file_count < MAX_FILES);
    t->files[t->file_count++] = p;
    return p;
}

static const char *write_file(tmp_dir *t, const char *name, const char *text) {
    const char *path = tmp_path(t, name);
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(text, 1, strlen(text), f), strlen(text));
    assert_int_equal(fclose(f), 0);
    return path;
}

static bool parse_obj(const char *text, sc_mesh *m, sc_msg *err) {
    return sc_obj_parse("test.obj", text, strlen(text), m, err);
}

static void assert_floats(const float *got, const float *want, int n) {
    for (int i = 0; i < n; i++) assert_float_equal(got[i], want[i], 1e-6);
}

static void assert_indices(const sc_mesh *m, const uint32_t *want, uint32_t n) {
    assert_int_equal(m->index_count, n);
    for (uint32_t i = 0; i < n; i++) assert_int_equal(m->indices[i], want[i]);
}

/* ---- OBJ ------------------------------------------------------------------------------------- */

static void obj_colour_extension(void **state) {
    (void)state;
    TEST_MSG(err);
    sc_mesh m;
    assert_true(parse_obj("# comment\n\no thing\ng group\ns 1\nusemtl red\nmtllib x.mtl\n"
                          "v 0 0 0 1 0 0\nv 1 0 0 0 0.5 0\nv 0 1 0\nf 1 2 3\n",
                          &m, &err));
    assert_int_equal(m.vertex_count, 3);
    assert_null(m.texcoords);
    assert_null(m.normals);
    const float pos[12] = {0, 0, 0, 1, 1, 0, 0, 1, 0, 1, 0, 1};
    const float col[12] = {1, 0, 0, 1, 0, 0.5f, 0, 1, 1, 1, 1, 1}; /* no colour: white */
    assert_floats(m.positions, pos, 12);
    assert_floats(m.colors, col, 12);
    const uint32_t idx[3] = {0, 1, 2};
    assert_indices(&m, idx, 3);
    sc_mesh_free(&m);
}

/* "v x y z r g b a": the colour's alpha reaches the mesh; lines without one keep alpha 1. */
static void obj_colour_with_alpha(void **state) {
    (void)state;
    TEST_MSG(err);
    sc_mesh m;
    if (!parse_obj("v 0 0 0 1 0 0 0.25\nv 1 0 0 0 1 0\nv 0 1 0 2\nf 1 2 3\n", &m, &err))
        fail_msg("%s", MSG(err));
    assert_int_equal(m.vertex_count, 3);
    const float pos[12] = {0, 0, 0, 1, 1, 0, 0, 1, 0, 1, 0, 1}; /* the weight 2 is ignored */
    const float col[12] = {1, 0, 0, 0.25f, 0, 1, 0, 1, 1, 1, 1, 1};
    assert_floats(m.positions, pos, 12);
    assert_floats(m.colors, col, 12);
    sc_mesh_free(&m);
}

/* A 'v' line is 3 or 4 numbers (position, weight), 6 (rgb) or 7 (rgba); other counts name the
 * line. */
static void obj_bad_position_count(void **state) {
    (void)state;
    TEST_MSG(err);
    sc_mesh m;
    static const struct {
        const char *text, *want1, *want2;
    } cases[] = {
        {"v 0 0 0\nv 1 0 0 1 0\nv 0 1 0\nf 1 2 3\n", "test.obj:2:", "got 5 numbers"},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0 1 1 1 1 1\nf 1 2 3\n", "test.obj:3:", "too many numbers"},
        {"v 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "test.obj:1:", "got 2 numbers"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        sc_msg_free(&err);
        assert_false(parse_obj(cases[i].text, &m, &err));
        if (!strstr(MSG(err), cases[i].want1) || !strstr(MSG(err), cases[i].want2))
            fail_msg("case %zu: '%s' lacks '%s' or '%s'", i, MSG(err), cases[i].want1,
                     cases[i].want2);
        assert_null(m.positions);
    }
}

static void obj_fan_split(void **state) {
    (void)state;
    TEST_MSG(err);
    sc_mesh m;
    const char *verts = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv -1 0.5 0\n";
    char text[256];

    snprintf(text, sizeof text, "%sf 1 2 3 4\n", verts);
    assert_true(parse_obj(text, &m, &err));
    const uint32_t quad[6] = {0, 1, 2, 0, 2, 3};
    assert_indices(&m, quad, 6);
    assert_int_equal(m.vertex_count, 4);
    sc_mesh_free(&m);

    snprintf(text, sizeof text, "%sf 1 2 3 4 5\n", verts);
    assert_true(parse_obj(text, &m, &err));
    const uint32_t penta[9] = {0, 1, 2, 0, 2, 3, 0, 3, 4};
    assert_indices(&m, penta, 9);
    sc_mesh_free(&m);
}

static void obj_negative_indices(void **state) {
    (void)state;
    TEST_MSG(err);
    sc_mesh m;
    /* -1 is the latest element defined before the face, so the second face reaches v 4..6. */
    assert_true(parse_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n"
                          "f -3/-3 -2/-2 -1/-1\n"
                          "v 5 0 0\nv 6 0 0\nv 7 0 0\n"
                          "f -3/1 -2/2 -1/3\n",
                          &m, &err));
    assert_int_equal(m.vertex_count, 6);
    const uint32_t idx[6] = {0, 1, 2, 3, 4, 5};
    assert_indices(&m, idx, 6);
    assert_float_equal(m.positions[3 * 4], 5.0f, 0);
    assert_float_equal(m.positions[5 * 4], 7.0f, 0);
    const float tc[4] = {0, 0, 1, 0};
    assert_floats(m.texcoords, tc, 4);
    sc_mesh_free(&m);
}

static void obj_position_and_normal(void **state) {
    (void)state;
    TEST_MSG(err);
    sc_mesh m;
    assert_true(parse_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvn 0 1 0\n"
                          "f 1//1 2//1 3//2\r\n",
                          &m, &err));
    assert_null(m.texcoords);
    assert_non_null(m.normals);
    const float n[9] = {0, 0, 1, 0, 0, 1, 0, 1, 0};
    assert_floats(m.normals, n, 9);
    sc_mesh_free(&m);

    /* a/b/c: all three attributes. */
    assert_true(parse_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0.25 0.75\nvn 1 0 0\n"
                          "f 1/1/1 2/1/1 3/1/1\n",
                          &m, &err));
    assert_non_null(m.texcoords);
    assert_non_null(m.normals);
    assert_float_equal(m.texcoords[4], 0.25f, 0);
    assert_float_equal(m.texcoords[5], 0.75f, 0);
    sc_mesh_free(&m);
}

static void obj_bad_index_is_an_error(void **state) {
    (void)state;
    TEST_MSG(err);
    sc_mesh m;
    static const struct {
        const char *text, *want;
    } cases[] = {
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", "test.obj:4:"},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", "out of range"},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "index 0"},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf -4 1 2\n", "out of range"},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1 2/1 3/1\n", "texture coordinate"},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//2 2//1 3//1\n", "normal"},
        /* A face may only use what is defined before it. */
        {"f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n", "test.obj:1:"},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999999\n", "out of range"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        sc_msg_free(&err);
        assert_false(parse_obj(cases[i].text, &m, &err));
        if (!strstr(MSG(err), cases[i].want))
            fail_msg("case %zu: '%s' lacks '%s'", i, MSG(err), cases[i].want);
        assert_null(m.positions);
        assert_int_equal(m.vertex_count, 0);
    }
}

static void obj_garbage_is_an_error(void **state) {
    (void)state;
    TEST_MSG(err);
    sc_mesh m;
    static const char *const cases[] = {
        "",
        "just some words\n",
        "v 1 2\nf 1 1 1\n",
        "v a b c\n",
        "v 1 2 3 4 5\n",
        "v 1 2 3 1e999\n",
        "v nan 0 0\n",
        "vn 1 2\n",
        "vt\n",
        "v 0 0 0\nf 1 1\n",
        "v 0 0 0\nf 1/ 1 1\n",
        "v 0 0 0\nf 1// 1 1\n",
        "v 0 0 0\nf 1/1/1/1 1 1\n",
        "v 0 0 0\nf 1x 1 1\n",
        "v 0 0 0\nf --1 1 1\n",
        "v 0.000000000000000000000000000000000000000000000000000000000000000000000000001 0 0\n",
        "\xff\xfe\x01\x02 v f / //\n",
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        sc_msg_free(&err);
        assert_false(parse_obj(cases[i], &m, &err));
        if (MSG(err)[0] == '\0') fail_msg("case %zu: no error message", i);
    }
    /* A NUL byte in the middle of a line. */
    static const char nul[] = "v 0 0 0\nv 1 0\0 0\nv 0 1 0\nf 1 2 3\n";
    assert_false(sc_obj_parse("nul.obj", nul, sizeof nul - 1, &m, &err));
    assert_non_null(strstr(MSG(err), "nul.obj:2:"));

    /* Random lines of OBJ-like tokens: any result is fine as long as it is a clean one. */
    static const char *const tokens[] = {"v", "vt", "vn",  "f",  " ", "1",    "2",  "-1", "-3",
                                         "/", "//", "0.5", "\n", "#", "1e30", "\t", "x",  "l"};
    const size_t ntok = sizeof tokens / sizeof tokens[0];
    uint32_t seed = 12345;
    char text[512];
    for (int round = 0; round < 3000; round++) {
        size_t len = 0;
        text[0] = '\0';
        int count = 1 + (int)(seed % 60);
        for (int k = 0; k < count; k++) {
            seed = seed * 1664525u + 1013904223u;
            const char *tok = tokens[(seed >> 16) % ntok];
            size_t n = strlen(tok);
            if (len + n + 1 >= sizeof text) break;
            memcpy(text + len, tok, n + 1);
            len += n;
        }
        if (parse_obj(text, &m, &err)) {
            for (uint32_t k = 0; k < m.index_count; k++) assert_true(m.indices[k] < m.vertex_count);
            for (uint32_t k = 0; k < m.line_index_count; k++)
                assert_true(m.line_indices[k] < m.vertex_count);
            assert_int_equal(m.line_index_count % 2, 0);
            sc_mesh_free(&m);
        } else {
            assert_true(MSG(err)[0] != '\0');
        }
    }
}

static void obj_shares_equal_tuples(void **state) {
    (void)state;
    TEST_MSG(err);
    sc_mesh m;
    /* Two triangles of a quad, position and texcoord indices equal: 4 vertices, not 6. */
    assert_true(parse_obj("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                          "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                          "f 1/1 2/2 3/3\nf 1/1 3/3 4/4\n",
                          &m, &err));
    assert_int_equal(m.vertex_count, 4);
    const uint32_t idx[6] = {0, 1, 2, 0, 2, 3};
    assert_indices(&m, idx, 6);
    sc_mesh_free(&m);

    /* The same position with other texcoords, or without one, is another vertex. */
    assert_true(parse_obj("v 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\nvt 1 0\n"
                          "f 1/1 2/1 3/1\nf 1/2 2/1 3\n",
                          &m, &err));
    assert_int_equal(m.vertex_count, 5);
    const uint32_t idx2[6] = {0, 1, 2, 3, 1, 4};
    assert_indices(&m, idx2, 6);
    assert_float_equal(m.texcoords[3 * 2], 1.0f, 0);
    assert_float_equal(m.texcoords[4 * 2], 0.0f, 0); /* none: zeros */
    sc_mesh_free(&m);
}

static void assert_line_indices(const sc_mesh *m, const uint32_t *want, uint32_t n) {
    assert_int_equal(m->line_index_count, n);
    for (uint32_t i = 0; i < n; i++) assert_int_equal(m->line_indices[i], want[i]);
}

/* "l a b c ..." is a polyline: segments a-b, b-c, ...; its vertices are shared with faces that
 * name the same position and texcoord. */
static void obj_polylines(void **state) {
    (void)state;
    TEST_MSG(err);
    sc_mesh m;
    if (!parse_obj("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0 1 0 0\nvt 0.5 0.25\n"
                   "f 1 2 3\n"
                   "l 1 2 3 4 1\n"
                   "l -1/1 2\t# a comment\n",
                   &m, &err))
        fail_msg("%s", MSG(err));
    const uint32_t tri[3] = {0, 1, 2};
    assert_indices(&m, tri, 3);
    /* 4/1 is a new vertex (the texcoord makes it one); 1 2 3 are the face's. */
    const uint32_t lines[10] = {0, 1, 1, 2, 2, 3, 3, 0, 4, 1};
    assert_line_indices(&m, lines, 10);
    assert_int_equal(m.vertex_count, 5);
    assert_non_null(m.texcoords);
    const float tc[10] = {0, 0, 0, 0, 0, 0, 0, 0, 0.5f, 0.25f};
    assert_floats(m.texcoords, tc, 10);
    const float red[4] = {1, 0, 0, 1};
    assert_floats(m.colors + 3 * 4, red, 4);
    sc_mesh_free(&m);

    /* Lines only: no triangles at all. */
    if (!parse_obj("v 0 0 0\nv 2 0 0\nv 0 3 0\nl 1 2\nl 3 1\n", &m, &err)) fail_msg("%s", MSG(err));
    assert_int_equal(m.index_count, 0);
    assert_null(m.indices);
    const uint32_t segs[4] = {0, 1, 2, 0};
    assert_line_indices(&m, segs, 4);
    assert_null(m.texcoords);
    assert_null(m.normals);
    sc_mesh_free(&m);

    /* Faces only: no line list. */
    assert_true(parse_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", &m, &err));
    assert_int_equal(m.line_index_count, 0);
    assert_null(m.line_indices);
    sc_mesh_free(&m);
}

/* Bad lines name the file and line: too few vertices, an index out of range, a normal, garbage. */
static void obj_bad_lines(void **state) {
    (void)state;
    TEST_MSG(err);
    sc_mesh m;
    static const struct {
        const char *text, *want1, *want2;
    } cases[] = {
        {"v 0 0 0\nv 1 0 0\nl 1\n", "test.obj:3:", "a line needs at least 2 vertices (got 1)"},
        {"v 0 0 0\nv 1 0 0\nl\n", "test.obj:3:", "a line needs at least 2 vertices (got 0)"},
        {"v 0 0 0\nv 1 0 0\nl 2 # 1\n", "test.obj:3:", "(got 1)"},
        {"v 0 0 0\nv 1 0 0\nl 1 3\n", "test.obj:3:", "position index 3 out of range"},
        {"v 0 0 0\nv 1 0 0\nl 1 -3\n", "test.obj:3:", "out of range"},
        {"v 0 0 0\nv 1 0 0\nl 0 1\n", "test.obj:3:", "index 0"},
        {"v 0 0 0\nv 1 0 0\nl 1/1 2\n", "test.obj:3:", "texture coordinate index 1"},
        {"v 0 0 0\nv 1 0 0\nvn 0 0 1\nl 1//1 2//1\n",
         "test.obj:4:", "bad line vertex '1//1' (expected a or a/b)"},
        {"v 0 0 0\nv 1 0 0\nvt 0 0\nvn 0 0 1\nl 1/1/1 2\n", "test.obj:5:", "bad line vertex"},
        {"v 0 0 0\nv 1 0 0\nl 1 2x\n", "test.obj:3:", "bad line vertex '2x'"},
        {"v 0 0 0\nv 1 0 0\nl 1 2/\n", "test.obj:3:", "bad line vertex"},
        /* A line may only use what is defined before it. */
        {"v 0 0 0\nl 1 2\nv 1 0 0\n", "test.obj:2:", "out of range"},
        {"v 0 0 0\nv 1 0 0\n", "test.obj: ", "no faces or lines"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        sc_msg_free(&err);
        assert_false(parse_obj(cases[i].text, &m, &err));
        if (!strstr(MSG(err), cases[i].want1) || !strstr(MSG(err), cases[i].want2))
            fail_msg("case %zu: '%s' lacks '%s' or '%s'", i, MSG(err), cases[i].want1,
                     cases[i].want2);
        assert_null(m.positions);
        assert_null(m.line_indices);
    }
}

static void obj_load_from_file(void **state) {
    tmp_dir *t = *state;
    TEST_MSG(err);
    sc_mesh m;
    const char *path = write_file(t, "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3");
    assert_true(sc_obj_load(path, &m, &err));
    assert_int_equal(m.index_count, 3);
    sc_mesh_free(&m);
    assert_false(sc_obj_load(tmp_path(t, "missing.obj"), &m, &err));
    assert_non_null(strstr(MSG(err), "missing.obj"));
}

/* ---- heightmap ------------------------------------------------------------------------------- */

static void heightmap_mesh(void **state) {
    tmp_dir *t = *state;
    TEST_MSG(err);
    /* 3x2 pixels, stored top row first; grid rows count from the bottom, so the stored second
     * row is grid row y = 0. Pixel (2, 1) has R+G+B = 255. */
    const unsigned char px[3 * 2 * 4] = {
        100, 100, 100, 255, 50,  50,  50,  255, 85, 85, 85, 255, /* y = 1 */
        0,   0,   0,   255, 255, 255, 255, 255, 10, 20, 30, 255, /* y = 0 */
    };
    assert_true(sc_image_write_png(tmp_path(t, "height.png"), 3, 2, px, &err));
    const char *path =
        write_file(t, "hm.json",
                   "{\"width\": 8, \"height\": 8, \"scenes\": [{\"name\": \"hm\", \"draws\": ["
                   "{\"mesh\": {\"heightmap\": \"height.png\", \"height_scale\": 3},"
                   " \"worldView\": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1],"
                   " \"proj\": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1]}]}]}");
    sc_file f;
    if (!sc_load(path, &f, &err)) fail_msg("%s", MSG(err));
    assert_int_equal(f.mesh_count, 1);
    const sc_mesh *m = &f.meshes[0];
    assert_int_equal(m->vertex_count, 6);
    assert_int_equal(m->index_count, 12); /* 2 cells x 2 triangles */
    const uint32_t idx[12] = {0, 3, 1, 1, 3, 4, 1, 4, 2, 2, 4, 5};
    assert_indices(m, idx, 12);
    /* Pixel (2, 1): x - W/2, scale * (R+G+B) / 765, y - H/2. */
    const float p5[4] = {0.5f, 1.0f, 0.0f, 1.0f};
    assert_floats(m->positions + 5 * 4, p5, 4);
    const float p1[4] = {-0.5f, 3.0f, -1.0f, 1.0f};
    assert_floats(m->positions + 1 * 4, p1, 4);
    assert_float_equal(m->texcoords[5 * 2], 2.0f / 3.0f, 1e-6);
    assert_float_equal(m->texcoords[5 * 2 + 1], 0.5f, 1e-6);
    assert_float_equal(m->colors[5 * 4], 1.0f, 0);
    /* The loader gives the grid smooth normals; its triangles face up (+y). */
    assert_non_null(m->normals);
    for (int v = 0; v < 6; v++) {
        const float *n = m->normals + v * 3;
        assert_true(n[1] > 0.0f);
        assert_float_equal(n[0] * n[0] + n[1] * n[1] + n[2] * n[2], 1.0f, 1e-6);
    }
    sc_free(&f);

    /* A heightmap needs two rows and two columns. */
    sc_image thin = {1, 2, (unsigned char *)px};
    sc_mesh none;
    assert_false(sc_heightmap_mesh(&thin, 1.0f, &none, &err));
}

/* ---- scene files ----------------------------------------------------------------------------- */

#define IDENTITY "[1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1]"
#define MATRICES "\"worldView\": " IDENTITY ", \"proj\": " IDENTITY

static void write_assets(tmp_dir *t) {
    write_file(t, "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/1\n");
    /* Casters a shadow light cannot be fitted to: one point, and no finite vertex. */
    write_file(t, "dot.obj", "v 1 2 3\nv 1 2 3\nv 1 2 3\nf 1 2 3\n");
    write_file(t, "nan.obj", "v nan 0 0\nv 0 nan 0\nv 0 0 inf\nf 1 2 3\n");
    /* Lines only; and a triangle with a line off it, whose far end no face gives a normal. */
    write_file(t, "lines.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nl 1 2 3\n");
    write_file(t, "stray.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 5 5\nf 1 2 3\nl 1 4\n");
    const unsigned char px[4] = {255, 0, 0, 255};
    TEST_MSG(err);
    assert_true(sc_image_write_png(tmp_path(t, "red.png"), 1, 1, px, &err));
}

/* Loads scene text written to name; on failure returns false with the message in err. */
static bool load_scene(tmp_dir *t, const char *name, const char *json, sc_file *f, sc_msg *err) {
    write_assets(t);
    return sc_load(write_file(t, name, json), f, err);
}

/* Unknown keys load with a warning each, naming the file, the key's line (a CR LF ends one line)
 * and path, with "did you mean" when a known key of that object is one edit away (insertion,
 * deletion, substitution, swap). */
static void scene_unknown_keys(void **state) {
    tmp_dir *t = *state;
    TEST_MSG(err);
    sc_file f;
    if (!load_scene(t, "keys.json",
                    "{\"width\": 8, \"height\": 8, \"matrices\": \"a note\", \"hieght\": 3,\n"
                    " \"lights\": [{\"type\": \"point\", \"position\": [0, 0, 0],\n"
                    " \"color\": [1, 1, 1], \"colour\": [1, 1, 1]}],\n"
                    " \"scenes\": [{\"name\": \"a\", \"draws\": []},\n"
                    " {\"name\": \"b\", \"shadow\": {\"light\": 0, \"pfc\": true}, \"draws\": [\n"
                    "{\"mesh\": \"tri.obj\", " MATRICES "},\n"
                    "{\"mesh\": \"tri.obj\", \"lightning\": \"phong\",\n"
                    "\r\n \"cul\": \"back\", " MATRICES "}]}]}",
                    &f, &err))
        fail_msg("%s", MSG(err));
    const char *want[] = {
        "keys.json:1: unknown key 'matrices'",
        "keys.json:1: unknown key 'hieght' (did you mean 'height'?)",
        "keys.json:3: unknown key 'lights[0].colour'",
        "keys.json:5: unknown key 'scenes[1].shadow.pfc' (did you mean 'pcf'?)",
        "keys.json:7: unknown key 'scenes[1].draws[1].lightning' (did you mean 'lighting'?)",
        "keys.json:9: unknown key 'scenes[1].draws[1].cul' (did you mean 'cull'?)",
    };
    assert_int_equal(f.warning_count, sizeof want / sizeof *want);
    for (size_t i = 0; i < f.warning_count; i++)
        if (!strstr(f.warnings[i], want[i])) fail_msg("'%s' lacks '%s'", f.warnings[i], want[i]);
    /* The key is ignored: the draw is unlit, as without it. */
    assert_int_equal(f.scenes[1].draws[1].lighting, SC_LIGHTING_NONE);
    assert_true(sc_report_warnings(&f, "test", false));
    assert_false(sc_report_warnings(&f, "test", true));
    sc_free(&f);
    /* A file without unknown keys has no warnings, and strict passes it. */
    if (!load_scene(t, "clean.json",
                    "{\"width\": 8, \"height\": 8, \"scenes\": [{\"name\": \"a\", \"draws\": []}]}",
                    &f, &err))
        fail_msg("%s", MSG(err));
    assert_int_equal(f.warning_count, 0);
    assert_true(sc_report_warnings(&f, "test", true));
    sc_free(&f);
}

static void scene_defaults(void **state) {
    tmp_dir *t = *state;
    TEST_MSG(err);
    sc_file f;
    if (!load_scene(t, "defaults.json",
                    "{\"width\": 64, \"height\": 32, \"matrices\": \"a note\", \"scenes\": ["
                    "{\"name\": \"a\", \"draws\": [{\"mesh\": \"tri.obj\", " MATRICES "}]}]}",
                    &f, &err))
        fail_msg("%s", MSG(err));
    assert_int_equal(f.scene_count, 1);
    const sc_scene *s = &f.scenes[0];
    assert_string_equal(s->name, "a");
    assert_int_equal(s->width, 64);
    assert_int_equal(s->height, 32);
    for (int i = 0; i < 4; i++) assert_float_equal(s->clear_color[i], 0.0f, 0);
    assert_int_equal(s->draw_count, 1);
    const sc_draw *d = &s->draws[0];
    assert_int_equal(d->mesh, 0);
    assert_int_equal(d->texture, -1);
    assert_int_equal(d->mode, SC_MODE_VERTEX_COLOR);
    assert_int_equal(d->filter, SC_FILTER_BILINEAR);
    assert_int_equal(d->mipmap, SC_MIPMAP_NONE);
    assert_int_equal(d->wrap, SC_WRAP_REPEAT);
    assert_int_equal(d->cull, SC_CULL_NONE);
    assert_int_equal(d->front_face, SC_FRONT_FACE_CCW);
    assert_int_equal(d->depth_compare, SC_COMPARE_LESS);
    assert_true(d->depth_write);
    assert_int_equal(d->blend, SC_BLEND_OPAQUE);
    for (int i = 0; i < 4; i++) assert_float_equal(d->color[i], 1.0f, 0);
    assert_int_equal(d->sort, SC_SORT_NONE);
    assert_int_equal(d->lighting, SC_LIGHTING_NONE);
    for (int i = 0; i < 3; i++) assert_float_equal(d->specular[i], 0.0f, 0);
    assert_float_equal(d->shininess, 0.0f, 0);
    for (int i = 0; i < 3; i++) assert_float_equal(s->ambient[i], 0.0f, 0);
    assert_int_equal(s->light_count, 0);
    assert_false(s->has_shadow);
    assert_true(d->casts_shadow);
    assert_true(d->receives_shadow);
    assert_int_equal(d->polygon_mode, SC_POLYGON_MODE_FILL);
    assert_float_equal(d->world_view[0], 1.0f, 0);
    assert_float_equal(d->proj[15], 1.0f, 0);
    sc_free(&f);
}

static void scene_overrides(void **state) {
    tmp_dir *t = *state;
    TEST_MSG(err);
    sc_file f;
    if (!load_scene(
            t, "overrides.json",
            "{\"width\": 64, \"height\": 32, \"clear_color\": [0, 0, 0, 1], \"scenes\": ["
            "{\"name\": \"a\", \"draws\": []},"
            "{\"name\": \"b.2-x\", \"width\": 10, \"height\": 20,"
            " \"clear_color\": [0.5, 0.25, 1, 0], \"draws\": ["
            "  {\"mesh\": \"tri.obj\", \"texture\": \"red.png\", \"filter\": \"nearest\","
            "   \"mipmap\": \"linear\","
            "   \"wrap\": \"clamp\", \"cull\": \"back\", \"front_face\": \"cw\","
            "   \"depth_compare\": \"greater_equal\", \"depth_write\": false,"
            "   \"worldView\": [2,0,0,0, 0,2,0,0, 0,0,2,0, 0,0,0,1], \"proj\": " IDENTITY "},"
            "  {\"mesh\": \"tri.obj\", \"mode\": \"vertex_color\", \"texture\": \"red.png\","
            "   \"cull\": \"front\", \"depth_compare\": \"always\", " MATRICES "}]}]}",
            &f, &err))
        fail_msg("%s", MSG(err));
    assert_int_equal(f.scene_count, 2);
    assert_int_equal(f.scenes[0].width, 64);
    assert_int_equal(f.scenes[0].draw_count, 0);
    assert_float_equal(f.scenes[0].clear_color[3], 1.0f, 0);
    const sc_scene *s = &f.scenes[1];
    assert_int_equal(s->width, 10);
    assert_int_equal(s->height, 20);
    assert_float_equal(s->clear_color[0], 0.5f, 0);
    assert_float_equal(s->clear_color[1], 0.25f, 0);
    assert_float_equal(s->clear_color[3], 0.0f, 0);

    /* Both draws share the one mesh and the one texture. */
    assert_int_equal(f.mesh_count, 1);
    assert_int_equal(f.texture_count, 1);
    assert_int_equal(f.textures[0].width, 1);
    assert_int_equal(f.textures[0].pixels[0], 255);

    const sc_draw *d = &s->draws[0];
    assert_int_equal(d->texture, 0);
    assert_int_equal(d->mode, SC_MODE_TEXTURE); /* implied by the texture */
    assert_int_equal(d->filter, SC_FILTER_NEAREST);
    assert_int_equal(d->mipmap, SC_MIPMAP_LINEAR);
    assert_true(sc_texture_mipmapped(&f, 0)); /* a draw samples it with mipmaps: its chain */
    sc_mipmap m;
    assert_true(sc_mipmap_from_name("nearest", &m) && m == SC_MIPMAP_NEAREST);
    assert_false(sc_mipmap_from_name("trilinear", &m));
    assert_int_equal(d->wrap, SC_WRAP_CLAMP);
    assert_int_equal(d->cull, SC_CULL_BACK);
    assert_int_equal(d->front_face, SC_FRONT_FACE_CW);
    assert_int_equal(d->depth_compare, SC_COMPARE_GREATER_EQUAL);
    assert_false(d->depth_write);
    assert_float_equal(d->world_view[0], 2.0f, 0);
    d = &s->draws[1];
    assert_int_equal(d->mesh, 0);
    assert_int_equal(d->texture, 0);
    assert_int_equal(d->mode, SC_MODE_VERTEX_COLOR);
    assert_int_equal(d->cull, SC_CULL_FRONT);
    assert_int_equal(d->depth_compare, SC_COMPARE_ALWAYS);
    sc_free(&f);
}

static void scene_texture_null(void **state) {
    tmp_dir *t = *state;
    TEST_MSG(err);
    sc_file f;
    if (!load_scene(t, "null.json",
                    "{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"n\", \"draws\": ["
                    "{\"mesh\": \"tri.obj\", \"mode\": \"texture\", \"texture\": null, " MATRICES
                    "}]}]}",
                    &f, &err))
        fail_msg("%s", MSG(err));
    assert_int_equal(f.scenes[0].draws[0].mode, SC_MODE_TEXTURE);
    assert_int_equal(f.scenes[0].draws[0].texture, -1);
    assert_int_equal(f.texture_count, 0);
    sc_free(&f);
}

/* The transparency keys: blend, a constant colour and the triangle order. */
static void scene_transparency(void **state) {
    tmp_dir *t = *state;
    TEST_MSG(err);
    sc_file f;
    if (!load_scene(t, "transparency.json",
                    "{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"t\", \"draws\": ["
                    "{\"mesh\": \"tri.obj\", \"blend\": \"alpha\", \"color\": [0.5, 0.25, 0, 0.75],"
                    " \"sort\": \"back_to_front\", \"depth_write\": false, " MATRICES "},"
                    "{\"mesh\": \"tri.obj\", \"blend\": \"opaque\", \"color\": [1, 1, 1, 1],"
                    " \"sort\": \"none\", " MATRICES "}]}]}",
                    &f, &err))
        fail_msg("%s", MSG(err));
    const sc_draw *d = &f.scenes[0].draws[0];
    assert_int_equal(d->blend, SC_BLEND_ALPHA);
    const float color[4] = {0.5f, 0.25f, 0.0f, 0.75f};
    assert_floats(d->color, color, 4);
    assert_int_equal(d->sort, SC_SORT_BACK_TO_FRONT);
    assert_false(d->depth_write);
    d = &f.scenes[0].draws[1];
    assert_int_equal(d->blend, SC_BLEND_OPAQUE);
    for (int i = 0; i < 4; i++) assert_float_equal(d->color[i], 1.0f, 0);
    assert_int_equal(d->sort, SC_SORT_NONE);
    sc_free(&f);
}

/* The lighting keys: per draw mode and material, per scene (or file) ambient and lights. */
static void scene_lighting(void **state) {
    tmp_dir *t = *state;
    TEST_MSG(err);
    sc_file f;
    if (!load_scene(
            t, "lighting.json",
            "{\"width\": 4, \"height\": 4, \"ambient\": [0.25, 0.5, 0],"
            " \"lights\": [{\"type\": \"point\", \"position\": [1, 2, 3], \"color\": [4, 0, 1]}],"
            " \"scenes\": ["
            "{\"name\": \"own\", \"ambient\": [0.125, 0, 2], \"lights\": ["
            "  {\"type\": \"directional\", \"direction\": [0, -1, -2], \"color\": [1, 0.5, 0]},"
            "  {\"type\": \"point\", \"position\": [-1, 0.5, -4], \"color\": [0, 0, 3],"
            "   \"attenuation\": [0.5, 0.25, 0.125]},"
            "  {\"type\": \"point\", \"position\": [0, 0, 0], \"color\": [1, 1, 1],"
            "   \"attenuation\": [0, 0, 0]}],"
            " \"draws\": ["
            "  {\"mesh\": \"tri.obj\", \"lighting\": \"flat\", \"specular\": [0.5, 2, 0],"
            "   \"shininess\": 32.5, " MATRICES "},"
            "  {\"mesh\": \"tri.obj\", \"lighting\": \"gouraud\", \"shininess\": 128, " MATRICES
            "},"
            "  {\"mesh\": \"tri.obj\", \"lighting\": \"phong\", " MATRICES "},"
            "  {\"mesh\": \"tri.obj\", \"lighting\": \"none\", " MATRICES "}]},"
            "{\"name\": \"inherits\", \"draws\": []},"
            "{\"name\": \"dark\", \"lights\": [], \"draws\": []}]}",
            &f, &err))
        fail_msg("%s", MSG(err));
    assert_int_equal(f.scene_count, 3);

    const sc_scene *s = &f.scenes[0];
    const float amb[3] = {0.125f, 0, 2};
    assert_floats(s->ambient, amb, 3);
    assert_int_equal(s->light_count, 3);
    const sc_light *l = &s->lights[0];
    assert_int_equal(l->type, SC_LIGHT_DIRECTIONAL);
    const float dir[3] = {0, -1, -2}, c0[3] = {1, 0.5f, 0};
    assert_floats(l->direction, dir, 3);
    assert_floats(l->color, c0, 3);
    l = &s->lights[1];
    assert_int_equal(l->type, SC_LIGHT_POINT);
    const float pos[3] = {-1, 0.5f, -4}, c1[3] = {0, 0, 3}, att[3] = {0.5f, 0.25f, 0.125f};
    assert_floats(l->position, pos, 3);
    assert_floats(l->color, c1, 3);
    assert_floats(l->attenuation, att, 3);
    /* (0, 0, 0) is sgapi's "no attenuation", written out as (1, 0, 0). */
    const float none[3] = {1, 0, 0};
    assert_floats(s->lights[2].attenuation, none, 3);

    const sc_draw *d = s->draws;
    assert_int_equal(d[0].lighting, SC_LIGHTING_FLAT);
    const float spec[3] = {0.5f, 2, 0};
    assert_floats(d[0].specular, spec, 3);
    assert_float_equal(d[0].shininess, 32.5f, 0);
    assert_int_equal(d[1].lighting, SC_LIGHTING_GOURAUD);
    assert_float_equal(d[1].shininess, 128.0f, 0);
    for (int i = 0; i < 3; i++) assert_float_equal(d[1].specular[i], 0.0f, 0);
    assert_int_equal(d[2].lighting, SC_LIGHTING_PHONG);
    assert_float_equal(d[2].shininess, 0.0f, 0);
    assert_int_equal(d[3].lighting, SC_LIGHTING_NONE);

    /* Without keys of its own a scene takes the top level's; the attenuation defaults to
     * (1, 0, 0). */
    s = &f.scenes[1];
    const float top_amb[3] = {0.25f, 0.5f, 0}, top_pos[3] = {1, 2, 3}, top_col[3] = {4, 0, 1};
    assert_floats(s->ambient, top_amb, 3);
    assert_int_equal(s->light_count, 1);
    assert_int_equal(s->lights[0].type, SC_LIGHT_POINT);
    assert_floats(s->lights[0].position, top_pos, 3);
    assert_floats(s->lights[0].color, top_col, 3);
    assert_floats(s->lights[0].attenuation, none, 3);
    /* An empty list replaces the top level's. */
    s = &f.scenes[2];
    assert_int_equal(s->light_count, 0);
    assert_floats(s->ambient, top_amb, 3);
    sc_free(&f);
}

/* Every loaded mesh has normals: its own, or smooth ones computed from its triangles. */
static void scene_mesh_normals(void **state) {
    tmp_dir *t = *state;
    TEST_MSG(err);
    sc_file f;
    write_file(t, "tri_n.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0.6 0 0.8\nf 1//1 2//1 3//1\n");
    if (!load_scene(t, "normals.json",
                    "{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"n\", \"draws\": ["
                    "{\"mesh\": \"tri.obj\", " MATRICES "},"
                    "{\"mesh\": \"tri_n.obj\", " MATRICES "}]}]}",
                    &f, &err))
        fail_msg("%s", MSG(err));
    assert_int_equal(f.mesh_count, 2);
    const float up[9] = {0, 0, 1, 0, 0, 1, 0, 0, 1},
                own[9] = {0.6f, 0, 0.8f, 0.6f, 0, 0.8f, 0.6f, 0, 0.8f};
    assert_non_null(f.meshes[0].normals);
    assert_floats(f.meshes[0].normals, up, 9);
    assert_floats(f.meshes[1].normals, own, 9);
    sc_free(&f);
}

/* "polygon_mode", and what a draw of a mesh with lines may be: lit Gouraud or Phong when faces give
 * every line vertex a normal, unlit always. */
static void scene_lines(void **state) {
    tmp_dir *t = *state;
    TEST_MSG(err);
    sc_file f;
    /* The outline of the triangle, vertex for vertex: its smooth normals reach the lines. */
    write_file(t, "outlined.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nl 1 2 3 1\n");
    if (!load_scene(
            t, "lines.json",
            "{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"l\", \"draws\": ["
            "{\"mesh\": \"tri.obj\", \"polygon_mode\": \"line\", \"cull\": \"back\", " MATRICES "},"
            "{\"mesh\": \"tri.obj\", \"polygon_mode\": \"fill\", \"lighting\": \"flat\", " MATRICES
            "},"
            "{\"mesh\": \"outlined.obj\", \"lighting\": \"phong\", " MATRICES "},"
            "{\"mesh\": \"outlined.obj\", \"lighting\": \"gouraud\", \"polygon_mode\": "
            "\"line\", " MATRICES "},"
            "{\"mesh\": \"stray.obj\", \"blend\": \"alpha\", " MATRICES "},"
            "{\"mesh\": \"lines.obj\", \"texture\": \"red.png\", " MATRICES "}]}]}",
            &f, &err))
        fail_msg("%s", MSG(err));
    const sc_scene *s = &f.scenes[0];
    assert_int_equal(s->draws[0].polygon_mode, SC_POLYGON_MODE_LINE);
    assert_int_equal(s->draws[0].cull, SC_CULL_BACK);
    assert_int_equal(s->draws[1].polygon_mode, SC_POLYGON_MODE_FILL);
    assert_int_equal(s->draws[3].polygon_mode, SC_POLYGON_MODE_LINE);
    const sc_mesh *outlined = &f.meshes[s->draws[2].mesh];
    assert_int_equal(outlined->index_count, 3);
    assert_int_equal(outlined->line_index_count, 6);
    const float up[9] = {0, 0, 1, 0, 0, 1, 0, 0, 1};
    assert_floats(outlined->normals, up, 9);
    /* Lines only: every mesh still gets normals (zero, without faces), and no triangles. */
    const sc_mesh *lines = &f.meshes[s->draws[5].mesh];
    assert_int_equal(lines->index_count, 0);
    assert_null(lines->indices);
    assert_int_equal(lines->line_index_count, 4);
    assert_non_null(lines->normals);
    assert_int_equal(s->draws[5].mode, SC_MODE_TEXTURE);
    sc_free(&f);

    /* Lines alone cast a shadow: the point light's near and far planes fit their segments. */
    if (!load_scene(t, "lines.json",
                    "{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"l\", \"lights\": ["
                    "{\"type\": \"point\", \"position\": [0.5, 0.5, 2], \"color\": [1, 1, 1]}],"
                    " \"shadow\": {\"light\": 0}, \"draws\": ["
                    "{\"mesh\": \"lines.obj\", " MATRICES "}]}]}",
                    &f, &err))
        fail_msg("%s", MSG(err));
    double view[16], proj[16];
    assert_true(f.scenes[0].has_shadow);
    assert_true(sc_shadow_light(&f, &f.scenes[0], view, proj));
    /* The segments lie at depth 2 from the light: near = 0.99 * 2, far = 1.01 * 2. */
    double n = proj[11] / (proj[10] - 1.0), far = proj[11] / (proj[10] + 1.0);
    if (!(fabs(n - 1.98) < 1e-9) || !(fabs(far - 2.02) < 1e-9))
        fail_msg("near %.17g, far %.17g", n, far);
    sc_free(&f);
}

/* The shadow keys: the scene's (or the file's) "shadow" with its defaults, and the draws'
 * "casts_shadow" and "receives_shadow". */
static void scene_shadow(void **state) {
    tmp_dir *t = *state;
    TEST_MSG(err);
    sc_file f;
    if (!load_scene(
            t, "shadow.json",
            "{\"width\": 4, \"height\": 4,"
            " \"lights\": [{\"type\": \"directional\", \"direction\": [0, 0, -1],"
            " \"color\": [1, 1, 1]}],"
            " \"shadow\": {\"light\": 0},"
            " \"scenes\": ["
            "{\"name\": \"inherits\", \"draws\": [{\"mesh\": \"tri.obj\", " MATRICES "}]},"
            "{\"name\": \"own\", \"lights\": ["
            "  {\"type\": \"directional\", \"direction\": [0, -1, 0], \"color\": [1, 1, 1]},"
            "  {\"type\": \"point\", \"position\": [0, 0, 5], \"color\": [1, 1, 1]}],"
            " \"shadow\": {\"light\": 1, \"size\": 512, \"bias\": -0.5, \"slope_bias\": 0,"
            "  \"pcf\": false},"
            " \"draws\": ["
            "  {\"mesh\": \"tri.obj\", \"lighting\": \"phong\", \"casts_shadow\": false, " MATRICES
            "},"
            "  {\"mesh\": \"tri.obj\", \"lighting\": \"flat\", \"receives_shadow\": false,"
            "   \"casts_shadow\": true, " MATRICES "},"
            "  {\"mesh\": \"tri.obj\", \"lighting\": \"gouraud\", \"receives_shadow\": "
            "false, " MATRICES "},"
            "  {\"mesh\": \"tri.obj\", \"receives_shadow\": true, " MATRICES "}]},"
            "{\"name\": \"none\", \"shadow\": null, \"draws\": ["
            "  {\"mesh\": \"tri.obj\", \"lighting\": \"gouraud\", " MATRICES "}]},"
            "{\"name\": \"no_casters\", \"draws\": ["
            "  {\"mesh\": \"tri.obj\", \"casts_shadow\": false, " MATRICES "}]},"
            "{\"name\": \"empty\", \"draws\": []}]}",
            &f, &err))
        fail_msg("%s", MSG(err));
    assert_int_equal(f.scene_count, 5);

    /* The file's shadow, with every default. */
    const sc_scene *s = &f.scenes[0];
    assert_true(s->has_shadow);
    assert_int_equal(s->shadow.light, 0);
    assert_int_equal(s->shadow.size, 2048);
    assert_int_equal(s->shadow.size, SC_SHADOW_SIZE);
    assert_true(s->shadow.bias == SC_SHADOW_BIAS);
    assert_true(s->shadow.slope_bias == SC_SHADOW_SLOPE_BIAS);
    assert_true(s->shadow.pcf);
    assert_true(s->draws[0].casts_shadow);
    assert_true(s->draws[0].receives_shadow);

    /* A scene's own replaces the file's as a whole. */
    s = &f.scenes[1];
    assert_true(s->has_shadow);
    assert_int_equal(s->shadow.light, 1);
    assert_int_equal(s->shadow.size, 512);
    assert_float_equal(s->shadow.bias, -0.5f, 0);
    assert_float_equal(s->shadow.slope_bias, 0.0f, 0);
    assert_false(s->shadow.pcf);
    assert_false(s->draws[0].casts_shadow);
    assert_true(s->draws[0].receives_shadow);
    assert_true(s->draws[1].casts_shadow);
    assert_false(s->draws[1].receives_shadow);
    assert_false(s->draws[2].receives_shadow);
    assert_true(s->draws[3].receives_shadow);

    /* null: none, so a Gouraud draw may keep receiving by default. */
    assert_false(f.scenes[2].has_shadow);
    assert_true(f.scenes[2].draws[0].receives_shadow);
    /* No draw casts: no shadow. */
    assert_false(f.scenes[3].has_shadow);
    assert_false(f.scenes[4].has_shadow);
    sc_free(&f);
}

/* Corners of [0, 1]^3 in view space after the cube's worldView (a translation by (0, 0, -5)). */
static void cube_corner(int k, double out[3]) {
    out[0] = k & 1 ? 1.0 : 0.0;
    out[1] = k & 2 ? 1.0 : 0.0;
    out[2] = (k & 4 ? 1.0 : 0.0) - 5.0;
}

/* The light's clip coordinates of a view-space point: proj x view x (p, 1). */
static void light_clip(const double view[16], const double proj[16], const double p[3],
                       double out[4]) {
    double v[4];
    for (int r = 0; r < 4; r++)
        v[r] =
            view[r * 4] * p[0] + view[r * 4 + 1] * p[1] + view[r * 4 + 2] * p[2] + view[r * 4 + 3];
    for (int r = 0; r < 4; r++)
        out[r] = proj[r * 4] * v[0] + proj[r * 4 + 1] * v[1] + proj[r * 4 + 2] * v[2] +
                 proj[r * 4 + 3] * v[3];
}

#define CUBE_OBJ                                                                                   \
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 0 0 1\nv 1 0 1\nv 0 1 1\nv 1 1 1\n"                     \
    "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n"
#define CUBE_WORLD_VIEW "[1,0,0,0, 0,1,0,0, 0,0,1,-5, 0,0,0,1]"

/* A directional light straight down on a unit cube: an orthographic projection that maps the
 * cube onto [-1, 1] in x and y exactly, with its depth inside (-1, 1), the top nearest. */
static void shadow_light_directional(void **state) {
    tmp_dir *t = *state;
    TEST_MSG(err);
    sc_file f;
    write_file(t, "cube.obj", CUBE_OBJ);
    if (!load_scene(t, "sun.json",
                    "{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"sun\","
                    " \"lights\": [{\"type\": \"directional\", \"direction\": [0, -2, 0],"
                    " \"color\": [1, 1, 1]}], \"shadow\": {\"light\": 0},"
                    " \"draws\": [{\"mesh\": \"cube.obj\", \"worldView\": " CUBE_WORLD_VIEW
                    ", \"proj\": " IDENTITY "}]}]}",
                    &f, &err))
        fail_msg("%s", MSG(err));
    double view[16], proj[16];
    assert_true(sc_shadow_light(&f, &f.scenes[0], view, proj));
    /* Orthographic: the last row is (0, 0, 0, 1). */
    assert_true(proj[12] == 0.0 && proj[13] == 0.0 && proj[14] == 0.0 && proj[15] == 1.0);
    double lo[3] = {1e9, 1e9, 1e9}, hi[3] = {-1e9, -1e9, -1e9}, top = 0.0, bottom = 0.0;
    for (int k = 0; k < 8; k++) {
        double p[3], c[4];
        cube_corner(k, p);
        light_clip(view, proj, p, c);
        assert_true(fabs(c[3] - 1.0) < 1e-12);
        for (int i = 0; i < 3; i++) {
            if (!(c[i] >= -1.0 - 1e-12 && c[i] <= 1.0 + 1e-12))
                fail_msg("corner %d: clip[%d] = %.17g is outside [-1, 1]", k, i, c[i]);
            lo[i] = fmin(lo[i], c[i]);
            hi[i] = fmax(hi[i], c[i]);
        }
        if (k == 2) top = c[2];
        if (k == 0) bottom = c[2];
    }
    /* x and y fit the cube exactly; depth has 1 % of its range on each side. */
    for (int i = 0; i < 2; i++) {
        assert_true(fabs(lo[i] + 1.0) < 1e-12);
        assert_true(fabs(hi[i] - 1.0) < 1e-12);
    }
    assert_true(fabs(lo[2] + 1.0 / 1.02) < 1e-12);
    assert_true(fabs(hi[2] - 1.0 / 1.02) < 1e-12);
    assert_true(top < bottom); /* the light comes from above: the top is nearer */

    /* The caster's world-view into the map, and the receivers' matrix, rounded from double. */
    float wv[16], m[16];
    const double ident[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    sc_shadow_caster_world_view(view, f.scenes[0].draws[0].world_view, wv);
    sc_mat4_mul_to_float(view, ident, m);
    for (int i = 0; i < 16; i++) {
        double want = i % 4 == 3 ? view[i] + (i < 12 ? -5.0 * view[i - 1] : 0.0) : view[i];
        assert_true(wv[i] == (float)want);
        assert_true(m[i] == (float)view[i]);
    }
    sc_free(&f);
}

/* A point light above the cube, and one inside it: every caster vertex inside the first one's
 * frustum; the second still fitted, with its widest cone, near and far fitted to what it sees. */
static void shadow_light_point(void **state) {
    tmp_dir *t = *state;
    TEST_MSG(err);
    sc_file f;
    write_file(t, "cube.obj", CUBE_OBJ);
    if (!load_scene(t, "lamp.json",
                    "{\"width\": 4, \"height\": 4, \"scenes\": ["
                    "{\"name\": \"above\", \"lights\": [{\"type\": \"point\","
                    " \"position\": [0.9, 2.5, -4.2], \"color\": [1, 1, 1]}],"
                    " \"shadow\": {\"light\": 0},"
                    " \"draws\": [{\"mesh\": \"cube.obj\", \"worldView\": " CUBE_WORLD_VIEW
                    ", \"proj\": " IDENTITY "}]},"
                    "{\"name\": \"inside\", \"lights\": [{\"type\": \"point\","
                    " \"position\": [0.5, 0.5, -4.5], \"color\": [1, 1, 1]}],"
                    " \"shadow\": {\"light\": 0},"
                    " \"draws\": [{\"mesh\": \"cube.obj\", \"worldView\": " CUBE_WORLD_VIEW
                    ", \"proj\": " IDENTITY "}]}]}",
                    &f, &err))
        fail_msg("%s", MSG(err));
    double view[16], proj[16];
    assert_true(sc_shadow_light(&f, &f.scenes[0], view, proj));
    assert_true(proj[14] == -1.0); /* perspective: w is the distance in front of the light */
    for (int k = 0; k < 8; k++) {
        double p[3], c[4];
        cube_corner(k, p);
        light_clip(view, proj, p, c);
        assert_true(c[3] > 0.0);
        for (int i = 0; i < 3; i++)
            if (!(fabs(c[i]) <= c[3]))
                fail_msg("corner %d: |clip[%d]| = %.17g > w = %.17g", k, i, fabs(c[i]), c[3]);
    }
    /* The light sits at the cube's centre: a 170 degree cone; near and far fitted to the faces
     * within it: the nearest point of a side face the cone reaches is 0.5 / tan(85 degrees)
     * ahead, the farthest the face ahead, 0.5 (near 99 %, far 101 % of those). */
    assert_true(sc_shadow_light(&f, &f.scenes[1], view, proj));
    double c = 1.0 / tan(85.0 * 3.14159265358979323846 / 180.0);
    assert_true(fabs(proj[0] - c) < 1e-12 && fabs(proj[5] - c) < 1e-12);
    double n = proj[11] / (proj[10] - 1.0), far = proj[11] / (proj[10] + 1.0);
    if (!(fabs(n - 0.99 * 0.5 * c) < 1e-9) || !(fabs(far - 1.01 * 0.5) < 1e-9))
        fail_msg("near %.17g, far %.17g", n, far);
    sc_free(&f);
}

/* Scene files that must fail, each with words its message must contain. */
static void scene_errors(void **state) {
    tmp_dir *t = *state;
    static const struct {
        const char *json, *want1, *want2;
    } cases[] = {
        {"{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"a\", \"draws\": [{\"mesh\": "
         "\"tri.obj\", \"filter\": \"trilinear\", " MATRICES "}]}]}",
         "scenes[0] ('a'), draws[0]",
         "'filter' must be one of bilinear, nearest (got 'trilinear')"},
        {"{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"a\", \"draws\": [{\"mesh\": "
         "\"tri.obj\", \"depth_compare\": 3, " MATRICES "}]}]}",
         "draws[0]", "'depth_compare' must be a string"},
        {"{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"a\", \"draws\": [{\"mesh\": "
         "\"nope.obj\", " MATRICES "}]}]}",
         "draws[0]", "nope.obj"},
        {"{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"a\", \"draws\": [{" MATRICES
         "}]}]}",
         "draws[0]", "missing 'mesh'"},
        {"{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"a\", \"draws\": [{\"mesh\": "
         "\"tri.obj\", \"texture\": \"nope.png\", " MATRICES "}]}]}",
         "draws[0]", "nope.png"},
        {"{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"a\", \"draws\": [{\"mesh\": "
         "\"tri.obj\", \"worldView\": [1,2,3], \"proj\": " IDENTITY "}]}]}",
         "draws[0]", "'worldView' must be an array of 16 numbers"},
        {"{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"a\", \"draws\": [{\"mesh\": "
         "\"tri.obj\", \"worldView\": " IDENTITY "}]}]}",
         "draws[0]", "missing 'proj'"},
        {"{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"a/b\", \"draws\": []}]}",
         "scenes[0]", "'name'"},
        {"{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"a\", \"draws\": []},"
         " {\"name\": \"a\", \"draws\": []}]}",
         "scenes[1]", "already used"},
        {"{\"width\": 0, \"height\": 4, \"scenes\": [{\"name\": \"a\", \"draws\": []}]}", "width",
         "1..16384"},
        {"{\"height\": 4, \"scenes\": [{\"name\": \"a\", \"draws\": []}]}", "scenes[0] ('a')",
         "no 'width'"},
        {"{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"a\", \"height\": 16385,"
         " \"draws\": []}]}",
         "scenes[0] ('a')", "'height'"},
        {"{\"width\": 4, \"height\": 4, \"clear_color\": [0, 0, 2, 0], \"scenes\": []}",
         "clear_color", "out of range"},
        {"{\"width\": 4, \"height\": 4, \"scenes\": []}", "'scenes' is empty", ".json"},
        {"{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"a\", \"draws\": [{\"mesh\": "
         "\"tri.obj\", \"depth_write\": 1, " MATRICES "}]}]}",
         "draws[0]", "'depth_write'"},
        {"{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"a\", \"draws\": [{\"mesh\": "
         "{\"heightmap\": \"red.png\"}, " MATRICES "}]}]}",
         "draws[0]", "2x2"},
        {"{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"a\", \"draws\": [{\"mesh\": "
         "\"tri.obj\", \"blend\": \"additive\", " MATRICES "}]}]}",
         "scenes[0] ('a'), draws[0]", "'blend' must be one of opaque, alpha (got 'additive')"},
        {"{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"a\", \"draws\": [{\"mesh\": "
         "\"tri.obj\", \"blend\": true, " MATRICES "}]}]}",
         "draws[0]", "'blend' must be a string, one of opaque, alpha"},
        {"{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"a\", \"draws\": [{\"mesh\": "
         "\"tri.obj\", \"sort\": \"front_to_back\", " MATRICES "}]}]}",
         "scenes[0] ('a'), draws[0]",
         "'sort' must be one of none, back_to_front (got 'front_to_back')"},
        {"{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"a\", \"draws\": [{\"mesh\": "
         "\"tri.obj\", " MATRICES
         "}, {\"mesh\": \"tri.obj\", \"color\": [1, 0.5, 0, 1.5], " MATRICES "}]}]}",
         "scenes[0] ('a'), draws[1]", "'color'[3] = 1.5 is out of range (0..1)"},
        {"{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"a\", \"draws\": [{\"mesh\": "
         "\"tri.obj\", \"color\": [-0.25, 0, 0, 1], " MATRICES "}]}]}",
         "draws[0]", "'color'[0] = -0.25 is out of range"},
        {"{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"a\", \"draws\": [{\"mesh\": "
         "\"tri.obj\", \"color\": [1, 1, 1], " MATRICES "}]}]}",
         "draws[0]", "'color' must be an array of 4 numbers"},
        {"{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"a\", \"draws\": [{\"mesh\": "
         "\"tri.obj\", \"color\": [1, 1, 1, 1, 1], " MATRICES "}]}]}",
         "draws[0]", "'color' must be an array of 4 numbers"},
        {"{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"a\", \"draws\": [{\"mesh\": "
         "\"tri.obj\", \"color\": [1, 1, \"1\", 1], " MATRICES "}]}]}",
         "draws[0]", "'color'[2] is not a number"},
        {"{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"a\", \"draws\": [{\"mesh\": "
         "\"tri.obj\", \"color\": 1, " MATRICES "}]}]}",
         "draws[0]", "'color' must be an array of 4 numbers"},
        /* Lighting. */
        /* Lines and wireframes. */
        {"{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"a\", \"draws\": [{\"mesh\": "
         "\"tri.obj\", \"polygon_mode\": \"point\", " MATRICES "}]}]}",
         "errors.json: scenes[0] ('a'), draws[0]: ",
         "'polygon_mode' must be one of fill, line (got 'point')"},
        {"{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"a\", \"draws\": [{\"mesh\": "
         "\"tri.obj\", \"polygon_mode\": true, " MATRICES "}]}]}",
         "draws[0]", "'polygon_mode' must be a string, one of fill, line"},
        {"{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"a\", \"draws\": [{\"mesh\": "
         "\"tri.obj\", " MATRICES "}, {\"mesh\": \"stray.obj\", \"lighting\": \"flat\", " MATRICES
         "}]}]}",
         "errors.json: scenes[0] ('a'), draws[1]: ", "'lighting' 'flat' lights faces, and mesh '"},
        {"{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"a\", \"draws\": [{\"mesh\": "
         "\"lines.obj\", \"sort\": \"back_to_front\", " MATRICES "}]}]}",
         "scenes[0] ('a'), draws[0]: ", "'sort' 'back_to_front' orders triangles, and mesh '"},
        {"{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"a\", \"draws\": [{\"mesh\": "
         "\"stray.obj\", \"lighting\": \"phong\", " MATRICES "}]}]}",
         "scenes[0] ('a'), draws[0]: ",
         "'lighting' 'phong' needs a normal at every line vertex, and line vertex (5, 5, 5)"},
        {"{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"a\", \"draws\": [{\"mesh\": "
         "\"lines.obj\", \"lighting\": \"gouraud\", " MATRICES "}]}]}",
         "draws[0]: ", "line vertex (0, 0, 0) of mesh '"},
        {"{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"a\", \"draws\": [{\"mesh\": "
         "\"tri.obj\", \"lighting\": \"toon\", " MATRICES "}]}]}",
         "scenes[0] ('a'), draws[0]",
         "'lighting' must be one of none, flat, gouraud, phong (got 'toon')"},
        {"{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"a\", \"draws\": [{\"mesh\": "
         "\"tri.obj\", \"lighting\": 1, " MATRICES "}]}]}",
         "draws[0]", "'lighting' must be a string"},
        {"{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"a\", \"draws\": [{\"mesh\": "
         "\"tri.obj\", \"shininess\": 129, " MATRICES "}]}]}",
         "scenes[0] ('a'), draws[0]", "'shininess' must be a number in 0..128 (got 129)"},
        {"{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"a\", \"draws\": [{\"mesh\": "
         "\"tri.obj\", \"shininess\": -1, " MATRICES "}]}]}",
         "draws[0]", "'shininess' must be a number in 0..128 (got -1)"},
        {"{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"a\", \"draws\": [{\"mesh\": "
         "\"tri.obj\", \"shininess\": \"8\", " MATRICES "}]}]}",
         "draws[0]", "'shininess' must be a number"},
        {"{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"a\", \"draws\": [{\"mesh\": "
         "\"tri.obj\", \"specular\": [1, -0.5, 0], " MATRICES "}]}]}",
         "scenes[0] ('a'), draws[0]", "'specular'[1] = -0.5 must be >= 0"},
        {"{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"a\", \"draws\": [{\"mesh\": "
         "\"tri.obj\", \"specular\": [1, 1], " MATRICES "}]}]}",
         "draws[0]", "'specular' must be an array of 3 numbers"},
        {"{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"a\", \"draws\": [{\"mesh\": "
         "\"tri.obj\", \"specular\": [1, 1, 1e39], " MATRICES "}]}]}",
         "draws[0]", "'specular'[2] = 1e+39 does not fit a float"},
        {"{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"a\", \"ambient\": [0, -1, 0],"
         " \"draws\": []}]}",
         "scenes[0] ('a'): ", "'ambient'[1] = -1 must be >= 0"},
        {"{\"width\": 4, \"height\": 4, \"ambient\": [1, 1], \"scenes\": []}",
         "errors.json: ", "'ambient' must be an array of 3 numbers"},
        {"{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"nine\", \"lights\": ["
         "{\"type\": \"directional\", \"direction\": [0, 0, -1], \"color\": [1, 1, 1]},"
         "{\"type\": \"directional\", \"direction\": [0, 0, -1], \"color\": [1, 1, 1]},"
         "{\"type\": \"directional\", \"direction\": [0, 0, -1], \"color\": [1, 1, 1]},"
         "{\"type\": \"directional\", \"direction\": [0, 0, -1], \"color\": [1, 1, 1]},"
         "{\"type\": \"directional\", \"direction\": [0, 0, -1], \"color\": [1, 1, 1]},"
         "{\"type\": \"directional\", \"direction\": [0, 0, -1], \"color\": [1, 1, 1]},"
         "{\"type\": \"directional\", \"direction\": [0, 0, -1], \"color\": [1, 1, 1]},"
         "{\"type\": \"directional\", \"direction\": [0, 0, -1], \"color\": [1, 1, 1]},"
         "{\"type\": \"directional\", \"direction\": [0, 0, -1], \"color\": [1, 1, 1]}],"
         " \"draws\": []}]}",
         "scenes[0] ('nine'): ", "'lights' holds 9 lights, more than the 8 allowed"},
        {"{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"a\", \"lights\": ["
         "{\"type\": \"point\", \"position\": [0, 0, 0], \"color\": [1, 1, 1]},"
         "{\"type\": \"point\", \"position\": [0, 0, 0], \"color\": [1, -0.25, 1]}],"
         " \"draws\": []}]}",
         "scenes[0] ('a'), lights[1]: ", "'color'[1] = -0.25 must be >= 0"},
        {"{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"a\", \"lights\": ["
         "{\"type\": \"spot\", \"position\": [0, 0, 0], \"color\": [1, 1, 1]}],"
         " \"draws\": []}]}",
         "scenes[0] ('a'), lights[0]: ", "'type' must be one of directional, point (got 'spot')"},
        {"{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"a\", \"lights\": ["
         "{\"position\": [0, 0, 0], \"color\": [1, 1, 1]}], \"draws\": []}]}",
         "lights[0]: ", "missing 'type'"},
        {"{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"a\", \"lights\": ["
         "{\"type\": \"directional\", \"color\": [1, 1, 1]}], \"draws\": []}]}",
         "lights[0]: ", "missing 'direction'"},
        {"{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"a\", \"lights\": ["
         "{\"type\": \"directional\", \"direction\": [0, -0.0, 0], \"color\": [1, 1, 1]}],"
         " \"draws\": []}]}",
         "lights[0]: ", "'direction' is (0, 0, 0)"},
        {"{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"a\", \"lights\": ["
         "{\"type\": \"point\", \"direction\": [0, 0, 1], \"color\": [1, 1, 1]}],"
         " \"draws\": []}]}",
         "lights[0]: ", "missing 'position'"},
        {"{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"a\", \"lights\": ["
         "{\"type\": \"point\", \"position\": [0, 0, 1]}], \"draws\": []}]}",
         "lights[0]: ", "missing 'color'"},
        {"{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"a\", \"lights\": ["
         "{\"type\": \"point\", \"position\": [0, 0, 1], \"color\": [1, 1, 1],"
         " \"attenuation\": [1, 0, -2]}], \"draws\": []}]}",
         "lights[0]: ", "'attenuation'[2] = -2 must be >= 0"},
        {"{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"a\", \"lights\": ["
         "{\"type\": \"point\", \"position\": [0, 0, 1e40], \"color\": [1, 1, 1]}],"
         " \"draws\": []}]}",
         "lights[0]: ", "'position'[2] = 1e+40 does not fit a float"},
        {"{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"a\", \"lights\": [1],"
         " \"draws\": []}]}",
         "scenes[0] ('a'), lights[0]: ", "a light must be an object"},
        {"{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"a\", \"lights\": {},"
         " \"draws\": []}]}",
         "scenes[0] ('a'): ", "'lights' must be an array"},
        /* At the top level, the light alone is named. */
        {"{\"width\": 4, \"height\": 4, \"lights\": [{\"type\": \"point\", \"position\":"
         " [0, 0, 1], \"color\": [1, 1, -1]}], \"scenes\": [{\"name\": \"a\", \"draws\": []}]}",
         "errors.json: lights[0]: ", "'color'[2] = -1 must be >= 0"},
    /* Shadows. */
#define SHADOW_SCENE(lights, shadow, draw)                                                         \
    "{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"a\", \"lights\": [" lights "],"       \
    " \"shadow\": " shadow ", \"draws\": [{\"mesh\": \"tri.obj\", " draw MATRICES "}]}]}"
#define SUN "{\"type\": \"directional\", \"direction\": [0, 0, -1], \"color\": [1, 1, 1]}"
        {SHADOW_SCENE(SUN, "{\"light\": 1}", ""),
         "scenes[0] ('a'), shadow: ", "'light' is 1, but the scene has 1 light (0..0)"},
        {SHADOW_SCENE(SUN "," SUN, "{\"light\": 3}", ""),
         "scenes[0] ('a'), shadow: ", "'light' is 3, but the scene has 2 lights (0..1)"},
        {SHADOW_SCENE("", "{\"light\": 0}", ""),
         "scenes[0] ('a'), shadow: ", "'light' is 0, but the scene has no lights"},
        {SHADOW_SCENE(SUN, "{\"size\": 16}", ""), "scenes[0] ('a'), shadow: ", "missing 'light'"},
        {SHADOW_SCENE(SUN, "{\"light\": 8}", ""), "shadow: ", "'light' must be an integer in 0..7"},
        {SHADOW_SCENE(SUN, "{\"light\": -1}", ""), "shadow: ", "'light' must be an integer"},
        {SHADOW_SCENE(SUN, "{\"light\": 0.5}", ""), "shadow: ", "'light' must be an integer"},
        {SHADOW_SCENE(SUN, "{\"light\": \"0\"}", ""), "shadow: ", "'light' must be an integer"},
        {SHADOW_SCENE(SUN, "{\"light\": 0, \"size\": 0}", ""),
         "scenes[0] ('a'), shadow: ", "'size' must be an integer in 1..16384 (got 0)"},
        {SHADOW_SCENE(SUN, "{\"light\": 0, \"size\": 16385}", ""),
         "shadow: ", "'size' must be an integer in 1..16384 (got 16385)"},
        {SHADOW_SCENE(SUN, "{\"light\": 0, \"size\": 100.5}", ""), "shadow: ", "'size'"},
        {SHADOW_SCENE(SUN, "{\"light\": 0, \"bias\": \"small\"}", ""),
         "shadow: ", "'bias' must be a number"},
        {SHADOW_SCENE(SUN, "{\"light\": 0, \"bias\": 1e39}", ""),
         "shadow: ", "'bias' = 1e+39 does not fit a float"},
        {SHADOW_SCENE(SUN, "{\"light\": 0, \"slope_bias\": null}", ""),
         "shadow: ", "'slope_bias' must be a number"},
        {SHADOW_SCENE(SUN, "{\"light\": 0, \"slope_bias\": -1e300}", ""),
         "shadow: ", "'slope_bias' = -1e+300 does not fit a float"},
        {SHADOW_SCENE(SUN, "{\"light\": 0, \"pcf\": 1}", ""),
         "scenes[0] ('a'), shadow: ", "'pcf' must be true or false"},
        {SHADOW_SCENE(SUN, "3", ""), "scenes[0] ('a'): ", "'shadow' must be an object or null"},
        {SHADOW_SCENE(SUN, "[0]", ""), "scenes[0] ('a'): ", "'shadow' must be an object or null"},
        {SHADOW_SCENE(SUN, "{\"light\": 0}", "\"casts_shadow\": \"yes\", "),
         "scenes[0] ('a'), draws[0]: ", "'casts_shadow' must be true or false"},
        {SHADOW_SCENE(SUN, "{\"light\": 0}", "\"receives_shadow\": 0, "),
         "scenes[0] ('a'), draws[0]: ", "'receives_shadow' must be true or false"},
        {SHADOW_SCENE(SUN, "null", "\"receives_shadow\": 0, "),
         "draws[0]: ", "'receives_shadow' must be true or false"},
        {"{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"a\", \"lights\": [" SUN "],"
         " \"shadow\": {\"light\": 0}, \"draws\": [{\"mesh\": \"dot.obj\", " MATRICES "}]}]}",
         "scenes[0] ('a'), shadow: ", "the light cannot be fitted to the casters"},
        {"{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"a\", \"lights\": [" SUN "],"
         " \"shadow\": {\"light\": 0}, \"draws\": [{\"mesh\": \"nan.obj\", " MATRICES "},"
         " {\"mesh\": \"tri.obj\", \"casts_shadow\": false, " MATRICES "}]}]}",
         "scenes[0] ('a'), shadow: ", "they have no finite vertex"},
        /* A light seen end-on: the triangle is a line from a light along its plane. */
        {"{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"a\", \"lights\": ["
         "{\"type\": \"directional\", \"direction\": [1, 0, 0], \"color\": [1, 1, 1]}],"
         " \"shadow\": {\"light\": 0}, \"draws\": [{\"mesh\": \"tri.obj\", \"worldView\":"
         " [1,0,0,0, 0,0,0,0, 0,0,1,0, 0,0,0,1], \"proj\": " IDENTITY "}]}]}",
         "scenes[0] ('a'), shadow: ", "they span no area as seen from the light"},
        /* The file's shadow: named alone, and against each scene's lights. */
        {"{\"width\": 4, \"height\": 4, \"shadow\": {\"light\": 0, \"size\": -3},"
         " \"scenes\": []}",
         "errors.json: shadow: ", "'size' must be an integer in 1..16384 (got -3)"},
        {"{\"width\": 4, \"height\": 4, \"shadow\": true, \"scenes\": []}",
         "errors.json: ", "'shadow' must be an object or null"},
        {"{\"width\": 4, \"height\": 4, \"lights\": [" SUN "], \"shadow\": {\"light\": 0},"
         " \"scenes\": [{\"name\": \"a\", \"draws\": []}, {\"name\": \"b\", \"lights\": [],"
         " \"draws\": []}]}",
         "scenes[1] ('b'), shadow: ", "'light' is 0, but the scene has no lights"},
#undef SHADOW_SCENE
#undef SUN
        {"{\n\"width\": 4,\n\"height\": x\n}", "invalid JSON", "line 3"},
        {"[1, 2]", "errors.json", "top level"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        TEST_MSG(err);
        sc_file f;
        if (load_scene(t, "errors.json", cases[i].json, &f, &err)) {
            sc_free(&f);
            fail_msg("case %zu loaded", i);
        }
        if (!strstr(MSG(err), cases[i].want1) || !strstr(MSG(err), cases[i].want2))
            fail_msg("case %zu: '%s' lacks '%s' or '%s'", i, MSG(err), cases[i].want1,
                     cases[i].want2);
        assert_null(f.scenes);
        assert_int_equal(f.mesh_count, 0);
    }
}

/* ---- back-to-front order --------------------------------------------------------------------- */

/* Three triangles whose vertices all share one position: the key is that position's view z. */
static void sort_order_and_ties(void **state) {
    (void)state;
    const float identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    /* Vertex z: -1, -3, -2, then -0 and +0 (a tie). */
    const float pos[5 * 4] = {0, 0, -1, 1, 0, 0, -3, 1, 0, 0, -2, 1, 0, 0, -0.0f, 1, 0, 0, 0, 1};
    const uint32_t idx[15] = {0, 0, 0, 4, 4, 4, 1, 1, 1, 3, 3, 3, 2, 2, 2};
    uint32_t out[15];
    assert_true(sc_sort_back_to_front(pos, idx, 15, identity, out));
    const uint32_t want[15] = {1, 1, 1, 2, 2, 2, 0, 0, 0, 4, 4, 4, 3, 3, 3};
    for (int i = 0; i < 15; i++) assert_int_equal(out[i], want[i]);

    /* Row 3 of worldView gives w = x: z is divided by it unless it is 1. Keys -4 / 1, -6 / 2,
     * -20 / 4: without the division the order would be C, B, A. */
    const float wx[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 1, 0, 0, 0};
    const float pos2[3 * 4] = {1, 0, -4, 1, 2, 0, -6, 1, 4, 0, -20, 1};
    const uint32_t idx2[9] = {0, 0, 0, 1, 1, 1, 2, 2, 2};
    uint32_t out2[9];
    assert_true(sc_sort_back_to_front(pos2, idx2, 9, wx, out2));
    const uint32_t want2[9] = {2, 2, 2, 0, 0, 0, 1, 1, 1};
    for (int i = 0; i < 9; i++) assert_int_equal(out2[i], want2[i]);

    /* No triangle at all, and one alone. */
    assert_true(sc_sort_back_to_front(pos, idx, 0, identity, out));
    assert_true(sc_sort_back_to_front(pos, idx, 3, identity, out));
    assert_int_equal(out[0], 0);
}

/* Many triangles with few distinct keys: the result is the stable order, whatever the merge
 * sort's run boundaries. */
static void sort_stable_at_scale(void **state) {
    (void)state;
    enum { TRIS = 1001, VERTS = 7 };
    const float m[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0.5f, 0, 1, -3, 0, 0, 0, 1};
    float pos[VERTS * 4];
    for (int v = 0; v < VERTS; v++) {
        pos[v * 4] = (float)(v % 3);
        pos[v * 4 + 1] = 0.0f;
        pos[v * 4 + 2] = (float)-v;
        pos[v * 4 + 3] = 1.0f;
    }
    uint32_t *idx = malloc(TRIS * 3 * sizeof *idx), *out = malloc(TRIS * 3 * sizeof *out);
    float *key = malloc(TRIS * sizeof *key);
    assert_non_null(idx);
    assert_non_null(out);
    assert_non_null(key);
    uint32_t seed = 7;
    for (int i = 0; i < TRIS * 3; i++) {
        seed = seed * 1664525u + 1013904223u;
        idx[i] = (seed >> 16) % VERTS;
    }
    for (int t = 0; t < TRIS; t++) {
        float z[3];
        for (int k = 0; k < 3; k++) {
            const float *p = pos + 4 * idx[3 * t + k];
            z[k] = ((m[8] * p[0] + m[9] * p[1]) + m[10] * p[2]) + m[11] * p[3];
        }
        key[t] = ((z[0] + z[1]) + z[2]) / 3.0f;
    }
    assert_true(sc_sort_back_to_front(pos, idx, TRIS * 3, m, out));
    /* The expected order by insertion sort, stable by construction. */
    int order[TRIS];
    for (int t = 0; t < TRIS; t++) {
        int j = t;
        while (j > 0 && key[order[j - 1]] > key[t]) {
            order[j] = order[j - 1];
            j--;
        }
        order[j] = t;
    }
    for (int t = 0; t < TRIS; t++)
        for (int k = 0; k < 3; k++) assert_int_equal(out[3 * t + k], idx[3 * order[t] + k]);
    free(idx);
    free(out);
    free(key);
}

/* ---- shader draws -----------------------------------------------------------------------------
 */

/* A file of one scene with one draw of tri.obj whose other keys are `keys`. */
static bool load_draw(tmp_dir *t, const char *keys, sc_file *f, sc_msg *err) {
    char json[2048];
    snprintf(json, sizeof json,
             "{\"width\": 4, \"height\": 4, \"scenes\": [{\"name\": \"s\", \"draws\": ["
             "{\"mesh\": \"tri.obj\", %s%s" MATRICES "}]}]}",
             keys, *keys ? ", " : "");
    return load_scene(t, "shader.json", json, f, err);
}

/* The shader keys: a name, uniforms, textures (loaded once per file, like "texture"), instances;
 * a shader draw neither casts nor receives the scene's shadow. */
static void scene_shader_keys(void **state) {
    tmp_dir *t = *state;
    TEST_MSG(err);
    sc_file f;
    if (!load_draw(t,
                   "\"shader\": \"my_shader2\", \"uniforms\": [1, -2.5, 1e30], "
                   "\"textures\": [\"red.png\", \"red.png\"], \"instances\": 7, "
                   "\"filter\": \"nearest\", \"wrap\": \"clamp\", \"blend\": \"alpha\"",
                   &f, &err))
        fail_msg("%s", MSG(err));
    const sc_draw *d = &f.scenes[0].draws[0];
    assert_string_equal(d->shader, "my_shader2");
    assert_int_equal(d->uniform_count, 3);
    const float u[3] = {1.0f, -2.5f, 1e30f};
    assert_memory_equal(d->uniforms, u, sizeof u);
    assert_int_equal(d->shader_texture_count, 2);
    assert_int_equal(f.texture_count, 1);
    assert_int_equal(d->shader_textures[0], 0);
    assert_int_equal(d->shader_textures[1], 0);
    assert_int_equal(d->instances, 7);
    assert_int_equal(d->texture, -1);
    assert_int_equal(d->filter, SC_FILTER_NEAREST);
    assert_false(d->casts_shadow);
    assert_false(d->receives_shadow);
    assert_int_equal(f.warning_count, 0);
    sc_free(&f);

    /* The defaults: no uniforms, no textures, one instance; a fixed draw has no shader. */
    if (!load_draw(t, "\"shader\": \"unlit\", \"uniforms\": []", &f, &err))
        fail_msg("%s", MSG(err));
    d = &f.scenes[0].draws[0];
    assert_int_equal(d->uniform_count, 0);
    assert_null(d->uniforms);
    assert_int_equal(d->shader_texture_count, 0);
    assert_int_equal(d->instances, 1);
    sc_free(&f);
    if (!load_draw(t, "", &f, &err)) fail_msg("%s", MSG(err));
    assert_null(f.scenes[0].draws[0].shader);
    assert_int_equal(f.scenes[0].draws[0].instances, 1);
    sc_free(&f);
}

/* Bad values of the shader keys are errors naming the file, the draw and the key; so are the
 * fixed keys a shader replaces, and the shader keys without a shader. */
static void scene_shader_bad_values(void **state) {
    tmp_dir *t = *state;
    static const struct {
        const char *keys, *want;
    } cases[] = {
        {"\"shader\": 3", "'shader' must be a shader's name"},
        {"\"shader\": \"\"", "'shader' must be a shader's name"},
        {"\"shader\": \"has space\"", "'shader' must be a shader's name"},
        {"\"shader\": \"u\", \"uniforms\": 1", "'uniforms' must be an array of numbers"},
        {"\"shader\": \"u\", \"uniforms\": [1, \"2\"]", "'uniforms'[1] is not a number"},
        {"\"shader\": \"u\", \"uniforms\": [1e39]", "'uniforms'[0] = 1e+39 does not fit a float"},
        {"\"shader\": \"u\", \"textures\": \"red.png\"", "'textures' must be an array of paths"},
        {"\"shader\": \"u\", \"textures\": [1]", "'textures'[0] must be a path"},
        {"\"shader\": \"u\", \"textures\": [\"red.png\", \"\"]", "'textures'[1] names an empty "
                                                                 "path"},
        {"\"shader\": \"u\", \"textures\": [\"red.png\", \"missing.png\"]", "'textures'[1]: "},
        {"\"shader\": \"u\", \"textures\": [\"red.png\", \"red.png\", \"red.png\", \"red.png\", "
         "\"red.png\", \"red.png\", \"red.png\", \"red.png\", \"red.png\"]",
         "'textures' names 9 textures, more than the 8 a draw binds"},
        {"\"shader\": \"u\", \"instances\": 0", "'instances' must be an integer in 1..16777216"},
        {"\"shader\": \"u\", \"instances\": 1.5", "'instances' must be an integer"},
        {"\"shader\": \"u\", \"instances\": \"2\"", "'instances' must be an integer"},
        {"\"shader\": \"u\", \"texture\": \"red.png\"", "'texture' with a 'shader'"},
        {"\"shader\": \"u\", \"mode\": \"texture\"", "'mode' 'texture' with a 'shader'"},
        {"\"shader\": \"u\", \"lighting\": \"phong\"", "'lighting' with a 'shader'"},
        {"\"shader\": \"u\", \"color\": [1, 0, 0, 1]", "'color' with a 'shader'"},
        {"\"shader\": \"u\", \"shininess\": 8", "'shininess' with a 'shader'"},
        {"\"shader\": \"u\", \"casts_shadow\": true", "'casts_shadow' true with a 'shader'"},
        {"\"uniforms\": [1]", "'uniforms' is for shader draws"},
        {"\"textures\": [\"red.png\"]", "'textures' is for shader draws"},
        {"\"instances\": 2", "'instances' is for shader draws"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        TEST_MSG(err);
        sc_file f;
        if (load_draw(t, cases[i].keys, &f, &err)) fail_msg("'%s' loaded", cases[i].keys);
        if (!strstr(MSG(err), "shader.json: scenes[0] ('s'), draws[0]: ") ||
            !strstr(MSG(err), cases[i].want))
            fail_msg("'%s': '%s' lacks '%s'", cases[i].keys, MSG(err), cases[i].want);
        assert_int_equal(f.scene_count, 0); /* zeroed */
    }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(obj_colour_extension),
        cmocka_unit_test(obj_colour_with_alpha),
        cmocka_unit_test(obj_bad_position_count),
        cmocka_unit_test(obj_fan_split),
        cmocka_unit_test(obj_negative_indices),
        cmocka_unit_test(obj_position_and_normal),
        cmocka_unit_test(obj_bad_index_is_an_error),
        cmocka_unit_test(obj_garbage_is_an_error),
        cmocka_unit_test(obj_shares_equal_tuples),
        cmocka_unit_test(obj_polylines),
        cmocka_unit_test(obj_bad_lines),
        cmocka_unit_test(obj_load_from_file),
        cmocka_unit_test(heightmap_mesh),
        cmocka_unit_test(scene_defaults),
        cmocka_unit_test(scene_overrides),
        cmocka_unit_test(scene_texture_null),
        cmocka_unit_test(scene_transparency),
        cmocka_unit_test(scene_lighting),
        cmocka_unit_test(scene_mesh_normals),
        cmocka_unit_test(scene_lines),
        cmocka_unit_test(scene_shadow),
        cmocka_unit_test(scene_shader_keys),
        cmocka_unit_test(scene_shader_bad_values),
        cmocka_unit_test(shadow_light_directional),
        cmocka_unit_test(shadow_light_point),
        cmocka_unit_test(scene_errors),
        cmocka_unit_test(scene_unknown_keys),
        cmocka_unit_test(sort_order_and_ties),
        cmocka_unit_test(sort_stable_at_scale),
    };
    return cmocka_run_group_tests(tests, group_setup, group_teardown);
}
