/* assemble.c - builds triangles from indices and sends them through clipping and setup. */
#include "pipeline/assemble.h"

#include "pipeline/line.h"
#include "pipeline/vertex.h"

#include <float.h>
#include <math.h>
#include <string.h>

/* The assembly of unlit, lit and shader draws (lit 0, 1, 2: vattr is set for the last two) are
 * compiled apart, `lit` a constant in each, so that the unlit path has no test of its own for
 * lighting or shaders. */
#define SG_ASM_INLINE static inline __attribute__((always_inline))

SG_ASM_INLINE void fetch_attributes(const sg_assembly *a, uint32_t idx, float attr[SG_MAX_ATTRS],
                                    const int lit) {
    static const float white[4] = {1.0f, 1.0f, 1.0f, 1.0f};
    if (lit) {
        memcpy(attr, a->vattr + (size_t)idx * (size_t)a->vstride,
               (size_t)a->vstride * sizeof(float));
        return;
    }
    memcpy(attr, a->colors ? a->colors + (size_t)idx * 4 : white, 4 * sizeof(float));
    if (a->tint)
        for (int k = 0; k < 4; k++) attr[k] *= a->tint[k];
    if (a->setup.nattr > 4) memcpy(attr + 4, a->texcoords + (size_t)idx * 2, 2 * sizeof(float));
}

/* Vertex idx's clip position (assemble.h: stored, or worked out again). */
static inline void clip_pos(const sg_assembly *a, uint32_t idx, float pos[4]) {
    if (a->positions)
        sg_vertex_clip(a->mvp, a->positions + (size_t)idx * 4, pos);
    else
        memcpy(pos, a->clip[idx], 4 * sizeof(float));
}

/* False when an attribute the draw reads is NaN or infinite: such a triangle is dropped whole,
 * as one with a non-finite position is, so it cannot paint garbage or sample out of range. (The
 * vertex stage makes the same check for vertices inside every clip plane.) */
SG_ASM_INLINE bool attributes_finite(const sg_assembly *a, uint32_t idx, const int lit) {
    if (lit) {
        const float *v = a->vattr + (size_t)idx * (size_t)a->vstride;
        for (int k = 0; k < a->vstride; k++)
            if (!(v[k] >= -FLT_MAX && v[k] <= FLT_MAX)) return false;
        return true;
    }
    return sg_vertex_attributes_finite(a->colors, a->texcoords, a->setup.nattr, idx);
}

/* Flat lighting: the equation once for the triangle, at the centroid of its view-space positions
 * with its face normal (P1 - P0) x (P2 - P0) and the base colour of its first vertex; every
 * vertex then carries the same primary and secondary colours (setup finds the triangle flat). */
static void light_flat(const sg_lights *ls, int split, int nattr, float *const attr[3]) {
    const float *p0 = attr[0] + SG_LIT_POS, *p1 = attr[1] + SG_LIT_POS, *p2 = attr[2] + SG_LIT_POS;
    float e1[3], e2[3], c[3];
    for (int k = 0; k < 3; k++) {
        e1[k] = p1[k] - p0[k];
        e2[k] = p2[k] - p0[k];
        c[k] = ((p0[k] + p1[k]) + p2[k]) / 3.0f;
    }
    float n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                  e1[0] * e2[1] - e1[1] * e2[0]};
    float prim[4], sec[3];
    if (split) { /* the view position stays for the shadow map; the colours split (light.h) */
        float rest[4], part[9];
        sg_light_eval_split(ls, c, n, attr[0] + SG_LIT_COLOR, split - 1, rest, part, part + 3,
                            part + 6);
        for (int i = 0; i < 3; i++) {
            memcpy(attr[i] + SG_LIT_COLOR, rest, sizeof rest);
            memcpy(attr[i] + SG_LIT_SPLIT_D, part,
                   (size_t)(nattr - SG_LIT_SPLIT_D) * sizeof(float));
        }
        return;
    }
    sg_light_eval(ls, c, n, attr[0] + SG_LIT_COLOR, prim, sec);
    for (int i = 0; i < 3; i++) {
        memcpy(attr[i] + SG_LIT_COLOR, prim, sizeof prim);
        memcpy(attr[i] + SG_LIT_SEC, sec, sizeof sec);
    }
}

/* The projection of a vertex inside every clip plane (made once by the vertex stage); false: the
 * triangles using it are dropped (it does not fit the raster's range, or an attribute the draw
 * reads is NaN or infinite: the vertex stage checked both). */
static inline bool screen_vertex(const sg_assembly *a, uint32_t idx, sg_svert *s) {
    if (!a->screen_ok[idx]) return false;
    *s = a->screen[idx];
    return true;
}

/* Under repeat wrapping only the fraction of a texcoord matters, so shifting a whole triangle's
 * texcoords by an integer changes no texel it samples. Moving them next to 0 before clipping and
 * interpolation keeps their full float precision: texcoords near 1e4 would otherwise be
 * interpolated with a resolution of 1e-3, a visible drift in the bilinear weights. The shift is
 * exact (the values are close to the integer), so the result does not depend on where the
 * texture's period starts. attr[0] is the triangle's first vertex. */
static void rebase_texcoords(float *const attr[], int n) {
    for (int k = 4; k < 6; k++) {
        float base = floorf(attr[0][k]);
        for (int i = 0; i < n; i++) attr[i][k] -= base;
    }
}

/* A shader draw's flat varyings: every vertex carries the first one's (Vulkan's provoking vertex),
 * which clipping keeps exactly (a + t (a - a) = a) and setup keeps as it is. */
static inline void copy_flat(const sg_assembly *a, float *const attr[], int n) {
    for (uint32_t m = a->setup.flat_mask; m; m &= m - 1) {
        int k = __builtin_ctz(m);
        for (int i = 1; i < n; i++) attr[i][k] = attr[0][k];
    }
}

/* What a shader draw's fragment stage is told of a triangle (of signed area `area`, as
 * sg_setup_area gives it) or line (area 0) it set up: lines face the viewer. */
static inline void stamp(const sg_assembly *a, sg_tri *t, int prim, int64_t area) {
    t->sh.primitive = prim;
    t->sh.instance = a->instance;
    t->sh.front_facing = area == 0 || (area < 0) != (a->setup.front_face == SG_FRONT_FACE_CW);
}

/* A shader triangle whose varyings are the same, bit for bit, at its three vertices (flat ones
 * are the first vertex's at all three already), of a stage that reads its varyings alone: shaded
 * once (sg_assembly.konst), its colour kept in the triangle. False: the stage discards it
 * everywhere, so it writes nothing, depth included, and is dropped. */
static inline bool shade_constant(const sg_assembly *a, sg_tri *t, const float *const attr[3]) {
    if (!a->konst) return true;
    const size_t n = (size_t)a->setup.nattr * sizeof(float);
    if (memcmp(attr[0], attr[1], n) != 0 || memcmp(attr[0], attr[2], n) != 0) return true;
    int discarded = 0;
    t->sh.color = a->konst(a->konst_user, attr[0], &discarded);
    t->shader_const = SG_CONST_COLOR;
    return !discarded;
}

/* A triangle that crosses a clip plane: clipped to a convex polygon, set up as a fan. Rare, and
 * kept out of line so that it does not weigh on the common path. */
static void __attribute__((noinline))
clipped_triangle(const sg_assembly *a, const uint32_t idx[3], uint32_t planes, int prim) {
    sg_cvert poly[SG_CLIP_MAX_VERTS];
    const int lit = a->vattr != NULL;
    for (int i = 0; i < 3; i++) {
        clip_pos(a, idx[i], poly[i].pos);
        if (lit ? !attributes_finite(a, idx[i], 1) : !attributes_finite(a, idx[i], 0)) return;
        if (lit)
            fetch_attributes(a, idx[i], poly[i].attr, 1);
        else
            fetch_attributes(a, idx[i], poly[i].attr, 0);
    }
    if (a->rebase_texcoords)
        rebase_texcoords((float *const[3]){poly[0].attr, poly[1].attr, poly[2].attr}, 3);
    if (a->flat)
        light_flat(a->flat, a->flat_split, a->setup.nattr,
                   (float *const[3]){poly[0].attr, poly[1].attr, poly[2].attr});
    if (a->setup.shader)
        copy_flat(a, (float *const[3]){poly[0].attr, poly[1].attr, poly[2].attr}, 3);
    int n = sg_clip_polygon(poly, 3, planes, a->setup.nattr, &a->guard);
    /* Each vertex is projected once, though the fan uses poly[0] in every triangle. */
    sg_svert s[SG_CLIP_MAX_VERTS];
    bool ok[SG_CLIP_MAX_VERTS];
    for (int i = 0; i < n; i++) ok[i] = sg_setup_project(&a->setup, poly[i].pos, &s[i]);
    for (int k = 1; k + 1 < n; k++) { /* a fan keeps the polygon's winding */
        if (!ok[0] || !ok[k] || !ok[k + 1]) continue;
        sg_svert t[3] = {s[0], s[k], s[k + 1]};
        const float *attr[3] = {poly[0].attr, poly[k].attr, poly[k + 1].attr};
        sg_tri_ext *ext = NULL;
        sg_tri *tri = a->slot(a->user, &ext);
        if (!tri) return;
        const int64_t area = sg_setup_area(t);
        if (!sg_setup_coverage(&a->setup, t, attr, tri)) continue;
        sg_setup_planes(&a->setup, t, attr, tri);
        if (ext) sg_setup_planes_ext(&a->setup, t, attr, tri, ext);
        if (a->setup.shader) {
            stamp(a, tri, prim, area);
            if (!shade_constant(a, tri, attr)) continue;
        }
        a->emit(a->user);
    }
}

SG_ASM_INLINE void triangle(const sg_assembly *a, uint32_t i0, uint32_t i1, uint32_t i2, int prim,
                            const int lit) {
    uint32_t c0 = a->outcodes[i0], c1 = a->outcodes[i1], c2 = a->outcodes[i2];
    /* Wholly outside one plane, or a NaN / infinite position: nothing of it is drawn. */
    if ((c0 & c1 & c2) || ((c0 | c1 | c2) & SG_CLIP_NONFINITE)) return;
    if (c0 | c1 | c2) {
        clipped_triangle(a, (const uint32_t[3]){i0, i1, i2}, c0 | c1 | c2, prim);
        return;
    }
    /* Inside every plane (the common case): no clipping, and the attributes are read only when
     * the triangle survives culling. */
    sg_svert s[3];
    if (!screen_vertex(a, i0, &s[0]) || !screen_vertex(a, i1, &s[1]) ||
        !screen_vertex(a, i2, &s[2]))
        return;
    float attr[3][SG_MAX_ATTRS];
    const float *order[3] = {attr[0], attr[1], attr[2]}; /* reordered by coverage */
    /* A slot only for a triangle that covers some pixel centre: on a dense mesh most do not (back
     * faces, culled here without a call, and faces between pixel centres). */
    const int64_t area = sg_setup_area(s);
    if (sg_setup_culled(&a->setup, area)) return;
    sg_bounds bounds;
    if (!sg_setup_bounds(&a->setup, s, area, order, &bounds)) return;
    sg_tri_ext *ext = NULL;
    sg_tri *tri = a->slot(a->user, &ext);
    if (!tri) return;
    sg_setup_edges(&bounds, s, tri);
    fetch_attributes(a, i0, attr[0], lit);
    fetch_attributes(a, i1, attr[1], lit);
    fetch_attributes(a, i2, attr[2], lit);
    if (a->rebase_texcoords) rebase_texcoords((float *const[3]){attr[0], attr[1], attr[2]}, 3);
    if (lit == 1 && a->flat)
        light_flat(a->flat, a->flat_split, a->setup.nattr,
                   (float *const[3]){attr[0], attr[1], attr[2]});
    if (lit == 2) copy_flat(a, (float *const[3]){attr[0], attr[1], attr[2]}, 3);
    sg_setup_planes(&a->setup, s, order, tri);
    if (lit && ext) sg_setup_planes_ext(&a->setup, s, order, tri, ext);
    if (lit == 2) {
        stamp(a, tri, prim, area);
        if (!shade_constant(a, tri, order)) return;
    }
    a->emit(a->user);
}

SG_ASM_INLINE void assemble(const sg_assembly *a, const int lit) {
    const uint32_t *ix = a->indices;
    if (a->quads) {
        for (int i = 0, q = 2 * a->prim_base; i + 3 < a->index_count; i += 4, q += 2) {
            triangle(a, ix[i], ix[i + 1], ix[i + 2], q, lit);
            triangle(a, ix[i], ix[i + 2], ix[i + 3], q + 1, lit);
        }
    } else {
        for (int i = 0, p = a->prim_base; i + 2 < a->index_count; i += 3, p++)
            triangle(a, ix[i], ix[i + 1], ix[i + 2], p, lit);
    }
}

static void __attribute__((noinline)) assemble_lit(const sg_assembly *a) {
    assemble(a, 1);
}

static void __attribute__((noinline)) assemble_shader(const sg_assembly *a) {
    assemble(a, 2);
}

/* ---- lines: line primitives and wireframe edges (line.h) ---- */

static void emit_line(const sg_assembly *a, const sg_svert s[2], const float *const attr[2],
                      int prim) {
    sg_tri_ext *ext = NULL;
    sg_tri *tri = a->slot(a->user, &ext);
    if (!tri || !sg_setup_line(&a->setup, s, attr, tri, ext)) return;
    if (a->setup.shader) stamp(a, tri, prim, 0);
    a->emit(a->user);
}

/* A segment that crosses a clip plane: clipped, keeping its direction, then projected. */
static void clipped_segment(const sg_assembly *a, const float *p0, const float *p1,
                            const float *attr0, const float *attr1, uint32_t planes, int prim) {
    sg_cvert v[2];
    const int n = a->setup.nattr;
    memcpy(v[0].pos, p0, sizeof v[0].pos);
    memcpy(v[1].pos, p1, sizeof v[1].pos);
    memcpy(v[0].attr, attr0, (size_t)n * sizeof(float));
    memcpy(v[1].attr, attr1, (size_t)n * sizeof(float));
    if (planes && !sg_clip_line(v, planes, n, &a->guard)) return;
    sg_svert s[2];
    if (!sg_setup_project(&a->setup, v[0].pos, &s[0]) ||
        !sg_setup_project(&a->setup, v[1].pos, &s[1]))
        return;
    emit_line(a, s, (const float *const[2]){v[0].attr, v[1].attr}, prim);
}

SG_ASM_INLINE void segment(const sg_assembly *a, uint32_t i0, uint32_t i1, int prim,
                           const int lit) {
    uint32_t c0 = a->outcodes[i0], c1 = a->outcodes[i1];
    if ((c0 & c1) || ((c0 | c1) & SG_CLIP_NONFINITE)) return;
    if (!attributes_finite(a, i0, lit) || !attributes_finite(a, i1, lit)) return;
    float attr[2][SG_MAX_ATTRS];
    fetch_attributes(a, i0, attr[0], lit);
    fetch_attributes(a, i1, attr[1], lit);
    if (a->rebase_texcoords) rebase_texcoords((float *const[2]){attr[0], attr[1]}, 2);
    if (lit == 2) copy_flat(a, (float *const[2]){attr[0], attr[1]}, 2);
    sg_svert s[2];
    if (c0 | c1) {
        float p[2][4];
        clip_pos(a, i0, p[0]);
        clip_pos(a, i1, p[1]);
        clipped_segment(a, p[0], p[1], attr[0], attr[1], c0 | c1, prim);
    } else if (screen_vertex(a, i0, &s[0]) && screen_vertex(a, i1, &s[1]))
        emit_line(a, s, (const float *const[2]){attr[0], attr[1]}, prim);
}

/* A triangle's edges `edges` (bit e: v[e] -> v[e + 1]), in the order v2 -> v0, v0 -> v1, v1 -> v2
 * (OpenGL's and lavapipe's: it decides which edge wins where two overlap), when the triangle
 * survives culling. One
 * that crosses a clip plane faces the way its clipped polygon does on screen; its edges are cut
 * at the planes, and the polygon's new edges along them are not drawn. */
SG_ASM_INLINE void wire_triangle(const sg_assembly *a, const uint32_t idx[3], unsigned edges,
                                 int prim, const int lit) {
    const uint32_t c[3] = {a->outcodes[idx[0]], a->outcodes[idx[1]], a->outcodes[idx[2]]};
    if ((c[0] & c[1] & c[2]) || ((c[0] | c[1] | c[2]) & SG_CLIP_NONFINITE)) return;
    float attr[3][SG_MAX_ATTRS];
    for (int i = 0; i < 3; i++) {
        if (!attributes_finite(a, idx[i], lit)) return;
        fetch_attributes(a, idx[i], attr[i], lit);
    }
    if (a->rebase_texcoords) rebase_texcoords((float *const[3]){attr[0], attr[1], attr[2]}, 3);
    if (lit == 1 && a->flat)
        light_flat(a->flat, a->flat_split, a->setup.nattr,
                   (float *const[3]){attr[0], attr[1], attr[2]});
    if (lit == 2) copy_flat(a, (float *const[3]){attr[0], attr[1], attr[2]}, 3);
    if (!(c[0] | c[1] | c[2])) {
        sg_svert s[3];
        for (int i = 0; i < 3; i++)
            if (!screen_vertex(a, idx[i], &s[i])) return;
        if (sg_setup_culled(&a->setup, sg_setup_area(s))) return;
        for (int k = 0; k < 3; k++) {
            int e = k == 0 ? 2 : k - 1, f = e == 2 ? 0 : e + 1; /* v2 -> v0 first */
            if (edges >> e & 1)
                emit_line(a, (const sg_svert[2]){s[e], s[f]},
                          (const float *const[2]){attr[e], attr[f]}, prim);
        }
        return;
    }
    sg_cvert poly[SG_CLIP_MAX_VERTS];
    float pos[3][4];
    for (int i = 0; i < 3; i++) {
        clip_pos(a, idx[i], pos[i]);
        memcpy(poly[i].pos, pos[i], sizeof poly[i].pos);
        memset(poly[i].attr, 0, sizeof poly[i].attr); /* facing needs positions only */
    }
    int n = sg_clip_polygon(poly, 3, c[0] | c[1] | c[2], 0, &a->guard);
    sg_svert s[SG_CLIP_MAX_VERTS];
    bool ok[SG_CLIP_MAX_VERTS];
    for (int i = 0; i < n; i++) ok[i] = sg_setup_project(&a->setup, poly[i].pos, &s[i]);
    int64_t area = 0;
    for (int k = 1; k + 1 < n; k++)
        if (ok[0] && ok[k] && ok[k + 1])
            area += sg_setup_area((const sg_svert[3]){s[0], s[k], s[k + 1]});
    if (n == 0 || sg_setup_culled(&a->setup, area)) return;
    for (int k = 0; k < 3; k++) {
        int e = k == 0 ? 2 : k - 1, f = e == 2 ? 0 : e + 1;
        if (edges >> e & 1) clipped_segment(a, pos[e], pos[f], attr[e], attr[f], c[e] | c[f], prim);
    }
}

SG_ASM_INLINE void assemble_edges(const sg_assembly *a, const int lit) {
    const uint32_t *ix = a->indices;
    const int p0 = a->prim_base;
    if (a->lines) {
        for (int i = 0; i + 1 < a->index_count; i += 2)
            segment(a, ix[i], ix[i + 1], p0 + i / 2, lit);
    } else if (a->quads) { /* the four outer edges: a b c without c -> a, a c d without a -> c */
        for (int i = 0; i + 3 < a->index_count; i += 4) {
            const int q = 2 * (p0 + i / 4);
            wire_triangle(a, (const uint32_t[3]){ix[i], ix[i + 1], ix[i + 2]}, 3u, q, lit);
            wire_triangle(a, (const uint32_t[3]){ix[i], ix[i + 2], ix[i + 3]}, 6u, q + 1, lit);
        }
    } else {
        for (int i = 0; i + 2 < a->index_count; i += 3)
            wire_triangle(a, (const uint32_t[3]){ix[i], ix[i + 1], ix[i + 2]}, 7u, p0 + i / 3, lit);
    }
}

/* Lines and wireframes are assembled apart, so the triangle path has no test of its own for
 * them. */
static void __attribute__((noinline)) assemble_lines(const sg_assembly *a) {
    if (a->setup.shader)
        assemble_edges(a, 2);
    else if (a->vattr)
        assemble_edges(a, 1);
    else
        assemble_edges(a, 0);
}

void sg_assemble(const sg_assembly *a) {
    if (a->lines || a->wire)
        assemble_lines(a);
    else if (a->setup.shader)
        assemble_shader(a);
    else if (a->vattr)
        assemble_lit(a);
    else
        assemble(a, 0);
}
