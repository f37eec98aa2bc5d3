#version 450
// SG_SHADE_VERTEX_COLOR: the perspective-correct interpolated vertex colour.
layout(location = 0) in vec4 v_color;
layout(location = 0) out vec4 o_color;

void main() {
    o_color = v_color;
}
