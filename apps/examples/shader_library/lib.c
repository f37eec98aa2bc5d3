/* lib.c - a shader library of its own: one shader, "stripes", as a shared object that
 * sgapi-render, sgapi-ref, sgapi-bench and sgapi-view load with --shaders. It builds with the
 * headers alone (the program that loads it provides sgSample), from the repository's root:
 *
 *     cc -O2 -shared -fPIC -I include apps/examples/shader_library/lib.c -o lib.so -lm
 *
 * and a scene file names its shader: "shader": "stripes", "uniforms": [8, 1, 0.9, 0.2].
 *
 * stripes: the vertex colour in bands across the object's x + y, every other band the given
 * colour; no lighting.
 *   u[0]      bands per object-space unit
 *   u[1..3]   colour r, g, b of every other band
 * Varyings: 0..2 the vertex colour, 3 the object-space x + y times u[0].
 */
#include <math.h>

#include "sgapi/sgapi_shaders.h"

static void stripes_vertex(sgVertexBatch *b, const void *uniforms) {
    const float *u = uniforms;
    const float *m = b->world_view, *p = b->proj;
    for (int i = 0; i < SG_SHADER_LANES; i++) {
        float x = b->position[0][i], y = b->position[1][i], z = b->position[2][i],
              w = b->position[3][i];
        float v[4];
        for (int r = 0; r < 4; r++)
            v[r] = ((m[4 * r] * x + m[4 * r + 1] * y) + m[4 * r + 2] * z) + m[4 * r + 3] * w;
        for (int r = 0; r < 4; r++)
            b->clip[r][i] = ((p[4 * r] * v[0] + p[4 * r + 1] * v[1]) + p[4 * r + 2] * v[2]) +
                            p[4 * r + 3] * v[3];
        for (int k = 0; k < 3; k++) b->varying[k][i] = b->color[k][i];
        b->varying[3][i] = (x + y) * u[0];
    }
}

static void stripes_fragment(sgFragmentBatch *b, const void *uniforms) {
    const float *u = uniforms;
    for (int i = 0; i < SG_SHADER_LANES; i++) {
        float s = b->varying[3][i];
        int odd = (s - 2.0f * floorf(0.5f * s)) >= 1.0f; /* s mod 2 >= 1 */
        for (int k = 0; k < 3; k++) b->color[k][i] = odd ? u[1 + k] : b->varying[k][i];
        b->color[3][i] = 1.0f;
    }
}

/* The twin: what the reference renderer runs in the C shader's place (docs/api.md, "Shaders"). */
static const char stripes_glsl_vertex[] =
    "#version 450\n"
    "layout(push_constant) uniform SgDraw { mat4 world_view; mat4 proj; };\n"
    "layout(std430, set = 0, binding = 0) readonly buffer SgUniforms { float u[]; };\n"
    "layout(location = 0) in vec4 sg_position;\n"
    "layout(location = 1) in vec4 sg_color;\n"
    "layout(location = 0) out vec3 v_color;\n"
    "layout(location = 1) out float v_s;\n"
    "void main() {\n"
    "    gl_Position = proj * (world_view * sg_position);\n"
    "    v_color = sg_color.rgb;\n"
    "    v_s = (sg_position.x + sg_position.y) * u[0];\n"
    "}\n";

static const char stripes_glsl_fragment[] =
    "#version 450\n"
    "layout(std430, set = 0, binding = 0) readonly buffer SgUniforms { float u[]; };\n"
    "layout(location = 0) in vec3 v_color;\n"
    "layout(location = 1) in float v_s;\n"
    "layout(location = 0) out vec4 color;\n"
    "void main() {\n"
    "    bool odd = v_s - 2.0 * floor(0.5 * v_s) >= 1.0;\n"
    "    color = vec4(odd ? vec3(u[1], u[2], u[3]) : v_color, 1.0);\n"
    "}\n";

static const sgShaderInfo shaders[] = {{
    .name = "stripes",
    /* The fragment stage reads each lane's own varyings only: batches may span triangles. */
    .desc = {.vertex = stripes_vertex,
             .fragment = stripes_fragment,
             .varying_count = 4,
             .independent_lanes = true},
    .uniform_count = 4,
    .glsl_vertex = stripes_glsl_vertex,
    .glsl_fragment = stripes_glsl_fragment,
}};

static const sgShaderLibrary library = {
    .abi_version = SGAPI_SHADER_ABI_VERSION,
    .count = (int)(sizeof shaders / sizeof shaders[0]),
    .shaders = shaders,
};

/* What the programs look up (SGAPI_SHADER_LIBRARY_SYMBOL). */
__attribute__((visibility("default"))) const sgShaderLibrary *sgapi_shader_library(void) {
    return &library;
}
