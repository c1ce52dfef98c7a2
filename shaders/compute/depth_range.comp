#version 450
// The depth range of the frame's geometry, for clustered culling's depth slices: with the
// reversed depth (culling.h) the largest depth is the nearest geometry, the smallest the
// farthest. Background pixels (depth 0, the clear value) are ignored. Each of a group's 64 threads folds a 4x4 block in
// registers (few invocations: their count, not the reads, is what costs on CPU drivers), the group
// reduces in shared memory, and one thread merges into the global pair. Depths are non-negative
// floats, whose bit patterns sort like the values, so integer atomicMin/Max order them correctly.
#extension GL_GOOGLE_include_directive : require
#include "gpu_types.h"
#include "culling.h"

layout(local_size_x = 8, local_size_y = 8) in;  // one group covers 32x32 pixels

layout(set = 0, binding = PUNCTUAL_BINDING_FRAME) uniform FrameBlock { GpuFrame frame; };
layout(set = 0, binding = PUNCTUAL_BINDING_DEPTH) uniform sampler2D depthImage;
layout(std430, set = 0, binding = PUNCTUAL_BINDING_DEPTH_RANGE) buffer DepthRangeBlock { GpuDepthRange depthRange; };
// The transparent surfaces' depth span per pixel, when the frame has any (frame.lightCounts.w):
// the range covers them too, so that their depths fall inside the slices.
layout(std430, set = 0, binding = PUNCTUAL_BINDING_TRANSPARENT_DEPTH) readonly buffer TransparentDepthBlock {
    uint transparentDepth[];
};

shared uint groupMin;
shared uint groupMax;

void main() {
    if (gl_LocalInvocationIndex == 0u) {
        groupMin = 0xFFFFFFFFu;
        groupMax = 0u;
    }
    barrier();
    uint threadMin = 0xFFFFFFFFu;
    uint threadMax = 0u;
    for (uint i = 0u; i < 16u; ++i) {
        uvec2 pixel = gl_GlobalInvocationID.xy * 4u + uvec2(i & 3u, i >> 2u);
        if (pixel.x >= uint(frame.viewport.x) || pixel.y >= uint(frame.viewport.y)) continue;
        float depth = texelFetch(depthImage, ivec2(pixel), 0).r;
        if (!isBackgroundDepth(depth)) {
            threadMin = min(threadMin, floatBitsToUint(depth));
            threadMax = max(threadMax, floatBitsToUint(depth));
        }
        if (frame.lightCounts.w != 0u) {
            uint index = pixel.y * uint(frame.viewport.x) + pixel.x;
            uint nearestBits = transparentDepth[index];
            if (nearestBits != 0u) {
                threadMax = max(threadMax, nearestBits);
                threadMin = min(threadMin, transparentDepth[uint(frame.viewport.x * frame.viewport.y) + index]);
            }
        }
    }
    if (threadMin <= threadMax) {
        atomicMin(groupMin, threadMin);
        atomicMax(groupMax, threadMax);
    }
    barrier();
    if (gl_LocalInvocationIndex == 0u && groupMin <= groupMax) {
        atomicMin(depthRange.minDepthBits, groupMin);
        atomicMax(depthRange.maxDepthBits, groupMax);
    }
}
