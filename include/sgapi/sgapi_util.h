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
 *
 * Tangents
 *
 *   float tangents[4 * VERTEX_COUNT];
 *   if (sgu_compute_tangents(positions, normals, texcoords, vertex_count, indices, index_count, 0,
 *                            tangents) != 0)
 *       ...bad input or out of memory...
 *   then pass `tangents` as one of sgGeomDesc.attributes, for a normal-mapping shader.
 *
 *   A tangent per vertex: the direction in which texture coordinate s grows on the surface, for a
 *   shader that reads a tangent-space normal map. Each triangle gives the directions in which s
 *   and t grow across it (from its edges and their texture coordinate differences); a vertex sums
 *   them over the triangles that use it, and its tangent is that s direction made orthogonal to
 *   its normal (Gram-Schmidt) and normalised:
 *
 *   - out (x, y, z, w): (x, y, z) is a unit vector perpendicular to the normal; w = +1 or -1 is the
 *     handedness, so that the bitangent (where t grows) is w * cross(normal, tangent); a mirrored
 *     texture gives -1.
 *   - Vertices are not merged by position: each side of a texture seam keeps its own tangent.
 *   - Sums are formed in double, triangle after triangle in index order; a position whose w is
 *     not 1 is divided by w first; normals need not be unit length.
 *   - A vertex whose triangles' texture coordinates span no area (or whose sum is parallel to
 *     its normal, or not finite) still gets a unit tangent perpendicular to its normal (the axis
 *     least aligned with the normal, made orthogonal to it) and w = +1; a zero normal gives the
 *     s direction, or (1, 0, 0). Never NaN.
 *   - quads as for sgu_compute_normals.
 *
 * Returns 0 on success; -1 on bad input (a NULL array, vertex_count < 1, index_count < 0 or not a
 * multiple of 3, or of 4 for quads, quads not 0 or 1, an index >= vertex_count) or when memory
 * runs out. On failure out_tangents is unchanged.
 *
 * Standard shapes
 *
 *   sguShapeDesc d = {.shape = SGU_SHAPE_UV_SPHERE};     (zeros: the defaults below)
 *   int nv, ni;
 *   sgu_shape_counts(&d, &nv, &ni);
 *   float pos[4 * nv], nrm[3 * nv], uv[2 * nv]; uint32_t idx[ni];   (or malloc)
 *   sgu_shape_build(&d, pos, nrm, uv, idx);
 *   then pass them as sgGeomDesc.positions, .normals, .texcoords, .indices (triangles).
 *
 *   Every shape is centred on the origin with +y up, its triangles counter-clockwise seen from
 *   outside, with unit normals and texture coordinates in [0, 1]:
 *
 *   - cube: edge `size` (1); each face its own 4 vertices, the texture whole on each face.
 *   - tetrahedron, octahedron: corners at distance `radius` (0.5); flat faces, each face's
 *     texture coordinates (0, 0), (1, 0), (0.5, 1).
 *   - icosphere: `radius` (0.5); each of the icosahedron's 20 faces split into 4^subdivisions
 *     (0..7, default 0) triangles on the sphere; s, t = longitude, latitude.
 *   - sphere (SGU_SHAPE_UV_SPHERE): `radius` (0.5), `segments` around (32), `rings` from pole to
 *     pole (16); s around from -z, t from the south pole.
 *   - cylinder: `radius` (0.5), `height` (1) along y, `segments` (32), with both caps.
 *   - cone: `radius` (0.5) of the base at y = -height/2, apex at +height/2, `segments` (32).
 *   - torus: ring `radius` (0.35) about y, tube `tube_radius` (0.15), `segments` around the ring
 *     (32), `rings` around the tube (16).
 *   - plane: a square of side `size` (1) in the x-z plane facing +y, `segments` (1) cells a side.
 *
 *   segments 3..1024 (plane: 1..1024), rings 2..1024; sizes finite and > 0. Both calls return 0,
 *   or -1 on a bad description (nothing written).
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
/** Per-vertex tangents (see above): normals xyz, texcoords st, out_tangents xyzw per vertex. */
int sgu_compute_tangents(const float *positions, const float *normals, const float *texcoords,
                         int vertex_count, const uint32_t *indices, int index_count, int quads,
                         float *out_tangents);

typedef enum sguShape {
    SGU_SHAPE_CUBE,
    SGU_SHAPE_TETRAHEDRON,
    SGU_SHAPE_OCTAHEDRON,
    SGU_SHAPE_ICOSPHERE,
    SGU_SHAPE_UV_SPHERE,
    SGU_SHAPE_CYLINDER,
    SGU_SHAPE_CONE,
    SGU_SHAPE_TORUS,
    SGU_SHAPE_PLANE,
} sguShape;

/* A standard shape; a field left 0 takes its default (see above). */
typedef struct sguShapeDesc {
    sguShape shape;
    int segments, rings, subdivisions;
    float size, radius, height, tube_radius;
} sguShapeDesc;

/** Vertex and index counts of a shape; 0, or -1 on a bad description. */
int sgu_shape_counts(const sguShapeDesc *desc, int *vertex_count, int *index_count);
/** Fills a shape's arrays (xyzw, xyz, st per vertex; 3 indices per triangle), sized by
 *  sgu_shape_counts; 0, or -1 on a bad description. */
int sgu_shape_build(const sguShapeDesc *desc, float *positions, float *normals, float *texcoords,
                    uint32_t *indices);
/** The shape of a name: cube, tetrahedron, octahedron, icosphere, sphere, cylinder, cone, torus or
 *  plane; 0, or -1 for another name. */
int sgu_shape_from_name(const char *name, sguShape *out);

/** The number of mipmap levels of a width x height image's full chain, down to 1 x 1 (what
 *  sgImage2DDesc.mip_levels = SG_MIP_LEVELS_ALL gives); -1 for a side below 1. */
int sgu_mip_level_count(int width, int height);
/** The mipmap level below src (width x height RGBA8, tightly packed, top row first), exactly as
 *  sgapi makes it (docs/api.md, "Mipmaps"), into dst (max(1, width / 2) x max(1, height / 2)
 *  texels, whose sides go to dst_width and dst_height when not NULL); 0, or -1 on bad
 *  arguments. */
int sgu_generate_mip_level(const uint8_t *src, int width, int height, uint8_t *dst, int *dst_width,
                           int *dst_height);

#ifdef __cplusplus
}
#endif
#endif
