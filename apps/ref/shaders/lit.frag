#version 450
// Fragment stage of a lit draw, built per mode (-DFLAT, -DGOURAUD, -DPHONG) and with -DTEXTURED for
// a textured draw: rgb = clamp(primary * texel + secondary, 0, 1), alpha = primary alpha * texel
// alpha (texel = 1 untextured). GOURAUD interpolates the vertices' colours (perspective-correct),
// FLAT takes the triangle's (flat), PHONG evaluates the equation here with the interpolated base
// colour, view position and normal, renormalised. PHONG with SHADOW: the shadowed light scaled by
// the visibility of the interpolated view position (shadow.glsl). FLAT or GOURAUD with SHADOW: the
// split colours (lighting.glsl, shade_split), flat or interpolated, the shadowed light's parts
// scaled by that visibility: primary = clamp(rest + vis light), secondary = rest_sec + vis
// light_sec.
#extension GL_GOOGLE_include_directive : require
#if defined(SHADOW)
#extension GL_EXT_samplerless_texture_functions : require
#include "shadow.glsl"
#endif
#include "lighting.glsl"

#if defined(PHONG)
layout(location = 0) in vec4 v_base;
layout(location = 1) in vec3 v_view;
layout(location = 3) in vec3 v_normal;
#elif defined(SHADOW) && defined(FLAT)
layout(location = 0) flat in vec4 v_rest;
layout(location = 1) flat in vec3 v_rest_sec;
layout(location = 3) in vec3 v_view;
layout(location = 4) flat in vec3 v_light;
layout(location = 5) flat in vec3 v_light_sec;
#elif defined(SHADOW)
layout(location = 0) in vec4 v_rest;
layout(location = 1) in vec3 v_rest_sec;
layout(location = 3) in vec3 v_view;
layout(location = 4) in vec3 v_light;
layout(location = 5) in vec3 v_light_sec;
#elif defined(FLAT)
layout(location = 0) flat in vec4 v_primary;
layout(location = 1) flat in vec3 v_secondary;
#else
layout(location = 0) in vec4 v_primary;
layout(location = 1) in vec3 v_secondary;
#endif
layout(location = 2) in vec2 v_texcoord;

#if defined(TEXTURED)
layout(set = 1, binding = 0) uniform sampler2D u_texture;
#endif

layout(location = 0) out vec4 o_color;

void main() {
#if defined(PHONG)
    vec4 primary;
    vec3 secondary;
#if defined(SHADOW)
    float vis = shadow_visibility(shadow_coord(vec4(v_view, 1.0)));
    shade(v_base, v_view, safe_normalize(v_normal), vis, primary, secondary);
#else
    shade(v_base, v_view, safe_normalize(v_normal), primary, secondary);
#endif
#elif defined(SHADOW)
    float vis = shadow_visibility(shadow_coord(vec4(v_view, 1.0)));
    precise vec3 lit = v_rest.rgb + vis * v_light;
    vec4 primary = vec4(clamp(lit, 0.0, 1.0), v_rest.a);
    precise vec3 secondary = v_rest_sec + vis * v_light_sec;
#else
    vec4 primary = v_primary;
    vec3 secondary = v_secondary;
#endif
#if defined(TEXTURED)
    vec4 texel = texture(u_texture, v_texcoord);
#else
    vec4 texel = vec4(1.0);
#endif
    precise vec3 rgb = primary.rgb * texel.rgb + secondary;
    o_color = vec4(clamp(rgb, 0.0, 1.0), primary.a * texel.a);
}
