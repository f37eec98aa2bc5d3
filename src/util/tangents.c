/* tangents.c - per-vertex tangents for normal mapping from positions, normals, texture coordinates
 * and indices (sgapi_util.h).
 *
 * Each triangle contributes the directions in which s and t grow across it (Lengyel's method);
 * each vertex sums them over its triangles, then its tangent is the s direction made orthogonal
 * to the vertex normal (Gram-Schmidt) and normalised, with the handedness of the (tangent,
 * bitangent, normal) frame in w. Vertices are not merged by position: a texture seam keeps
 * separate tangents on its two sides, as it keeps separate texture coordinates.
 */
#include <sgapi/sgapi_util.h>

#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>

/* The position as the normals are made from it: xyz / w unless w is 1. */
static void position_of(const float *p, double out[3]) {
    const float w = p[3];
    for (int c = 0; c < 3; c++) out[c] = w == 1.0f ? (double)p[c] : (double)(p[c] / w);
}

static double dot3(const double a[3], const double b[3]) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* Adds one triangle's s and t directions to its three vertices; a triangle whose texture
 * coordinates span no area (or whose values are not finite) adds nothing. */
static void add_triangle(const float *positions, const float *texcoords, const uint32_t v[3],
                         double *sdir, double *tdir) {
    double p[3][3];
    for (int k = 0; k < 3; k++) position_of(positions + (size_t)v[k] * 4, p[k]);
    const float *t0 = texcoords + (size_t)v[0] * 2, *t1 = texcoords + (size_t)v[1] * 2,
                *t2 = texcoords + (size_t)v[2] * 2;
    const double du1 = (double)t1[0] - t0[0], dv1 = (double)t1[1] - t0[1];
    const double du2 = (double)t2[0] - t0[0], dv2 = (double)t2[1] - t0[1];
    const double det = du1 * dv2 - du2 * dv1;
    if (det == 0.0 || !isfinite(det)) return;
    const double r = 1.0 / det;
    double s[3], t[3];
    for (int c = 0; c < 3; c++) {
        const double e1 = p[1][c] - p[0][c], e2 = p[2][c] - p[0][c];
        s[c] = (e1 * dv2 - e2 * dv1) * r;
        t[c] = (e2 * du1 - e1 * du2) * r;
    }
    if (!isfinite(dot3(s, s)) || !isfinite(dot3(t, t))) return;
    for (int k = 0; k < 3; k++) {
        for (int c = 0; c < 3; c++) {
            sdir[(size_t)v[k] * 3 + c] += s[c];
            tdir[(size_t)v[k] * 3 + c] += t[c];
        }
    }
}

/* A unit vector perpendicular to unit n: the axis least aligned with n, made orthogonal to it. */
static void any_perpendicular(const double n[3], double out[3]) {
    const double ax = fabs(n[0]), ay = fabs(n[1]), az = fabs(n[2]);
    double a[3] = {0.0, 0.0, 0.0};
    a[ax <= ay && ax <= az ? 0 : ay <= az ? 1 : 2] = 1.0;
    const double d = dot3(n, a);
    double len2 = 0.0;
    for (int c = 0; c < 3; c++) {
        out[c] = a[c] - n[c] * d;
        len2 += out[c] * out[c];
    }
    const double inv = 1.0 / sqrt(len2); /* >= 2/3 for a unit n: never 0 */
    for (int c = 0; c < 3; c++) out[c] *= inv;
}

/* The tangent of one vertex from its summed directions and its normal. */
static void finish_vertex(const float *normal, const double s[3], const double t[3], float out[4]) {
    double n[3] = {normal[0], normal[1], normal[2]};
    const double nl = sqrt(dot3(n, n));
    if (!(nl > 0.0) || !isfinite(nl)) {
        /* No usable normal: any tangent is as good as another; the s direction when there is
         * one, else +x. */
        const double sl = sqrt(dot3(s, s));
        const bool use_s = sl > 0.0 && isfinite(sl);
        for (int c = 0; c < 3; c++) out[c] = use_s ? (float)(s[c] / sl) : (c == 0 ? 1.0f : 0.0f);
        out[3] = 1.0f;
        return;
    }
    for (int c = 0; c < 3; c++) n[c] /= nl;
    double tan[3];
    const double d = dot3(n, s);
    for (int c = 0; c < 3; c++) tan[c] = s[c] - n[c] * d;
    const double tl = sqrt(dot3(tan, tan));
    /* Relative to the sum's own length, so that a tangent barely off the normal, which rounding
     * alone decides, counts as none. */
    if (tl > 1e-9 * sqrt(dot3(s, s)) && isfinite(tl)) {
        for (int c = 0; c < 3; c++) tan[c] /= tl;
    } else {
        any_perpendicular(n, tan);
    }
    /* Handedness: whether the t direction lies on the side of n x tangent. */
    const double b[3] = {n[1] * tan[2] - n[2] * tan[1], n[2] * tan[0] - n[0] * tan[2],
                         n[0] * tan[1] - n[1] * tan[0]};
    for (int c = 0; c < 3; c++) out[c] = (float)tan[c];
    out[3] = dot3(b, t) < 0.0 ? -1.0f : 1.0f;
}

int sgu_compute_tangents(const float *positions, const float *normals, const float *texcoords,
                         int vertex_count, const uint32_t *indices, int index_count, int quads,
                         float *out_tangents) {
    if (!positions || !normals || !texcoords || !out_tangents || vertex_count < 1 ||
        index_count < 0 || (quads != 0 && quads != 1) || (index_count > 0 && !indices))
        return -1;
    const int per_prim = quads ? 4 : 3;
    if (index_count % per_prim != 0) return -1;
    const size_t n = (size_t)vertex_count;
    for (int i = 0; i < index_count; i++)
        if (indices[i] >= n) return -1;
    double *sdir = calloc(n, 3 * sizeof *sdir); /* calloc checks the product */
    double *tdir = calloc(n, 3 * sizeof *tdir);
    if (!sdir || !tdir) {
        free(sdir);
        free(tdir);
        return -1;
    }
    for (int i = 0; i < index_count; i += per_prim) {
        const uint32_t *q = indices + i;
        const uint32_t a[3] = {q[0], q[1], q[2]};
        add_triangle(positions, texcoords, a, sdir, tdir);
        if (quads) { /* a b c d as the triangles a b c and a c d, as sgapi draws quads */
            const uint32_t b[3] = {q[0], q[2], q[3]};
            add_triangle(positions, texcoords, b, sdir, tdir);
        }
    }
    for (size_t v = 0; v < n; v++)
        finish_vertex(normals + v * 3, sdir + v * 3, tdir + v * 3, out_tangents + v * 4);
    free(sdir);
    free(tdir);
    return 0;
}
