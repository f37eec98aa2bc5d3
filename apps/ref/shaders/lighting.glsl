// lighting.glsl - the lighting equation of sgapi (docs/scene-format.md, "Lighting"), shared by the
// lit shaders. Intermediate values are `precise` (SPIR-V NoContraction) so that no multiply-add is
// fused and sums are formed left to right, as sgapi's C does. With SHADOW, shade() takes the
// visibility of the scene's shadowed light at the point (shadow.glsl); shade_split() is the
// equation of flat and Gouraud draws that receive the shadow, the shadowed light kept apart.
#include "draw.glsl"

const float SMALLEST_NORMAL = 1.17549435e-38;

precise float dot3(vec3 a, vec3 b) {
    return (a.x * b.x + a.y * b.y) + a.z * b.z;
}

// v / |v|; a zero or NaN length gives (0, 0, 0), never NaN. normalize() is not used: it is
// undefined for a zero vector and may use an approximate inverse square root.
vec3 safe_normalize(vec3 v) {
    precise float len = sqrt(dot3(v, v));
    return len > 0.0 ? v / len : vec3(0.0);
}

// The unnormalised view-space normal NM * n.
vec3 normal_matrix_times(vec3 n) {
    return vec3(dot3(u.nm[0].xyz, n), dot3(u.nm[1].xyz, n), dot3(u.nm[2].xyz, n));
}

// Light i seen from view-space point P: the unit vector L towards it and its attenuation.
float light_vector(int i, vec3 P, out vec3 L) {
    if (u.lights[i].vec.w == 0.0) {
        L = u.lights[i].vec.xyz;
        return 1.0;
    }
    precise vec3 v = u.lights[i].vec.xyz - P;
    precise float d = sqrt(dot3(v, v));
    L = d > 0.0 ? v / d : vec3(0.0);
    vec3 k = u.lights[i].attenuation.xyz;
    // A light at the surface: a finite att, and L = 0 makes its contribution 0.
    precise float den = (k.x + k.y * d) + k.z * (d * d);
    precise float att = 1.0 / max(den, SMALLEST_NORMAL);
    return att;
}

// OpenGL 1.x lighting with a local viewer, colour material on ambient and diffuse and a separate
// specular colour. base: vertex colour * draw colour; P: view-space position; N: unit normal, or
// zero; with SHADOW, vis: the visibility of light u.shadow_flags.x at P, in [0, 1].
void shade(vec4 base, vec3 P, vec3 N,
#if defined(SHADOW)
           float vis,
#endif
           out vec4 primary, out vec3 secondary) {
    vec3 V = safe_normalize(-P);
    float shininess = u.specular.w;
    precise vec3 sum = base.rgb * u.ambient.rgb;
    precise vec3 spec = vec3(0.0);
    for (int i = 0; i < u.light_count.x; i++) {
        vec3 L;
        precise float att = light_vector(i, P, L);
#if defined(SHADOW)
        // Where the map hides the point from the shadowed light, its diffuse and specular terms
        // both go: att scales the two alike.
        if (i == u.shadow_flags.x) att = att * vis;
#endif
        precise float nl = dot3(N, L);
        sum += ((att * max(nl, 0.0)) * base.rgb) * u.lights[i].color.rgb;
        if (nl > 0.0) {
            vec3 H = safe_normalize(L + V);
            float nh = max(dot3(N, H), 0.0);
            // x^0 = 1 even for x = 0 (OpenGL's rule; GLSL leaves pow(0, 0) undefined), and
            // pow(0, s) is 0 without relying on log2(0).
            float pw = shininess == 0.0 ? 1.0 : (nh > 0.0 ? pow(nh, shininess) : 0.0);
            spec += ((att * pw) * u.lights[i].color.rgb) * u.specular.rgb;
        }
    }
    primary = vec4(clamp(sum, 0.0, 1.0), base.a);
    secondary = spec;
}

// The equation split for a flat or Gouraud draw that receives the scene's shadow: rest = base
// ambient + the diffuse terms of every light but u.shadow_flags.x, unclamped, with base alpha;
// light = that light's diffuse term; rest_sec and light_sec the same split of the specular terms.
// The fragment stage scales the light's parts by the visibility of its pixel:
// primary = clamp(rest + vis light, 0, 1), secondary = rest_sec + vis light_sec.
void shade_split(vec4 base, vec3 P, vec3 N, out vec4 rest, out vec3 light, out vec3 rest_sec,
                 out vec3 light_sec) {
    vec3 V = safe_normalize(-P);
    float shininess = u.specular.w;
    precise vec3 sum = base.rgb * u.ambient.rgb;
    precise vec3 sum_l = vec3(0.0);
    precise vec3 spec = vec3(0.0);
    precise vec3 spec_l = vec3(0.0);
    for (int i = 0; i < u.light_count.x; i++) {
        vec3 L;
        precise float att = light_vector(i, P, L);
        precise float nl = dot3(N, L);
        precise vec3 d_term = ((att * max(nl, 0.0)) * base.rgb) * u.lights[i].color.rgb;
        precise vec3 s_term = vec3(0.0);
        if (nl > 0.0) {
            vec3 H = safe_normalize(L + V);
            float nh = max(dot3(N, H), 0.0);
            float pw = shininess == 0.0 ? 1.0 : (nh > 0.0 ? pow(nh, shininess) : 0.0);
            s_term = ((att * pw) * u.lights[i].color.rgb) * u.specular.rgb;
        }
        if (i == u.shadow_flags.x) {
            sum_l += d_term;
            spec_l += s_term;
        } else {
            sum += d_term;
            spec += s_term;
        }
    }
    rest = vec4(sum, base.a);
    light = sum_l;
    rest_sec = spec;
    light_sec = spec_l;
}
