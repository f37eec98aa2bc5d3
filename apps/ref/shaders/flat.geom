#version 450
// SG_LIGHTING_FLAT: the lighting equation once per triangle, at the mean of its three view
// positions, with its face normal normalize((P1 - P0) x (P2 - P0)) and the base colour of its first
// vertex (in index order). The triangle passes on unchanged, in the same vertex order, so its
// winding, culling and rasterisation are those of the unlit pipeline.
#extension GL_GOOGLE_include_directive : require
#include "lighting.glsl"

layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;

layout(location = 0) in vec4 v_base[];
layout(location = 1) in vec3 v_view[];
layout(location = 2) in vec2 v_texcoord[];

layout(location = 0) flat out vec4 g_primary;
layout(location = 1) flat out vec3 g_secondary;
layout(location = 2) out vec2 g_texcoord;

void main() {
    precise vec3 mid = ((v_view[0] + v_view[1]) + v_view[2]) / 3.0;
    precise vec3 a = v_view[1] - v_view[0];
    precise vec3 b = v_view[2] - v_view[0];
    precise vec3 n = vec3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
    vec4 primary;
    vec3 secondary;
    shade(v_base[0], mid, safe_normalize(n), primary, secondary);
    for (int i = 0; i < 3; i++) {
        gl_Position = gl_in[i].gl_Position;
        g_primary = primary;
        g_secondary = secondary;
        g_texcoord = v_texcoord[i];
        EmitVertex();
    }
    EndPrimitive();
}
