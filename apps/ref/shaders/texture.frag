#version 450
// SG_SHADE_TEXTURE_MODULATE: vertex colour times texel. The texture's rows are uploaded bottom row
// first, so t = 0 addresses the bottom row as in OpenGL; filter and wrap come from the sampler.
// With SHADOW, rgb is then darkened to half where the scene's shadow hides the point.
#if defined(SHADOW)
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "shadow.glsl"
layout(location = 2) in vec3 v_view;
#endif
layout(location = 0) in vec4 v_color;
layout(location = 1) in vec2 v_texcoord;
layout(set = 1, binding = 0) uniform sampler2D u_texture;
layout(location = 0) out vec4 o_color;

void main() {
#if defined(SHADOW)
    vec4 c = v_color * texture(u_texture, v_texcoord);
    precise float k = 0.5 + 0.5 * shadow_visibility(shadow_coord(vec4(v_view, 1.0)));
    precise vec3 rgb = c.rgb * k;
    o_color = vec4(rgb, c.a);
#else
    o_color = v_color * texture(u_texture, v_texcoord);
#endif
}
