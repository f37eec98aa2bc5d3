#version 450
// Vertex stage of a vertex-colour draw: the fixed-function transform of the reference, with sgapi's
// conventions (OpenGL clip space, NDC y = +1 at the top) mapped to Vulkan's. With SHADOW (a draw
// that receives the scene's shadow), also the point in the light's clip space, interpolated.
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
layout(location = 1) out vec4 v_shadow;
#endif

void main() {
    vec4 clip = pc.proj * (pc.world_view * a_position);
    // Vulkan's framebuffer has y down with NDC y = -1 at the top, and clips z to [0, w].
    gl_Position = vec4(clip.x, -clip.y, 0.5 * (clip.z + clip.w), clip.w);
    v_color = a_color * DRAW_COLOR;
#if defined(SHADOW)
    // shadow_matrix x (worldView x p), undivided: interpolated perspective-correct like a colour.
    precise vec4 e = vec4(row_times(pc.world_view, 0, a_position),
                          row_times(pc.world_view, 1, a_position),
                          row_times(pc.world_view, 2, a_position),
                          row_times(pc.world_view, 3, a_position));
    v_shadow = shadow_coord(e);
#endif
}
