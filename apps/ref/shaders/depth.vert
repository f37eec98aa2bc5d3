#version 450
// Vertex stage of the shadow's depth-only pass: a caster's position with the transform of
// color.vert, its matrices being the light's (worldView' = light view x worldView, proj' = the
// light's projection).
layout(location = 0) in vec4 a_position;

layout(push_constant, row_major) uniform Transform {
    mat4 world_view;
    mat4 proj;
} pc;

void main() {
    vec4 clip = pc.proj * (pc.world_view * a_position);
    // Vulkan's framebuffer has y down with NDC y = -1 at the top, and clips z to [0, w].
    gl_Position = vec4(clip.x, -clip.y, 0.5 * (clip.z + clip.w), clip.w);
}
