/* shadow.h - where a scene's shadow light looks from and what it sees: its view and projection,
 * fitted to the casters' view-space bounds (docs/scene-format.md, "Shadows"), and the matrix
 * products every renderer forms from them.
 *
 * API-neutral, in double, so that every renderer draws the shadow map with the same matrices.
 */
#ifndef SC_SHADOW_H
#define SC_SHADOW_H

#include <stdbool.h>

#include "scene.h"

/** The view and the projection of the scene's shadow light, row-major (column vectors, OpenGL
 *  clip space), from every finite view-space vertex of every draw with casts_shadow. False when
 *  the scene has no shadow, no caster has a finite vertex, or the casters are too small to fit a
 *  projection to (a single point, or a line seen end-on from the light): the matrices are then
 *  the identity. */
bool sc_shadow_light(const sc_file *file, const sc_scene *scene, double light_view[16],
                     double light_proj[16]);

/** The axis-aligned box of a scene's draws in view space: every finite (worldView * p).xyz /
 *  (worldView * p).w of every vertex of the mesh of draw `draw`, or of every draw when draw < 0
 *  (the same points the shadow's fit takes from its casters). False, and a box of zeros, when
 *  there is no such vertex. */
bool sc_view_bounds(const sc_file *file, const sc_scene *scene, int draw, double lo[3],
                    double hi[3]);

/** out = a x b (row-major 4x4), formed in double and each entry rounded once to float. */
void sc_mat4_mul_to_float(const double a[16], const double b[16], float out[16]);

/** The world-view a caster is drawn with into the shadow map: light_view x world_view. */
void sc_shadow_caster_world_view(const double light_view[16], const float world_view[16],
                                 float out[16]);

#endif
