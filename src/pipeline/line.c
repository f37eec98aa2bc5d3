/* line.c - line setup: a segment between two projected vertices becomes an sg_tri the triangle
 * raster draws unchanged (see line.h for the rule and how it is encoded). */
#include "pipeline/line.h"

#include <string.h>

/* v + a e + b e^2 for an infinitesimal e > 0: the diamond-exit rule moves both end points by
 * (-e, -e^2), which decides every tie, and these numbers carry that move exactly. */
typedef struct sym {
    int64_t v, a, b;
} sym;

static int sym_sign(sym s) {
    if (s.v) return s.v > 0 ? 1 : -1;
    if (s.a) return s.a > 0 ? 1 : -1;
    return s.b > 0 ? 1 : (s.b < 0 ? -1 : 0);
}

static sym sym_add(sym s, int64_t k) {
    s.v += k;
    return s;
}

static sym sym_abs(sym s) {
    if (sym_sign(s) < 0) {
        s.v = -s.v;
        s.a = -s.a;
        s.b = -s.b;
    }
    return s;
}

/* The closed range of p and q meets the open range (-h, h). */
static bool overlaps(sym p, sym q, int64_t h) {
    return (sym_sign(sym_add(p, h)) > 0 || sym_sign(sym_add(q, h)) > 0) &&
           (sym_sign(sym_add(p, -h)) < 0 || sym_sign(sym_add(q, -h)) < 0);
}

enum { HALF = SG_SUBPIXEL_ONE / 2 }; /* the diamond: |x - cx| + |y - cy| < HALF */

/* Whether the moved segment a'b' meets the open diamond around (cx, cy): no separating axis
 * among the diamond's two edge normals and the segment's normal. */
static bool meets_diamond(const sg_svert *a, const sg_svert *b, int64_t cx, int64_t cy) {
    const int64_t ax = a->x - cx, ay = a->y - cy, bx = b->x - cx, by = b->y - cy;
    if (!overlaps((sym){ax + ay, -1, -1}, (sym){bx + by, -1, -1}, HALF)) return false;
    if (!overlaps((sym){ax - ay, -1, 1}, (sym){bx - by, -1, 1}, HALF)) return false;
    const int64_t dx = bx - ax, dy = by - ay;
    /* n = (-dy, dx): the segment projects to one value, the diamond to |n|_inf HALF around 0. */
    const sym n = {-dy * ax + dx * ay, dy, -dx};
    const int64_t r = HALF * (dx < 0 ? -dx : dx) > HALF * (dy < 0 ? -dy : dy)
                          ? HALF * (dx < 0 ? -dx : dx)
                          : HALF * (dy < 0 ? -dy : dy);
    return sym_sign(sym_add(n, -r)) < 0 && sym_sign(sym_add(n, r)) > 0;
}

/* Whether the moved point p' lies inside the open diamond around (cx, cy). */
static bool in_diamond(const sg_svert *p, int64_t cx, int64_t cy) {
    sym dx = sym_abs((sym){p->x - cx, -1, 0}), dy = sym_abs((sym){p->y - cy, 0, -1});
    sym sum = {dx.v + dy.v, dx.a + dy.a, dx.b + dy.b};
    return sym_sign(sym_add(sum, -HALF)) < 0;
}

static int64_t floor_div(int64_t a, int64_t b) { /* b > 0 */
    int64_t q = a / b;
    return q - (a % b < 0);
}

/* The segment in its major-axis frame: u along the major axis, v across, from the end with the
 * smaller u (du > 0). */
typedef struct frame {
    bool x_major;
    int64_t ua, va, du, dv;
    bool low_tie; /* a centre exactly on the band's lower boundary is inside */
    bool up_tie;  /* ... on its upper boundary */
} frame;

/* The pixel row (x-major; column, y-major) of the band at major pixel c: the one whose centre
 * lies within half a pixel of the moved line there. */
static int64_t band_at(const frame *f, int64_t c) {
    const int64_t U = c * SG_SUBPIXEL_ONE + HALF, den = (int64_t)SG_SUBPIXEL_ONE * f->du;
    const int64_t num = f->va * f->du + (U - f->ua) * f->dv;
    int64_t j = floor_div(num, den);
    if (num - j * den == 0 && !f->low_tie) j--;
    return j;
}

/* Whether the segment meets the diamond of the band's pixel at major pixel c. */
static bool hits(const frame *f, const sg_svert *a, const sg_svert *b, int64_t c) {
    const int64_t m = c * SG_SUBPIXEL_ONE + HALF, n = band_at(f, c) * SG_SUBPIXEL_ONE + HALF;
    return f->x_major ? meets_diamond(a, b, m, n) : meets_diamond(a, b, n, m);
}

bool sg_setup_line_coverage(const sg_setup_params *p, const sg_svert s[2], sg_tri *out) {
    const sg_svert *pa = &s[0], *pb = &s[1];
    const int64_t dx = (int64_t)pb->x - pa->x, dy = (int64_t)pb->y - pa->y;
    if (dx == 0 && dy == 0) return false; /* a point: inside its own diamond, never leaves it */
    frame f;
    f.x_major = (dx < 0 ? -dx : dx) >= (dy < 0 ? -dy : dy);
    const bool forward = f.x_major ? dx > 0 : dy > 0; /* pa has the smaller u */
    const sg_svert *lo = forward ? pa : pb, *hi = forward ? pb : pa;
    f.ua = f.x_major ? lo->x : lo->y;
    f.va = f.x_major ? lo->y : lo->x;
    f.du = (f.x_major ? hi->x : hi->y) - f.ua;
    f.dv = (f.x_major ? hi->y : hi->x) - f.va;
    /* The move is (-e, -e^2): along u by e (x-major) or e^2 (y-major), across by the other. At a
     * tie the moved line lies above the boundary when its slope carries it up faster than the
     * move across brings it down: x-major when dv > 0; y-major never. */
    f.low_tie = f.x_major && f.dv > 0;
    f.up_tie = !f.x_major || f.dv <= 0;

    /* The major pixels whose band diamond the segment meets: every one strictly between the end
     * points' pixels, and of the few around each end those the exact test passes. */
    const int64_t one = SG_SUBPIXEL_ONE;
    const int64_t c_lo = floor_div(f.ua, one), c_hi = floor_div(f.ua + f.du, one);
    int64_t first = c_lo - 1, last = c_hi + 1;
    while (first <= c_hi + 1 && !(first > c_lo && first < c_hi) && !hits(&f, lo, hi, first))
        first++;
    while (last >= first && !(last > c_lo && last < c_hi) && !hits(&f, lo, hi, last)) last--;
    if (first > last) return false;
    /* Diamond exit: no pixel whose diamond holds the moved end point pb'. Its major pixel is the
     * one that holds u - e (or u - e^2): at an exact pixel edge, the one before. */
    const int64_t ub = f.x_major ? pb->x : pb->y;
    const int64_t c_b = floor_div(ub, one) - (ub % one == 0 ? 1 : 0);
    const int64_t m = c_b * one + HALF, n = band_at(&f, c_b) * one + HALF;
    if (f.x_major ? in_diamond(pb, m, n) : in_diamond(pb, n, m)) {
        if (forward)
            last = last < c_b - 1 ? last : c_b - 1;
        else
            first = first > c_b + 1 ? first : c_b + 1;
        if (first > last) return false;
    }

    /* Bounds: the major range, cut to the setup rectangle, and the band's pixels at its ends. */
    const int64_t rmaj0 = f.x_major ? p->rect_x0 : p->rect_y0;
    const int64_t rmaj1 = f.x_major ? p->rect_x1 : p->rect_y1;
    const int64_t rmin0 = f.x_major ? p->rect_y0 : p->rect_x0;
    const int64_t rmin1 = f.x_major ? p->rect_y1 : p->rect_x1;
    if (first < rmaj0) first = rmaj0;
    if (last > rmaj1 - 1) last = rmaj1 - 1;
    if (first > last) return false;
    int64_t j0 = band_at(&f, first), j1 = band_at(&f, last);
    int64_t jmin = j0 < j1 ? j0 : j1, jmax = j0 < j1 ? j1 : j0;
    if (jmin < rmin0) jmin = rmin0;
    if (jmax > rmin1 - 1) jmax = rmin1 - 1;
    if (jmin > jmax) return false;
    out->minx = (int)(f.x_major ? first : jmin);
    out->maxx = (int)(f.x_major ? last : jmax);
    out->miny = (int)(f.x_major ? jmin : first);
    out->maxy = (int)(f.x_major ? jmax : last);
    out->rect_cut = 1; /* the major range is exact: the raster masks the bounds */
    out->line = f.x_major ? 1 : 2;

    /* The band: F(U, V) = du (L(U) - V), L the line, at pixel centres (U, V):
     *   lower: F + HALF du > 0 (= 0 when low_tie), upper: HALF du - F > 0 (= 0 when up_tie). */
    const int64_t ox = (int64_t)out->minx * one + HALF, oy = (int64_t)out->miny * one + HALF;
    const int64_t U0 = f.x_major ? ox : oy, V0 = f.x_major ? oy : ox;
    const int64_t F0 = (f.va - V0) * f.du + (U0 - f.ua) * f.dv;
    const int64_t dF_du = one * f.dv, dF_dv = -one * f.du;
    out->edge[0] = F0 + HALF * f.du - (f.low_tie ? 0 : 1);
    out->edge[1] = HALF * f.du - F0 - (f.up_tie ? 0 : 1);
    out->edge[2] = 0; /* always inside */
    out->edge_dx[0] = f.x_major ? dF_du : dF_dv;
    out->edge_dy[0] = f.x_major ? dF_dv : dF_du;
    out->edge_dx[1] = -out->edge_dx[0];
    out->edge_dy[1] = -out->edge_dy[0];
    out->edge_dx[2] = 0;
    out->edge_dy[2] = 0;
    return true;
}

bool sg_setup_line(const sg_setup_params *p, const sg_svert s[2], const float *const attr[2],
                   sg_tri *out, sg_tri_ext *ext) {
    if (!sg_setup_line_coverage(p, s, out)) return false;
    /* The planes vary along the major axis only (the wide-line formula of OpenGL, which lavapipe
     * uses for its lines): the triangle setup finds that plane through the two end points and a
     * third point one pixel across from the first, with the first's values. */
    const bool x_major = (s[1].x > s[0].x ? s[1].x - s[0].x : s[0].x - s[1].x) >=
                         (s[1].y > s[0].y ? s[1].y - s[0].y : s[0].y - s[1].y);
    sg_svert v[3] = {s[0], s[1], s[0]};
    if (x_major)
        v[2].y += SG_SUBPIXEL_ONE;
    else
        v[2].x += SG_SUBPIXEL_ONE;
    const float *a3[3] = {attr[0], attr[1], attr[0]};
    sg_setup_planes(p, v, a3, out);
    if (p->nattr > SG_TRI_ATTRS) sg_setup_planes_ext(p, v, a3, out, ext);
    return true;
}
