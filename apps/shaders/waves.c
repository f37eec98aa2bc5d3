/* waves.c - a grid made water: each vertex raised by a sum of three travelling sine waves of its
 * x and z, with the normal from the sum's derivatives (not from the mesh), lit per pixel by one
 * directional light with a specular highlight (the equation of phong.c). Meant for a flat grid in
 * x-z (the "plane" shape with many segments).
 *
 * Uniforms (29 floats):
 *   u[0]      time
 *   u[1..4]   wave 1: amplitude a, wave numbers kx, kz, angular speed w:
 *             y += a sin(kx x + kz z + w time)
 *   u[5..8]   wave 2, u[9..12] wave 3: the same
 *   u[13..15] colour r, g, b: multiplies the vertex colour
 *   u[16..18] ambient light r, g, b
 *   u[19..21] light direction x, y, z: the way it travels, in view space (not zero)
 *   u[22..24] light colour r, g, b
 *   u[25..27] material specular colour r, g, b
 *   u[28]     shininess, 0..128
 * Varyings: 0..2 view-space position, 3..5 normal, 6..8 base colour. Alpha is 1.
 */
#include "builtin.h"
#include "shader_math.h"

SGS_STAGE static void waves_vertex(sgVertexBatch *b, const void *uniforms) {
    const float *u = uniforms;
    const float time = u[0];
    float p[4][SGS_LANES], n[3][SGS_LANES];
    SGS_EACH_VECTOR(h) {
        const sgs_vf x = sgs_vload(b->position[0] + h), z = sgs_vload(b->position[2] + h);
        sgs_vf y = sgs_vload(b->position[1] + h), dx = sgs_vsplat(0.0f), dz = sgs_vsplat(0.0f);
        for (int w = 0; w < 3; w++) {
            const float *wave = u + 1 + 4 * w;
            sgs_vf phase = (wave[1] * x + wave[2] * z) + wave[3] * time;
            sgs_vf s = sgs_vsin(phase), c = sgs_vcos(phase);
            y = y + wave[0] * s;
            dx = dx + (wave[0] * wave[1]) * c;
            dz = dz + (wave[0] * wave[2]) * c;
        }
        sgs_vstore(p[0] + h, x), sgs_vstore(p[1] + h, y), sgs_vstore(p[2] + h, z);
        /* The surface (x, y(x, z), z): tangents (1, dy/dx, 0) and (0, dy/dz, 1). */
        sgs_vstore(n[0] + h, -dx), sgs_vstore(n[1] + h, sgs_vsplat(1.0f));
        sgs_vstore(n[2] + h, -dz);
    }
    memcpy(p[3], b->position[3], sizeof p[3]);
    for (int k = 0; k < 3; k++)
        SGS_SIMD for (int i = 0; i < SGS_LANES; i++) b->varying[6 + k][i] =
            b->color[k][i] * u[13 + k];
    sgs_transform_from(b, (const float(*)[SGS_LANES])p, (const float(*)[SGS_LANES])n, 0, 3);
}

SGS_STAGE static void waves_fragment(sgFragmentBatch *b, const void *uniforms) {
    const float *u = uniforms;
    const sgs_light l = sgs_light_read(u, 16, 19, 22, 25, 28);
    sgs_vlight_varyings(&l, b, 0);
    SGS_EACH_VECTOR(h) sgs_vstore(b->color[3] + h, sgs_vsplat(1.0f));
}

static const char waves_glsl_vertex[] = SGS_GLSL_HEADER SGS_GLSL_DRAW SGS_GLSL_INPUTS
    "layout(location = 0) out vec3 v_pos;\n"
    "layout(location = 1) out vec3 v_normal;\n"
    "layout(location = 2) out vec3 v_base;\n"
    "void main() {\n"
    "    vec4 q = sg_position;\n"
    "    float dx = 0.0, dz = 0.0;\n"
    "    for (int w = 0; w < 3; w++) {\n"
    "        int k = 1 + 4 * w;\n"
    "        float phase = (u[k + 1] * q.x + u[k + 2] * q.z) + u[k + 3] * u[0];\n"
    "        q.y += u[k] * sin(phase);\n"
    "        dx += (u[k] * u[k + 1]) * cos(phase);\n"
    "        dz += (u[k] * u[k + 2]) * cos(phase);\n"
    "    }\n"
    "    vec4 p = world_view * q;\n"
    "    gl_Position = proj * p;\n"
    "    v_pos = p.xyz;\n"
    "    v_normal = transpose(inverse(mat3(world_view))) * vec3(-dx, 1.0, -dz);\n"
    "    v_base = sg_color.rgb * vec3(u[13], u[14], u[15]);\n"
    "}\n";

static const char waves_glsl_fragment[] = SGS_GLSL_HEADER SGS_GLSL_LIGHT SGS_GLSL_OUTPUT
    "layout(location = 0) in vec3 v_pos;\n"
    "layout(location = 1) in vec3 v_normal;\n"
    "layout(location = 2) in vec3 v_base;\n"
    "void main() {\n"
    "    sg_frag_color = vec4(light(v_pos, v_normal, v_base, 16, 19, 22, 25, 28), 1.0);\n"
    "}\n";

const sgShaderInfo SGS_NAME(sg_shader_waves) = {
    .name = "waves",
    .desc = {.vertex = waves_vertex,
             .fragment = waves_fragment,
             .varying_count = 9,
             .flat_varyings = 0,
             .texture_count = 0,
             .independent_lanes = true},
    .uniform_count = 29,
    .glsl_vertex = waves_glsl_vertex,
    .glsl_fragment = waves_glsl_fragment,
};
