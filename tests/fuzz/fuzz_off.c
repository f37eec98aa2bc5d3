/* fuzz_off.c - libFuzzer target: OFF text through sc_off_parse, and the mesh it promises. */
#include "fuzz.h"
#include "../test_msg.h"

#include "off.h"

int fuzz_off(const uint8_t *data, size_t size) {
    TEST_MSG(err);
    sc_mesh m;
    sc_warnings w = {0};
    if (!sc_off_parse("fuzz.off", (const char *)data, size, &m, &w, &err)) {
        FUZZ_CHECK(MSG(err)[0] != '\0');
        FUZZ_CHECK(!m.positions && !m.colors && !m.indices && m.vertex_count == 0);
        sc_warnings_free(&w);
        return 0;
    }
    FUZZ_CHECK(m.index_count % 3 == 0 && m.index_count > 0 && m.vertex_count >= 1);
    FUZZ_CHECK(m.line_index_count == 0 && !m.line_indices);
    /* Memory the file's size justifies: a vertex of its own per face corner at most, and every
     * corner takes at least two bytes ("0 "). */
    FUZZ_CHECK(m.vertex_count <= size && m.index_count <= 3 * (uint64_t)size);
    for (uint32_t i = 0; i < m.index_count; i++) FUZZ_CHECK(m.indices[i] < m.vertex_count);
    size_t n = m.vertex_count;
    fuzz_touch(m.positions, n * 4 * sizeof(float));
    fuzz_touch(m.colors, n * 4 * sizeof(float));
    if (m.texcoords) fuzz_touch(m.texcoords, n * 2 * sizeof(float));
    if (m.normals) fuzz_touch(m.normals, n * 3 * sizeof(float));
    FUZZ_CHECK(w.count >= 0 && w.count <= SC_MAX_WARNINGS);
    sc_warnings_free(&w);
    sc_mesh_free(&m);
    return 0;
}

#ifndef FUZZ_REPLAY
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    return fuzz_off(data, size);
}
#endif
