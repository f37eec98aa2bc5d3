/* dissolve.c - a surface burning away: fractal noise (shader_math.h, 4 octaves of value noise) of
 * the object-space position decides where it is gone (noise below the threshold: discarded, depth
 * included) and where it glows (a band of the given width just above the threshold, fading from
 * the glow colour at the cut to the lit surface). Back faces seen through the holes are lit with
 * their normal turned towards the viewer.
 *
 * Uniforms (18 floats):
 *   u[0]      threshold, 0..1: the fraction of the noise's range that is gone (the noise is
 *             mostly between 0.3 and 0.7)
 *   u[1]      edge width (> 0): the glowing band above the threshold
 *   u[2]      scale: noise cells per object-space unit
 *   u[3..5]   glow colour r, g, b
 *   u[6..8]   colour r, g, b: multiplies the vertex colour
 *   u[9..11]  ambient light r, g, b
 *   u[12..14] light direction x, y, z: the way it travels, in view space (not zero)
 *   u[15..17] light colour r, g, b
 * Varyings: 0..2 the object-space position times the scale, 3..5 view-space position, 6..8
 * normal, 9..11 base colour. Alpha is 1.
 */
#include "builtin.h"
#include "shader_math.h"

SGS_STAGE static void dissolve_vertex(sgVertexBatch *b, const void *uniforms) {
    const float *u = uniforms;
    sgs_transform(b, 3, 6);
    for (int k = 0; k < 3; k++) SGS_SIMD for (int i = 0; i < SGS_LANES; i++) {
            b->varying[k][i] = b->position[k][i] * u[2];
            b->varying[9 + k][i] = b->color[k][i] * u[6 + k];
        }
}

SGS_STAGE static void dissolve_fragment(sgFragmentBatch *b, const void *uniforms) {
    const float *u = uniforms;
    const sgs_light l = sgs_light_read(u, 9, 12, 15, -1, -1);
    const float threshold = u[0], inv_width = u[1] > 0.0f ? 1.0f / u[1] : 0.0f;
    const float flip = b->front_facing ? 1.0f : -1.0f;
    const float glow[3] = {u[3], u[4], u[5]};
    float noise[SGS_LANES];
    uint32_t discard = 0;
    SGS_EACH_VECTOR(h) {
        const sgs_vf n = sgs_vfbm(sgs_vload(b->varying[0] + h), sgs_vload(b->varying[1] + h),
                                  sgs_vload(b->varying[2] + h));
        sgs_vstore(noise + h, n);
        const sgs_vi gone = n < threshold;
        for (int i = 0; i < SGS_W; i++) discard |= ((uint32_t)gone[i] & 1u) << (h + i);
    }
    b->discard = discard;
    if ((discard & b->mask) == b->mask) return; /* nothing of the tile is drawn */
    SGS_EACH_VECTOR(h) {
        /* 1 at the cut, 0 from the band's top up */
        const sgs_vf e = 1.0f - sgs_vclamp01((sgs_vload(noise + h) - threshold) * inv_width);
        const sgs_vf base[3] = {sgs_vload(b->varying[9] + h), sgs_vload(b->varying[10] + h),
                                sgs_vload(b->varying[11] + h)};
        sgs_vf c[3];
        sgs_vlight_eval(&l, sgs_vload(b->varying[3] + h), sgs_vload(b->varying[4] + h),
                        sgs_vload(b->varying[5] + h), sgs_vload(b->varying[6] + h) * flip,
                        sgs_vload(b->varying[7] + h) * flip, sgs_vload(b->varying[8] + h) * flip,
                        base, c);
        for (int k = 0; k < 3; k++) sgs_vstore(b->color[k] + h, c[k] + (glow[k] - c[k]) * e);
        sgs_vstore(b->color[3] + h, sgs_vsplat(1.0f));
    }
}

static const char dissolve_glsl_vertex[] = SGS_GLSL_HEADER SGS_GLSL_DRAW SGS_GLSL_INPUTS
    "layout(location = 0) out vec3 v_obj;\n"
    "layout(location = 1) out vec3 v_pos;\n"
    "layout(location = 2) out vec3 v_normal;\n"
    "layout(location = 3) out vec3 v_base;\n"
    "void main() {\n"
    "    vec4 p = world_view * sg_position;\n"
    "    gl_Position = proj * p;\n"
    "    v_obj = sg_position.xyz * u[2];\n"
    "    v_pos = p.xyz;\n"
    "    v_normal = transpose(inverse(mat3(world_view))) * sg_normal;\n"
    "    v_base = sg_color.rgb * vec3(u[6], u[7], u[8]);\n"
    "}\n";

static const char dissolve_glsl_fragment[] =
    SGS_GLSL_HEADER SGS_GLSL_LIGHT SGS_GLSL_NOISE SGS_GLSL_OUTPUT
    "layout(location = 0) in vec3 v_obj;\n"
    "layout(location = 1) in vec3 v_pos;\n"
    "layout(location = 2) in vec3 v_normal;\n"
    "layout(location = 3) in vec3 v_base;\n"
    "void main() {\n"
    "    float n = fbm(v_obj);\n"
    "    if (n < u[0]) discard;\n"
    "    float inv_width = u[1] > 0.0 ? 1.0 / u[1] : 0.0;\n"
    "    precise float e = 1.0 - clamp((n - u[0]) * inv_width, 0.0, 1.0);\n"
    "    vec3 N = gl_FrontFacing ? v_normal : -v_normal;\n"
    "    vec3 c = light(v_pos, N, v_base, 9, 12, 15, -1, -1);\n"
    "    sg_frag_color = vec4(c + (u3(3) - c) * e, 1.0);\n"
    "}\n";

const sgShaderInfo SGS_NAME(sg_shader_dissolve) = {
    .name = "dissolve",
    .desc = {.vertex = dissolve_vertex,
             .fragment = dissolve_fragment,
             .varying_count = 12,
             .flat_varyings = 0,
             .texture_count = 0,
             .independent_lanes = true},
    .uniform_count = 18,
    .glsl_vertex = dissolve_glsl_vertex,
    .glsl_fragment = dissolve_glsl_fragment,
};
