/* assemble.h - primitive assembly: indices to triangles, trivial reject, clipping, setup. */
#ifndef SG_ASSEMBLE_H
#define SG_ASSEMBLE_H

#include <stdint.h>

#include "pipeline/light.h"
#include "pipeline/setup.h"

typedef struct sg_assembly {
    const uint32_t *indices;
    int index_count;
    int quads; /* 4 indices a primitive (a b c d -> a b c, a c d), else 3 */
    int lines; /* 2 indices a primitive: segments a -> b (line.h) */
    int wire;  /* triangles and quads drawn as their edges (polygon mode line) */
    /* Clip positions: `clip` (a shader's vertex stage stores them), or, when `positions` is set
     * (the fixed stage stores none), worked out again from the geom's positions with `mvp` for
     * the rare primitive that needs them (sg_vertex_clip: the same bits). */
    const float (*clip)[4];
    const float *positions;
    float mvp[16];
    const uint32_t *outcodes;
    const sg_svert *screen;   /* projections of the vertices inside every plane (vertex stage) */
    const uint8_t *screen_ok; /* 1: that projection fits and the attributes read are finite */
    const float *colors;      /* 4 floats a vertex, NULL: opaque white */
    const float *texcoords;   /* 2 floats a vertex, read when setup.nattr > 4 */
    const float *tint;        /* r g b a multiplying every vertex colour, or NULL */
    /* Lit draws: every attribute of each vertex, `vstride` floats a vertex, made by the vertex
     * stage (vertex.h, sg_vertex_lit); read instead of colors, texcoords and tint. */
    const float *vattr;
    int vstride;
    /* Flat lighting: the lights, evaluated once per triangle before clipping (vattr then holds
     * base colour, texcoords, view position: SG_LIT_*). */
    const sg_lights *flat;
    /* Flat lighting receiving a shadow map: 1 + the light it hides, whose part of the colours is
     * kept apart (light.h: SG_LIT_SPLIT_*, the view position stays); 0: none. */
    int flat_split;
    int rebase_texcoords; /* repeat wrapping: move each triangle's texcoords next to 0 */
    /* Shader draws (setup.shader): vattr holds each vertex's varyings; each triangle is told its
     * primitive (prim_base + its index in `indices`, a quad's two triangles 2 q and 2 q + 1) and
     * the instance. */
    int prim_base, instance;
    /* Shader draws whose stage reads its varyings alone (sgShaderDesc.varyings_only; NULL:
     * others): a triangle whose varyings are the same at its three vertices is shaded once, here,
     * konst(konst_user, its varyings, &discarded) giving its colour (sg_tri.shader_const). */
    uint32_t (*konst)(const void *user, const float *varyings, int *discarded);
    const void *konst_user;
    sg_guard guard;
    sg_setup_params setup;
    /* Where the next triangle (and its extension, when setup.nattr > SG_TRI_ATTRS) is set up
     * (NULL: no room, it is dropped), then emit when it survives: triangles are built in place,
     * in submission order. */
    sg_tri *(*slot)(void *user, sg_tri_ext **ext);
    void (*emit)(void *user);
    void *user;
} sg_assembly;

/** Assembles, clips and sets up every primitive of a draw. */
void sg_assemble(const sg_assembly *a);

#endif
