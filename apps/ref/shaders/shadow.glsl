// shadow.glsl - the shadow test of sgapi (docs/reference.md, "Shadows"): where a point is in the
// light's clip space, and whether the map's depth hides it there, read with texelFetch (no
// filtering, no depth compare of the sampler: the test is written out here). Intermediates are
// `precise`, as in lighting.glsl. For fragment stages (texelFetch without a sampler needs
// GL_EXT_samplerless_texture_functions, which the including shader enables first).
#ifndef SHADOW_GLSL
#define SHADOW_GLSL
#include "draw.glsl"

layout(set = 2, binding = 0) uniform texture2D u_shadow_map;

// 1 when texel (i, j) of the map does not hide depth, or lies outside the map; 0 when it does.
// The range is checked on the floats, so a NaN coordinate counts as outside.
float shadow_texel(float i, float j, float depth) {
    float size = u.shadow.x;
    if (!(i >= 0.0 && i < size && j >= 0.0 && j < size)) return 1.0;
    return depth <= texelFetch(u_shadow_map, ivec2(int(i), int(j)), 0).r ? 1.0 : 0.0;
}

// The visibility of a point from the shadowed light, from its light clip coordinates s: 1 lit,
// 0 hidden; with PCF the mean of the 2 x 2 texels around it (0, 1/4, 1/2, 3/4 or 1). Image row 0
// of the map is the light's NDC y = +1, as in every target.
float shadow_visibility(vec4 s) {
    if (s.w <= 0.0) return 1.0; // behind the light: nothing in the map can hide it
    precise vec3 ndc = s.xyz / s.w;
    float size = u.shadow.x;
    precise float x = (ndc.x * 0.5 + 0.5) * size;
    precise float y = (0.5 - ndc.y * 0.5) * size;
    precise float depth = min(ndc.z * 0.5 + 0.5, 1.0); // beyond the far plane: as on it
    if (u.shadow_flags.y == 0) return shadow_texel(floor(x), floor(y), depth);
    precise float i0 = floor(x - 0.5), j0 = floor(y - 0.5);
    float sum = ((shadow_texel(i0, j0, depth) + shadow_texel(i0 + 1.0, j0, depth)) +
                 shadow_texel(i0, j0 + 1.0, depth)) +
                shadow_texel(i0 + 1.0, j0 + 1.0, depth);
    return sum * 0.25;
}

#endif
