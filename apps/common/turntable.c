/* turntable.c - a scene turned about view-space +y through a centre (see turntable.h). */
#include "turntable.h"

#include <math.h>
#include <string.h>

#include "shadow.h"

static const double PI = 3.14159265358979323846;

bool sc_turntable_init(const sc_file *f, const sc_scene *s, int spin, int up, sc_turntable *out) {
    memset(out, 0, sizeof *out);
    out->draw = spin < 0 ? -1 : spin;
    double lo[3], hi[3];
    if (sc_view_bounds(f, s, out->draw, lo, hi))
        for (int i = 0; i < 3; i++) out->centre[i] = 0.5 * (lo[i] + hi[i]);
    out->axis[1] = 1.0;
    if (up < 0) return true;
    const float *wv = s->draws[up].world_view;
    double a[3] = {wv[1], wv[5], wv[9]};
    double len = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    if (!(len > 0.0) || !isfinite(len)) return false;
    for (int i = 0; i < 3; i++) out->axis[i] = a[i] / len;
    return true;
}

/* Sine and cosine of an angle in degrees, exact at multiples of 90 (a quarter turn of a frame
 * count divisible by 4 is then an exact rotation, with no 6e-17 left in a zero). */
static void sincos_degrees(double degrees, double *s, double *c) {
    double d = fmod(degrees, 360.0);
    if (d < 0.0) d += 360.0;
    int quadrant = (int)(d / 90.0);
    double r = (d - 90.0 * quadrant) * (PI / 180.0), sr = sin(r), cr = cos(r);
    switch (quadrant & 3) {
    case 0:
        *s = sr, *c = cr;
        break;
    case 1:
        *s = cr, *c = -sr;
        break;
    case 2:
        *s = -sr, *c = -cr;
        break;
    default:
        *s = -cr, *c = sr;
        break;
    }
}

/* A point (or a direction, without the translation) times the upper 3 x 4 of m. */
static void turn_point(const double m[16], const float in[3], float out[3]) {
    for (int r = 0; r < 3; r++)
        out[r] =
            (float)(m[r * 4] * in[0] + m[r * 4 + 1] * in[1] + m[r * 4 + 2] * in[2] + m[r * 4 + 3]);
}

static void turn_vector(const double m[16], const float in[3], float out[3]) {
    for (int r = 0; r < 3; r++)
        out[r] = (float)(m[r * 4] * in[0] + m[r * 4 + 1] * in[1] + m[r * 4 + 2] * in[2]);
}

void sc_turntable_at(const sc_turntable *t, const sc_scene *s, double degrees, sc_draw *draws,
                     sc_scene *out) {
    *out = *s;
    out->draws = draws;
    if (s->draw_count) memcpy(draws, s->draws, s->draw_count * sizeof *draws);
    double sn, cs;
    sincos_degrees(degrees, &sn, &cs);
    if (sn == 0.0 && cs == 1.0) return; /* the scene as written */
    /* M = T(c) R(-a) T(-c): the scene turns one way as the camera goes the other. R(-a) about
     * the unit axis u is cos a I - sin a [u]x + (1 - cos a) u u^T (Rodrigues); about +y it is
     * Ry(-a), exactly. */
    const double *c = t->centre, *u = t->axis;
    const double k = 1.0 - cs;
    double m[16] = {cs + k * u[0] * u[0],
                    k * u[0] * u[1] + sn * u[2],
                    k * u[0] * u[2] - sn * u[1],
                    0.0,
                    k * u[1] * u[0] - sn * u[2],
                    cs + k * u[1] * u[1],
                    k * u[1] * u[2] + sn * u[0],
                    0.0,
                    k * u[2] * u[0] + sn * u[1],
                    k * u[2] * u[1] - sn * u[0],
                    cs + k * u[2] * u[2],
                    0.0,
                    0.0,
                    0.0,
                    0.0,
                    1.0};
    for (int r = 0; r < 3; r++)
        m[r * 4 + 3] = c[r] - (m[r * 4] * c[0] + m[r * 4 + 1] * c[1] + m[r * 4 + 2] * c[2]);
    for (size_t i = 0; i < s->draw_count; i++) {
        if (t->draw >= 0 && (size_t)t->draw != i) continue;
        double wv[16];
        for (int k = 0; k < 16; k++) wv[k] = s->draws[i].world_view[k];
        sc_mat4_mul_to_float(m, wv, draws[i].world_view);
    }
    if (t->draw >= 0) return; /* a spinning draw leaves the world's lights where they are */
    for (int i = 0; i < s->light_count; i++) {
        sc_light *l = &out->lights[i];
        turn_vector(m, s->lights[i].direction, l->direction);
        turn_point(m, s->lights[i].position, l->position);
    }
}
