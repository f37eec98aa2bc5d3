/* obj.h - meshes of triangles and lines in plain arrays, and a Wavefront OBJ loader that produces
 * them.
 *
 * API-neutral: nothing here knows about any graphics API, so every renderer can share it.
 */
#ifndef SC_OBJ_H
#define SC_OBJ_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "msg.h"
#include "warn.h"

/* Upper bound of vertex_count, index_count and line_index_count: small enough for a signed 32-bit
 * count. */
#define SC_MESH_MAX_COUNT 0x7fffffffu

/* An indexed triangle list and an indexed line list over the same vertices. Every vertex array has
 * one entry per vertex; the mesh owns them all. A mesh has triangles, lines or both. */
typedef struct sc_mesh {
    uint32_t vertex_count;
    float *positions;     /* vertex_count * 4: x, y, z, w (w = 1) */
    float *colors;        /* vertex_count * 4: r, g, b, a (a = 1 unless given; white when none) */
    float *texcoords;     /* vertex_count * 2: s, t, or NULL when no face or line uses a texture
                             coordinate */
    float *normals;       /* vertex_count * 3, or NULL when no face uses a normal */
    uint32_t index_count; /* triangles: a multiple of 3; 0 when the mesh has lines only */
    uint32_t *indices;    /* each < vertex_count; NULL when index_count is 0 */
    uint32_t line_index_count; /* line segments a -> b: a multiple of 2; 0 when there are none */
    uint32_t *line_indices;    /* each < vertex_count; NULL when line_index_count is 0 */
} sc_mesh;

/** Parses OBJ text of len bytes (NUL bytes are an error); name is used in error messages only. */
bool sc_obj_parse(const char *name, const char *text, size_t len, sc_mesh *out, sc_msg *err);
/* The triangles [first_index, first_index + index_count) of a mesh take one material. */
typedef struct sc_obj_group {
    char *material; /* the usemtl name as written */
    uint32_t first_index, index_count;
} sc_obj_group;

/* What an OBJ file says of materials: its libraries and its usemtl ranges (triangles before the
 * first usemtl belong to no group). */
typedef struct sc_obj_extra {
    char **mtllibs; /* mtllib names as written, relative to the OBJ file's folder */
    size_t mtllib_count;
    sc_obj_group *groups; /* in index order, none empty */
    size_t group_count;
} sc_obj_extra;

/** sc_obj_parse that also returns the materials (extra, may be NULL) and warns once per kind of
 *  statement it ignores (warnings, may be NULL). */
bool sc_obj_parse_ex(const char *name, const char *text, size_t len, sc_mesh *out,
                     sc_obj_extra *extra, sc_warnings *warnings, sc_msg *err);
/** Frees what sc_obj_parse_ex put in extra and zeroes it. */
void sc_obj_extra_free(sc_obj_extra *extra);
/** Reads and parses an OBJ file. On failure *out is zeroed and err says why (with the line). */
bool sc_obj_load(const char *path, sc_mesh *out, sc_msg *err);
/** Frees a mesh's arrays and zeroes it; a zeroed mesh is fine. */
void sc_mesh_free(sc_mesh *mesh);

/** Reads a whole file into a NUL-terminated buffer (for the loaders). Free with free(). */
bool sc_read_file(const char *path, char **out_data, size_t *out_len, sc_msg *err);

#endif
