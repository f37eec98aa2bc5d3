#version 450
// SG_LIGHTING_FLAT: the lighting equation once per triangle, at the mean of its three view
// positions, with its face normal normalize((P1 - P0) x (P2 - P0)) and the base colour of its first
// vertex (in index order). The triangle passes on unchanged, in the same vertex order, so its
// winding, culling and rasterisation are those of the unlit pipeline. With SHADOW (a draw that
// receives the scene's shadow): the equation split (lighting.glsl, shade_split), the shadowed
// light's parts apart, each flat, and the view positions passed on for the shadow test per pixel.
#extension GL_GOOGLE_include_directive : require
#include "lighting.glsl"

layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;

layout(location = 0) in vec4 v_base[];
layout(location = 1) in vec3 v_view[];
layout(location = 2) in vec2 v_texcoord[];

#if defined(SHADOW)
layout(location = 0) flat out vec4 g_rest;
layout(location = 1) flat out vec3 g_rest_sec;
layout(location = 3) out vec3 g_view;
layout(location = 4) flat out vec3 g_light;
layout(location = 5) flat out vec3 g_light_sec;
#else
layout(location = 0) flat out vec4 g_primary;
layout(location = 1) flat out vec3 g_secondary;
#endif
layout(location = 2) out vec2 g_texcoord;

void main() {
    precise vec3 mid = ((v_view[0] + v_view[1]) + v_view[2]) / 3.0;
    precise vec3 a = v_view[1] - v_view[0];
    precise vec3 b = v_view[2] - v_view[0];
    precise vec3 n = vec3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
#if defined(SHADOW)
    vec4 rest;
    vec3 light, rest_sec, light_sec;
    shade_split(v_base[0], mid, safe_normalize(n), rest, light, rest_sec, light_sec);
#else
    vec4 primary;
    vec3 secondary;
    shade(v_base[0], mid, safe_normalize(n), primary, secondary);
#endif
    for (int i = 0; i < 3; i++) {
        gl_Position = gl_in[i].gl_Position;
#if defined(SHADOW)
        g_rest = rest;
        g_rest_sec = rest_sec;
        g_light = light;
        g_light_sec = light_sec;
        g_view = v_view[i];
#else
        g_primary = primary;
        g_secondary = secondary;
#endif
        g_texcoord = v_texcoord[i];
        EmitVertex();
    }
    EndPrimitive();
}
