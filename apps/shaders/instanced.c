/* instanced.c - many copies of one mesh in a single draw ("instances"), each placed, turned and
 * coloured from its instance number alone: instance i sits in column i mod C and row i / C of a
 * grid in x-z centred on the origin, is turned about y and tilted about x by one of eight steps
 * each, raised or lowered, and gets a colour of its own, all from hashes of i. The steps' cosines
 * and sines are values a float holds exactly (nearly a unit vector: the copy grows by less than
 * 0.4 %), so that C and GLSL place every vertex at the same bits and cover the same pixels. Lit
 * once per vertex (ambient and diffuse of one directional light) and passed on flat: a cube's faces
 * are flat-coloured.
 *
 * Uniforms (14 floats):
 *   u[0]      columns C of the grid (>= 1); there are C rows centred too: draw C x C instances
 *   u[1]      spacing between neighbours, object-space units
 *   u[2]      scale of each copy
 *   u[3]      a turn: steps (of eight a revolution) added to every copy's turn about y
 *   u[4]      bob: the largest rise or drop of a copy, in spacings
 *   u[5..7]   ambient light r, g, b
 *   u[8..10]  light direction x, y, z: the way it travels, in view space (not zero)
 *   u[11..13] light colour r, g, b
 * Varyings: 0..2 the lit colour (flat). Alpha is 1.
 */
#include "builtin.h"
#include "shader_math.h"

/* Eight turns (cos, sin), a float's exact values: 0, 41, 90, ... degrees. */
static const float STEP[8][2] = {{1.0f, 0.0f},       {0.75f, 0.65625f}, {0.0f, 1.0f},
                                 {-0.75f, 0.65625f}, {-1.0f, 0.0f},     {-0.75f, -0.65625f},
                                 {0.0f, -1.0f},      {0.75f, -0.65625f}};

SGS_STAGE static void instanced_vertex(sgVertexBatch *b, const void *uniforms) {
    const float *u = uniforms;
    const int32_t inst = b->instance;
    const int32_t cols = u[0] >= 1.0f && u[0] < 65536.0f ? (int32_t)u[0] : 1;
    const float half = 0.5f * (float)(cols - 1);
    const float ox = ((float)(inst % cols) - half) * u[1],
                oz = ((float)(inst / cols) - half) * u[1];
    const int32_t turn = u[3] >= -65536.0f && u[3] <= 65536.0f ? (int32_t)u[3] : 0;
    const int ky = ((int32_t)(sgs_hash3(inst, 0, 0) * 8.0f) + turn) & 7;
    const int kx = (int32_t)(sgs_hash3(inst, 4, 0) * 8.0f) & 7;
    const float cy = STEP[ky][0], sy = STEP[ky][1], cx = STEP[kx][0], sx = STEP[kx][1];
    const float oy = (sgs_hash3(inst, 5, 0) - 0.5f) * (2.0f * u[4] * u[1]);
    float rgb[3];
    for (int k = 0; k < 3; k++) rgb[k] = 0.25f + 0.75f * sgs_hash3(inst, k + 1, 0);
    const float s = u[2];
    float p[4][SGS_LANES], n[3][SGS_LANES];
    SGS_SIMD for (int i = 0; i < SGS_LANES; i++) {
        /* R = Ry Rx, applied to the scaled vertex and to its normal. */
        float v[2][3] = {{b->position[0][i] * s, b->position[1][i] * s, b->position[2][i] * s},
                         {b->normal[0][i], b->normal[1][i], b->normal[2][i]}};
        float r[2][3];
        for (int j = 0; j < 2; j++) {
            float x = v[j][0], y = cx * v[j][1] - sx * v[j][2], z = sx * v[j][1] + cx * v[j][2];
            r[j][0] = cy * x + sy * z, r[j][1] = y, r[j][2] = cy * z - sy * x;
        }
        p[0][i] = r[0][0] + ox, p[1][i] = r[0][1] + oy, p[2][i] = r[0][2] + oz, p[3][i] = 1.0f;
        n[0][i] = r[1][0], n[1][i] = r[1][1], n[2][i] = r[1][2];
    }
    sgs_transform_from(b, (const float(*)[SGS_LANES])p, (const float(*)[SGS_LANES])n, -1, 0);
    float il = sgs_inv_len(u[8], u[9], u[10]);
    const float lx = -u[8] * il, ly = -u[9] * il, lz = -u[10] * il;
    SGS_SIMD for (int i = 0; i < SGS_LANES; i++) {
        float nx = b->varying[0][i], ny = b->varying[1][i], nz = b->varying[2][i];
        float in = sgs_inv_len(nx, ny, nz);
        float d = sgs_max(((nx * lx + ny * ly) + nz * lz) * in, 0.0f);
        for (int k = 0; k < 3; k++)
            b->varying[k][i] = sgs_clamp01(rgb[k] * u[5 + k] + rgb[k] * (d * u[11 + k]));
    }
}

SGS_STAGE static void instanced_fragment(sgFragmentBatch *b, const void *uniforms) {
    (void)uniforms;
    SGS_SIMD for (int i = 0; i < SGS_LANES; i++) {
        b->color[0][i] = b->varying[0][i];
        b->color[1][i] = b->varying[1][i];
        b->color[2][i] = b->varying[2][i];
        b->color[3][i] = 1.0f;
    }
}

static const char instanced_glsl_vertex[] =
    SGS_GLSL_HEADER SGS_GLSL_DRAW SGS_GLSL_INPUTS SGS_GLSL_U3 SGS_GLSL_HASH
    "layout(location = 0) flat out vec3 v_color;\n"
    "vec3 safe_normalize(vec3 v) {\n"
    "    float len2 = dot(v, v);\n"
    "    return len2 > 0.0 ? v / sqrt(len2) : vec3(0.0);\n"
    "}\n"
    "void main() {\n"
    "    int inst = gl_InstanceIndex;\n"
    "    int cols = u[0] >= 1.0 && u[0] < 65536.0 ? int(u[0]) : 1;\n"
    "    float half_ = 0.5 * float(cols - 1);\n"
    "    vec3 o = vec3((float(inst % cols) - half_) * u[1], 0.0,\n"
    "                  (float(inst / cols) - half_) * u[1]);\n"
    "    const vec2 STEP[8] = vec2[8](vec2(1.0, 0.0), vec2(0.75, 0.65625), vec2(0.0, 1.0),\n"
    "        vec2(-0.75, 0.65625), vec2(-1.0, 0.0), vec2(-0.75, -0.65625), vec2(0.0, -1.0),\n"
    "        vec2(0.75, -0.65625));\n"
    "    int turn = u[3] >= -65536.0 && u[3] <= 65536.0 ? int(u[3]) : 0;\n"
    "    int ky = (int(hash3(ivec3(inst, 0, 0)) * 8.0) + turn) & 7;\n"
    "    int kx = int(hash3(ivec3(inst, 4, 0)) * 8.0) & 7;\n"
    "    float cy = STEP[ky].x, sy = STEP[ky].y, cx = STEP[kx].x, sx = STEP[kx].y;\n"
    "    precise float bob = (hash3(ivec3(inst, 5, 0)) - 0.5) * (2.0 * u[4] * u[1]);\n"
    "    o.y = bob;\n"
    "    vec3 rgb = 0.25 + 0.75 * vec3(hash3(ivec3(inst, 1, 0)), hash3(ivec3(inst, 2, 0)),\n"
    "                                  hash3(ivec3(inst, 3, 0)));\n"
    "    mat3 rx = mat3(1.0, 0.0, 0.0,  0.0, cx, sx,  0.0, -sx, cx);\n"
    "    mat3 ry = mat3(cy, 0.0, -sy,  0.0, 1.0, 0.0,  sy, 0.0, cy);\n"
    "    precise vec3 v = sg_position.xyz * u[2];\n"
    "    precise float y1 = cx * v.y - sx * v.z, z1 = sx * v.y + cx * v.z;\n"
    "    precise vec3 q = vec3((cy * v.x + sy * z1) + o.x, y1 + o.y, (cy * z1 - sy * v.x) + o.z);\n"
    "    precise vec4 p = world_view * vec4(q, 1.0);\n"
    "    precise vec4 clip = proj * p;\n"
    "    gl_Position = clip;\n"
    "    vec3 N = safe_normalize(transpose(inverse(mat3(world_view))) * (ry * (rx * sg_normal)));\n"
    "    vec3 L = -safe_normalize(u3(8));\n"
    "    v_color = clamp(rgb * u3(5) + rgb * (max(dot(N, L), 0.0) * u3(11)), 0.0, 1.0);\n"
    "}\n";

static const char instanced_glsl_fragment[] =
    SGS_GLSL_HEADER SGS_GLSL_OUTPUT "layout(location = 0) flat in vec3 v_color;\n"
                                    "void main() {\n"
                                    "    sg_frag_color = vec4(v_color, 1.0);\n"
                                    "}\n";

const sgShaderInfo SGS_NAME(sg_shader_instanced) = {
    .name = "instanced",
    .desc = {.vertex = instanced_vertex,
             .fragment = instanced_fragment,
             .varying_count = 3,
             .flat_varyings = 0x7u,
             .texture_count = 0,
             .independent_lanes = true,
             .varyings_only = true},
    .uniform_count = 14,
    .glsl_vertex = instanced_glsl_vertex,
    .glsl_fragment = instanced_glsl_fragment,
};
