/* test_vertex_lit_simd.c - the AVX2, AVX-512 and NEON Gouraud lighting of vertices gives the
 * scalar path's bytes (sg_vertex_lit_attributes without and with a vector function), on random
 * cases: one to eight lights, point and directional, near and at the vertices; specular materials
 * on and off, shininess 0 to 128; split colours for a shadow map or not; vertex colours, texcoords
 * and a tint or none; affine and projective world-view matrices; normals zero, tiny or huge; and
 * some values not finite, which must clear the same vertices' flags. Runs of any length from any
 * first vertex, so both whole vectors and the scalar remainder are compared.
 */
#include "test_common.h"
#include "test_rng.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pipeline/light.h"
#include "pipeline/vertex.h"
#include "raster/shade.h"

enum { CASES = 6000, MAX_VERTS = 80 };

/* Mostly an ordinary value in [lo, hi]; rarely an extreme or one that is not finite. */
static float value(rng *g, float lo, float hi) {
    static const float special[] = {0.0f, -0.0f, 1e-30f, -1e-30f, 1e30f, -1e30f, INFINITY, NAN};
    if (chance(g, 2)) return special[irange(g, 0, (int)(sizeof special / sizeof *special) - 1)];
    return frange(g, lo, hi);
}

typedef struct lit_case {
    float world_view[16], normal_matrix[9], tint[4];
    float positions[MAX_VERTS * 4], normals[MAX_VERTS * 3], colors[MAX_VERTS * 4];
    float texcoords[MAX_VERTS * 2];
    sg_lights lights;
    sg_vertex_lit lit;
    int first, count;
} lit_case;

static void make_case(rng *g, lit_case *c) {
    memset(c, 0, sizeof *c);
    for (int r = 0; r < 3; r++)
        for (int k = 0; k < 4; k++) c->world_view[r * 4 + k] = frange(g, -2.0f, 2.0f);
    c->world_view[11] = frange(g, -8.0f, -1.0f);
    c->world_view[15] = 1.0f;
    if (chance(g, 20)) /* projective: w is not 1 */
        for (int k = 0; k < 4; k++) c->world_view[12 + k] = frange(g, -0.5f, 1.5f);
    sg_normal_matrix(c->world_view, c->normal_matrix);
    const int total = irange(g, 1, MAX_VERTS);
    c->first = irange(g, 0, total - 1);
    c->count = total - c->first;
    for (int i = 0; i < total; i++) {
        for (int k = 0; k < 3; k++) c->positions[i * 4 + k] = value(g, -3.0f, 3.0f);
        c->positions[i * 4 + 3] = chance(g, 90) ? 1.0f : value(g, -2.0f, 2.0f);
        const int kind = irange(g, 0, 9); /* zero, tiny, huge or ordinary normals */
        const float scale = kind == 0 ? 0.0f : kind == 1 ? 1e-20f : kind == 2 ? 1e20f : 1.0f;
        for (int k = 0; k < 3; k++) c->normals[i * 3 + k] = value(g, -1.0f, 1.0f) * scale;
        for (int k = 0; k < 4; k++) c->colors[i * 4 + k] = value(g, -0.5f, 1.5f);
        for (int k = 0; k < 2; k++) c->texcoords[i * 2 + k] = value(g, -4.0f, 4.0f);
    }
    for (int k = 0; k < 4; k++) c->tint[k] = frange(g, 0.0f, 2.0f);

    sgLighting in;
    memset(&in, 0, sizeof in);
    for (int k = 0; k < 3; k++) in.ambient[k] = frange(g, 0.0f, 0.5f);
    in.light_count = irange(g, 1, SG_MAX_LIGHTS);
    for (int i = 0; i < in.light_count; i++) {
        sgLight *l = &in.lights[i];
        l->type = chance(g, 50) ? SG_LIGHT_POINT : SG_LIGHT_DIRECTIONAL;
        for (int k = 0; k < 3; k++) {
            l->direction[k] = frange(g, -1.0f, 1.0f);
            /* sometimes at a vertex, where L is 0 */
            const float at = c->positions[c->first * 4 + k];
            l->position[k] = chance(g, 10) && isfinite(at) ? at : frange(g, -6.0f, 6.0f);
            l->color[k] = chance(g, 3) ? 1e30f : frange(g, 0.0f, 1.5f);
            l->attenuation[k] = chance(g, 50) ? 0.0f : frange(g, 0.0f, 1.0f);
        }
        if (l->direction[0] == 0.0f) l->direction[0] = 0.5f;
    }
    float specular[3] = {0.0f, 0.0f, 0.0f};
    if (chance(g, 60))
        for (int k = 0; k < 3; k++) specular[k] = frange(g, 0.0f, 1.0f);
    const float shininess = chance(g, 10) ? 0.0f : chance(g, 10) ? 128.0f : frange(g, 0.0f, 128.0f);
    assert_true(sg_light_prepare(&in, specular, shininess, &c->lights, NULL, NULL));

    sg_vertex_lit *l = &c->lit;
    l->mode = SG_LIGHTING_GOURAUD;
    l->world_view = c->world_view;
    l->normal_matrix = c->normal_matrix;
    l->positions = c->positions;
    l->normals = c->normals;
    l->colors = chance(g, 70) ? c->colors : NULL;
    l->texcoords = chance(g, 50) ? c->texcoords : NULL;
    l->tint = chance(g, 50) ? c->tint : NULL;
    l->lights = &c->lights;
    l->split = chance(g, 40) ? 1 + irange(g, 0, in.light_count - 1) : 0;
    if (l->split)
        l->stride = c->lights.has_specular ? SG_LIT_SPLIT_END : SG_LIT_SPLIT_SEC;
    else if (c->lights.has_specular)
        l->stride = SG_LIT_SEC + 3;
    else /* an untextured draw stores its colour alone */
        l->stride = !l->texcoords && chance(g, 50) ? SG_LIT_ST : SG_LIT_SEC;
}

/* The scalar path's output and flags against fn's, sentinel-filled, for one case. */
static void compare_case(const lit_case *c, sg_vertex_lit_fn fn, const char *name, int index) {
    enum { FLOATS = MAX_VERTS * SG_LIT_SPLIT_END };
    static float want[FLOATS], got[FLOATS];
    uint8_t ok_want[MAX_VERTS], ok_got[MAX_VERTS];
    memset(want, 0x5a, sizeof want);
    memset(got, 0x5a, sizeof got);
    for (int i = 0; i < MAX_VERTS; i++) ok_want[i] = ok_got[i] = (uint8_t)(i % 7 != 3);
    sg_vertex_lit l = c->lit;
    l.gouraud = NULL;
    sg_vertex_lit_attributes(&l, c->first, c->count, want, ok_want);
    l.gouraud = fn;
    sg_vertex_lit_attributes(&l, c->first, c->count, got, ok_got);
    if (memcmp(want, got, sizeof want) != 0 || memcmp(ok_want, ok_got, sizeof ok_want) != 0) {
        for (int i = 0; i < MAX_VERTS * l.stride; i++)
            if (memcmp(&want[i], &got[i], sizeof want[i]) != 0) {
                fprintf(stderr,
                        "%s, case %d (split %d, stride %d, lights %d): vertex %d attribute %d: "
                        "%.9g, scalar %.9g\n",
                        name, index, l.split, l.stride, c->lights.count, i / l.stride, i % l.stride,
                        (double)got[i], (double)want[i]);
                break;
            }
        fail_msg("%s differs from the scalar Gouraud lighting", name);
    }
}

static void compare_set(sg_isa isa, sg_vertex_lit_fn fn, const char *name) {
    if (!sg_isa_runs(isa) || !fn) {
        printf("%s: not in this build or not on this CPU, skipped\n", name);
        return;
    }
    static lit_case c;
    rng g = {0x51ce5eedu + (uint64_t)isa};
    for (int i = 0; i < CASES; i++) {
        make_case(&g, &c);
        compare_case(&c, fn, name, i);
    }
}

static void avx2(void **state) {
    (void)state;
    compare_set(SG_ISA_AVX2, sg_vertex_gouraud_avx2(), "AVX2");
}

static void avx512(void **state) {
    (void)state;
    compare_set(SG_ISA_AVX512, sg_vertex_gouraud_avx512(), "AVX-512");
}

static void neon(void **state) {
    (void)state;
    compare_set(SG_ISA_NEON, sg_vertex_gouraud_neon(), "NEON");
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(avx2),
        cmocka_unit_test(avx512),
        cmocka_unit_test(neon),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
