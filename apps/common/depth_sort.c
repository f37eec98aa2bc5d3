/* depth_sort.c - back-to-front order of a mesh's triangles: a key per triangle, then a stable
 * merge sort. The key's arithmetic is spelled out operation by operation (and the file is built
 * without fused multiply-add) so that every renderer that follows the format orders ties alike.
 */
#include "depth_sort.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* View-space z of one vertex: row 2 of m times p, divided by row 3 times p unless that is 1. */
static float view_z(const float m[16], const float *p) {
    float z = ((m[8] * p[0] + m[9] * p[1]) + m[10] * p[2]) + m[11] * p[3];
    float w = ((m[12] * p[0] + m[13] * p[1]) + m[14] * p[2]) + m[15] * p[3];
    return w != 1.0f ? z / w : z;
}

/* a sorts before b: numbers by value (so -0 and +0 tie), every NaN after every number. */
static bool before(float a, float b) {
    return a < b || (!isnan(a) && isnan(b));
}

/* Merges the sorted runs src[lo, mid) and src[mid, hi) into dst; on ties the left run wins,
 * which keeps the sort stable. */
static void merge(const float *key, const uint32_t *src, uint32_t *dst, size_t lo, size_t mid,
                  size_t hi) {
    size_t i = lo, j = mid, k = lo;
    while (i < mid && j < hi) dst[k++] = before(key[src[j]], key[src[i]]) ? src[j++] : src[i++];
    while (i < mid) dst[k++] = src[i++];
    while (j < hi) dst[k++] = src[j++];
}

bool sc_sort_back_to_front(const float *positions, const uint32_t *indices, uint32_t index_count,
                           const float world_view[16], uint32_t *out_indices) {
    size_t n = index_count / 3;
    float *key = malloc((n ? n : 1) * sizeof *key);
    uint32_t *a = malloc((n ? n : 1) * sizeof *a);
    uint32_t *b = malloc((n ? n : 1) * sizeof *b);
    if (!key || !a || !b) {
        free(key);
        free(a);
        free(b);
        return false;
    }
    for (size_t t = 0; t < n; t++) {
        const uint32_t *tri = indices + 3 * t;
        float z0 = view_z(world_view, positions + 4 * (size_t)tri[0]);
        float z1 = view_z(world_view, positions + 4 * (size_t)tri[1]);
        float z2 = view_z(world_view, positions + 4 * (size_t)tri[2]);
        key[t] = ((z0 + z1) + z2) / 3.0f;
        a[t] = (uint32_t)t;
    }
    /* Bottom-up: runs of 1, 2, 4, ... merged back and forth between a and b. */
    uint32_t *src = a, *dst = b;
    for (size_t width = 1; width < n; width *= 2) {
        for (size_t lo = 0; lo < n; lo += 2 * width) {
            size_t mid = lo + width < n ? lo + width : n;
            size_t hi = lo + 2 * width < n ? lo + 2 * width : n;
            merge(key, src, dst, lo, mid, hi);
        }
        uint32_t *swap = src;
        src = dst;
        dst = swap;
    }
    for (size_t t = 0; t < n; t++) memcpy(out_indices + 3 * t, indices + 3 * (size_t)src[t], 12);
    for (size_t i = 3 * n; i < index_count; i++) out_indices[i] = indices[i];
    free(key);
    free(a);
    free(b);
    return true;
}
