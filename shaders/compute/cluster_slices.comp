#version 450
// Cluster slice boundaries for this frame, from the geometry depth range the depth-range pass
// found: sliceStartDepth[s] = depth of D_s = Dnear (Dfar / Dnear)^(s / S) (see culling.h). One
// workgroup, one thread per slice. Every later reader compares depths against these values.
#extension GL_GOOGLE_include_directive : require
#include "gpu_types.h"
#include "culling.h"

layout(local_size_x = PUNCTUAL_MAX_CLUSTER_SLICES) in;
layout(constant_id = PUNCTUAL_SPEC_SLICE_COUNT) const uint SLICE_COUNT = 1u;

layout(set = 0, binding = PUNCTUAL_BINDING_FRAME) uniform FrameBlock { GpuFrame frame; };
layout(std430, set = 0, binding = PUNCTUAL_BINDING_DEPTH_RANGE) buffer DepthRangeBlock { GpuDepthRange depthRange; };

void main() {
    uint slice = gl_LocalInvocationIndex;
    if (slice >= PUNCTUAL_MAX_CLUSTER_SLICES) return;
    if (slice == 0u) depthRange.sliceCount = SLICE_COUNT;
    // Depth is reversed (culling.h): slice starts fall from 1 (the near plane) towards 0. An
    // empty frame (no geometry) leaves min > max: every slice starts at depth 1. Slices past
    // SLICE_COUNT start at -1, below every depth, so the search never picks them.
    if (depthRange.minDepthBits > depthRange.maxDepthBits || slice >= SLICE_COUNT) {
        depthRange.sliceStartDepth[slice] = slice == 0u || depthRange.minDepthBits > depthRange.maxDepthBits ? 1.0 : -1.0;
        return;
    }
    float nearestDepth = uintBitsToFloat(depthRange.maxDepthBits);
    float farthestDepth = uintBitsToFloat(depthRange.minDepthBits);
    float nearDistance = viewDistanceFromDepth(nearestDepth, frame.depthToView.xy);
    float farDistance = viewDistanceFromDepth(farthestDepth, frame.depthToView.xy);
    float start = slice == 0u ? 1.0
                              : depthFromViewDistance(sliceStartDistance(slice, nearDistance, farDistance, SLICE_COUNT),
                                                      frame.depthToView.xy);
    depthRange.sliceStartDepth[slice] = start;
}
