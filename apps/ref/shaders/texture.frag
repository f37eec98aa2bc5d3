#version 450
// SG_SHADE_TEXTURE_MODULATE: vertex colour times texel. The texture's rows are uploaded bottom row
// first, so t = 0 addresses the bottom row as in OpenGL; filter and wrap come from the sampler.
layout(location = 0) in vec4 v_color;
layout(location = 1) in vec2 v_texcoord;
layout(set = 1, binding = 0) uniform sampler2D u_texture;
layout(location = 0) out vec4 o_color;

void main() {
    o_color = v_color * texture(u_texture, v_texcoord);
}
