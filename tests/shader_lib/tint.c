/* tint.c - a shader library as a user builds it, with the headers alone:
 *     cc -O2 -shared -fPIC -I include tint.c -o tint.so -lm
 * One shader, "tint": positions through proj * world_view, the fragment colour the draw's three
 * uniforms. Built with -DTINT_ABI_OFFSET=1 it claims the next ABI version, which programs refuse;
 * with -DTINT_UNLIT=1 it names a built-in shader. */
#include <sgapi/sgapi_shaders.h>

#ifndef TINT_ABI_OFFSET
#define TINT_ABI_OFFSET 0
#endif
#ifdef TINT_UNLIT
#define TINT_NAME "unlit"
#else
#define TINT_NAME "tint"
#endif

static void tint_vertex(sgVertexBatch *b, const void *uniforms) {
    (void)uniforms;
    for (int r = 0; r < 4; r++)
        for (int i = 0; i < SG_SHADER_LANES; i++) {
            float s = 0.0f;
            for (int k = 0; k < 4; k++) {
                float m = 0.0f; /* row r of proj * world_view, column k */
                for (int j = 0; j < 4; j++) m += b->proj[r * 4 + j] * b->world_view[j * 4 + k];
                s += m * b->position[k][i];
            }
            b->clip[r][i] = s;
        }
}

static void tint_fragment(sgFragmentBatch *b, const void *uniforms) {
    const float *u = uniforms;
    for (int i = 0; i < SG_SHADER_LANES; i++) {
        for (int c = 0; c < 3; c++) b->color[c][i] = u[c];
        b->color[3][i] = 1.0f;
    }
    b->discard = 0;
}

static const sgShaderInfo shaders[] = {{
    .name = TINT_NAME,
    .desc = {.vertex = tint_vertex, .fragment = tint_fragment},
    .uniform_count = 3,
    .glsl_vertex = "#version 450\n"
                   "layout(location = 0) in vec4 sg_position;\n"
                   "layout(push_constant) uniform SgDraw { mat4 world_view; mat4 proj; };\n"
                   "void main() { gl_Position = proj * world_view * sg_position; }\n",
    .glsl_fragment =
        "#version 450\n"
        "layout(std430, set = 0, binding = 0) readonly buffer SgUniforms { float u[]; };\n"
        "layout(location = 0) out vec4 o_color;\n"
        "void main() { o_color = vec4(u[0], u[1], u[2], 1.0); }\n",
}};

static const sgShaderLibrary library = {SGAPI_SHADER_ABI_VERSION + TINT_ABI_OFFSET, 1, shaders};

const sgShaderLibrary *sgapi_shader_library(void) {
    return &library;
}
