#version 450
// The resolve of a 4-sample colour image as sgapi does it (docs/api.md, "Multisampling"): each
// channel's four unorm8 values summed and divided by 4, rounded to nearest (halves up), in
// integers. Vulkan's own resolve averages in float, which puts exact halves either side.
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0) uniform sampler2DMS samples;
layout(set = 0, binding = 1) writeonly buffer Pixels { uint pixels[]; };
layout(push_constant) uniform Size { int width, height; };

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (p.x >= width || p.y >= height) return;
    uvec4 sum = uvec4(2u);
    for (int k = 0; k < 4; k++) sum += uvec4(round(texelFetch(samples, p, k) * 255.0));
    uvec4 c = sum >> 2u;
    pixels[p.y * width + p.x] = c.r | c.g << 8 | c.b << 16 | c.a << 24;
}
