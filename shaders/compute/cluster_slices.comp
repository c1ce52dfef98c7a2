#version 450
// Cluster slice boundaries for this frame, from the geometry depth range the depth-range pass
// found: sliceStartDepth[s] = depth of D_s = Dnear (Dfar / Dnear)^(s / S) (see culling.h), and each
// slice's lights: those whose view-distance extent meets the slice's distances. One workgroup: an
// invocation a light finds its extent (into shared memory), then one a slice reads them all. (One
// thread a slice reading every light from the buffer itself cost an NVIDIA H200 125 us, a chain of
// 96 dependent global loads and extents in one warp; this way 96 run side by side.) Every later
// reader compares depths against these values.
#extension GL_GOOGLE_include_directive : require
#include "gpu_types.h"
#include "culling.h"

// An invocation for each light bit of the grid's words (the most lights a frame has), at least one
// a slice.
layout(local_size_x = PUNCTUAL_GRID_WORDS * 32) in;
layout(constant_id = PUNCTUAL_SPEC_SLICE_COUNT) const uint SLICE_COUNT = 1u;

layout(set = 0, binding = PUNCTUAL_BINDING_FRAME) uniform FrameBlock { GpuFrame frame; };
layout(std430, set = 0, binding = PUNCTUAL_BINDING_CULL_LIGHTS) readonly buffer CullLightBlock { CullLight frameCullLights[]; };
layout(std430, set = 0, binding = PUNCTUAL_BINDING_DEPTH_RANGE) buffer DepthRangeBlock { GpuDepthRange depthRange; };

// The start of slice `slice` (1 .. SLICE_COUNT - 1) between the given distances. The starts fall
// with the slice, and are made to even where rounding (pow, the division in depthFromViewDistance)
// might not: each is the smallest of its own and its predecessors'. Then "slice s holds depth d" is
// exactly sliceStart[s] >= d > sliceStart[s + 1], both for the search (PUNCTUAL_CLUSTER_SLICE_OF_DEPTH,
// which assumes it) and for cluster_culling.comp's per-slice comparisons.
float sliceStart(uint slice, float nearDistance, float farDistance) {
    float start = 1.0;
    for (uint s = 1u; s <= slice; ++s) {
        start = min(start, depthFromViewDistance(sliceStartDistance(s, nearDistance, farDistance, SLICE_COUNT),
                                                 frame.depthToView.xy));
    }
    return start;
}

shared vec2 lightExtents[PUNCTUAL_GRID_WORDS * 32];

void main() {
    uint spotCount = frame.lightCounts.x;
    uint lightCount = frame.lightCounts.x + frame.lightCounts.y;
    uint index = gl_LocalInvocationIndex;
    if (index < lightCount) lightExtents[index] = lightDistanceExtent(frameCullLights[index]);
    barrier();

    uint slice = index;
    if (slice >= PUNCTUAL_MAX_CLUSTER_SLICES) return;
    if (slice == 0u) depthRange.sliceCount = SLICE_COUNT;
    for (uint word = 0u; word < PUNCTUAL_GRID_WORDS; ++word) depthRange.sliceLights[slice * PUNCTUAL_GRID_WORDS + word] = 0u;
    // Depth is reversed (culling.h): slice starts fall from 1 (the near plane) towards 0. An
    // empty frame (no geometry) leaves min > max: every slice starts at depth 1 and has no light
    // (no pixel reads one). Slices past SLICE_COUNT start at -1, below every depth, so the search
    // never picks them.
    if (depthRange.minDepthBits > depthRange.maxDepthBits || slice >= SLICE_COUNT) {
        depthRange.sliceStartDepth[slice] = slice == 0u || depthRange.minDepthBits > depthRange.maxDepthBits ? 1.0 : -1.0;
        return;
    }
    float nearestDepth = uintBitsToFloat(depthRange.maxDepthBits);
    float farthestDepth = uintBitsToFloat(depthRange.minDepthBits);
    float nearDistance = viewDistanceFromDepth(nearestDepth, frame.depthToView.xy);
    float farDistance = viewDistanceFromDepth(farthestDepth, frame.depthToView.xy);
    float start = sliceStart(slice, nearDistance, farDistance);
    depthRange.sliceStartDepth[slice] = start;

    // The slice's distances: from its start's to the next slice's start's (view distance falls
    // monotonically with depth, also as rounded, so every segment culling makes in the slice lies
    // within), the first slice from 0 and the last to infinity. Widened by 1e-5 of themselves, so
    // that a light whose extent comes out an ulp apart here and in the culling kernel is kept:
    // the kernel's own test (lightMayTouchTile) decides.
    float sliceNear = slice == 0u ? 0.0 : viewDistanceFromDepth(start, frame.depthToView.xy) * (1.0 - 1e-5);
    float sliceFar = slice + 1u < SLICE_COUNT
                         ? viewDistanceFromDepth(sliceStart(slice + 1u, nearDistance, farDistance), frame.depthToView.xy) * (1.0 + 1e-5)
                         : 3.4e38;
    uvec3 lights = uvec3(0u);
    for (uint light = 0u; light < lightCount; ++light) {
        vec2 extent = lightExtents[light];
        if (extent.y < sliceNear || extent.x > sliceFar) continue;
        uint bit = 1u << lightGridBit(light, spotCount);
        uint word = lightGridWord(light, spotCount);
        lights |= uvec3(word == 0u ? bit : 0u, word == 1u ? bit : 0u, word == 2u ? bit : 0u);
    }
    depthRange.sliceLights[slice * PUNCTUAL_GRID_WORDS] = lights.x;
    depthRange.sliceLights[slice * PUNCTUAL_GRID_WORDS + 1u] = lights.y;
    depthRange.sliceLights[slice * PUNCTUAL_GRID_WORDS + 2u] = lights.z;
}
