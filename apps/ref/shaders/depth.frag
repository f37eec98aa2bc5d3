#version 450
// Fragment stage of the shadow's depth-only pass: the depth bias of sgapi's pipeline
// (sgPipelineDesc.depth.bias_constant, .bias_slope), written out. Vulkan's own depthBias state is
// not used: the unit of its constant term is the implementation's.
#extension GL_GOOGLE_include_directive : require
#include "draw.glsl"

void main() {
    float z = gl_FragCoord.z;
    precise float biased = z + u.shadow.y + u.shadow.z * max(abs(dFdx(z)), abs(dFdy(z)));
    gl_FragDepth = clamp(biased, 0.0, 1.0);
}
