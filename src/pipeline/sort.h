/* sort.h - back-to-front order of a draw's triangles or lines (SG_SORT_BACK_TO_FRONT), for
 * transparent meshes that are not convex: each primitive is keyed by the view-space z of its
 * centroid and the draw's primitives are listed farthest first, equal keys in their original
 * order. */
#ifndef SG_SORT_H
#define SG_SORT_H

#include <stddef.h>
#include <stdint.h>

/** Bytes of scratch sg_sort_back_to_front needs for a draw (16-byte aligned pointer). */
size_t sg_sort_scratch_size(int vertex_count, size_t triangles);

/** Writes the draw's primitives, `per` indices each in `indices` (2 lines, 3 triangles, 4 quads)
 *  to out, farthest first: triangles 3 indices each (quads split into a b c, a c d first), keyed
 *  ((z0 + z1) + z2) / 3 of the view-space z of their three vertices; lines 2 indices each, keyed
 *  (z0 + z1) / 2; where
 *  (z, w) = rows 2 and 3 of world_view times the position and z is divided by w when w != 1.
 *  A NaN key sorts last. A stable LSD radix sort: linear in the triangles, the same order on any
 * thread count. */
void sg_sort_back_to_front(const float world_view[16], const float *positions, int vertex_count,
                           const uint32_t *indices, int index_count, int per, void *scratch,
                           uint32_t *out);

#endif
