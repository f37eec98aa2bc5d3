#version 450
// Vertex stage of a lit draw, built once per mode (-DFLAT, -DGOURAUD or -DPHONG): the transform of
// color.vert, and per mode
//   GOURAUD: the lighting equation at the vertex: primary and secondary colours;
//   PHONG:   what the fragment stage lights with: base colour, view position and NM * n;
//   FLAT:    base colour and view position, for the geometry stage that lights the triangle.
// The texture coordinate always passes (the vertex buffer holds zeros when the mesh has none).
// GOURAUD with SHADOW (a draw that receives the scene's shadow): the equation split, the shadowed
// light's parts apart (lighting.glsl, shade_split), and the view position for the shadow test.
#extension GL_GOOGLE_include_directive : require
#include "lighting.glsl"

layout(location = 0) in vec4 a_position;
layout(location = 1) in vec4 a_color;
layout(location = 2) in vec2 a_texcoord;
#if !defined(FLAT)
layout(location = 3) in vec3 a_normal;
#endif

layout(push_constant, row_major) uniform Transform {
    mat4 world_view;
    mat4 proj;
} pc;

#if defined(GOURAUD) && defined(SHADOW)
layout(location = 0) out vec4 v_rest;
layout(location = 1) out vec3 v_rest_sec;
layout(location = 3) out vec3 v_view;
layout(location = 4) out vec3 v_light;
layout(location = 5) out vec3 v_light_sec;
#elif defined(GOURAUD)
layout(location = 0) out vec4 v_primary;
layout(location = 1) out vec3 v_secondary;
#else
layout(location = 0) out vec4 v_base;
layout(location = 1) out vec3 v_view;
#endif
layout(location = 2) out vec2 v_texcoord;
#if defined(PHONG)
layout(location = 3) out vec3 v_normal;
#endif

void main() {
    vec4 clip = pc.proj * (pc.world_view * a_position);
    // Vulkan's framebuffer has y down with NDC y = -1 at the top, and clips z to [0, w].
    gl_Position = vec4(clip.x, -clip.y, 0.5 * (clip.z + clip.w), clip.w);
    vec4 base = a_color * u.color;
    vec3 P = view_position(pc.world_view, a_position);
#if defined(GOURAUD) && defined(SHADOW)
    shade_split(base, P, safe_normalize(normal_matrix_times(a_normal)), v_rest, v_light,
                v_rest_sec, v_light_sec);
    v_view = P;
#elif defined(GOURAUD)
    shade(base, P, safe_normalize(normal_matrix_times(a_normal)), v_primary, v_secondary);
#else
    v_base = base;
    v_view = P;
#endif
#if defined(PHONG)
    v_normal = normal_matrix_times(a_normal);
#endif
    v_texcoord = a_texcoord;
}
