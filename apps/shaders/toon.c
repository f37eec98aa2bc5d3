/* toon.c - cel shading: the diffuse light quantised into a few flat bands, and a dark rim where
 * the surface turns away from the viewer (its silhouette).
 *
 * Uniforms (15 floats):
 *   u[0..2]   colour r, g, b: multiplies the vertex colour
 *   u[3..5]   light direction x, y, z: the way it travels, in view space (not zero)
 *   u[6..8]   light colour r, g, b
 *   u[9]      ambient: the brightness of the darkest band, 0..1
 *   u[10]     bands, >= 2: the diffuse term max(N.L, 0) becomes floor(N.L bands) / (bands - 1),
 *             at most 1
 *   u[11]     rim width: N.V below it turns to the rim colour (over a further 0.05, smoothly)
 *   u[12..14] rim colour r, g, b
 * Varyings: 0..2 view-space position, 3..5 normal, 6..8 base colour. Alpha is 1.
 */
#include "builtin.h"
#include "shader_math.h"

SGS_STAGE static void toon_vertex(sgVertexBatch *b, const void *uniforms) {
    const float *u = uniforms;
    sgs_transform(b, 0, 3);
    for (int k = 0; k < 3; k++)
        SGS_SIMD for (int i = 0; i < SGS_LANES; i++) b->varying[6 + k][i] = b->color[k][i] * u[k];
}

SGS_STAGE static void toon_fragment(sgFragmentBatch *b, const void *uniforms) {
    const float *u = uniforms;
    float il = sgs_inv_len(u[3], u[4], u[5]);
    const float lx = -u[3] * il, ly = -u[4] * il, lz = -u[5] * il;
    const float ambient = u[9], bands = u[10] >= 2.0f ? u[10] : 2.0f, width = u[11];
    const float lr = u[6], lg = u[7], lb = u[8], rr = u[12], rg = u[13], rb = u[14];
    SGS_SIMD for (int i = 0; i < SGS_LANES; i++) {
        float px = b->varying[0][i], py = b->varying[1][i], pz = b->varying[2][i];
        float nx = b->varying[3][i], ny = b->varying[4][i], nz = b->varying[5][i];
        float in = sgs_inv_len(nx, ny, nz), iv = sgs_inv_len(px, py, pz);
        nx *= in, ny *= in, nz *= in;
        float ndotl = (nx * lx + ny * ly) + nz * lz;
        float ndotv = ((nx * -px + ny * -py) + nz * -pz) * iv;
        float band = sgs_floor(sgs_max(ndotl, 0.0f) * bands);
        float level = sgs_min(band / (bands - 1.0f), 1.0f);
        float shade = ambient + (1.0f - ambient) * level;
        /* rim = 1 - smoothstep(width, width + 0.05, N.V) */
        float t = sgs_clamp01((ndotv - width) * 20.0f);
        float rim = 1.0f - t * t * (3.0f - 2.0f * t);
        float c0 = b->varying[6][i] * (shade * lr), c1 = b->varying[7][i] * (shade * lg),
              c2 = b->varying[8][i] * (shade * lb);
        b->color[0][i] = c0 + (rr - c0) * rim;
        b->color[1][i] = c1 + (rg - c1) * rim;
        b->color[2][i] = c2 + (rb - c2) * rim;
        b->color[3][i] = 1.0f;
    }
}

static const char toon_glsl_vertex[] = SGS_GLSL_HEADER SGS_GLSL_DRAW SGS_GLSL_INPUTS
    "layout(location = 0) out vec3 v_pos;\n"
    "layout(location = 1) out vec3 v_normal;\n"
    "layout(location = 2) out vec3 v_base;\n"
    "void main() {\n"
    "    vec4 p = world_view * sg_position;\n"
    "    gl_Position = proj * p;\n"
    "    v_pos = p.xyz;\n"
    "    v_normal = transpose(inverse(mat3(world_view))) * sg_normal;\n"
    "    v_base = sg_color.rgb * vec3(u[0], u[1], u[2]);\n"
    "}\n";

static const char toon_glsl_fragment[] = SGS_GLSL_HEADER SGS_GLSL_U3 SGS_GLSL_OUTPUT
    "layout(location = 0) in vec3 v_pos;\n"
    "layout(location = 1) in vec3 v_normal;\n"
    "layout(location = 2) in vec3 v_base;\n"
    "vec3 safe_normalize(vec3 v) {\n"
    "    float len2 = dot(v, v);\n"
    "    return len2 > 0.0 ? v / sqrt(len2) : vec3(0.0);\n"
    "}\n"
    "void main() {\n"
    "    vec3 L = -safe_normalize(u3(3));\n"
    "    vec3 N = safe_normalize(v_normal), V = safe_normalize(-v_pos);\n"
    "    float bands = max(u[10], 2.0);\n"
    "    float level = min(floor(max(dot(N, L), 0.0) * bands) / (bands - 1.0), 1.0);\n"
    "    float shade = u[9] + (1.0 - u[9]) * level;\n"
    "    float t = clamp((dot(N, V) - u[11]) * 20.0, 0.0, 1.0);\n"
    "    float rim = 1.0 - t * t * (3.0 - 2.0 * t);\n"
    "    vec3 c = v_base * (shade * u3(6));\n"
    "    sg_frag_color = vec4(c + (u3(12) - c) * rim, 1.0);\n"
    "}\n";

const sgShaderInfo SGS_NAME(sg_shader_toon) = {
    .name = "toon",
    .desc = {.vertex = toon_vertex,
             .fragment = toon_fragment,
             .varying_count = 9,
             .flat_varyings = 0,
             .texture_count = 0,
             .independent_lanes = true},
    .uniform_count = 15,
    .glsl_vertex = toon_glsl_vertex,
    .glsl_fragment = toon_glsl_fragment,
};
