/* clip.c - Sutherland-Hodgman clipping in homogeneous clip space (see clip.h). */
#include "pipeline/clip.h"

#include <float.h>
#include <math.h>
#include <string.h>

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
#if defined(__SSE2__) && defined(__SSE_MATH__)
    /* The vertex stage's four-lane classification, on one position in every lane. */
    return (uint32_t)_mm_cvtsi128_si32(sg_clip_outcode4(
        _mm_set1_ps(pos[0]), _mm_set1_ps(pos[1]), _mm_set1_ps(pos[2]), _mm_set1_ps(pos[3]), guard));
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
    for (int k = 0; k < nattr; k++)
        out->attr[k] = in->attr[k] + t * (outside->attr[k] - in->attr[k]);
    /* The rest defined too, so that a new vertex is the same bytes however it is reached. */
    memset(out->attr + nattr, 0, (size_t)(SG_MAX_ATTRS - nattr) * sizeof(float));
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

bool sg_clip_line(sg_cvert v[2], uint32_t planes, int nattr, const sg_guard *guard) {
    for (int i = 0; i < SG_CLIP_PLANE_COUNT; i++) {
        uint32_t plane = 1u << i;
        if (!(planes & plane)) continue;
        float d0 = plane_dist(plane, v[0].pos, guard), d1 = plane_dist(plane, v[1].pos, guard);
        bool in0 = d0 >= 0.0f, in1 = d1 >= 0.0f;
        if (!in0 && !in1) return false;
        /* From the inside end, as a triangle's edge is clipped: the same point. */
        if (!in1) intersect(&v[1], plane, guard, &v[0], d0, &v[1], d1, nattr);
        if (!in0) intersect(&v[0], plane, guard, &v[1], d1, &v[0], d0, nattr);
    }
    return true;
}
