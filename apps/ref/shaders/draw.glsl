// draw.glsl - the per-draw uniform block every shader of the reference reads (std140; the C side
// is sgapi-ref.c's draw_block), and the matrix row products the shaders share. The unlit shaders
// without a shadow declare only its first member, `color`, themselves.
#ifndef DRAW_GLSL
#define DRAW_GLSL

struct Light {
    vec4 vec;         // w = 0: directional, xyz = L = -normalize(direction) (done in double on
                      // the CPU); w = 1: point, xyz = position
    vec4 color;       // rgb
    vec4 attenuation; // constant, linear, quadratic
};

layout(set = 0, binding = 0) uniform Draw {
    vec4 color;        // the draw colour: base = vertex colour * color
    vec4 ambient;      // rgb: the scene's ambient light
    vec4 specular;     // rgb: the material's specular colour; w: shininess
    vec4 nm[3];        // rows of the inverse transpose of worldView's 3x3 (zero when singular)
    ivec4 light_count; // x
    Light lights[8];
    // The scene's shadow (zero without one): view space -> the light's clip space, the light's
    // projection x its view, formed in double on the CPU.
    layout(row_major) mat4 shadow_matrix;
    vec4 shadow;        // x: the map's size, y: bias, z: slope bias (window depth)
    ivec4 shadow_flags; // x: the index of the shadowed light, y: 1 for 2 x 2 PCF
} u;

// Row i of a row-major matrix declared row_major (GLSL indexes it [column][row]) times p, summed
// left to right.
precise float row_times(mat4 m, int i, vec4 p) {
    return ((m[0][i] * p.x + m[1][i] * p.y) + m[2][i] * p.z) + m[3][i] * p.w;
}

// The view-space position (worldView * p).xyz / (worldView * p).w.
vec3 view_position(mat4 world_view, vec4 p) {
    precise vec4 e = vec4(row_times(world_view, 0, p), row_times(world_view, 1, p),
                          row_times(world_view, 2, p), row_times(world_view, 3, p));
    precise vec3 v = e.xyz / e.w;
    return v;
}

// The light's clip coordinates of a view-space point e (w = 1 for a divided position):
// shadow_matrix * e, each row summed left to right.
vec4 shadow_coord(vec4 e) {
    precise vec4 s = vec4(row_times(u.shadow_matrix, 0, e), row_times(u.shadow_matrix, 1, e),
                          row_times(u.shadow_matrix, 2, e), row_times(u.shadow_matrix, 3, e));
    return s;
}

#endif
