/* normal_map.c - a tangent-space normal map: texture 0 holds the surface's normal in the frame of
 * its tangent T, bitangent B and normal N (r, g, b = x, y, z mapped from [-1, 1] to [0, 1]),
 * attribute 0 the tangent (x, y, z) and handedness w (B = w N x T); lit per pixel by one
 * directional light (the equation of phong.c). The base colour is the vertex colour, times
 * texture 1 as far as u[0] says.
 *
 * Uniforms (15 floats):
 *   u[0]      texture weight: base = vertex colour x mix(1, texture 1, u[0]) (0: no texture)
 *   u[1]      bump strength: the map's x and y are scaled by it (0: flat, 1: as stored)
 *   u[2..4]   ambient light r, g, b
 *   u[5..7]   light direction x, y, z: the way it travels, in view space (not zero)
 *   u[8..10]  light colour r, g, b
 *   u[11..13] material specular colour r, g, b
 *   u[14]     shininess, 0..128
 * Textures: 0 the normal map, 1 the colour. Varyings: 0..2 view-space position, 3..5 normal,
 * 6..8 tangent (world_view x T), 9 handedness, 10..11 texcoords, 12..15 vertex colour.
 */
#include "builtin.h"
#include "shader_math.h"

SGS_STAGE static void normal_map_vertex(sgVertexBatch *b, const void *uniforms) {
    (void)uniforms;
    const float *m = b->world_view;
    sgs_transform(b, 0, 3);
    SGS_SIMD for (int i = 0; i < SGS_LANES; i++) {
        float tx = b->attribute[0][0][i], ty = b->attribute[0][1][i], tz = b->attribute[0][2][i];
        for (int r = 0; r < 3; r++)
            b->varying[6 + r][i] = (m[4 * r] * tx + m[4 * r + 1] * ty) + m[4 * r + 2] * tz;
        b->varying[9][i] = b->attribute[0][3][i];
        b->varying[10][i] = b->texcoord[0][i];
        b->varying[11][i] = b->texcoord[1][i];
        for (int k = 0; k < 4; k++) b->varying[12 + k][i] = b->color[k][i];
    }
}

SGS_STAGE static void normal_map_fragment(sgFragmentBatch *b, const void *uniforms) {
    const float *u = uniforms;
    const sgs_light l = sgs_light_read(u, 2, 5, 8, 11, 14);
    const float weight = u[0], strength = u[1];
    float map[4][SGS_LANES], tex[4][SGS_LANES];
    sgSample(b, 0, b->varying[10], b->varying[11], map);
    sgSample(b, 1, b->varying[10], b->varying[11], tex);
    SGS_EACH_VECTOR(h) {
        sgs_vf nx = sgs_vload(b->varying[3] + h), ny = sgs_vload(b->varying[4] + h),
               nz = sgs_vload(b->varying[5] + h);
        sgs_vf in = sgs_vinv_len(nx, ny, nz);
        nx *= in, ny *= in, nz *= in;
        /* T made perpendicular to N (Gram-Schmidt): interpolation bends them apart. */
        sgs_vf tx = sgs_vload(b->varying[6] + h), ty = sgs_vload(b->varying[7] + h),
               tz = sgs_vload(b->varying[8] + h);
        sgs_vf d = (nx * tx + ny * ty) + nz * tz;
        tx = tx - nx * d, ty = ty - ny * d, tz = tz - nz * d;
        sgs_vf it = sgs_vinv_len(tx, ty, tz);
        tx *= it, ty *= it, tz *= it;
        sgs_vf w =
            sgs_vsel(sgs_vload(b->varying[9] + h) < 0.0f, sgs_vsplat(-1.0f), sgs_vsplat(1.0f));
        sgs_vf bx = (ny * tz - nz * ty) * w, by = (nz * tx - nx * tz) * w,
               bz = (nx * ty - ny * tx) * w;
        sgs_vf mx = (sgs_vload(map[0] + h) * 2.0f - 1.0f) * strength,
               my = (sgs_vload(map[1] + h) * 2.0f - 1.0f) * strength,
               mz = sgs_vload(map[2] + h) * 2.0f - 1.0f;
        sgs_vf sx = (tx * mx + bx * my) + nx * mz, sy = (ty * mx + by * my) + ny * mz,
               sz = (tz * mx + bz * my) + nz * mz;
        sgs_vf base[3];
        for (int k = 0; k < 3; k++)
            base[k] = sgs_vload(b->varying[12 + k] + h) *
                      (1.0f + (sgs_vload(tex[k] + h) - 1.0f) * weight);
        sgs_vf c[3];
        sgs_vlight_eval(&l, sgs_vload(b->varying[0] + h), sgs_vload(b->varying[1] + h),
                        sgs_vload(b->varying[2] + h), sx, sy, sz, base, c);
        for (int k = 0; k < 3; k++) sgs_vstore(b->color[k] + h, c[k]);
    }
    memcpy(b->color[3], b->varying[15], sizeof b->color[3]);
}

static const char normal_map_glsl_vertex[] = SGS_GLSL_HEADER SGS_GLSL_DRAW SGS_GLSL_INPUTS
    "layout(location = 0) out vec3 v_pos;\n"
    "layout(location = 1) out vec3 v_normal;\n"
    "layout(location = 2) out vec3 v_tangent;\n"
    "layout(location = 3) out float v_hand;\n"
    "layout(location = 4) out vec2 v_st;\n"
    "layout(location = 5) out vec4 v_color;\n"
    "void main() {\n"
    "    vec4 p = world_view * sg_position;\n"
    "    gl_Position = proj * p;\n"
    "    v_pos = p.xyz;\n"
    "    v_normal = transpose(inverse(mat3(world_view))) * sg_normal;\n"
    "    v_tangent = mat3(world_view) * sg_attribute0.xyz;\n"
    "    v_hand = sg_attribute0.w;\n"
    "    v_st = sg_texcoord;\n"
    "    v_color = sg_color;\n"
    "}\n";

static const char normal_map_glsl_fragment[] =
    SGS_GLSL_HEADER SGS_GLSL_TEXTURES SGS_GLSL_LIGHT SGS_GLSL_OUTPUT
    "layout(location = 0) in vec3 v_pos;\n"
    "layout(location = 1) in vec3 v_normal;\n"
    "layout(location = 2) in vec3 v_tangent;\n"
    "layout(location = 3) in float v_hand;\n"
    "layout(location = 4) in vec2 v_st;\n"
    "layout(location = 5) in vec4 v_color;\n"
    "void main() {\n"
    "    vec3 N = safe_normalize(v_normal);\n"
    "    vec3 T = safe_normalize(v_tangent - N * dot(N, v_tangent));\n"
    "    vec3 B = cross(N, T) * (v_hand < 0.0 ? -1.0 : 1.0);\n"
    "    vec3 m = texture(sg_textures[0], v_st).rgb * 2.0 - 1.0;\n"
    "    m.xy *= u[1];\n"
    "    vec3 n = T * m.x + B * m.y + N * m.z;\n"
    "    vec3 tex = texture(sg_textures[1], v_st).rgb;\n"
    "    vec3 base = v_color.rgb * (1.0 + (tex - 1.0) * u[0]);\n"
    "    sg_frag_color = vec4(light(v_pos, n, base, 2, 5, 8, 11, 14), v_color.a);\n"
    "}\n";

const sgShaderInfo SGS_NAME(sg_shader_normal_map) = {
    .name = "normal_map",
    .desc = {.vertex = normal_map_vertex,
             .fragment = normal_map_fragment,
             .varying_count = 16,
             .flat_varyings = 0,
             .texture_count = 2,
             .independent_lanes = true},
    .uniform_count = 15,
    .glsl_vertex = normal_map_glsl_vertex,
    .glsl_fragment = normal_map_glsl_fragment,
};
