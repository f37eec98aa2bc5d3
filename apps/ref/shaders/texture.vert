#version 450
// Vertex stage of a textured draw: as color.vert, plus the texture coordinate.
#if defined(SHADOW)
#extension GL_GOOGLE_include_directive : require
#include "draw.glsl"
#define DRAW_COLOR u.color
#endif
layout(location = 0) in vec4 a_position;
layout(location = 1) in vec4 a_color;
layout(location = 2) in vec2 a_texcoord;

layout(push_constant, row_major) uniform Transform {
    mat4 world_view;
    mat4 proj;
} pc;

#if !defined(SHADOW)
layout(set = 0, binding = 0) uniform DrawColor {
    vec4 color;
} u_draw;
#define DRAW_COLOR u_draw.color
#endif

layout(location = 0) out vec4 v_color;
layout(location = 1) out vec2 v_texcoord;
#if defined(SHADOW)
layout(location = 2) out vec3 v_view;
#endif

void main() {
    vec4 clip = pc.proj * (pc.world_view * a_position);
    gl_Position = vec4(clip.x, -clip.y, 0.5 * (clip.z + clip.w), clip.w);
    v_color = a_color * DRAW_COLOR;
    v_texcoord = a_texcoord;
#if defined(SHADOW)
    // The view position, interpolated perspective-correct; the fragment takes it to the light.
    v_view = view_position(pc.world_view, a_position);
#endif
}
