#version 450
// The depth span of the transparent (alphaMode BLEND) surfaces at each pixel, for the culling
// kernels: tiled and clustered light lists are built from the depths of what a pixel shades, and
// the depth prepass holds the opaque surfaces only. Run with the prepass's depth attached
// read-only and tested (GREATER: nearer), so only transparent fragments in front of the opaque
// surface count. Depths are non-negative floats, whose bits order like the values.
#extension GL_GOOGLE_include_directive : require
#include "gpu_types.h"

layout(early_fragment_tests) in;

layout(set = 0, binding = PUNCTUAL_BINDING_FRAME) uniform FrameBlock { GpuFrame frame; };
layout(std430, set = 0, binding = PUNCTUAL_BINDING_TRANSPARENT_DEPTH) buffer TransparentDepthBlock {
    uint transparentDepth[];
};

// mesh.vert's interface (unread: the depth is all this needs).
layout(location = 0) in vec3 inWorldPosition;
layout(location = 1) in vec3 inWorldNormal;
layout(location = 2) in vec2 inUv;
layout(location = 3) in vec2 inUv1;
layout(location = 4) flat in uint inObject;

void main() {
    uvec2 pixel = uvec2(gl_FragCoord.xy);
    uint index = pixel.y * uint(frame.viewport.x) + pixel.x;
    uint pixels = uint(frame.viewport.x * frame.viewport.y);
    uint depthBits = floatBitsToUint(gl_FragCoord.z);
    atomicMax(transparentDepth[index], depthBits);           // reversed depth: larger is nearer
    atomicMin(transparentDepth[pixels + index], depthBits);
}
