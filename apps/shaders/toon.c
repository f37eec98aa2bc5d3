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

/* On the set's vectors, not a loop over lanes: the floor's and the clamps' selects kept the loop
 * scalar in every compilation. */
SGS_STAGE static void toon_fragment(sgFragmentBatch *b, const void *uniforms) {
    const float *u = uniforms;
    float il = sgs_inv_len(u[3], u[4], u[5]);
    const float lx = -u[3] * il, ly = -u[4] * il, lz = -u[5] * il;
    const float ambient = u[9], bands = u[10] >= 2.0f ? u[10] : 2.0f, width = u[11];
    const float steps = bands - 1.0f, lit = 1.0f - ambient;
    const float light[3] = {u[6], u[7], u[8]}, rim_color[3] = {u[12], u[13], u[14]};
    SGS_EACH_VECTOR(h) {
        const sgs_vf px = sgs_vload(b->varying[0] + h), py = sgs_vload(b->varying[1] + h),
                     pz = sgs_vload(b->varying[2] + h);
        sgs_vf nx = sgs_vload(b->varying[3] + h), ny = sgs_vload(b->varying[4] + h),
               nz = sgs_vload(b->varying[5] + h);
        const sgs_vf in = sgs_vinv_len(nx, ny, nz), iv = sgs_vinv_len(px, py, pz);
        nx *= in, ny *= in, nz *= in;
        const sgs_vf ndotl = (nx * lx + ny * ly) + nz * lz;
        const sgs_vf ndotv = ((nx * -px + ny * -py) + nz * -pz) * iv;
        const sgs_vf d = sgs_vsel(ndotl > 0.0f, ndotl, sgs_vsplat(0.0f));
        const sgs_vf band = sgs_vfloor(d * bands), level = band / steps;
        const sgs_vf shade = ambient + lit * sgs_vsel(level < 1.0f, level, sgs_vsplat(1.0f));
        /* rim = 1 - smoothstep(width, width + 0.05, N.V) */
        const sgs_vf t = sgs_vclamp01((ndotv - width) * 20.0f);
        const sgs_vf rim = 1.0f - t * t * (3.0f - 2.0f * t);
        for (int k = 0; k < 3; k++) {
            const sgs_vf c = sgs_vload(b->varying[6 + k] + h) * (shade * light[k]);
            sgs_vstore(b->color[k] + h, c + (rim_color[k] - c) * rim);
        }
        sgs_vstore(b->color[3] + h, sgs_vsplat(1.0f));
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
