/* depth_sort.h - back-to-front order of a mesh's triangles, as the scene format's
 * "sort": "back_to_front" defines it (docs/scene-format.md), for renderers whose API does not sort.
 *
 * API-neutral: plain arrays in, an index list out.
 */
#ifndef SC_DEPTH_SORT_H
#define SC_DEPTH_SORT_H

#include <stdbool.h>
#include <stdint.h>

/** Writes the triangles of indices (index_count / 3 of them, 3 indices each) to out_indices,
 *  farthest first: by key = ((z0 + z1) + z2) / 3, smallest first, where z_i is row 2 of the
 *  row-major world_view times the vertex's (x, y, z, w), divided by row 3 times it when that is
 *  not 1, each dot product summed left to right in float. Equal keys (-0 equals +0) keep their
 *  order; NaN keys go last, in their order. positions holds x, y, z, w per vertex; out_indices
 *  must not overlap indices. Indices past the last whole triangle are copied as they are. False
 *  when out of memory (out_indices is then untouched). */
bool sc_sort_back_to_front(const float *positions, const uint32_t *indices, uint32_t index_count,
                           const float world_view[16], uint32_t *out_indices);

#endif
