/* marble.c - a procedural stone: turbulence (shader_math.h: 3D value noise, 4 octaves of
 * |2 noise - 1|) of the object-space position bends parallel bands into veins; lit per pixel by
 * one directional light with a specular highlight (the equation of phong.c). The pattern is fixed
 * to the object: it turns and moves with it.
 *
 * Uniforms (21 floats):
 *   u[0]      scale: noise cells per object-space unit
 *   u[1]      turbulence: how far the veins are bent (in bands)
 *   u[2..4]   stone colour r, g, b
 *   u[5..7]   vein colour r, g, b
 *   u[8..10]  ambient light r, g, b
 *   u[11..13] light direction x, y, z: the way it travels, in view space (not zero)
 *   u[14..16] light colour r, g, b
 *   u[17..19] material specular colour r, g, b
 *   u[20]     shininess, 0..128
 * Varyings: 0..2 the object-space position times the scale, 3..5 view-space position, 6..8
 * normal. Alpha is 1.
 */
#include "builtin.h"
#include "shader_math.h"

SGS_STAGE static void marble_vertex(sgVertexBatch *b, const void *uniforms) {
    const float *u = uniforms;
    sgs_transform(b, 3, 6);
    for (int k = 0; k < 3; k++)
        SGS_SIMD for (int i = 0; i < SGS_LANES; i++) b->varying[k][i] = b->position[k][i] * u[0];
}

SGS_STAGE static void marble_fragment(sgFragmentBatch *b, const void *uniforms) {
    const float *u = uniforms;
    const sgs_light l = sgs_light_read(u, 8, 11, 14, 17, 20);
    const float turb = u[1], sr = u[2], sg = u[3], sb = u[4], vr = u[5], vg = u[6], vb = u[7];
    SGS_EACH_VECTOR(h) {
        const sgs_vf x = sgs_vload(b->varying[0] + h), y = sgs_vload(b->varying[1] + h),
                     z = sgs_vload(b->varying[2] + h);
        sgs_vf t = sgs_vturbulence(x, y, z);
        /* Bands across x + y / 2, two units apart, shifted by the turbulence; v is 0 on a vein. */
        sgs_vf s = 0.5f * ((x + 0.5f * y) + turb * t);
        sgs_vf w = s - sgs_vfloor_small(s);
        sgs_vf v = 2.0f * w - 1.0f;
        v = sgs_vsel(v < 0.0f, -v, v);
        sgs_vf q = sgs_vclamp01(v * 2.85714286f); /* smoothstep(0, 0.35, v) */
        sgs_vf vein = 1.0f - q * q * (3.0f - 2.0f * q);
        sgs_vf grain = 0.85f + 0.15f * t;
        sgs_vf s0 = sr * grain, s1 = sg * grain, s2 = sb * grain;
        const sgs_vf base[3] = {s0 + (vr - s0) * vein, s1 + (vg - s1) * vein,
                                s2 + (vb - s2) * vein};
        sgs_vf c[3];
        sgs_vlight_eval(&l, sgs_vload(b->varying[3] + h), sgs_vload(b->varying[4] + h),
                        sgs_vload(b->varying[5] + h), sgs_vload(b->varying[6] + h),
                        sgs_vload(b->varying[7] + h), sgs_vload(b->varying[8] + h), base, c);
        for (int k = 0; k < 3; k++) sgs_vstore(b->color[k] + h, c[k]);
        sgs_vstore(b->color[3] + h, sgs_vsplat(1.0f));
    }
}

static const char marble_glsl_vertex[] = SGS_GLSL_HEADER SGS_GLSL_DRAW SGS_GLSL_INPUTS
    "layout(location = 0) out vec3 v_obj;\n"
    "layout(location = 1) out vec3 v_pos;\n"
    "layout(location = 2) out vec3 v_normal;\n"
    "void main() {\n"
    "    vec4 p = world_view * sg_position;\n"
    "    gl_Position = proj * p;\n"
    "    v_obj = sg_position.xyz * u[0];\n"
    "    v_pos = p.xyz;\n"
    "    v_normal = transpose(inverse(mat3(world_view))) * sg_normal;\n"
    "}\n";

static const char marble_glsl_fragment[] =
    SGS_GLSL_HEADER SGS_GLSL_LIGHT SGS_GLSL_NOISE SGS_GLSL_OUTPUT
    "layout(location = 0) in vec3 v_obj;\n"
    "layout(location = 1) in vec3 v_pos;\n"
    "layout(location = 2) in vec3 v_normal;\n"
    "void main() {\n"
    "    float t = turbulence(v_obj);\n"
    "    precise float s = 0.5 * ((v_obj.x + 0.5 * v_obj.y) + u[1] * t);\n"
    "    precise float v = abs(2.0 * (s - floor(s)) - 1.0);\n"
    "    precise float q = clamp(v * 2.85714286, 0.0, 1.0);\n"
    "    precise float vein = 1.0 - q * q * (3.0 - 2.0 * q);\n"
    "    precise vec3 stone = u3(2) * (0.85 + 0.15 * t);\n"
    "    precise vec3 base = stone + (u3(5) - stone) * vein;\n"
    "    sg_frag_color = vec4(light(v_pos, v_normal, base, 8, 11, 14, 17, 20), 1.0);\n"
    "}\n";

const sgShaderInfo SGS_NAME(sg_shader_marble) = {
    .name = "marble",
    .desc = {.vertex = marble_vertex,
             .fragment = marble_fragment,
             .varying_count = 9,
             .flat_varyings = 0,
             .texture_count = 0,
             .independent_lanes = true},
    .uniform_count = 21,
    .glsl_vertex = marble_glsl_vertex,
    .glsl_fragment = marble_glsl_fragment,
};
