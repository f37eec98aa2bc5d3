/* phong_lights.c - the fixed per-pixel lighting (SG_LIGHTING_PHONG, src/pipeline/light.h) as a
 * shader, as the fixed path's Phong draws have it: up to four lights, directional or point (with
 * attenuation), and texture 0 modulating the lit colour before the specular term is added
 * (SG_SHADE_TEXTURE_MODULATE). `phong` is the same equation for one directional light and no
 * texture, with fewer uniforms; this one exists to compare a shader pipeline's cost with the fixed
 * path's on lit scenes of several lights (tools/shader-vs-fixed.py).
 *
 *   N = normalize(n), V = normalize(-P)
 *   per light: directional L = -normalize(direction), att = 1;
 *     point v = position - P, d = |v|, L = v / d, att = 1 / max((c + l d) + q d^2, FLT_MIN);
 *     where N.L > 0: diffuse += (att N.L) colour,
 *                    specular += (att pow(max(N.H, 0), shininess)) colour, H = normalize(L + V)
 *   colour = clamp(base ambient + base diffuse, 0, 1) (x texel) + specular x material specular
 *   alpha = base alpha (x texel alpha)
 *
 * Uniforms (53 floats):
 *   u[0..3]    colour r, g, b, a: multiplies the vertex colour (the base colour)
 *   u[4]       1: modulate by texture 0 (the draw binds it); 0: no texture
 *   u[5..7]    ambient light r, g, b
 *   u[8..10]   material specular colour r, g, b
 *   u[11]      shininess, 0..128
 *   u[12]      lights, 0..4 (rounded down)
 *   u[13 + 10 j .. 22 + 10 j], light j (0..3): kind (0 directional, else point), then its
 *              direction (the way it travels) or position, in view space, its colour r, g, b and
 *              its attenuation constant, linear, quadratic (point lights)
 * Varyings: 0..2 view-space position, 3..5 normal (normal matrix x n), 6..9 base colour, 10..11
 * texture coordinates.
 */
#include "builtin.h"
#include "shader_math.h"

enum { MAX_LIGHTS = 4, LIGHT0 = 13, LIGHT_FLOATS = 10 };

SGS_STAGE static void phong_lights_vertex(sgVertexBatch *b, const void *uniforms) {
    const float *u = uniforms;
    sgs_transform(b, 0, 3);
    for (int k = 0; k < 4; k++)
        SGS_SIMD for (int i = 0; i < SGS_LANES; i++) b->varying[6 + k][i] = b->color[k][i] * u[k];
    for (int k = 0; k < 2; k++)
        SGS_SIMD for (int i = 0; i < SGS_LANES; i++) b->varying[10 + k][i] = b->texcoord[k][i];
}

/* A draw's lights as the stage reads them, prepared once a call. */
typedef struct lights {
    int count, point[MAX_LIGHTS];
    float v[MAX_LIGHTS][3]; /* directional: L = -normalize(direction); point: position */
    float color[MAX_LIGHTS][3], att[MAX_LIGHTS][3];
    float shininess, min_x; /* min_x: as sgs_light's */
    int specular_on;        /* as sgs_light's */
} lights;

/* Filled in place: a struct returned by value was copied through the stack with narrow stores
 * read back as wide ones, a stall on every call. */
static inline void lights_read(const float *u, lights *l) {
    const float n = u[12] >= 0.0f ? (u[12] <= (float)MAX_LIGHTS ? u[12] : (float)MAX_LIGHTS) : 0.0f;
    l->count = (int)n;
    l->shininess = u[11] >= 0.0f ? (u[11] <= 128.0f ? u[11] : 128.0f) : 0.0f;
    l->min_x = l->shininess == 0.0f ? FLT_MIN : 0.0f;
    l->specular_on = 0;
    for (int k = 0; k < 3; k++) l->specular_on |= u[8 + k] != 0.0f;
    for (int j = 0; j < l->count; j++) {
        const float *s = u + LIGHT0 + LIGHT_FLOATS * j;
        l->point[j] = s[0] != 0.0f;
        const float inv = sgs_inv_len(s[1], s[2], s[3]); /* directional lights' */
        for (int k = 0; k < 3; k++) {
            l->v[j][k] = l->point[j] ? s[1 + k] : -s[1 + k] * inv;
            l->color[j][k] = s[4 + k];
            l->att[j][k] = s[7 + k];
            /* a colour that is not finite makes the specular term NaN even for a zero material */
            l->specular_on |= !(s[4 + k] >= -FLT_MAX && s[4 + k] <= FLT_MAX);
        }
    }
}

SGS_STAGE static void phong_lights_fragment(sgFragmentBatch *b, const void *uniforms) {
    const float *u = uniforms;
    lights l;
    lights_read(u, &l);
    float(*v)[SGS_LANES] = b->varying;
    float texel[4][SG_SHADER_LANES];
    if (u[4] != 0.0f) sgSample(b, 0, v[10], v[11], texel);
    SGS_EACH_VECTOR(h) {
        const sgs_vf px = sgs_vload(v[0] + h), py = sgs_vload(v[1] + h), pz = sgs_vload(v[2] + h);
        sgs_vf nx = sgs_vload(v[3] + h), ny = sgs_vload(v[4] + h), nz = sgs_vload(v[5] + h);
        const sgs_vf in = sgs_vinv_len(nx, ny, nz);
        nx *= in, ny *= in, nz *= in;
        const sgs_vf iv = sgs_vinv_len(px, py, pz);
        const sgs_vf vx = -px * iv, vy = -py * iv, vz = -pz * iv;
        const sgs_vf zero = sgs_vsplat(0.0f);
        sgs_vf diff[3] = {zero, zero, zero}, spec[3] = {zero, zero, zero};
        for (int j = 0; j < l.count; j++) {
            sgs_vf lx, ly, lz, att;
            if (l.point[j]) {
                const sgs_vf dx = l.v[j][0] - px, dy = l.v[j][1] - py, dz = l.v[j][2] - pz;
                const sgs_vf d2 = (dx * dx + dy * dy) + dz * dz, d = sgs_vsqrt(d2);
                const sgs_vf inv = sgs_vsel((d > 0.0f) & (d <= FLT_MAX), 1.0f / d, zero);
                lx = dx * inv, ly = dy * inv, lz = dz * inv;
                const sgs_vf den = (l.att[j][0] + l.att[j][1] * d) + l.att[j][2] * d2;
                att = 1.0f / sgs_vsel(den > FLT_MIN, den, sgs_vsplat(FLT_MIN));
            } else {
                lx = sgs_vsplat(l.v[j][0]), ly = sgs_vsplat(l.v[j][1]), lz = sgs_vsplat(l.v[j][2]);
                att = sgs_vsplat(1.0f);
            }
            const sgs_vf ndotl = (nx * lx + ny * ly) + nz * lz;
            const sgs_vi lit = ndotl > 0.0f;
            const sgs_vf f = att * ndotl;
            for (int k = 0; k < 3; k++)
                diff[k] = sgs_vsel(lit, diff[k] + f * l.color[j][k], diff[k]);
            if (!l.specular_on) continue;
            sgs_vf hx = lx + vx, hy = ly + vy, hz = lz + vz;
            const sgs_vf ih = sgs_vinv_len(hx, hy, hz);
            hx *= ih, hy *= ih, hz *= ih;
            const sgs_vf ndoth = (nx * hx + ny * hy) + nz * hz;
            const sgs_vf g =
                att *
                sgs_vpow_unit(sgs_vsel(ndoth > l.min_x, ndoth, sgs_vsplat(l.min_x)), l.shininess);
            for (int k = 0; k < 3; k++)
                spec[k] = sgs_vsel(lit, spec[k] + g * l.color[j][k], spec[k]);
        }
        sgs_vf prim[4];
        for (int k = 0; k < 3; k++) {
            /* sums that overflowed stop at FLT_MAX, as the fixed lighting's (light.h) */
            const sgs_vf dk = sgs_vsel(diff[k] < FLT_MAX, diff[k], sgs_vsplat(FLT_MAX));
            const sgs_vf base = sgs_vload(v[6 + k] + h);
            prim[k] = sgs_vclamp01(base * u[5 + k] + base * dk);
        }
        prim[3] = sgs_vload(v[9] + h);
        if (u[4] != 0.0f)
            for (int k = 0; k < 4; k++) prim[k] = prim[k] * sgs_vload(texel[k] + h);
        for (int k = 0; k < 3; k++) {
            sgs_vf c = prim[k];
            if (l.specular_on) { /* clamped as the output is: a huge light gives 1, not infinity */
                const sgs_vf sk = sgs_vsel(spec[k] < FLT_MAX, spec[k], sgs_vsplat(FLT_MAX));
                c = sgs_vclamp01(c + sk * u[8 + k]);
            }
            sgs_vstore(b->color[k] + h, c);
        }
        sgs_vstore(b->color[3] + h, prim[3]);
    }
}

static const char phong_lights_glsl_vertex[] =
    SGS_GLSL_HEADER SGS_GLSL_DRAW SGS_GLSL_INPUTS SGS_GLSL_LIT_VERTEX_OUT
    "layout(location = 3) out vec2 v_st;\n"
    "void main() {\n" SGS_GLSL_LIT_VERTEX "    v_st = sg_texcoord;\n"
    "}\n";

static const char phong_lights_glsl_fragment[] = SGS_GLSL_HEADER SGS_GLSL_TEXTURES SGS_GLSL_U3
    SGS_GLSL_POW_UNIT SGS_GLSL_SAFE_NORMALIZE SGS_GLSL_OUTPUT
    "layout(location = 0) in vec3 v_pos;\n"
    "layout(location = 1) in vec3 v_normal;\n"
    "layout(location = 2) in vec4 v_base;\n"
    "layout(location = 3) in vec2 v_st;\n"
    "void main() {\n"
    "    vec3 N = safe_normalize(v_normal), V = safe_normalize(-v_pos);\n"
    "    float s = clamp(u[11], 0.0, 128.0);\n"
    "    int count = int(clamp(u[12], 0.0, 4.0));\n"
    "    vec3 diff = vec3(0.0), spec = vec3(0.0);\n"
    "    for (int j = 0; j < count; j++) {\n"
    "        int o = 13 + 10 * j;\n"
    "        vec3 L;\n"
    "        float att = 1.0;\n"
    "        if (u[o] == 0.0) {\n"
    "            L = -safe_normalize(u3(o + 1));\n"
    "        } else {\n"
    "            vec3 v = u3(o + 1) - v_pos;\n"
    "            precise float d2 = (v.x * v.x + v.y * v.y) + v.z * v.z;\n"
    "            float d = sqrt(d2);\n"
    "            L = d > 0.0 ? v / d : vec3(0.0);\n"
    "            precise float den = (u[o + 7] + u[o + 8] * d) + u[o + 9] * d2;\n"
    "            att = 1.0 / max(den, 1.17549435e-38);\n"
    "        }\n"
    "        float ndotl = dot(N, L);\n"
    "        if (!(ndotl > 0.0)) continue;\n"
    "        diff += (att * ndotl) * u3(o + 4);\n"
    "        float ndoth = dot(N, safe_normalize(L + V));\n"
    "        spec += (att * pow_unit(max(ndoth, 0.0), s)) * u3(o + 4);\n"
    "    }\n"
    "    vec4 prim = vec4(clamp(v_base.rgb * u3(5) + v_base.rgb * diff, 0.0, 1.0), v_base.a);\n"
    "    if (u[4] != 0.0) prim *= texture(sg_textures[0], v_st);\n"
    "    sg_frag_color = vec4(prim.rgb + spec * u3(8), prim.a);\n"
    "}\n";

const sgShaderInfo SGS_NAME(sg_shader_phong_lights) = {
    .name = "phong_lights",
    .desc = {.vertex = phong_lights_vertex,
             .fragment = phong_lights_fragment,
             .varying_count = 12,
             .flat_varyings = 0,
             .texture_count = 0,
             .independent_lanes = true},
    .uniform_count = 53,
    .glsl_vertex = phong_lights_glsl_vertex,
    .glsl_fragment = phong_lights_glsl_fragment,
};
