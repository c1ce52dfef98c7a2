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
//
// The last subgroup of the dispatch to finish then cuts the frame's cluster slices from that range
// (below): the slice starts and each slice's lights, which every later reader compares against.
// They were a dispatch of their own (cluster_slices.comp) behind a barrier; on an NVIDIA H200 that
// second dependent dispatch cost 11.3 us of clustered culling's 54, with tiled's whole culling 27
// (bench/RESULTS.md, sixth part). A counter of finished subgroups (GpuDepthRange) finds the last
// one, as single-pass reductions do (AMD's FidelityFX SPD): each subgroup's invocations make their
// atomics, then a memory barrier, and one of them counts the subgroup; the one that counts last
// knows every other subgroup's atomics came before its own count. Subgroup basic operations only
// (elect, barrier), which every Vulkan 1.1 device has in compute shaders.
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#include "gpu_types.h"
#include "culling.h"

layout(local_size_x = PUNCTUAL_DEPTH_RANGE_THREADS) in;  // a row of squares a workgroup row
layout(constant_id = PUNCTUAL_SPEC_SLICE_COUNT) const uint SLICE_COUNT = 1u;
layout(constant_id = PUNCTUAL_SPEC_GRID_WORDS) const uint GRID_WORDS = 3u;  // words a light-grid cell

layout(set = 0, binding = PUNCTUAL_BINDING_FRAME) uniform FrameBlock { GpuFrame frame; };
layout(set = 0, binding = PUNCTUAL_BINDING_DEPTH) uniform sampler2D depthImage;
layout(std430, set = 0, binding = PUNCTUAL_BINDING_CULL_LIGHTS) readonly buffer CullLightBlock { CullLight frameCullLights[]; };
layout(std430, set = 0, binding = PUNCTUAL_BINDING_DEPTH_RANGE) coherent buffer DepthRangeBlock {
    GpuDepthRange depthRange;
    uint sliceLights[];  // per slice (all PUNCTUAL_MAX_CLUSTER_SLICES), GRID_WORDS mask words
};
// The transparent surfaces' depth span per pixel, when the frame has any (frame.transparentSpans):
// the range covers them too, so that their depths fall inside the slices.
layout(std430, set = 0, binding = PUNCTUAL_BINDING_TRANSPARENT_DEPTH) readonly buffer TransparentDepthBlock {
    uint transparentDepth[];
};

#include "depth_blocks.glsl"

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

// The lights' view-distance extents, for the last subgroup's slices, a chunk of 32 words' lights
// at a time (8 KiB; all of them up to 1,024 lights). Only that subgroup touches them, so subgroup
// barriers order its writes and reads (no workgroup barrier: the other subgroups of its workgroup
// have left).
const uint kChunkWords = GRID_WORDS < 32u ? GRID_WORDS : 32u;
shared vec2 lightExtents[32u * kChunkWords];
// Each slice's distances, from the slice's start's to the next slice's start's (x > y: a slice
// with no light, past SLICE_COUNT or in an empty frame).
shared vec2 sliceDistances[PUNCTUAL_MAX_CLUSTER_SLICES];
// Each subgroup's place in the count of finished subgroups (1 = first, gl_NumSubgroups x the
// workgroups = last).
shared uint subgroupCounts[PUNCTUAL_DEPTH_RANGE_THREADS];

// The slices of the depth range now complete, by the dispatch's last subgroup: each of its
// invocations cuts its share of the slices, then, a chunk of lights at a time, finds the extents of
// its share of the chunk's lights and sets its slices' bits for them.
// Slice s: sliceStartDepth[s] = depth of D_s = Dnear (Dfar / Dnear)^(s / S) (culling.h), and its
// lights: those whose view-distance extent meets the slice's distances.
void cutSlices(uint minDepthBits, uint maxDepthBits) {
    uint lightCount = frame.spotCount + frame.pointCount;
    if (gl_SubgroupInvocationID == 0u) depthRange.sliceCount = SLICE_COUNT;
    bool empty = minDepthBits > maxDepthBits;
    float nearDistance = viewDistanceFromDepth(uintBitsToFloat(maxDepthBits), frame.depthToView.xy);
    float farDistance = viewDistanceFromDepth(uintBitsToFloat(minDepthBits), frame.depthToView.xy);
    for (uint slice = gl_SubgroupInvocationID; slice < PUNCTUAL_MAX_CLUSTER_SLICES; slice += gl_SubgroupSize) {
        // Depth is reversed (culling.h): slice starts fall from 1 (the near plane) towards 0. An
        // empty frame (no geometry) leaves min > max: every slice starts at depth 1 and has no
        // light (no pixel reads one). Slices past SLICE_COUNT start at -1, below every depth, so
        // the search never picks them.
        if (empty || slice >= SLICE_COUNT) {
            depthRange.sliceStartDepth[slice] = slice == 0u || empty ? 1.0 : -1.0;
            sliceDistances[slice] = vec2(1.0, 0.0);
            continue;
        }
        float start = sliceStart(slice, nearDistance, farDistance);
        depthRange.sliceStartDepth[slice] = start;
        // The slice's distances: from its start's to the next slice's start's (view distance
        // falls monotonically with depth, also as rounded, so every segment culling makes in the
        // slice lies within), the first slice from 0 and the last to infinity. Widened as the
        // segments are (makeTileVolume: by the culling margin), and by 1e-5 more, so that a light
        // whose extent comes out an ulp apart here and in the culling kernel is kept: the kernel's
        // own test (lightMayTouchTile) decides. (With the margin left out, a light ending within
        // it before the slice was dropped here and kept by light_culling.comp's test, which reads
        // no slice lists: 2,500 lights, tests/gpu/test_culling.cpp.)
        const float kWider = 1.0 + PUNCTUAL_CULL_RELATIVE_MARGIN;
        float sliceNear = slice == 0u ? 0.0 : viewDistanceFromDepth(start, frame.depthToView.xy) * ((2.0 - kWider) * (1.0 - 1e-5));
        float sliceFar = slice + 1u < SLICE_COUNT
                             ? viewDistanceFromDepth(sliceStart(slice + 1u, nearDistance, farDistance), frame.depthToView.xy) * (kWider * (1.0 + 1e-5))
                             : 3.4e38;
        sliceDistances[slice] = vec2(sliceNear, sliceFar);
    }
    for (uint chunk = 0u; chunk < GRID_WORDS; chunk += kChunkWords) {
        uint chunkWords = min(kChunkWords, GRID_WORDS - chunk);
        uint firstLight = lightGridFirstLight(chunk);
        subgroupMemoryBarrierShared();
        subgroupBarrier();  // the last chunk's extents read, sliceDistances written
        for (uint k = gl_SubgroupInvocationID; k < 32u * chunkWords; k += gl_SubgroupSize) {
            if (firstLight + k < lightCount) lightExtents[k] = lightDistanceExtent(frameCullLights[firstLight + k]);
        }
        subgroupMemoryBarrierShared();
        subgroupBarrier();
        for (uint slice = gl_SubgroupInvocationID; slice < PUNCTUAL_MAX_CLUSTER_SLICES; slice += gl_SubgroupSize) {
            vec2 distances = sliceDistances[slice];
            for (uint word = 0u; word < chunkWords; ++word) {
                uint candidates = distances.x <= distances.y ? allLightsWord(chunk + word, lightCount) : 0u;
                uint bits = 0u;
                for (; candidates != 0u; candidates &= candidates - 1u) {
                    uint bit = uint(findLSB(candidates));
                    vec2 extent = lightExtents[32u * word + bit];
                    if (extent.y >= distances.x && extent.x <= distances.y) bits |= 1u << bit;
                }
                sliceLights[slice * GRID_WORDS + chunk + word] = bits;
            }
        }
    }
}

void main() {
    const uint kSide = PUNCTUAL_DEPTH_RANGE_SIDE;
    uvec2 viewport = uvec2(frame.viewport.xy);
    // Invocation x of workgroup row y: square (x, y); the rows of workgroups are the squares' rows.
    uvec2 square = uvec2(gl_GlobalInvocationID.x, gl_WorkGroupID.y);
    // Invocations past the last square stay, for their subgroup's count, with an empty square.
    uvec2 origin = square * kSide;
    uvec2 end = square.x < (viewport.x + kSide - 1u) / kSide ? min(origin + kSide, viewport) : origin;
    vec2 extent = vec2(0.0, 1.0);  // nearest (largest) and farthest (smallest) geometry depth; x = 0: none
    for (uint block = 0u; block < (kSide / 2u) * (kSide / 2u); ++block) {
        extent = quadExtent(origin + 2u * uvec2(block % (kSide / 2u), block / (kSide / 2u)), end, extent);
    }
    uint threadMin = extent.x > 0.0 ? floatBitsToUint(extent.y) : 0xFFFFFFFFu;
    uint threadMax = extent.x > 0.0 ? floatBitsToUint(extent.x) : 0u;
    if (frame.transparentSpans != 0u) {
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
    if (SLICE_COUNT <= 1u) return;  // no slices to cut (not used so: tiled culling runs no range pass)

    // Count this subgroup once its atomics are made; the last one counted cuts the slices. The
    // count reaches the subgroup's other invocations through shared memory (a broadcast would need
    // the ballot operations, which Vulkan does not promise).
    memoryBarrierBuffer();
    subgroupBarrier();
    uint subgroups = gl_NumWorkGroups.x * gl_NumWorkGroups.y * gl_NumSubgroups;
    if (subgroupElect()) subgroupCounts[gl_SubgroupID] = atomicAdd(depthRange.finishedSubgroups, 1u) + 1u;
    subgroupMemoryBarrierShared();
    subgroupBarrier();
    if (subgroupCounts[gl_SubgroupID] != subgroups) return;  // (uniform in the subgroup)
    memoryBarrierBuffer();
    // Read the finished range as atomics do (coherent, and after the count).
    cutSlices(atomicOr(depthRange.minDepthBits, 0u), atomicOr(depthRange.maxDepthBits, 0u));
}
