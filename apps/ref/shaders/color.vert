#version 450
// Vertex stage of a vertex-colour draw: the fixed-function transform of the reference, with sgapi's
// conventions (OpenGL clip space, NDC y = +1 at the top) mapped to Vulkan's. With SHADOW (a draw
// that receives the scene's shadow), also the view position, interpolated.
#if defined(SHADOW)
#extension GL_GOOGLE_include_directive : require
#include "draw.glsl"
#define DRAW_COLOR u.color
#endif
layout(location = 0) in vec4 a_position;
layout(location = 1) in vec4 a_color;

// The scene's matrices as given: row-major, acting on column vectors.
layout(push_constant, row_major) uniform Transform {
    mat4 world_view;
    mat4 proj;
} pc;

#if !defined(SHADOW)
// The draw's constant colour (scene key "color"). Vulkan promises only 128 bytes of push
// constants, all taken by the matrices, so it comes from a uniform buffer.
layout(set = 0, binding = 0) uniform DrawColor {
    vec4 color;
} u_draw;
#define DRAW_COLOR u_draw.color
#endif

layout(location = 0) out vec4 v_color;
#if defined(SHADOW)
layout(location = 1) out vec3 v_view;
#endif

void main() {
    vec4 clip = pc.proj * (pc.world_view * a_position);
    // Vulkan's framebuffer has y down with NDC y = -1 at the top, and clips z to [0, w].
    gl_Position = vec4(clip.x, -clip.y, 0.5 * (clip.z + clip.w), clip.w);
    v_color = a_color * DRAW_COLOR;
#if defined(SHADOW)
    // The view position, interpolated perspective-correct; the fragment takes it to the light.
    v_view = view_position(pc.world_view, a_position);
#endif
}
