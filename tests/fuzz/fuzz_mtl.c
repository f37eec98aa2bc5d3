/* fuzz_mtl.c - libFuzzer target: MTL text through sc_mtl_parse, and the materials it promises;
 * then OBJ text with materials (usemtl groups) through sc_obj_parse_ex. */
#include "fuzz.h"
#include "../test_msg.h"

#include <math.h>
#include <string.h>

#include "mtl.h"
#include "obj.h"

int fuzz_mtl(const uint8_t *data, size_t size) {
    TEST_MSG(err);
    sc_mtl lib;
    sc_warnings w = {0};
    if (!sc_mtl_parse("fuzz.mtl", (const char *)data, size, &lib, &w, &err)) {
        FUZZ_CHECK(MSG(err)[0] != '\0');
        FUZZ_CHECK(!lib.materials && lib.count == 0);
    } else {
        for (size_t i = 0; i < lib.count; i++) {
            const sc_material *m = &lib.materials[i];
            FUZZ_CHECK(m->name != NULL);
            fuzz_touch(m->name, strlen(m->name) + 1);
            if (m->diffuse_map) fuzz_touch(m->diffuse_map, strlen(m->diffuse_map) + 1);
            FUZZ_CHECK(m->alpha >= 0 && m->alpha <= 1);
            FUZZ_CHECK(m->shininess >= 0 && m->shininess <= 128);
            for (int c = 0; c < 3; c++)
                FUZZ_CHECK(isfinite(m->diffuse[c]) && m->diffuse[c] >= 0 &&
                           isfinite(m->specular[c]) && m->specular[c] >= 0);
            FUZZ_CHECK(sc_mtl_find(&lib, m->name) != NULL);
        }
        sc_mtl_free(&lib);
    }
    /* The same bytes as an OBJ file with materials: its groups cover its triangles in order. */
    sc_mesh mesh;
    sc_obj_extra x;
    if (sc_obj_parse_ex("fuzz.obj", (const char *)data, size, &mesh, &x, &w, &err)) {
        uint32_t at = x.group_count ? x.groups[0].first_index : 0;
        for (size_t g = 0; g < x.group_count; g++) {
            FUZZ_CHECK(x.groups[g].first_index == at && x.groups[g].index_count > 0);
            FUZZ_CHECK(x.groups[g].index_count % 3 == 0 && x.groups[g].first_index % 3 == 0);
            fuzz_touch(x.groups[g].material, strlen(x.groups[g].material) + 1);
            at += x.groups[g].index_count;
        }
        FUZZ_CHECK(!x.group_count || at == mesh.index_count);
        for (size_t i = 0; i < x.mtllib_count; i++) FUZZ_CHECK(x.mtllibs[i][0] != '\0');
        sc_obj_extra_free(&x);
        sc_mesh_free(&mesh);
    } else {
        FUZZ_CHECK(!x.groups && !x.mtllibs && x.group_count == 0 && x.mtllib_count == 0);
    }
    sc_warnings_free(&w);
    return 0;
}

#ifndef FUZZ_REPLAY
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    return fuzz_mtl(data, size);
}
#endif
