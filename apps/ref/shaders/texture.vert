#version 450
// Vertex stage of a textured draw: as color.vert, plus the texture coordinate.
layout(location = 0) in vec4 a_position;
layout(location = 1) in vec4 a_color;
layout(location = 2) in vec2 a_texcoord;

layout(push_constant, row_major) uniform Transform {
    mat4 world_view;
    mat4 proj;
} pc;

layout(set = 0, binding = 0) uniform DrawColor {
    vec4 color;
} u_draw;

layout(location = 0) out vec4 v_color;
layout(location = 1) out vec2 v_texcoord;

void main() {
    vec4 clip = pc.proj * (pc.world_view * a_position);
    gl_Position = vec4(clip.x, -clip.y, 0.5 * (clip.z + clip.w), clip.w);
    v_color = a_color * u_draw.color;
    v_texcoord = a_texcoord;
}
