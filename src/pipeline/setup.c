/* setup.c - from clipped triangles to raster-ready edge and plane equations (see setup.h). */
#include "pipeline/setup.h"

#include <math.h>
#include <string.h>

typedef struct screen_vert {
    int32_t x, y; /* snapped, 1/256 pixel */
    float z;      /* window depth */
    float q;      /* 1 / w */
    const float *attr;
} screen_vert;

/* Floor division by a positive constant, correct for negative numerators. */
static int64_t floor_div(int64_t a, int64_t b) {
    int64_t q = a / b;
    return (a % b != 0 && a < 0) ? q - 1 : q;
}

static bool to_screen(const sg_setup_params *p, const sg_cvert *v, screen_vert *s) {
    float q = 1.0f / v->pos[3];
    float xn = v->pos[0] * q, yn = v->pos[1] * q, zn = v->pos[2] * q;
    float hw = 0.5f * (float)p->width, hh = 0.5f * (float)p->height;
    float xs = xn * hw + hw;
    float ys = hh - yn * hh; /* NDC y = +1 is the top row */
    float xf = xs * (float)SG_SUBPIXEL_ONE, yf = ys * (float)SG_SUBPIXEL_ONE;
    /* The guard band keeps finite input far inside int32; NaN or inf fails these tests. */
    if (!(fabsf(xf) < 2147483520.0f && fabsf(yf) < 2147483520.0f) || !isfinite(zn) || !isfinite(q))
        return false;
    s->x = (int32_t)lrintf(xf);
    s->y = (int32_t)lrintf(yf);
    s->z = zn * 0.5f + 0.5f;
    s->q = q;
    s->attr = v->attr;
    return true;
}

/* Gradient of a value given at the three vertices, over the screen-space triangle. */
static void plane(double f0, double f1, double f2, double e1x, double e1y, double e2x, double e2y,
                  double inv_det, double ox, double oy, float *at, float *dx, float *dy) {
    double d1 = f1 - f0, d2 = f2 - f0;
    double gx = (d1 * e2y - d2 * e1y) * inv_det;
    double gy = (d2 * e1x - d1 * e2x) * inv_det;
    *at = (float)(f0 + gx * ox + gy * oy);
    *dx = (float)gx;
    *dy = (float)gy;
}

bool sg_setup_triangle(const sg_setup_params *p, const sg_cvert *v0, const sg_cvert *v1,
                       const sg_cvert *v2, sg_tri *out) {
    screen_vert s[3];
    if (!to_screen(p, v0, &s[0]) || !to_screen(p, v1, &s[1]) || !to_screen(p, v2, &s[2]))
        return false;

    /* Twice the signed area in y-down pixel space: exact. Positive is clockwise on screen. */
    int64_t area = (int64_t)(s[1].x - s[0].x) * (s[2].y - s[0].y) -
                   (int64_t)(s[2].x - s[0].x) * (s[1].y - s[0].y);
    if (area == 0) return false;
    bool ccw = area < 0; /* counter-clockwise as seen with y up */
    bool front = (p->front_face == SG_FRONT_FACE_CW) ? !ccw : ccw;
    if ((p->cull == SG_CULL_BACK && !front) || (p->cull == SG_CULL_FRONT && front)) return false;
    if (area < 0) { /* one orientation for the edge functions below */
        screen_vert t = s[1];
        s[1] = s[2];
        s[2] = t;
        area = -area;
    }

    /* Pixel bounds: pixel px is reachable when its centre 256 px + 128 lies within [min, max]. */
    int32_t xmin = s[0].x, xmax = s[0].x, ymin = s[0].y, ymax = s[0].y;
    for (int i = 1; i < 3; i++) {
        if (s[i].x < xmin) xmin = s[i].x;
        if (s[i].x > xmax) xmax = s[i].x;
        if (s[i].y < ymin) ymin = s[i].y;
        if (s[i].y > ymax) ymax = s[i].y;
    }
    const int64_t one = SG_SUBPIXEL_ONE, half = SG_SUBPIXEL_ONE / 2;
    int64_t minx = -floor_div(-(xmin - half), one), maxx = floor_div(xmax - half, one);
    int64_t miny = -floor_div(-(ymin - half), one), maxy = floor_div(ymax - half, one);
    if (minx < p->rect_x0) minx = p->rect_x0;
    if (miny < p->rect_y0) miny = p->rect_y0;
    if (maxx > p->rect_x1 - 1) maxx = p->rect_x1 - 1;
    if (maxy > p->rect_y1 - 1) maxy = p->rect_y1 - 1;
    if (minx > maxx || miny > maxy) return false;
    out->minx = (int)minx;
    out->miny = (int)miny;
    out->maxx = (int)maxx;
    out->maxy = (int)maxy;

    /* Edge a->b: E(P) = DX (Py - ay) - DY (Px - ax), positive inside. A top edge (DY == 0, DX > 0)
     * or a left edge (DY < 0) keeps pixels whose centre lies exactly on it; others lose them, which
     * the -1 bias does in integer arithmetic. */
    int64_t ox = minx * one + half, oy = miny * one + half;
    for (int i = 0; i < 3; i++) {
        const screen_vert *a = &s[i], *b = &s[(i + 1) % 3];
        int64_t dx = (int64_t)b->x - a->x, dy = (int64_t)b->y - a->y;
        bool top_left = dy < 0 || (dy == 0 && dx > 0);
        out->edge[i] = dx * (oy - a->y) - dy * (ox - a->x) - (top_left ? 0 : 1);
        out->edge_dx[i] = -dy * one;
        out->edge_dy[i] = dx * one;
    }

    /* Plane equations from the snapped positions, in double, relative to vertex 0. */
    double x0 = (double)s[0].x / one, y0 = (double)s[0].y / one;
    double e1x = (double)s[1].x / one - x0, e1y = (double)s[1].y / one - y0;
    double e2x = (double)s[2].x / one - x0, e2y = (double)s[2].y / one - y0;
    double inv_det = 1.0 / (e1x * e2y - e2x * e1y);
    double pox = (double)minx + 0.5 - x0, poy = (double)miny + 0.5 - y0;
    plane(s[0].z, s[1].z, s[2].z, e1x, e1y, e2x, e2y, inv_det, pox, poy, &out->z, &out->z_dx,
          &out->z_dy);
    plane(s[0].q, s[1].q, s[2].q, e1x, e1y, e2x, e2y, inv_det, pox, poy, &out->q, &out->q_dx,
          &out->q_dy);
    for (int k = 0; k < p->nattr; k++) {
        plane((double)s[0].attr[k] * s[0].q, (double)s[1].attr[k] * s[1].q,
              (double)s[2].attr[k] * s[2].q, e1x, e1y, e2x, e2y, inv_det, pox, poy, &out->a[k],
              &out->a_dx[k], &out->a_dy[k]);
    }
    out->nattr = p->nattr;
    out->flat = SG_FLAT_NONE;
    if (p->nattr >= 4 && memcmp(s[0].attr, s[1].attr, 4 * sizeof(float)) == 0 &&
        memcmp(s[0].attr, s[2].attr, 4 * sizeof(float)) == 0) {
        memcpy(out->color, s[0].attr, sizeof out->color);
        bool white = true;
        for (int k = 0; k < 4; k++) white &= out->color[k] == 1.0f;
        out->flat = white ? SG_FLAT_WHITE : SG_FLAT_COLOR;
    }
    return true;
}
