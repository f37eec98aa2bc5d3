/* assemble.c - builds triangles from indices and sends them through clipping and setup. */
#include "pipeline/assemble.h"

#include <math.h>
#include <string.h>

/* What assembly keeps for one draw. */
typedef struct draw_state {
    const sg_assembly *a;
    /* The exponent bits (0x7f800000) of each attribute float the draw reads, 0 for the others,
     * as three 8-byte words: colour 0-1, colour 2-3, texcoords. */
    uint64_t exponents[3];
} draw_state;

static void fetch_attributes(const sg_assembly *a, uint32_t idx, float attr[SG_MAX_ATTRS]) {
    static const float white[4] = {1.0f, 1.0f, 1.0f, 1.0f};
    memcpy(attr, a->colors ? a->colors + (size_t)idx * 4 : white, 4 * sizeof(float));
    if (a->setup.nattr > 4) {
        memcpy(attr + 4, a->texcoords + (size_t)idx * 2, 2 * sizeof(float));
    } else { /* setup reads them all (see sg_setup_planes) */
        attr[4] = 0.0f;
        attr[5] = 0.0f;
    }
}

/* Two floats at once: one of those `exponents` selects is NaN or infinite (exponent all ones)
 * exactly when adding 1 to its exponent carries into the sign bit of its half. */
static uint64_t nonfinite_bits(const float *v, uint64_t exponents) {
    uint64_t u;
    memcpy(&u, v, sizeof u);
    return ((u & exponents) + 0x0080000000800000u) & 0x8000000080000000u;
}

/* False when an attribute the draw reads is NaN or infinite: such a triangle is dropped whole,
 * as one with a non-finite position is, so it cannot paint garbage or sample out of range. */
static bool attributes_finite(const draw_state *d, uint32_t idx) {
    const sg_assembly *a = d->a;
    uint64_t bad = 0;
    if (a->colors) { /* else opaque white */
        const float *c = a->colors + (size_t)idx * 4;
        bad |= nonfinite_bits(c, d->exponents[0]) | nonfinite_bits(c + 2, d->exponents[1]);
    }
    if (a->setup.nattr > 4) bad |= nonfinite_bits(a->texcoords + (size_t)idx * 2, d->exponents[2]);
    return bad == 0;
}

/* The projection of a vertex inside every clip plane (made once by the vertex stage); false: the
 * triangles using it are dropped (it does not fit the raster's range, or an attribute the draw
 * reads is NaN or infinite: the vertex stage checked both). */
static inline bool screen_vertex(const draw_state *d, uint32_t idx, sg_svert *s) {
    if (!d->a->screen_ok[idx]) return false;
    *s = d->a->screen[idx];
    return true;
}

/* Under repeat wrapping only the fraction of a texcoord matters, so shifting a whole triangle's
 * texcoords by an integer changes no texel it samples. Moving them next to 0 before clipping and
 * interpolation keeps their full float precision: texcoords near 1e4 would otherwise be
 * interpolated with a resolution of 1e-3, a visible drift in the bilinear weights. The shift is
 * exact (the values are close to the integer), so the result does not depend on where the
 * texture's period starts. attr[0] is the triangle's first vertex. */
static void rebase_texcoords(float *const attr[3]) {
    for (int k = 4; k < 6; k++) {
        float base = floorf(attr[0][k]);
        for (int i = 0; i < 3; i++) attr[i][k] -= base;
    }
}

/* A triangle that crosses a clip plane: clipped to a convex polygon, set up as a fan. Rare, and
 * kept out of line so that it does not weigh on the common path. */
static void __attribute__((noinline))
clipped_triangle(const draw_state *d, const uint32_t idx[3], uint32_t planes) {
    const sg_assembly *a = d->a;
    sg_cvert poly[SG_CLIP_MAX_VERTS];
    for (int i = 0; i < 3; i++) {
        for (int k = 0; k < 4; k++) poly[i].pos[k] = a->clip[idx[i]][k];
        if (!attributes_finite(d, idx[i])) return;
        fetch_attributes(a, idx[i], poly[i].attr);
    }
    if (a->rebase_texcoords)
        rebase_texcoords((float *const[3]){poly[0].attr, poly[1].attr, poly[2].attr});
    int n = sg_clip_polygon(poly, 3, planes, a->setup.nattr, &a->guard);
    /* Each vertex is projected once, though the fan uses poly[0] in every triangle. */
    sg_svert s[SG_CLIP_MAX_VERTS];
    bool ok[SG_CLIP_MAX_VERTS];
    for (int i = 0; i < n; i++) ok[i] = sg_setup_project(&a->setup, poly[i].pos, &s[i]);
    for (int k = 1; k + 1 < n; k++) { /* a fan keeps the polygon's winding */
        if (!ok[0] || !ok[k] || !ok[k + 1]) continue;
        sg_svert t[3] = {s[0], s[k], s[k + 1]};
        const float *attr[3] = {poly[0].attr, poly[k].attr, poly[k + 1].attr};
        sg_tri *tri = a->slot(a->user);
        if (!tri) return;
        if (!sg_setup_coverage(&a->setup, t, attr, tri)) continue;
        sg_setup_planes(&a->setup, t, attr, tri);
        a->emit(a->user);
    }
}

static void triangle(const draw_state *d, uint32_t i0, uint32_t i1, uint32_t i2) {
    const sg_assembly *a = d->a;
    uint32_t c0 = a->outcodes[i0], c1 = a->outcodes[i1], c2 = a->outcodes[i2];
    /* Wholly outside one plane, or a NaN / infinite position: nothing of it is drawn. */
    if ((c0 & c1 & c2) || ((c0 | c1 | c2) & SG_CLIP_NONFINITE)) return;
    if (c0 | c1 | c2) {
        clipped_triangle(d, (const uint32_t[3]){i0, i1, i2}, c0 | c1 | c2);
        return;
    }
    /* Inside every plane (the common case): no clipping, and the attributes are read only when
     * the triangle survives culling. */
    sg_svert s[3];
    if (!screen_vertex(d, i0, &s[0]) || !screen_vertex(d, i1, &s[1]) ||
        !screen_vertex(d, i2, &s[2]))
        return;
    float attr[3][SG_MAX_ATTRS];
    const float *order[3] = {attr[0], attr[1], attr[2]}; /* reordered by coverage */
    sg_tri *tri = a->slot(a->user);
    if (!tri || !sg_setup_coverage(&a->setup, s, order, tri)) return;
    fetch_attributes(a, i0, attr[0]);
    fetch_attributes(a, i1, attr[1]);
    fetch_attributes(a, i2, attr[2]);
    if (a->rebase_texcoords) rebase_texcoords((float *const[3]){attr[0], attr[1], attr[2]});
    sg_setup_planes(&a->setup, s, order, tri);
    a->emit(a->user);
}

void sg_assemble(const sg_assembly *a) {
    draw_state d;
    d.a = a;
    uint32_t exponents[SG_MAX_ATTRS];
    _Static_assert(sizeof exponents == sizeof d.exponents, "one exponent per attribute");
    for (int k = 0; k < SG_MAX_ATTRS; k++) exponents[k] = k < a->setup.nattr ? 0x7f800000u : 0;
    memcpy(d.exponents, exponents, sizeof d.exponents); /* float k lands on exponent k */

    const uint32_t *ix = a->indices;
    if (a->quads) {
        for (int i = 0; i + 3 < a->index_count; i += 4) {
            triangle(&d, ix[i], ix[i + 1], ix[i + 2]);
            triangle(&d, ix[i], ix[i + 2], ix[i + 3]);
        }
    } else {
        for (int i = 0; i + 2 < a->index_count; i += 3) triangle(&d, ix[i], ix[i + 1], ix[i + 2]);
    }
}
