/* normals.c - smooth vertex normals from positions and indices (sgapi_util.h).
 *
 * Vertices are grouped by position: a sort of their indices by the bit patterns of x, y and z,
 * so equal positions end up next to each other whatever the mesh's vertex order. Each group sums
 * the face normals of the triangles that touch it; every vertex of the group gets that sum,
 * normalised.
 */
#include <sgapi/sgapi_util.h>

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* A vertex's position as sort key, and the vertex it belongs to. */
typedef struct vkey {
    uint32_t x, y, z;
    uint32_t vertex;
} vkey;

/* The position a vertex is grouped and lit by: xyz / w unless w is 1, with -0 turned into +0 so
 * that both zeros compare equal as bits. */
static void position_of(const float *p, float out[3]) {
    const float w = p[3];
    for (int c = 0; c < 3; c++) {
        float v = w == 1.0f ? p[c] : p[c] / w;
        out[c] = v == 0.0f ? 0.0f : v;
    }
}

static uint32_t bits_of(float f) {
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    return u;
}

/* Any total order works for grouping; the vertex index as the last key makes it unique, so the
 * result does not depend on the qsort implementation. */
static int cmp_key(const void *pa, const void *pb) {
    const vkey *a = pa, *b = pb;
    if (a->x != b->x) return a->x < b->x ? -1 : 1;
    if (a->y != b->y) return a->y < b->y ? -1 : 1;
    if (a->z != b->z) return a->z < b->z ? -1 : 1;
    return (a->vertex > b->vertex) - (a->vertex < b->vertex);
}

/* Adds face normal n to a group's sum. */
static void add3(double *acc, const double n[3]) {
    acc[0] += n[0];
    acc[1] += n[1];
    acc[2] += n[2];
}

int sgu_compute_normals(const float *positions, int vertex_count, const uint32_t *indices,
                        int index_count, int quads, float *out_normals) {
    if (!positions || !out_normals || vertex_count < 1 || index_count < 0 ||
        (quads != 0 && quads != 1) || (index_count > 0 && !indices))
        return -1;
    const int per_prim = quads ? 4 : 3;
    if (index_count % per_prim != 0) return -1;
    const size_t n = (size_t)vertex_count;
    for (int i = 0; i < index_count; i++)
        if (indices[i] >= n) return -1;
    if (n > SIZE_MAX / sizeof(vkey)) return -1;

    /* Group id of every vertex: the rank of its distinct position. */
    vkey *keys = malloc(n * sizeof *keys);
    uint32_t *group = malloc(n * sizeof *group);
    if (!keys || !group) {
        free(keys);
        free(group);
        return -1;
    }
    for (size_t v = 0; v < n; v++) {
        float p[3];
        position_of(positions + v * 4, p);
        keys[v] = (vkey){bits_of(p[0]), bits_of(p[1]), bits_of(p[2]), (uint32_t)v};
    }
    qsort(keys, n, sizeof *keys, cmp_key);
    size_t groups = 0;
    for (size_t i = 0; i < n; i++) {
        if (i > 0 && (keys[i].x != keys[i - 1].x || keys[i].y != keys[i - 1].y ||
                      keys[i].z != keys[i - 1].z))
            groups++;
        group[keys[i].vertex] = (uint32_t)groups;
    }
    groups++;
    free(keys);

    double *acc = calloc(groups, 3 * sizeof *acc);
    if (!acc) {
        free(group);
        return -1;
    }
    /* Quad a b c d is the triangles a b c and a c d, as the rasteriser draws it. */
    for (int base = 0; base < index_count; base += per_prim) {
        for (int t = 0; t < per_prim - 2; t++) {
            const uint32_t tri[3] = {indices[base], indices[base + 1 + t], indices[base + 2 + t]};
            float p[3][3];
            for (int k = 0; k < 3; k++) position_of(positions + (size_t)tri[k] * 4, p[k]);
            const double a[3] = {(double)p[1][0] - p[0][0], (double)p[1][1] - p[0][1],
                                 (double)p[1][2] - p[0][2]};
            const double b[3] = {(double)p[2][0] - p[0][0], (double)p[2][1] - p[0][1],
                                 (double)p[2][2] - p[0][2]};
            const double fn[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                                  a[0] * b[1] - a[1] * b[0]};
            /* Each group the triangle touches counts it once, even when two of its corners
             * share a position. */
            const uint32_t g0 = group[tri[0]], g1 = group[tri[1]], g2 = group[tri[2]];
            add3(acc + (size_t)g0 * 3, fn);
            if (g1 != g0) add3(acc + (size_t)g1 * 3, fn);
            if (g2 != g0 && g2 != g1) add3(acc + (size_t)g2 * 3, fn);
        }
    }
    for (size_t v = 0; v < n; v++) {
        const double *s = acc + (size_t)group[v] * 3;
        const double len = sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
        float *o = out_normals + v * 3;
        /* Zero, NaN or infinite: no direction to give, and no NaN to hand on. */
        if (len > 0.0 && isfinite(len)) {
            o[0] = (float)(s[0] / len);
            o[1] = (float)(s[1] / len);
            o[2] = (float)(s[2] / len);
        } else {
            o[0] = o[1] = o[2] = 0.0f;
        }
    }
    free(acc);
    free(group);
    return 0;
}
