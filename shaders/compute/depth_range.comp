#version 450
// The depth range of the frame's geometry, for clustered culling's depth slices: with the
// reversed depth (culling.h) the largest depth is the nearest geometry, the smallest the
// farthest. Background pixels (depth 0, the clear value) are ignored. Each invocation folds a
// square of PUNCTUAL_DEPTH_RANGE_SIDE pixels a side in registers, 2x2 blocks a gather
// (quadExtent), and merges it into the global pair with two atomics: no shared memory and no
// barriers (a 64-invocation workgroup reducing through shared memory behind two barriers cost
// lavapipe, which switches coroutines at every barrier, about 2 ms more at 1280x720; the atomics
// are one pair per 64 pixels). The square's side trades the two machines: each invocation's
// gathers run one after another, so 16-pixel squares (64 gathers, 3,600 invocations at 1280x720,
// under one warp a multiprocessor) took an NVIDIA H200 18.4 us and 8-pixel ones 9.1 (4-pixel ones
// no less); lavapipe, for which fewer and longer invocations are cheaper, pays 0.89 -> 1.02 ms for
// the 8 (4: 2.0). Depths are non-negative floats, whose bit patterns sort like the values, so
// integer atomicMin/Max order them correctly.
#extension GL_GOOGLE_include_directive : require
#include "gpu_types.h"
#include "culling.h"

layout(local_size_x = PUNCTUAL_DEPTH_RANGE_THREADS) in;  // a row of squares a workgroup row

layout(set = 0, binding = PUNCTUAL_BINDING_FRAME) uniform FrameBlock { GpuFrame frame; };
layout(set = 0, binding = PUNCTUAL_BINDING_DEPTH) uniform sampler2D depthImage;
layout(std430, set = 0, binding = PUNCTUAL_BINDING_DEPTH_RANGE) buffer DepthRangeBlock { GpuDepthRange depthRange; };
// The transparent surfaces' depth span per pixel, when the frame has any (frame.lightCounts.w):
// the range covers them too, so that their depths fall inside the slices.
layout(std430, set = 0, binding = PUNCTUAL_BINDING_TRANSPARENT_DEPTH) readonly buffer TransparentDepthBlock {
    uint transparentDepth[];
};

#include "depth_blocks.glsl"

void main() {
    const uint kSide = PUNCTUAL_DEPTH_RANGE_SIDE;
    uvec2 viewport = uvec2(frame.viewport.xy);
    // Invocation x of workgroup row y: square (x, y); the rows of workgroups are the squares' rows.
    uvec2 square = uvec2(gl_GlobalInvocationID.x, gl_WorkGroupID.y);
    if (square.x >= (viewport.x + kSide - 1u) / kSide) return;
    uvec2 origin = square * kSide;
    uvec2 end = min(origin + kSide, viewport);
    vec2 extent = vec2(0.0, 1.0);  // nearest (largest) and farthest (smallest) geometry depth; x = 0: none
    for (uint block = 0u; block < (kSide / 2u) * (kSide / 2u); ++block) {
        extent = quadExtent(origin + 2u * uvec2(block % (kSide / 2u), block / (kSide / 2u)), end, extent);
    }
    uint threadMin = extent.x > 0.0 ? floatBitsToUint(extent.y) : 0xFFFFFFFFu;
    uint threadMax = extent.x > 0.0 ? floatBitsToUint(extent.x) : 0u;
    if (frame.lightCounts.w != 0u) {
        for (uint y = origin.y; y < end.y; ++y) {
            for (uint x = origin.x; x < end.x; ++x) {
                uint index = y * viewport.x + x;
                uint nearestBits = transparentDepth[index];
                if (nearestBits != 0u) {
                    threadMax = max(threadMax, nearestBits);
                    threadMin = min(threadMin, transparentDepth[viewport.x * viewport.y + index]);
                }
            }
        }
    }
    if (threadMin <= threadMax) {
        atomicMin(depthRange.minDepthBits, threadMin);
        atomicMax(depthRange.maxDepthBits, threadMax);
    }
}
