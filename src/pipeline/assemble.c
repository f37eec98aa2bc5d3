/* assemble.c - builds triangles from indices and sends them through clipping and setup. */
#include "pipeline/assemble.h"

#include <math.h>

static void fetch(const sg_assembly *a, uint32_t idx, sg_cvert *v) {
    for (int k = 0; k < 4; k++) v->pos[k] = a->clip[idx][k];
    if (a->colors) {
        for (int k = 0; k < 4; k++) v->attr[k] = a->colors[(size_t)idx * 4 + (size_t)k];
    } else {
        for (int k = 0; k < 4; k++) v->attr[k] = 1.0f;
    }
    if (a->setup.nattr > 4) {
        v->attr[4] = a->texcoords[(size_t)idx * 2];
        v->attr[5] = a->texcoords[(size_t)idx * 2 + 1];
    }
}

/* False when an attribute the draw reads is NaN or infinite: such a triangle is dropped whole,
 * as one with a non-finite position is, so it cannot paint garbage or sample out of range. */
static bool attributes_finite(const sg_cvert *v, int nattr) {
    for (int i = 0; i < 3; i++)
        for (int k = 0; k < nattr; k++)
            if (!isfinite(v[i].attr[k])) return false;
    return true;
}

/* Under repeat wrapping only the fraction of a texcoord matters, so shifting a whole triangle's
 * texcoords by an integer changes no texel it samples. Moving them next to 0 before clipping and
 * interpolation keeps their full float precision: texcoords near 1e4 would otherwise be
 * interpolated with a resolution of 1e-3, a visible drift in the bilinear weights. The shift is
 * exact (the values are close to the integer), so the result does not depend on where the
 * texture's period starts. */
static void rebase_texcoords(sg_cvert *v) {
    for (int k = 4; k < 6; k++) {
        float base = floorf(v[0].attr[k]);
        for (int i = 0; i < 3; i++) v[i].attr[k] -= base;
    }
}

static void triangle(const sg_assembly *a, uint32_t i0, uint32_t i1, uint32_t i2) {
    uint32_t c0 = a->outcodes[i0], c1 = a->outcodes[i1], c2 = a->outcodes[i2];
    /* Wholly outside one plane, or a NaN / infinite position: nothing of it is drawn. */
    if ((c0 & c1 & c2) || ((c0 | c1 | c2) & SG_CLIP_NONFINITE)) return;
    sg_cvert poly[SG_CLIP_MAX_VERTS];
    fetch(a, i0, &poly[0]);
    fetch(a, i1, &poly[1]);
    fetch(a, i2, &poly[2]);
    if (!attributes_finite(poly, a->setup.nattr)) return;
    if (a->rebase_texcoords) rebase_texcoords(poly);
    int n = 3;
    if (c0 | c1 | c2) n = sg_clip_polygon(poly, 3, c0 | c1 | c2, a->setup.nattr, &a->guard);
    sg_tri tri;
    for (int k = 1; k + 1 < n; k++) { /* a fan keeps the polygon's winding */
        if (sg_setup_triangle(&a->setup, &poly[0], &poly[k], &poly[k + 1], &tri))
            a->emit(&tri, a->user);
    }
}

void sg_assemble(const sg_assembly *a) {
    const uint32_t *ix = a->indices;
    if (a->quads) {
        for (int i = 0; i + 3 < a->index_count; i += 4) {
            triangle(a, ix[i], ix[i + 1], ix[i + 2]);
            triangle(a, ix[i], ix[i + 2], ix[i + 3]);
        }
    } else {
        for (int i = 0; i + 2 < a->index_count; i += 3) triangle(a, ix[i], ix[i + 1], ix[i + 2]);
    }
}
