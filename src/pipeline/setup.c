/* setup.c - from clipped triangles to raster-ready edge and plane equations (see setup.h).
 * Assembly runs the steps one by one (see assemble.h); sg_setup_triangle runs them all. */
#include "pipeline/setup.h"

#include <float.h>
#include <math.h>
#include <string.h>
#if defined(__SSE__)
#include <xmmintrin.h>
#endif
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "pipeline/assemble.h"

/* lrintf without the libm call: on x86 lrintf is CVTSS2SI, which rounds as the MXCSR says (to
 * nearest even unless the caller changed it), so the two agree for every |f| < 2^31. */
static int32_t round_to_int(float f) {
#if defined(__SSE__)
    return _mm_cvtss_si32(_mm_set_ss(f));
#else
    return (int32_t)lrintf(f);
#endif
}

bool sg_setup_project(const sg_setup_params *p, const float pos[4], sg_svert *s) {
    float q = 1.0f / pos[3];
    float xn = pos[0] * q, yn = pos[1] * q, zn = pos[2] * q;
    float hw = 0.5f * (float)p->width, hh = 0.5f * (float)p->height;
    float xs = xn * hw + hw;
    float ys = hh - yn * hh; /* NDC y = +1 is the top row */
    float xf = xs * (float)SG_SUBPIXEL_ONE, yf = ys * (float)SG_SUBPIXEL_ONE;
    /* The guard band keeps finite input far inside int32; NaN or inf fails these tests
     * (|v| <= FLT_MAX is isfinite). One branch for all four: they almost never fail. */
    bool ok = (fabsf(xf) < 2147483520.0f) & (fabsf(yf) < 2147483520.0f) & (fabsf(zn) <= FLT_MAX) &
              (fabsf(q) <= FLT_MAX);
    if (!ok) return false;
    s->x = round_to_int(xf);
    s->y = round_to_int(yf);
    s->z = zn * 0.5f + 0.5f;
    s->q = q;
    return true;
}

bool sg_setup_bounds(const sg_setup_params *p, sg_svert s[3], int64_t area, const float *attr[3],
                     sg_bounds *out) {
    if (area < 0) { /* one orientation for the edge functions of sg_setup_edges */
        sg_svert t = s[1];
        s[1] = s[2];
        s[2] = t;
        const float *ta = attr[1];
        attr[1] = attr[2];
        attr[2] = ta;
    }

    /* Pixel bounds: pixel px is reachable when its centre 256 px + 128 lies within [min, max],
     * so minx = ceil((xmin - 128) / 256) and maxx = floor((xmax - 128) / 256). The shifts are
     * floor divisions (arithmetic on signed values with gcc, clang and msvc). */
    int32_t xmin = s[0].x, xmax = s[0].x, ymin = s[0].y, ymax = s[0].y;
    for (int i = 1; i < 3; i++) {
        if (s[i].x < xmin) xmin = s[i].x;
        if (s[i].x > xmax) xmax = s[i].x;
        if (s[i].y < ymin) ymin = s[i].y;
        if (s[i].y > ymax) ymax = s[i].y;
    }
    const int64_t one = SG_SUBPIXEL_ONE, half = SG_SUBPIXEL_ONE / 2;
    /* With 4 samples a pixel is reachable when one of its samples, at 32 .. 224 / 256 of the
     * pixel in x and in y (rast_msaa.h), lies within [min, max]. */
    const int64_t lo = p->samples > 1 ? 32 : half, hi = p->samples > 1 ? 224 : half;
    int64_t minx = ((int64_t)xmin - hi + one - 1) >> SG_SUBPIXEL_BITS;
    int64_t maxx = ((int64_t)xmax - lo) >> SG_SUBPIXEL_BITS;
    int64_t miny = ((int64_t)ymin - hi + one - 1) >> SG_SUBPIXEL_BITS;
    int64_t maxy = ((int64_t)ymax - lo) >> SG_SUBPIXEL_BITS;
    out->rect_cut =
        minx < p->rect_x0 || miny < p->rect_y0 || maxx > p->rect_x1 - 1 || maxy > p->rect_y1 - 1;
    if (minx < p->rect_x0) minx = p->rect_x0;
    if (miny < p->rect_y0) miny = p->rect_y0;
    if (maxx > p->rect_x1 - 1) maxx = p->rect_x1 - 1;
    if (maxy > p->rect_y1 - 1) maxy = p->rect_y1 - 1;
    if (minx > maxx || miny > maxy) return false;
    out->minx = (int)minx;
    out->miny = (int)miny;
    out->maxx = (int)maxx;
    out->maxy = (int)maxy;
    return true;
}

void sg_setup_edges(const sg_bounds *bounds, const sg_svert s[3], sg_tri *out) {
    out->line = 0;
    out->rect_cut = bounds->rect_cut;
    out->minx = bounds->minx;
    out->miny = bounds->miny;
    out->maxx = bounds->maxx;
    out->maxy = bounds->maxy;

    /* Edge a->b: E(P) = DX (Py - ay) - DY (Px - ax), positive inside. A top edge (DY == 0, DX > 0)
     * or a left edge (DY < 0) keeps pixels whose centre lies exactly on it; others lose them, which
     * the -1 bias does in integer arithmetic. */
    const int64_t one = SG_SUBPIXEL_ONE, half = SG_SUBPIXEL_ONE / 2;
    int64_t ox = bounds->minx * one + half, oy = bounds->miny * one + half;
    for (int i = 0; i < 3; i++) {
        const sg_svert *a = &s[i], *b = &s[i == 2 ? 0 : i + 1];
        int64_t dx = (int64_t)b->x - a->x, dy = (int64_t)b->y - a->y;
        bool top_left = dy < 0 || (dy == 0 && dx > 0);
        out->edge[i] = dx * (oy - a->y) - dy * (ox - a->x) - (top_left ? 0 : 1);
        out->edge_dx[i] = -dy * one;
        out->edge_dy[i] = dx * one;
    }
}

bool sg_setup_coverage(const sg_setup_params *p, sg_svert s[3], const float *attr[3], sg_tri *out) {
    /* Twice the signed area in y-down pixel space: exact. Positive is clockwise on screen. */
    int64_t area = sg_setup_area(s);
    sg_bounds bounds;
    if (sg_setup_culled(p, area) || !sg_setup_bounds(p, s, area, attr, &bounds)) return false;
    sg_setup_edges(&bounds, s, out);
    return true;
}

/* What every plane of a triangle shares: its edges from vertex 0, 1 / their determinant, and
 * the offset from vertex 0 to the centre of pixel (minx, miny). */
typedef struct plane_basis {
    double e1x, e1y, e2x, e2y, inv_det, pox, poy;
} plane_basis;

/* The plane of a value with f0, f1, f2 at the vertices: its gradient over the triangle and its
 * value at the centre of pixel (minx, miny). Scalar doubles from registers: a vector version
 * would gather its lanes through memory, and stall on it. */
static inline void plane(const plane_basis *b, double f0, double f1, double f2, float *at,
                         float *gx, float *gy) {
    double d1 = f1 - f0, d2 = f2 - f0;
    double dx = (d1 * b->e2y - d2 * b->e1y) * b->inv_det;
    double dy = (d2 * b->e1x - d1 * b->e2x) * b->inv_det;
    *at = (float)(f0 + dx * b->pox + dy * b->poy);
    *gx = (float)dx;
    *gy = (float)dy;
}

/* The first four floats (a colour) of a and b are the same bits, as memcmp would find. */
static bool same_color(const float *a, const float *b) {
    uint64_t x[2], y[2];
    memcpy(x, a, sizeof x);
    memcpy(y, b, sizeof y);
    return ((x[0] ^ y[0]) | (x[1] ^ y[1])) == 0;
}

/* The three floats at a and b are the same bits. */
static bool same3(const float *a, const float *b) {
    return memcmp(a, b, 3 * sizeof(float)) == 0;
}

/* Bit k: attribute k (of n) is the same, bit for bit, at the three vertices. A shader's flat
 * varyings are (the first vertex's at all three). */
static uint16_t same_varyings(const float *const attr[3], int n) {
    uint32_t same = 0;
    int k = 0;
#if defined(__SSE2__) /* four at a time: every shader triangle pays this */
    for (; k + 4 <= n; k += 4) {
        __m128i v[3];
        for (int i = 0; i < 3; i++)
            v[i] = _mm_loadu_si128((const __m128i *)(const void *)(attr[i] + k));
        const __m128i eq = _mm_and_si128(_mm_cmpeq_epi32(v[0], v[1]), _mm_cmpeq_epi32(v[0], v[2]));
        same |= (uint32_t)_mm_movemask_ps(_mm_castsi128_ps(eq)) << k;
    }
#endif
    for (; k < n; k++) {
        uint32_t v[3];
        for (int i = 0; i < 3; i++) memcpy(&v[i], attr[i] + k, sizeof v[i]);
        same |= (uint32_t)(v[0] == v[1] && v[0] == v[2]) << k;
    }
    return (uint16_t)same;
}

/* What every plane of a triangle shares, from its snapped vertices and pixel bounds. */
static plane_basis basis_of(const sg_svert s[3], const sg_tri *t) {
    const int64_t one = SG_SUBPIXEL_ONE;
    double x0 = (double)s[0].x / one, y0 = (double)s[0].y / one;
    double e1x = (double)s[1].x / one - x0, e1y = (double)s[1].y / one - y0;
    double e2x = (double)s[2].x / one - x0, e2y = (double)s[2].y / one - y0;
    double inv_det = 1.0 / (e1x * e2y - e2x * e1y);
    double pox = (double)t->minx + 0.5 - x0, poy = (double)t->miny + 0.5 - y0;
    const plane_basis b = {e1x, e1y, e2x, e2y, inv_det, pox, poy};
    return b;
}

void sg_setup_planes(const sg_setup_params *p, const sg_svert s[3], const float *const attr[3],
                     sg_tri *out) {
    out->nattr = p->nattr;
    out->flat = SG_FLAT_NONE;
    out->shader_const = SG_CONST_NONE;
    out->same = p->shader ? same_varyings(attr, p->nattr) : 0;
    /* A secondary colour (and the split colours of a shadow receiver) must be constant too for
     * the triangle to be flat. */
    const int sec = p->sec;
    bool flat =
        !p->shader && p->nattr >= 4 && same_color(attr[0], attr[1]) && same_color(attr[0], attr[2]);
    if (flat && sec) {
        const int end = p->sec_end ? p->sec_end : sec + 3;
        for (int k = sec; k < end && flat; k += 3)
            flat = same3(attr[0] + k, attr[1] + k) && same3(attr[0] + k, attr[2] + k);
    }
    if (flat) {
        memcpy(out->color, attr[0], sizeof out->color);
        /* == 1.0f as bits: 1.0f has no other encoding. */
        uint64_t c[2], white;
        memcpy(c, out->color, sizeof c);
        white = 0x3f8000003f800000u;
        out->flat = c[0] == white && c[1] == white ? SG_FLAT_WHITE : SG_FLAT_COLOR;
    }

    /* Plane equations from the snapped positions, in double, relative to vertex 0. Depth, 1/w,
     * then each attribute / w the shading reads (not a flat colour, which it takes as it is);
     * the others stay zero: never read, but every byte of a triangle is defined. */
    const plane_basis b = basis_of(s, out);
    plane(&b, s[0].z, s[1].z, s[2].z, &out->z, &out->z_dx, &out->z_dy);
    if (p->bias_constant != 0.0f || p->bias_slope != 0.0f) { /* shadow maps: the plane moves */
        float slope = fabsf(out->z_dx) > fabsf(out->z_dy) ? fabsf(out->z_dx) : fabsf(out->z_dy);
        out->z += p->bias_constant + (p->bias_slope != 0.0f ? p->bias_slope * slope : 0.0f);
    }
    plane(&b, s[0].q, s[1].q, s[2].q, &out->q, &out->q_dx, &out->q_dy);
    memset(out->a, 0, sizeof out->a);
    memset(out->a_dx, 0, sizeof out->a_dx);
    memset(out->a_dy, 0, sizeof out->a_dy);
    int n = p->nattr < SG_TRI_ATTRS ? p->nattr : SG_TRI_ATTRS;
    for (int k = out->flat != SG_FLAT_NONE ? 4 : 0; k < n; k++) {
        if (out->same >> k & 1) { /* a shader's varying the same at every vertex, as it is */
            out->a[k] = attr[0][k];
            continue;
        }
        plane(&b, (double)attr[0][k] * s[0].q, (double)attr[1][k] * s[1].q,
              (double)attr[2][k] * s[2].q, &out->a[k], &out->a_dx[k], &out->a_dy[k]);
    }
}

void sg_setup_planes_ext(const sg_setup_params *p, const sg_svert s[3], const float *const attr[3],
                         const sg_tri *t, sg_tri_ext *ext) {
    memset(ext, 0, sizeof *ext);
    const plane_basis b = basis_of(s, t);
    const int sec = p->sec, sec_end = p->sec_end ? p->sec_end : sec + 3;
    for (int k = SG_TRI_ATTRS; k < p->nattr; k++) {
        int e = k - SG_TRI_ATTRS;
        if ((t->flat != SG_FLAT_NONE && sec && k >= sec && k < sec_end) || (t->same >> k & 1))
            ext->a[e] = attr[0][k]; /* the flat secondary colour or same varying, as it is */
        else
            plane(&b, (double)attr[0][k] * s[0].q, (double)attr[1][k] * s[1].q,
                  (double)attr[2][k] * s[2].q, &ext->a[e], &ext->a_dx[e], &ext->a_dy[e]);
    }
}

bool sg_setup_triangle(const sg_setup_params *p, const sg_cvert *v0, const sg_cvert *v1,
                       const sg_cvert *v2, sg_tri *out, sg_tri_ext *ext) {
    const sg_cvert *v[3] = {v0, v1, v2};
    const float *attr[3] = {v0->attr, v1->attr, v2->attr};
    sg_svert s[3];
    for (int i = 0; i < 3; i++)
        if (!sg_setup_project(p, v[i]->pos, &s[i])) return false;
    if (!sg_setup_coverage(p, s, attr, out)) return false;
    sg_setup_planes(p, s, attr, out);
    if (p->nattr > SG_TRI_ATTRS) sg_setup_planes_ext(p, s, attr, out, ext);
    return true;
}
