#version 450
// Vertex stage of a vertex-colour draw: the fixed-function transform of the reference, with sgapi's
// conventions (OpenGL clip space, NDC y = +1 at the top) mapped to Vulkan's.
layout(location = 0) in vec4 a_position;
layout(location = 1) in vec4 a_color;

// The scene's matrices as given: row-major, acting on column vectors.
layout(push_constant, row_major) uniform Transform {
    mat4 world_view;
    mat4 proj;
} pc;

// The draw's constant colour (scene key "color"). Vulkan promises only 128 bytes of push
// constants, all taken by the matrices, so it comes from a uniform buffer.
layout(set = 0, binding = 0) uniform DrawColor {
    vec4 color;
} u_draw;

layout(location = 0) out vec4 v_color;

void main() {
    vec4 clip = pc.proj * (pc.world_view * a_position);
    // Vulkan's framebuffer has y down with NDC y = -1 at the top, and clips z to [0, w].
    gl_Position = vec4(clip.x, -clip.y, 0.5 * (clip.z + clip.w), clip.w);
    v_color = a_color * u_draw.color;
}
