/* fuzz_obj.c - libFuzzer target: OBJ text through sc_obj_parse, and the mesh it promises. */
#include "fuzz.h"
#include "../test_msg.h"

#include "obj.h"

int fuzz_obj(const uint8_t *data, size_t size) {
    TEST_MSG(err);
    sc_mesh m;
    if (!sc_obj_parse("fuzz.obj", (const char *)data, size, &m, &err)) {
        /* A failure says why and leaves nothing to free. */
        FUZZ_CHECK(MSG(err)[0] != '\0');
        FUZZ_CHECK(!m.positions && !m.colors && !m.indices && !m.line_indices &&
                   m.vertex_count == 0);
        return 0;
    }
    /* What obj.h promises of a mesh. */
    FUZZ_CHECK(m.index_count % 3 == 0 && m.line_index_count % 2 == 0 && m.vertex_count >= 1);
    FUZZ_CHECK(m.index_count + (uint64_t)m.line_index_count > 0);
    FUZZ_CHECK((m.index_count == 0) == !m.indices && (m.line_index_count == 0) == !m.line_indices);
    FUZZ_CHECK(m.index_count <= SC_MESH_MAX_COUNT && m.vertex_count <= SC_MESH_MAX_COUNT);
    FUZZ_CHECK(m.line_index_count <= SC_MESH_MAX_COUNT);
    for (uint32_t i = 0; i < m.index_count; i++) FUZZ_CHECK(m.indices[i] < m.vertex_count);
    for (uint32_t i = 0; i < m.line_index_count; i++)
        FUZZ_CHECK(m.line_indices[i] < m.vertex_count);
    size_t n = m.vertex_count;
    fuzz_touch(m.positions, n * 4 * sizeof(float));
    fuzz_touch(m.colors, n * 4 * sizeof(float));
    if (m.texcoords) fuzz_touch(m.texcoords, n * 2 * sizeof(float));
    if (m.normals) fuzz_touch(m.normals, n * 3 * sizeof(float));
    sc_mesh_free(&m);
    return 0;
}

#ifndef FUZZ_REPLAY
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    return fuzz_obj(data, size);
}
#endif
