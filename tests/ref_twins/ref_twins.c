/* ref_twins.c - a shader library whose shaders redo the fixed unlit shading, so that sgapi-ref
 * can be checked on scenes whose draws become shader draws: the image must not change.
 *   ref_color:   vertex colour times uniforms u[0..3] (the draw's "color")
 *   ref_texture: the same times texture 0 at the texcoord
 * Builds with the headers alone: cc -O2 -shared -fPIC -I include ref_twins.c -o ref_twins.so */
#include "sgapi/sgapi_shaders.h"

/* clip = proj * (world_view * position), the colour times u[0..3] into varyings 0..3, the
 * texcoord into 4..5. */
static void vertex(sgVertexBatch *b, const void *uniforms) {
    const float *u = uniforms;
    for (int i = 0; i < SG_SHADER_LANES; i++) {
        float e[4];
        for (int r = 0; r < 4; r++)
            e[r] = b->world_view[r * 4 + 0] * b->position[0][i] +
                   b->world_view[r * 4 + 1] * b->position[1][i] +
                   b->world_view[r * 4 + 2] * b->position[2][i] +
                   b->world_view[r * 4 + 3] * b->position[3][i];
        for (int r = 0; r < 4; r++)
            b->clip[r][i] = b->proj[r * 4 + 0] * e[0] + b->proj[r * 4 + 1] * e[1] +
                            b->proj[r * 4 + 2] * e[2] + b->proj[r * 4 + 3] * e[3];
        for (int c = 0; c < 4; c++) b->varying[c][i] = b->color[c][i] * u[c];
        b->varying[4][i] = b->texcoord[0][i];
        b->varying[5][i] = b->texcoord[1][i];
    }
}

static void fragment_color(sgFragmentBatch *b, const void *uniforms) {
    (void)uniforms;
    for (int c = 0; c < 4; c++)
        for (int i = 0; i < SG_SHADER_LANES; i++) b->color[c][i] = b->varying[c][i];
}

static void fragment_texture(sgFragmentBatch *b, const void *uniforms) {
    (void)uniforms;
    float t[4][SG_SHADER_LANES];
    sgSample(b, 0, b->varying[4], b->varying[5], t);
    for (int c = 0; c < 4; c++)
        for (int i = 0; i < SG_SHADER_LANES; i++) b->color[c][i] = b->varying[c][i] * t[c][i];
}

#define TWIN_VERTEX                                                                                \
    "#version 450\n"                                                                               \
    "layout(location = 0) in vec4 position;\n"                                                     \
    "layout(location = 1) in vec4 color;\n"                                                        \
    "layout(location = 3) in vec2 texcoord;\n"                                                     \
    "layout(push_constant) uniform SgDraw { mat4 world_view; mat4 proj; };\n"                      \
    "layout(std430, set = 0, binding = 0) readonly buffer SgUniforms { float u[]; };\n"            \
    "layout(location = 0) out vec4 v_color;\n"                                                     \
    "layout(location = 1) out vec2 v_texcoord;\n"                                                  \
    "void main() {\n"                                                                              \
    "    gl_Position = proj * (world_view * position);\n"                                          \
    "    v_color = color * vec4(u[0], u[1], u[2], u[3]);\n"                                        \
    "    v_texcoord = texcoord;\n"                                                                 \
    "}\n"

static const sgShaderInfo shaders[] = {
    {.name = "ref_color",
     .desc = {.vertex = vertex, .fragment = fragment_color, .varying_count = 6},
     .uniform_count = 4,
     .glsl_vertex = TWIN_VERTEX,
     .glsl_fragment = "#version 450\n"
                      "layout(location = 0) in vec4 v_color;\n"
                      "layout(location = 0) out vec4 o_color;\n"
                      "void main() { o_color = v_color; }\n"},
    {.name = "ref_texture",
     .desc =
         {.vertex = vertex, .fragment = fragment_texture, .varying_count = 6, .texture_count = 1},
     .uniform_count = 4,
     .glsl_vertex = TWIN_VERTEX,
     .glsl_fragment = "#version 450\n"
                      "layout(location = 0) in vec4 v_color;\n"
                      "layout(location = 1) in vec2 v_texcoord;\n"
                      "layout(set = 0, binding = 1) uniform sampler2D sg_textures[8];\n"
                      "layout(location = 0) out vec4 o_color;\n"
                      "void main() { o_color = v_color * texture(sg_textures[0], v_texcoord); }\n"},
};

static const sgShaderLibrary library = {SGAPI_SHADER_ABI_VERSION, 2, shaders};

const sgShaderLibrary *sgapi_shader_library(void);
const sgShaderLibrary *sgapi_shader_library(void) {
    return &library;
}
