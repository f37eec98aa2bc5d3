/* phong.c - the fixed per-pixel lighting (SG_LIGHTING_PHONG, the equation of src/pipeline/light.h)
 * as a shader, for one directional light: view-space position and normal interpolated, the light
 * evaluated per pixel.
 *
 * Uniforms (17 floats):
 *   u[0..3]   colour r, g, b, a: multiplies the vertex colour (the base colour)
 *   u[4..6]   ambient light r, g, b
 *   u[7..9]   light direction x, y, z: the way it travels, in view space (not zero)
 *   u[10..12] light colour r, g, b
 *   u[13..15] material specular colour r, g, b
 *   u[16]     shininess, 0..128
 * Varyings: 0..2 view-space position, 3..5 normal (normal matrix x n), 6..9 base colour.
 */
#include "builtin.h"
#include "shader_math.h"

SGS_STAGE static void phong_vertex(sgVertexBatch *b, const void *uniforms) {
    const float *u = uniforms;
    sgs_transform(b, 0, 3);
    for (int k = 0; k < 4; k++)
        SGS_SIMD for (int i = 0; i < SGS_LANES; i++) b->varying[6 + k][i] = b->color[k][i] * u[k];
}

SGS_STAGE static void phong_fragment(sgFragmentBatch *b, const void *uniforms) {
    const float *u = uniforms;
    const sgs_light l = sgs_light_read(u, 4, 7, 10, 13, 16);
    sgs_vlight_varyings(&l, b, 0);
    memcpy(b->color[3], b->varying[9], sizeof b->color[3]);
}

static const char phong_glsl_vertex[] =
    SGS_GLSL_HEADER SGS_GLSL_DRAW SGS_GLSL_INPUTS SGS_GLSL_LIT_VERTEX_OUT
    "void main() {\n" SGS_GLSL_LIT_VERTEX "}\n";

static const char phong_glsl_fragment[] = SGS_GLSL_HEADER SGS_GLSL_LIGHT SGS_GLSL_OUTPUT
    "layout(location = 0) in vec3 v_pos;\n"
    "layout(location = 1) in vec3 v_normal;\n"
    "layout(location = 2) in vec4 v_base;\n"
    "void main() {\n"
    "    vec3 c = light(v_pos, v_normal, v_base.rgb, 4, 7, 10, 13, 16);\n"
    "    sg_frag_color = vec4(c, v_base.a);\n"
    "}\n";

const sgShaderInfo SGS_NAME(sg_shader_phong) = {
    .name = "phong",
    .desc = {.vertex = phong_vertex,
             .fragment = phong_fragment,
             .varying_count = 10,
             .flat_varyings = 0,
             .texture_count = 0,
             .independent_lanes = true},
    .uniform_count = 17,
    .glsl_vertex = phong_glsl_vertex,
    .glsl_fragment = phong_glsl_fragment,
};
