/* clip.c - Sutherland-Hodgman clipping in homogeneous clip space (see clip.h). */
#include "pipeline/clip.h"

#include <float.h>
#include <math.h>
#include <string.h>
/* SSE lanes only where SSE also does scalar float maths: then they round as the scalar code. */
#if defined(__SSE_MATH__)
#include <xmmintrin.h>
#endif

sg_guard sg_guard_for_viewport(int width, int height) {
    /* x_screen = (x_ndc + 1) * W / 2 stays in [-G, G] when |x_ndc| <= 2G / W - 1. */
    sg_guard g;
    g.gx = (float)(2.0 * SG_GUARD_BAND_PIXELS / width - 1.0);
    g.gy = (float)(2.0 * SG_GUARD_BAND_PIXELS / height - 1.0);
    return g;
}

/* Signed distance to a plane: >= 0 inside. */
static float plane_dist(uint32_t plane, const float p[4], const sg_guard *g) {
    switch (plane) {
    case SG_CLIP_NEAR:
        return p[2] + p[3];
    case SG_CLIP_FAR:
        return p[3] - p[2];
    case SG_CLIP_WMIN:
        return p[3] - SG_CLIP_W_MIN;
    case SG_CLIP_LEFT:
        return p[0] + g->gx * p[3];
    case SG_CLIP_RIGHT:
        return g->gx * p[3] - p[0];
    case SG_CLIP_BOTTOM:
        return p[1] + g->gy * p[3];
    default:
        return g->gy * p[3] - p[1];
    }
}

uint32_t sg_clip_outcode(const float pos[4], const sg_guard *guard) {
#if defined(__SSE_MATH__)
    const __m128 p = _mm_loadu_ps(pos);
    /* isfinite: |v| <= FLT_MAX, false for NaN and infinity. */
    const __m128 mag = _mm_andnot_ps(_mm_set1_ps(-0.0f), p);
    if (_mm_movemask_ps(_mm_cmple_ps(mag, _mm_set1_ps(FLT_MAX))) != 15)
        return SG_CLIP_NONFINITE | ((1u << SG_CLIP_PLANE_COUNT) - 1);
    /* The seven distances of plane_dist, in bit order, as the lanes of two sums: a - b is exactly
     * a + (-b), so every lane rounds as plane_dist does. The eighth lane is 0 + 0: inside. */
    float x = pos[0], y = pos[1], z = pos[2], w = pos[3];
    float gxw = guard->gx * w, gyw = guard->gy * w;
    __m128 d0 = _mm_add_ps(_mm_setr_ps(z, w, w, x), _mm_setr_ps(w, -z, -SG_CLIP_W_MIN, gxw));
    __m128 d1 = _mm_add_ps(_mm_setr_ps(gxw, y, gyw, 0.0f), _mm_setr_ps(-x, gyw, -y, 0.0f));
    /* Outside: !(d >= 0), as in the scalar code below. */
    const __m128 zero = _mm_setzero_ps();
    return (uint32_t)(_mm_movemask_ps(_mm_cmpnge_ps(d0, zero)) |
                      _mm_movemask_ps(_mm_cmpnge_ps(d1, zero)) << 4);
#else
    if (!isfinite(pos[0]) || !isfinite(pos[1]) || !isfinite(pos[2]) || !isfinite(pos[3]))
        return SG_CLIP_NONFINITE | ((1u << SG_CLIP_PLANE_COUNT) - 1);
    uint32_t code = 0;
    for (int i = 0; i < SG_CLIP_PLANE_COUNT; i++) {
        /* Written as !(d >= 0) so that NaN counts as outside every plane. */
        if (!(plane_dist(1u << i, pos, guard) >= 0.0f)) code |= 1u << i;
    }
    return code;
#endif
}

/* The point where edge a->b leaves the plane. Always computed from the inside vertex, so the two
 * triangles that share a clipped edge get bit-identical new vertices. */
static void intersect(sg_cvert *out, uint32_t plane, const sg_guard *g, const sg_cvert *in,
                      float d_in, const sg_cvert *outside, float d_out, int nattr) {
    float t = d_in / (d_in - d_out);
    for (int k = 0; k < 4; k++) out->pos[k] = in->pos[k] + t * (outside->pos[k] - in->pos[k]);
    for (int k = 0; k < SG_MAX_ATTRS; k++)
        out->attr[k] = k < nattr ? in->attr[k] + t * (outside->attr[k] - in->attr[k]) : 0.0f;
    /* Put the point exactly on the plane: rounding could leave it a hair outside, and a later
     * plane or the divide must never see it there. */
    float *p = out->pos;
    switch (plane) {
    case SG_CLIP_NEAR:
        p[2] = -p[3];
        break;
    case SG_CLIP_FAR:
        p[2] = p[3];
        break;
    case SG_CLIP_WMIN:
        p[3] = SG_CLIP_W_MIN;
        break;
    case SG_CLIP_LEFT:
        p[0] = -g->gx * p[3];
        break;
    case SG_CLIP_RIGHT:
        p[0] = g->gx * p[3];
        break;
    case SG_CLIP_BOTTOM:
        p[1] = -g->gy * p[3];
        break;
    default:
        p[1] = g->gy * p[3];
        break;
    }
}

int sg_clip_polygon(sg_cvert *poly, int n, uint32_t planes, int nattr, const sg_guard *guard) {
    sg_cvert tmp[SG_CLIP_MAX_VERTS];
    for (int i = 0; i < SG_CLIP_PLANE_COUNT && n >= 3; i++) {
        uint32_t plane = 1u << i;
        if (!(planes & plane)) continue;
        float d[SG_CLIP_MAX_VERTS];
        for (int v = 0; v < n; v++) d[v] = plane_dist(plane, poly[v].pos, guard);
        int m = 0;
        for (int v = 0; v < n; v++) {
            int w = v + 1 == n ? 0 : v + 1;
            int in_v = d[v] >= 0.0f, in_w = d[w] >= 0.0f;
            /* A convex polygon gains at most one vertex per plane; rounding on a sliver that lies
             * along the plane could break that, and such a sliver covers nothing: drop it. */
            if (m + in_v + (in_v != in_w) > SG_CLIP_MAX_VERTS) return 0;
            if (in_v) tmp[m++] = poly[v];
            if (in_v && !in_w)
                intersect(&tmp[m++], plane, guard, &poly[v], d[v], &poly[w], d[w], nattr);
            else if (!in_v && in_w)
                intersect(&tmp[m++], plane, guard, &poly[w], d[w], &poly[v], d[v], nattr);
        }
        memcpy(poly, tmp, (size_t)m * sizeof *poly);
        n = m;
    }
    return n >= 3 ? n : 0;
}
