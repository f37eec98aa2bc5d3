#version 450
// SG_SHADE_VERTEX_COLOR: the perspective-correct interpolated vertex colour. With SHADOW, its rgb
// is darkened to half where the scene's shadow hides the point from the light.
#if defined(SHADOW)
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "shadow.glsl"
layout(location = 1) in vec3 v_view;
#endif
layout(location = 0) in vec4 v_color;
layout(location = 0) out vec4 o_color;

void main() {
#if defined(SHADOW)
    precise float k = 0.5 + 0.5 * shadow_visibility(shadow_coord(vec4(v_view, 1.0)));
    precise vec3 rgb = v_color.rgb * k;
    o_color = vec4(rgb, v_color.a);
#else
    o_color = v_color;
#endif
}
