/* sort.c - back-to-front order of a draw's triangles (see sort.h). */
#include "pipeline/sort.h"

#include <string.h>

size_t sg_sort_scratch_size(int vertex_count, size_t triangles) {
    /* view-space z per vertex, then two arrays of (key, triangle) pairs */
    size_t z = ((size_t)vertex_count * sizeof(float) + 15) & ~(size_t)15;
    return z + 2 * triangles * sizeof(uint64_t);
}

/* A float's bits turned into an unsigned key with the same order (-0 counted as +0, so equal
 * values keep their submission order). A NaN key (a vertex with view-space w = 0, say) sorts
 * last, whatever its sign bit. */
static uint32_t order_key(float f) {
    if (f != f) return UINT32_MAX;
    f += 0.0f; /* -0 + 0 = +0 */
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    return (u & 0x80000000u) ? ~u : u | 0x80000000u;
}

/* The view-space z of a position: row 2 of worldView over row 3, the products summed left to
 * right (the reference computes it the same way). */
static float view_z(const float m[16], const float *p) {
    float z = ((m[8] * p[0] + m[9] * p[1]) + m[10] * p[2]) + m[11] * p[3];
    float w = ((m[12] * p[0] + m[13] * p[1]) + m[14] * p[2]) + m[15] * p[3];
    return w != 1.0f ? z / w : z;
}

void sg_sort_back_to_front(const float world_view[16], const float *positions, int vertex_count,
                           const uint32_t *indices, int index_count, int per, void *scratch,
                           uint32_t *out) {
    const int quads = per == 4, lines = per == 2;
    float *z = scratch;
    size_t zbytes = ((size_t)vertex_count * sizeof(float) + 15) & ~(size_t)15;
    uint64_t *a = (uint64_t *)(void *)((char *)scratch + zbytes);
    for (int i = 0; i < vertex_count; i++) z[i] = view_z(world_view, positions + (size_t)i * 4);

    /* Primitive k is (out order before sorting): for quads, 2 triangles per quad. */
    size_t n = 0;
    for (int i = 0; i + per <= index_count; i += per) {
        const uint32_t *ix = indices + i;
        float key =
            lines ? (z[ix[0]] + z[ix[1]]) / 2.0f : ((z[ix[0]] + z[ix[1]]) + z[ix[2]]) / 3.0f;
        a[n] = (uint64_t)order_key(key) << 32 | (uint32_t)n;
        n++;
        if (quads) {
            key = ((z[ix[0]] + z[ix[2]]) + z[ix[3]]) / 3.0f;
            a[n] = (uint64_t)order_key(key) << 32 | (uint32_t)n;
            n++;
        }
    }

    /* LSD radix sort on the 32 key bits, 8 at a time; each pass is stable, and the triangle
     * number in the low half breaks no ties (it only rides along). Passes whose byte is the same
     * in every key are skipped. */
    uint64_t *b = a + n;
    for (int shift = 32; shift < 64; shift += 8) {
        size_t count[256] = {0};
        for (size_t i = 0; i < n; i++) count[(a[i] >> shift) & 255]++;
        if (n && count[(a[0] >> shift) & 255] == n) continue;
        size_t pos = 0;
        for (int d = 0; d < 256; d++) {
            size_t c = count[d];
            count[d] = pos;
            pos += c;
        }
        for (size_t i = 0; i < n; i++) b[count[(a[i] >> shift) & 255]++] = a[i];
        uint64_t *t = a;
        a = b;
        b = t;
    }

    for (size_t k = 0; k < n; k++) {
        uint32_t tri = (uint32_t)a[k];
        const uint32_t *ix = indices + (size_t)(quads ? tri / 2 : tri) * (size_t)per;
        if (lines) {
            out[2 * k] = ix[0], out[2 * k + 1] = ix[1];
            continue;
        }
        uint32_t *o = out + 3 * k;
        if (!quads) {
            o[0] = ix[0], o[1] = ix[1], o[2] = ix[2];
        } else if (tri % 2 == 0) {
            o[0] = ix[0], o[1] = ix[1], o[2] = ix[2];
        } else {
            o[0] = ix[0], o[1] = ix[2], o[2] = ix[3];
        }
    }
}
