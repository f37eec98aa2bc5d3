/* shadow.c - the shadow light's view and projection, fitted to the view-space bounds of the
 * casters, in double (docs/scene-format.md, "Shadows"). */
#include "shadow.h"

#include <float.h>
#include <math.h>
#include <stddef.h>
#include <string.h>

static const double PI = 3.14159265358979323846;

static void identity(double m[16]) {
    memset(m, 0, 16 * sizeof *m);
    m[0] = m[5] = m[10] = m[15] = 1.0;
}

static double dot3(const double a[3], const double b[3]) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void cross3(const double a[3], const double b[3], double out[3]) {
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

static void normalize3(double v[3]) {
    double len = sqrt(dot3(v, v));
    for (int i = 0; i < 3; i++) v[i] /= len;
}

/* Bounds of a set of points; count says how many were added. */
typedef struct bounds {
    double lo[3], hi[3];
    size_t count;
} bounds;

static void add_point(bounds *b, const double p[3]) {
    for (int i = 0; i < 3; i++) {
        if (b->count == 0 || p[i] < b->lo[i]) b->lo[i] = p[i];
        if (b->count == 0 || p[i] > b->hi[i]) b->hi[i] = p[i];
    }
    b->count++;
}

/* Which draws a box takes: every caster (the shadow's fit), every draw, or one draw (>= 0). */
enum { CASTERS = -1, ALL_DRAWS = -2 };

/* Adds every finite view-space vertex of the draws `which` names to b, after the row-major matrix
 * to (NULL: none). A vertex is (worldView * p).xyz / (worldView * p).w; one whose result is not
 * finite (a NaN vertex, w = 0) cannot be bounded and is left out. */
static void add_draws(const sc_file *f, const sc_scene *s, int which, const double *to, bounds *b) {
    for (size_t d = 0; d < s->draw_count; d++) {
        const sc_draw *draw = &s->draws[d];
        if (which == CASTERS ? !draw->casts_shadow : which >= 0 && (size_t)which != d) continue;
        const sc_mesh *m = &f->meshes[draw->mesh];
        const float *wv = draw->world_view;
        for (uint32_t v = 0; v < m->vertex_count; v++) {
            const float *p = m->positions + (size_t)v * 4;
            double e[4], q[3];
            for (int r = 0; r < 4; r++)
                e[r] = (double)wv[r * 4] * p[0] + (double)wv[r * 4 + 1] * p[1] +
                       (double)wv[r * 4 + 2] * p[2] + (double)wv[r * 4 + 3] * p[3];
            for (int i = 0; i < 3; i++) q[i] = e[i] / e[3];
            if (!isfinite(q[0]) || !isfinite(q[1]) || !isfinite(q[2])) continue;
            if (to) {
                double t[3];
                for (int r = 0; r < 3; r++)
                    t[r] = to[r * 4] * q[0] + to[r * 4 + 1] * q[1] + to[r * 4 + 2] * q[2] +
                           to[r * 4 + 3];
                add_point(b, t);
            } else {
                add_point(b, q);
            }
        }
    }
}

bool sc_view_bounds(const sc_file *f, const sc_scene *s, int draw, double lo[3], double hi[3]) {
    bounds box = {0};
    add_draws(f, s, draw < 0 ? ALL_DRAWS : draw, NULL, &box);
    for (int i = 0; i < 3; i++) {
        lo[i] = box.count ? box.lo[i] : 0.0;
        hi[i] = box.count ? box.hi[i] : 0.0;
    }
    return box.count > 0;
}

/* A caster vertex in the light's view (v): (worldView * p).xyz / w, then v; false when not
 * finite. */
static bool light_space(const float *wv, const float *p, const double v[16], double out[3]) {
    double e[4], q[3];
    for (int r = 0; r < 4; r++)
        e[r] = (double)wv[r * 4] * p[0] + (double)wv[r * 4 + 1] * p[1] +
               (double)wv[r * 4 + 2] * p[2] + (double)wv[r * 4 + 3] * p[3];
    for (int k = 0; k < 3; k++) q[k] = e[k] / e[3];
    for (int r = 0; r < 3; r++)
        out[r] = v[r * 4] * q[0] + v[r * 4 + 1] * q[1] + v[r * 4 + 2] * q[2] + v[r * 4 + 3];
    return isfinite(out[0]) && isfinite(out[1]) && isfinite(out[2]);
}

/* Clips a convex polygon (n points, room for n + 5) to a * x + b * y + c * z >= 0. */
static int clip_plane(double (*poly)[3], int n, double a, double b, double c) {
    double out[12][3];
    int m = 0;
    for (int i = 0; i < n; i++) {
        const double *p = poly[i], *q = poly[(i + 1) % n];
        double dp = a * p[0] + b * p[1] + c * p[2], dq = a * q[0] + b * q[1] + c * q[2];
        if (dp >= 0.0) memcpy(out[m++], p, sizeof out[0]);
        if ((dp >= 0.0) != (dq >= 0.0)) {
            double t = dp / (dp - dq);
            for (int k = 0; k < 3; k++) out[m][k] = p[k] + t * (q[k] - p[k]);
            m++;
        }
    }
    memcpy(poly, out, (size_t)m * sizeof out[0]);
    return m;
}

/* Adds the depths (along the light's -z) of what remains of a convex polygon of n points (n <= 3;
 * 2 for a line segment, walked there and back) inside the square frustum of half-angle tangent t
 * to the range [*lo, *hi]; *any says whether the range has a point. */
static void clip_depths(double (*poly)[3], int n, double t, double *lo, double *hi, bool *any) {
    /* Inside: |x| <= t * depth and |y| <= t * depth, depth = -z. */
    n = clip_plane(poly, n, -1.0, 0.0, -t);
    n = n ? clip_plane(poly, n, 1.0, 0.0, -t) : 0;
    n = n ? clip_plane(poly, n, 0.0, -1.0, -t) : 0;
    n = n ? clip_plane(poly, n, 0.0, 1.0, -t) : 0;
    for (int k = 0; k < n; k++) {
        double depth = -poly[k][2];
        if (!(depth >= 0.0)) continue;
        if (!*any || depth < *lo) *lo = depth;
        if (!*any || depth > *hi) *hi = depth;
        *any = true;
    }
}

/* The nearest and farthest depth, along the light's -z, of the casters' triangles and line
 * segments within its square frustum of half-angle tangent t (view v): each clipped to the
 * frustum's four sides, so one that passes close to the light between its vertices counts there.
 * Also the largest half-angle tangent of any caster vertex (infinite for one at or behind the
 * light). False when nothing lies within the frustum. */
static bool view_depths(const sc_file *f, const sc_scene *s, const double v[16], double t,
                        double *lo, double *hi, double *spread) {
    bool any = false;
    *spread = 0.0;
    for (size_t d = 0; d < s->draw_count; d++) {
        const sc_draw *draw = &s->draws[d];
        if (!draw->casts_shadow) continue;
        const sc_mesh *m = &f->meshes[draw->mesh];
        for (uint32_t i = 0; i < m->vertex_count; i++) {
            double l[3];
            if (!light_space(draw->world_view, m->positions + (size_t)i * 4, v, l)) continue;
            double depth = -l[2];
            double off = depth > 0.0 ? fmax(fabs(l[0]), fabs(l[1])) / depth : INFINITY;
            if (off > *spread) *spread = off;
        }
        for (uint32_t i = 0; i + 2 < m->index_count; i += 3) {
            double poly[12][3];
            bool ok = true;
            for (int k = 0; k < 3 && ok; k++)
                ok = light_space(draw->world_view, m->positions + (size_t)m->indices[i + k] * 4, v,
                                 poly[k]);
            if (ok) clip_depths(poly, 3, t, lo, hi, &any);
        }
        for (uint32_t i = 0; i + 1 < m->line_index_count; i += 2) {
            double poly[12][3];
            bool ok = true;
            for (int k = 0; k < 2 && ok; k++)
                ok = light_space(draw->world_view,
                                 m->positions + (size_t)m->line_indices[i + k] * 4, v, poly[k]);
            if (ok) clip_depths(poly, 2, t, lo, hi, &any);
        }
    }
    return any;
}

/* gluLookAt from eye along the unit vector fwd: the light looks down its -z. Up is view-space +y,
 * or +x when fwd is within about 8 degrees of the y axis (a cross product with a near-parallel
 * vector would lose its precision). */
static void look_at(const double eye[3], const double fwd[3], double m[16]) {
    double up[3] = {0.0, 1.0, 0.0}, s[3], u[3];
    if (fabs(fwd[1]) > 0.99) up[0] = 1.0, up[1] = 0.0;
    cross3(fwd, up, s);
    normalize3(s);
    cross3(s, fwd, u);
    identity(m);
    for (int i = 0; i < 3; i++) {
        m[i] = s[i];
        m[4 + i] = u[i];
        m[8 + i] = -fwd[i];
    }
    m[3] = -dot3(s, eye);
    m[7] = -dot3(u, eye);
    m[11] = dot3(fwd, eye);
}

/* glOrtho: x in [l, r], y in [b, t] and z in [-f, -n] to [-1, 1]. */
static void ortho(double l, double r, double b, double t, double n, double f, double m[16]) {
    identity(m);
    m[0] = 2.0 / (r - l);
    m[3] = -(r + l) / (r - l);
    m[5] = 2.0 / (t - b);
    m[7] = -(t + b) / (t - b);
    m[10] = -2.0 / (f - n);
    m[11] = -(f + n) / (f - n);
}

/* gluPerspective with a square aspect; fovy in radians. */
static void perspective(double fovy, double n, double f, double m[16]) {
    double c = 1.0 / tan(fovy / 2.0);
    memset(m, 0, 16 * sizeof *m);
    m[0] = c;
    m[5] = c;
    m[10] = (f + n) / (n - f);
    m[11] = 2.0 * f * n / (n - f);
    m[14] = -1.0;
}

/* Every entry finite and within a float's range, so the renderers' float copies are finite. */
static bool fits_float(const double m[16]) {
    for (int i = 0; i < 16; i++)
        if (!(fabs(m[i]) <= FLT_MAX)) return false;
    return true;
}

bool sc_shadow_light(const sc_file *f, const sc_scene *s, double view[16], double proj[16]) {
    identity(view);
    identity(proj);
    if (!s->has_shadow || s->shadow.light < 0 || s->shadow.light >= s->light_count) return false;
    bounds box = {0};
    add_draws(f, s, CASTERS, NULL, &box);
    if (box.count == 0) return false;
    double centre[3], half[3];
    for (int i = 0; i < 3; i++) {
        centre[i] = 0.5 * (box.lo[i] + box.hi[i]);
        half[i] = 0.5 * (box.hi[i] - box.lo[i]);
    }
    const double R = sqrt(dot3(half, half)); /* half the diagonal: every caster is this close */
    if (!(R > 0.0) || !isfinite(R)) return false;

    const sc_light *light = &s->lights[s->shadow.light];
    double v[16], p[16];
    if (light->type == SC_LIGHT_DIRECTIONAL) {
        /* From 2R before the centre, against the light's direction: every caster is then between
         * R and 3R in front of the light. */
        double d[3] = {light->direction[0], light->direction[1], light->direction[2]}, eye[3];
        normalize3(d);
        for (int i = 0; i < 3; i++) eye[i] = centre[i] - d[i] * 2.0 * R;
        look_at(eye, d, v);
        bounds ls = {0};
        add_draws(f, s, CASTERS, v, &ls);
        /* Depth gets 1 % of its range on each side, so that no caster touches the near or far
         * plane after rounding; casters flat across the light get 1 % of R. */
        double n = -ls.hi[2], fa = -ls.lo[2], margin = 0.01 * (fa - n);
        if (!(margin > 0.0)) margin = 0.01 * R;
        if (!(ls.hi[0] > ls.lo[0]) || !(ls.hi[1] > ls.lo[1])) return false;
        ortho(ls.lo[0], ls.hi[0], ls.lo[1], ls.hi[1], n - margin, fa + margin, p);
    } else {
        double L[3] = {light->position[0], light->position[1], light->position[2]}, fwd[3];
        for (int i = 0; i < 3; i++) fwd[i] = centre[i] - L[i];
        double dist = sqrt(dot3(fwd, fwd)), fovy, n;
        if (dist > 0.0) {
            for (int i = 0; i < 3; i++) fwd[i] /= dist;
        } else {
            fwd[0] = 0.0, fwd[1] = 0.0, fwd[2] = -1.0; /* at the centre: any way will do */
        }
        look_at(L, fwd, v);
        if (dist <= R) {
            /* Inside the bounds no cone holds every caster: the widest useful one. */
            fovy = 170.0 * PI / 180.0;
            n = 1e-3 * R;
        } else {
            /* The cone that touches the bounding sphere, and 2 degrees more. */
            fovy = 2.0 * asin(fmin(R / dist, 0.999)) + 2.0 * PI / 180.0;
            n = fmax(fmax(dist - R, 0.01 * R), 1e-3);
        }
        double fa = dist + R;
        /* Near and far fitted to the caster vertices the light sees: the depth a perspective map
         * resolves between two points grows with near, so a light close to or among the casters
         * keeps the precision it would have far away. A caster crossing the near plane between
         * its vertices loses that part. */
        double lo = 0.0, hi = 0.0, spread = 0.0;
        if (view_depths(f, s, v, tan(0.5 * fovy), &lo, &hi, &spread)) {
            /* The cone that holds every caster vertex, and 2 degrees more, when narrower: a light
             * among the casters need not spread its texels over 170 degrees. */
            double tight = 2.0 * atan(spread) + 2.0 * PI / 180.0;
            if (tight < fovy) {
                fovy = tight;
                view_depths(f, s, v, tan(0.5 * fovy), &lo, &hi, &spread);
            }
            n = fmax(0.99 * lo, 1e-3 * R);
            fa = fmin(1.01 * hi, fa);
        }
        if (!(fa > n)) return false;
        perspective(fovy, n, fa, p);
    }
    if (!fits_float(v) || !fits_float(p)) {
        identity(view);
        identity(proj);
        return false;
    }
    memcpy(view, v, sizeof v);
    memcpy(proj, p, sizeof p);
    return true;
}

void sc_mat4_mul_to_float(const double a[16], const double b[16], float out[16]) {
    for (int r = 0; r < 4; r++)
        for (int c = 0; c < 4; c++)
            out[r * 4 + c] = (float)(a[r * 4] * b[c] + a[r * 4 + 1] * b[4 + c] +
                                     a[r * 4 + 2] * b[8 + c] + a[r * 4 + 3] * b[12 + c]);
}

void sc_shadow_caster_world_view(const double light_view[16], const float world_view[16],
                                 float out[16]) {
    double wv[16];
    for (int i = 0; i < 16; i++) wv[i] = world_view[i];
    sc_mat4_mul_to_float(light_view, wv, out);
}
