/* test_models.c - standard shapes (sgapi_util), the OFF and MTL parsers, OBJ material groups and
 * the loaders' tolerance of other tools' text (CRLF, byte-order marks, tabs). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <sgapi/sgapi_util.h>

#include "model.h"
#include "mtl.h"
#include "obj.h"
#include "off.h"
#include "scene.h"
#include "test_msg.h"

/* Every shape: indices in range, unit normals, texcoords in [0, 1], and each triangle wound
 * counter-clockwise seen from outside (its face normal agrees with its vertices' normals). */
static void shapes_are_closed_and_outward(void **state) {
    (void)state;
    for (int s = SGU_SHAPE_CUBE; s <= SGU_SHAPE_PLANE; s++) {
        for (int sub = 0; sub < 3; sub++) {
            sguShapeDesc d = {.shape = (sguShape)s, .subdivisions = sub, .segments = 5 + sub};
            int nv, ni;
            assert_int_equal(sgu_shape_counts(&d, &nv, &ni), 0);
            assert_true(nv > 0 && ni > 0 && ni % 3 == 0);
            float *p = malloc((size_t)nv * 16), *n = malloc((size_t)nv * 12);
            float *t = malloc((size_t)nv * 8);
            uint32_t *idx = malloc((size_t)ni * 4);
            assert_int_equal(sgu_shape_build(&d, p, n, t, idx), 0);
            for (int i = 0; i < nv; i++) {
                double l = sqrt(n[i * 3] * n[i * 3] + n[i * 3 + 1] * n[i * 3 + 1] +
                                n[i * 3 + 2] * n[i * 3 + 2]);
                assert_true(fabs(l - 1) < 1e-5);
                assert_true(t[i * 2] >= 0 && t[i * 2] <= 1 && t[i * 2 + 1] >= 0 &&
                            t[i * 2 + 1] <= 1);
                assert_true(p[i * 4 + 3] == 1.0f);
            }
            for (int k = 0; k < ni; k += 3) {
                assert_true(idx[k] < (uint32_t)nv && idx[k + 1] < (uint32_t)nv &&
                            idx[k + 2] < (uint32_t)nv);
                const float *a = p + idx[k] * 4, *b = p + idx[k + 1] * 4, *c = p + idx[k + 2] * 4;
                double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
                double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
                double f[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                               u[0] * v[1] - u[1] * v[0]};
                double area = sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
                if (area < 1e-9) continue; /* a cone's apex: no face to test */
                double dot = 0;
                for (int j = 0; j < 3; j++)
                    dot += f[0] * n[idx[k + j] * 3] + f[1] * n[idx[k + j] * 3 + 1] +
                           f[2] * n[idx[k + j] * 3 + 2];
                if (dot <= 0) fail_msg("shape %d, triangle %d wound inwards", s, k / 3);
            }
            free(p), free(n), free(t), free(idx);
        }
    }
}

static void shape_bad_descriptions(void **state) {
    (void)state;
    int nv, ni;
    assert_int_equal(sgu_shape_counts(&(sguShapeDesc){.shape = (sguShape)99}, &nv, &ni), -1);
    assert_int_equal(
        sgu_shape_counts(&(sguShapeDesc){.segments = 2, .shape = SGU_SHAPE_TORUS}, &nv, &ni), -1);
    assert_int_equal(
        sgu_shape_counts(&(sguShapeDesc){.radius = -1, .shape = SGU_SHAPE_CONE}, &nv, &ni), -1);
    assert_int_equal(
        sgu_shape_counts(&(sguShapeDesc){.subdivisions = 8, .shape = SGU_SHAPE_ICOSPHERE}, &nv,
                         &ni),
        -1);
    assert_int_equal(sgu_shape_counts(NULL, &nv, &ni), -1);
    sguShape s;
    assert_int_equal(sgu_shape_from_name("sphere", &s), 0);
    assert_int_equal(s, SGU_SHAPE_UV_SPHERE);
    assert_int_equal(sgu_shape_from_name("spheres", &s), -1);
}

static bool off(const char *text, sc_mesh *m, sc_warnings *w, sc_msg *err) {
    return sc_off_parse("t.off", text, strlen(text), m, w, err);
}

/* Face colours as integers are 0..255, as floats 0..1; each coloured face has its own vertices;
 * a quad is fanned into two triangles. */
static void off_face_colours(void **state) {
    (void)state;
    sc_mesh m;
    TEST_MSG(err);
    assert_true(off("OFF\n# c\n\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n"
                    "3 0 1 2 255 0 51\n3 0 2 3 0.5 1 0 0.25\n",
                    &m, NULL, &err));
    assert_int_equal(m.vertex_count, 6);
    assert_int_equal(m.index_count, 6);
    assert_true(fabsf(m.colors[0] - 1) < 1e-6f && fabsf(m.colors[2] - 0.2f) < 1e-6f);
    assert_true(fabsf(m.colors[3] - 1) < 1e-6f);
    assert_true(fabsf(m.colors[12] - 0.5f) < 1e-6f && fabsf(m.colors[15] - 0.25f) < 1e-6f);
    sc_mesh_free(&m);
    assert_true(off("OFF 4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n", &m, NULL, &err));
    assert_int_equal(m.vertex_count, 4); /* shared: no face colour */
    assert_int_equal(m.index_count, 6);
    uint32_t want[6] = {0, 1, 2, 0, 2, 3};
    assert_memory_equal(m.indices, want, sizeof want);
    sc_mesh_free(&m);
}

/* COFF, NOFF and STOFF vertices; a BOM, CRLF and tabs. */
static void off_variants(void **state) {
    (void)state;
    sc_mesh m;
    TEST_MSG(err);
    assert_true(off("\xEF\xBB\xBF"
                    "CNOFF\r\n3\t1 0\r\n0 0 0 0 0 1 255 0 0 255\r\n1 0 0 0 0 1 0 255 0 255\r\n"
                    "0 1 0  0 0 1  0 0 255 128\r\n3 0 1 2\r\n",
                    &m, NULL, &err));
    assert_non_null(m.normals);
    assert_true(m.colors[0] == 1 && m.colors[5] == 1 && fabsf(m.colors[11] - 128 / 255.0f) < 1e-6f);
    sc_mesh_free(&m);
    assert_true(off("STOFF\n3 1 0\n0 0 0 0 0\n1 0 0 1 0\n0 1 0 0 1\n3 0 1 2\n", &m, NULL, &err));
    assert_non_null(m.texcoords);
    assert_true(m.texcoords[2] == 1 && m.texcoords[5] == 1);
    sc_mesh_free(&m);
}

/* Errors name the line; a header claiming more than the file holds is refused before any
 * allocation of that size. */
static void off_errors(void **state) {
    (void)state;
    sc_mesh m;
    TEST_MSG(err);
    sc_warnings w = {0};
    assert_false(off("OFF\n4000000000 1 0\n0 0 0\n", &m, NULL, &err));
    assert_non_null(strstr(MSG(err), "t.off:2:"));
    assert_false(off("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n", &m, NULL, &err));
    assert_non_null(strstr(MSG(err), "t.off:6:"));
    assert_non_null(strstr(MSG(err), "out of range"));
    assert_false(off("OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", &m, NULL, &err));
    assert_non_null(strstr(MSG(err), "ends after 1 of its 2 faces"));
    assert_false(off("OFF\n3 1 0\n0 0\n1 0 0\n0 1 0\n3 0 1 2\n", &m, NULL, &err));
    assert_false(off("4OFF\n", &m, NULL, &err));
    assert_false(off("", &m, NULL, &err));
    /* Small faces and colour-map indices: skipped with one warning per kind. */
    assert_true(
        off("OFF\n3 4 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n1 2\n3 0 1 2 4\n3 0 2 1 5\n", &m, &w, &err));
    assert_int_equal(w.count, 2);
    assert_int_equal(m.index_count, 6);
    sc_mesh_free(&m);
    sc_warnings_free(&w);
}

static void mtl_materials(void **state) {
    (void)state;
    const char *t = "# exported\r\nnewmtl red paint\r\nKd 1 0 0\r\nKs 0.5 0.5 0.5\r\nNs 500\r\n"
                    "d 0.5\r\nmap_Kd -s 2 2 1 -clamp on tex\\bricks 2.png\r\n"
                    "newmtl glass\nTr 0.75\nKa 1 1 1\nillum 2\n";
    sc_mtl lib;
    sc_warnings w = {0};
    TEST_MSG(err);
    assert_true(sc_mtl_parse("t.mtl", t, strlen(t), &lib, &w, &err));
    assert_int_equal(lib.count, 2);
    const sc_material *r = sc_mtl_find(&lib, "red paint");
    assert_non_null(r);
    assert_true(r->diffuse[0] == 1 && r->diffuse[1] == 0 && r->alpha == 0.5f);
    assert_true(r->shininess == 128);
    assert_string_equal(r->diffuse_map, "tex/bricks 2.png");
    const sc_material *g = sc_mtl_find(&lib, "glass");
    assert_true(fabsf(g->alpha - 0.25f) < 1e-6f);
    assert_int_equal(w.count, 1); /* Ka and illum: one warning */
    sc_warnings_free(&w);
    sc_mtl_free(&lib);
    const char *bad = "newmtl a\nKd 1 x 0\n";
    assert_false(sc_mtl_parse("b.mtl", bad, strlen(bad), &lib, NULL, &err));
    assert_non_null(strstr(MSG(err), "b.mtl:2:"));
    const char *early = "d 0.5\n";
    assert_false(sc_mtl_parse("c.mtl", early, strlen(early), &lib, NULL, &err));
    assert_non_null(strstr(MSG(err), "c.mtl:1:"));
}

/* usemtl ranges of triangles, mtllib names with spaces; a BOM and CRLF in OBJ text. */
static void obj_groups(void **state) {
    (void)state;
    const char *t = "\xEF\xBB\xBFmtllib my lib.mtl\r\nv 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nv 1 1 0\r\n"
                    "f 1 2 3\r\nusemtl a\r\nf 1 2 3 4\r\nusemtl  b c \r\nusemtl a\r\nf 2 3 4\r\n"
                    "p 1\r\n";
    sc_mesh m;
    sc_obj_extra x;
    sc_warnings w = {0};
    TEST_MSG(err);
    assert_true(sc_obj_parse_ex("t.obj", t, strlen(t), &m, &x, &w, &err));
    assert_int_equal(x.mtllib_count, 1);
    assert_string_equal(x.mtllibs[0], "my lib.mtl");
    assert_int_equal(x.group_count, 2); /* "b c" holds no triangle */
    assert_string_equal(x.groups[0].material, "a");
    assert_int_equal(x.groups[0].first_index, 3);
    assert_int_equal(x.groups[0].index_count, 6);
    assert_int_equal(x.groups[1].first_index, 9);
    assert_int_equal(x.groups[1].index_count, 3);
    assert_int_equal(w.count, 1); /* points */
    sc_warnings_free(&w);
    sc_obj_extra_free(&x);
    sc_mesh_free(&m);
}

/* A model OFF file's faces with alpha below 1 (Geomview's facecube.off writes 0.75) are drawn as an
 * MTL 'd' below 1 is: after the opaque faces, blended and sorted, without depth writes. */
static void off_model_alpha(void **state) {
    (void)state;
    const char *path = "off_model_alpha.off";
    FILE *fp = fopen(path, "w");
    assert_non_null(fp);
    fputs("# per-face colour, two faces opaque\nOFF\n8 6 12\n1 1 1\n1 1 -1\n1 -1 1\n1 -1 -1\n"
          "-1 1 1\n-1 1 -1\n-1 -1 1\n-1 -1 -1\n4 0 2 3 1 .05 .8 .1 .75\n"
          "4 4 5 7 6 .2 .05 .8 1\n4 0 4 6 2 .9 .9 .02 .75\n4 1 3 7 5 0 .7 .4 .75\n"
          "4 0 1 5 4 .1 .4 .7 1\n4 2 6 7 3 191 191 0 191\n",
          fp);
    fclose(fp);
    sc_file f;
    sc_warnings w = {0};
    sc_msg err = {0};
    assert_true(sc_model_scene(&path, 1, "m", 64, 48, &f, &w, &err));
    const sc_scene *sc = &f.scenes[0];
    assert_int_equal(sc->draw_count, 2);
    const sc_draw *solid = &sc->draws[0], *glass = &sc->draws[1];
    assert_int_equal(solid->blend, SC_BLEND_OPAQUE);
    assert_true(solid->depth_write);
    assert_int_equal(f.meshes[solid->mesh].index_count, 2 * 6);
    assert_int_equal(glass->blend, SC_BLEND_ALPHA);
    assert_int_equal(glass->sort, SC_SORT_BACK_TO_FRONT);
    assert_false(glass->depth_write);
    const sc_mesh *gm = &f.meshes[glass->mesh];
    assert_int_equal(gm->index_count, 4 * 6);
    for (uint32_t v = 0; v < gm->vertex_count; v++)
        assert_float_equal(gm->colors[v * 4 + 3], 0.75f, 0.005f);
    sc_free(&f);
    /* All opaque: one draw, as before. */
    fp = fopen(path, "w");
    assert_non_null(fp);
    fputs("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 0.9 0.1 0.1 1.0\n", fp);
    fclose(fp);
    assert_true(sc_model_scene(&path, 1, "m", 64, 48, &f, &w, &err));
    assert_int_equal(f.scenes[0].draw_count, 1);
    assert_int_equal(f.scenes[0].draws[0].blend, SC_BLEND_OPAQUE);
    sc_free(&f);
    sc_warnings_free(&w);
    sc_msg_free(&err);
    remove(path);
}

/* Scene files: {"shape": ...} meshes (shared when equal), bad parameters refused with the draw
 * named. */
static void scene_shapes(void **state) {
    (void)state;
    const char *mats = "\"worldView\": [1,0,0,0, 0,1,0,0, 0,0,1,-3, 0,0,0,1], "
                       "\"proj\": [1,0,0,0, 0,1,0,0, 0,0,-1,-0.2, 0,0,-1,0]";
    char json[2048];
    TEST_MSG(err);
    snprintf(json, sizeof json,
             "{\"width\": 8, \"height\": 8, \"scenes\": [{\"name\": \"s\", \"draws\": ["
             "{\"mesh\": {\"shape\": \"torus\", \"rings\": 8}, %s},"
             "{\"mesh\": {\"shape\": \"torus\", \"rings\": 8}, %s},"
             "{\"mesh\": {\"shape\": \"cube\", \"size\": 2}, %s}]}]}",
             mats, mats, mats);
    sc_file f;
    assert_true(sc_parse("/nonexistent/s.json", json, strlen(json), &f, &err));
    assert_int_equal(f.mesh_count, 2);
    assert_int_equal(f.scenes[0].draws[0].mesh, f.scenes[0].draws[1].mesh);
    assert_int_equal(f.meshes[1].vertex_count, 24);
    assert_non_null(f.meshes[0].normals);
    assert_non_null(f.meshes[0].texcoords);
    sc_free(&f);
    snprintf(json, sizeof json,
             "{\"width\": 8, \"height\": 8, \"scenes\": [{\"name\": \"s\", \"draws\": ["
             "{\"mesh\": {\"shape\": \"sphere\", \"segments\": 2}, %s}]}]}",
             mats);
    assert_false(sc_parse("/nonexistent/s.json", json, strlen(json), &f, &err));
    assert_non_null(strstr(MSG(err), "draws[0]"));
    assert_non_null(strstr(MSG(err), "segments"));
    snprintf(json, sizeof json,
             "{\"width\": 8, \"height\": 8, \"scenes\": [{\"name\": \"s\", \"draws\": ["
             "{\"mesh\": {\"shape\": \"blob\"}, %s}]}]}",
             mats);
    assert_false(sc_parse("/nonexistent/s.json", json, strlen(json), &f, &err));
    assert_non_null(strstr(MSG(err), "'shape' must be one of"));
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(shapes_are_closed_and_outward),
        cmocka_unit_test(shape_bad_descriptions),
        cmocka_unit_test(off_face_colours),
        cmocka_unit_test(off_variants),
        cmocka_unit_test(off_errors),
        cmocka_unit_test(off_model_alpha),
        cmocka_unit_test(mtl_materials),
        cmocka_unit_test(obj_groups),
        cmocka_unit_test(scene_shapes),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
