/* unlit.c - the fixed unlit equations as a shader: the interpolated vertex colour
 * (SG_SHADE_VERTEX_COLOR), times texture 0 when u[0] is not 0 (SG_SHADE_TEXTURE_MODULATE, with
 * the pipeline's filter and wrap). It exists to compare a shader pipeline's cost with the fixed
 * path's on the same image, so its clip positions are those of the fixed path bit for bit.
 *
 * Uniforms (1 float): u[0] 1: modulate by texture 0; 0: the vertex colour alone.
 * Varyings: 0..3 the colour, 4..5 the texture coordinates. */
#include "builtin.h"
#include "shader_math.h"

/* The fixed path's combined matrix: proj * world_view, each element summed in double and rounded
 * to float once (sgapi's vertex stage forms it the same way, once per draw). */
static void mvp_of(const float *proj, const float *world_view, float out[16]) {
    for (int r = 0; r < 4; r++)
        for (int c = 0; c < 4; c++) {
            double s = 0.0;
            for (int k = 0; k < 4; k++)
                s += (double)proj[r * 4 + k] * (double)world_view[k * 4 + c];
            out[r * 4 + c] = (float)s;
        }
}

SGS_STAGE static void unlit_vertex(sgVertexBatch *b, const void *uniforms) {
    (void)uniforms;
    /* Once per batch: 64 products against 16 lanes of 16 each. */
    float m[16];
    mvp_of(b->proj, b->world_view, m);
    for (int r = 0; r < 4; r++)
        /* ((m0 x + m1 y) + m2 z) + m3 w in float, the fixed path's order (no fused multiply-add:
         * this file is compiled with -ffp-contract=off). */
        for (int i = 0; i < SG_SHADER_LANES; i++)
            b->clip[r][i] = m[r * 4 + 0] * b->position[0][i] + m[r * 4 + 1] * b->position[1][i] +
                            m[r * 4 + 2] * b->position[2][i] + m[r * 4 + 3] * b->position[3][i];
    for (int c = 0; c < 4; c++)
        for (int i = 0; i < SG_SHADER_LANES; i++) b->varying[c][i] = b->color[c][i];
    for (int c = 0; c < 2; c++)
        for (int i = 0; i < SG_SHADER_LANES; i++) b->varying[4 + c][i] = b->texcoord[c][i];
}

SGS_STAGE static void unlit_fragment(sgFragmentBatch *b, const void *uniforms) {
    const float *u = uniforms;
    b->discard = 0;
    if (u[0] == 0.0f) { /* the vertex colour alone: no texture to sample */
        memcpy(b->color, b->varying, sizeof b->color);
        return;
    }
    float texel[4][SG_SHADER_LANES];
    sgSample(b, 0, b->varying[4], b->varying[5], texel);
    for (int c = 0; c < 4; c++)
        SGS_SIMD for (int i = 0; i < SG_SHADER_LANES; i++) b->color[c][i] =
            b->varying[c][i] * texel[c][i];
}

/* The twin: the same product (the reference gives world_view and proj so that proj * world_view *
 * p is the C computation) and the same interpolated colour at location 0. */
static const char unlit_glsl_vertex[] =
    "#version 450\n"
    "layout(location = 0) in vec4 sg_position;\n"
    "layout(location = 1) in vec4 sg_color;\n"
    "layout(push_constant) uniform SgDraw { mat4 world_view; mat4 proj; };\n"
    "layout(std430, set = 0, binding = 0) readonly buffer SgUniforms { float u[]; };\n"
    "layout(location = 3) in vec2 sg_texcoord;\n"
    "layout(location = 0) out vec4 v_color;\n"
    "layout(location = 1) out vec2 v_st;\n"
    "void main() {\n"
    "    gl_Position = proj * world_view * sg_position;\n"
    "    v_color = sg_color;\n"
    "    v_st = sg_texcoord;\n"
    "}\n";

static const char unlit_glsl_fragment[] =
    "#version 450\n"
    "layout(std430, set = 0, binding = 0) readonly buffer SgUniforms { float u[]; };\n"
    "layout(set = 0, binding = 1) uniform sampler2D sg_textures[8];\n"
    "layout(location = 0) in vec4 v_color;\n"
    "layout(location = 1) in vec2 v_st;\n"
    "layout(location = 0) out vec4 o_color;\n"
    "void main() {\n"
    "    o_color = u[0] != 0.0 ? v_color * texture(sg_textures[0], v_st) : v_color;\n"
    "}\n";

const sgShaderInfo SGS_NAME(sg_shader_unlit) = {
    .name = "unlit",
    .desc = {.vertex = unlit_vertex,
             .fragment = unlit_fragment,
             .varying_count = 6,
             .independent_lanes = true,
             .varyings_only = true},
    .uniform_count = 1,
    .glsl_vertex = unlit_glsl_vertex,
    .glsl_fragment = unlit_glsl_fragment,
};
