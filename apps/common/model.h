/* model.h - model files (OBJ with its materials, OFF) and standard shapes turned into scenes: one
 * draw per material, the camera framed on the models' bounding sphere, a default light.
 *
 * API-neutral, like scene.h.
 */
#ifndef SC_MODEL_H
#define SC_MODEL_H

#include <stdbool.h>
#include <stddef.h>

#include <sgapi/sgapi_util.h>

#include "scene.h"
#include "warn.h"

/** A standard shape (sgapi_util) as a mesh: white, with normals and texture coordinates. */
bool sc_shape_mesh(const sguShapeDesc *desc, sc_mesh *out, sc_msg *err);

/** True when a path names a model file this module reads (.obj or .off, any case). */
bool sc_is_model_path(const char *path);

/** Builds a file of one scene, named `name` ([A-Za-z0-9_.-]), of width x height pixels that draws
 *  every model: OBJ files with their materials (Kd, d/Tr, map_Kd; one draw per material), OFF
 *  files with their colours; the camera looks at the centre of the models' bounding sphere from
 *  the front, a little above and to the right, and frames the sphere; one directional light from
 *  over the camera's shoulder and an ambient light. What is missing (a material library, a
 *  texture) is warned of and left out; a file that cannot be read is an error. */
bool sc_model_scene(const char *const *paths, int count, const char *name, int width, int height,
                    sc_file *out, sc_warnings *warnings, sc_msg *err);

/** Appends a mesh (taken over, even on failure) and its source text (copied) to a file; *index
 *  gets its index. */
bool sc_file_add_mesh(sc_file *file, sc_mesh *mesh, const char *source, int *index);
/** Appends a draw to scene s of a file. */
bool sc_scene_add_draw(sc_scene *scene, const sc_draw *draw);

/** The centre and radius of the bounding sphere (about the box's centre) of the finite vertices
 *  of a scene's draws, in view space (each through its draw's worldView); false when there are
 *  none. */
bool sc_scene_bounds(const sc_file *file, const sc_scene *scene, double centre[3], double *radius);

/** A look-at view matrix (row-major) from eye towards target with +y up. */
void sc_look_at(const double eye[3], const double target[3], float out[16]);
/** An OpenGL perspective projection (row-major) of vertical field fovy (radians). */
void sc_perspective(double fovy, double aspect, double near_z, double far_z, float out[16]);

#endif
