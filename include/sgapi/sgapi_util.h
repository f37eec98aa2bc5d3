/* sgapi_util.h - helpers that prepare vertex arrays for sgapi. They only fill arrays the caller
 * owns and never call the core API, so they work with any renderer.
 *
 * Link the static library sgapi_util (CMake: sgapi::sgapi_util; it needs only libm).
 *
 * Normals
 *
 *   float normals[3 * VERTEX_COUNT];
 *   if (sgu_compute_normals(positions, vertex_count, indices, index_count, 0, normals) != 0)
 *       ...bad input or out of memory...
 *   then pass `normals` as sgGeomDesc.normals.
 *
 *   Smooth vertex normals for a mesh that has none. The normal of a vertex is the normalised sum
 *   of the unnormalised face normals (v1 - v0) x (v2 - v0) of every triangle that touches a vertex
 *   with the same position, so a larger triangle weighs more, and a mesh whose vertices are
 *   duplicated per face (to carry per-face texture coordinates, say) still comes out smooth:
 *
 *   - "Same position" means bitwise-equal x, y and z, where -0 counts as +0 and w is ignored; a
 *     position whose w is not 1 is divided by w (in float) first.
 *   - Sums are formed in double, triangle after triangle in index order, then normalised in
 *     double and stored as float. A sum that is zero or not finite (a degenerate triangle alone,
 *     or a triangle with a NaN or infinite position) gives (0, 0, 0): never NaN.
 *   - Winding: counter-clockwise triangles (as seen from outside) give outward normals.
 *   - quads = 1 reads the indices as quads a b c d, drawn as the triangles a b c and a c d (as
 *     sgapi's SG_PRIMITIVE_QUADS); quads = 0 as triangles.
 *   - It takes O(n log n) time and O(vertex_count) memory, whatever the index count.
 *
 * Returns 0 on success; -1 on bad input (a NULL array, vertex_count < 1, index_count < 0 or not
 * a multiple of 3, or of 4 for quads, quads not 0 or 1, an index >= vertex_count) or when memory
 * runs out. On failure out_normals is unchanged. indices may be NULL when index_count is 0 (every
 * normal is then (0, 0, 0)).
 */
#ifndef SGAPI_UTIL_H
#define SGAPI_UTIL_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Smooth vertex normals (see above): positions are xyzw per vertex, out_normals xyz per vertex. */
int sgu_compute_normals(const float *positions, int vertex_count, const uint32_t *indices,
                        int index_count, int quads, float *out_normals);

#ifdef __cplusplus
}
#endif
#endif
