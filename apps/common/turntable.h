/* turntable.h - a scene turned about a vertical axis: the camera orbiting the whole scene, or one
 * draw spinning in place (sgapi-render --turntable, --spin; docs/scale-out.md).
 *
 * API-neutral, in double, so that every renderer animates a scene with the same matrices.
 */
#ifndef SC_TURNTABLE_H
#define SC_TURNTABLE_H

#include <stdbool.h>

#include "scene.h"

/* What turns, about which point and which axis. */
typedef struct sc_turntable {
    int draw;         /* -1: the camera orbits the whole scene; else the draw that spins */
    double centre[3]; /* view space: the centre of the box of the turning draws' vertices */
    double axis[3];   /* view space, unit length: +y (the image's vertical), or a draw's up */
} sc_turntable;

/** Sets up a turntable of a scene: spin < 0 orbits the camera about the centre of every draw's
 *  view-space box, spin >= 0 (a draw index, < draw_count) spins that draw about its own. Without
 *  any finite vertex the centre is the eye (the origin). The axis is view-space +y when up < 0,
 *  else the view-space direction of draw `up`'s own +y (worldView's second column, normalised):
 *  the up of a floor, when the camera looks down on it. False when that direction is zero or not
 *  finite. */
bool sc_turntable_init(const sc_file *file, const sc_scene *scene, int spin, int up,
                       sc_turntable *out);

/** The scene at `degrees`: *out becomes a copy of *scene whose draws are `draws` (room for
 *  scene->draw_count), their worldView (and, for an orbit, the lights) turned.
 *
 *  Orbit: the camera turns by +degrees about the axis (right-hand rule: seen from above it goes
 *  counter-clockwise, moving to its right), so the scene turns by -degrees in view space: every
 *  worldView becomes T(c) R(-a) T(-c) worldView (R a rotation about the axis, Ry for +y), point
 * lights' positions and directional lights' directions turn alike (the lights belong to the world).
 * Spin: only the draw's worldView turns, by the same -degrees, so it turns as it would on the orbit
 * while the camera and the rest stay. Products are formed in double and each entry rounded once to
 * float. At 0 degrees (or any whole turn) the scene is copied as it is, so that frame 0 is the
 * scene as written, bit for bit. */
void sc_turntable_at(const sc_turntable *t, const sc_scene *scene, double degrees, sc_draw *draws,
                     sc_scene *out);

#endif
