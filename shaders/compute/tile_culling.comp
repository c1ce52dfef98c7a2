#version 450
// Tile culling for the methods with one depth extent per tile: tiled and zbin (culled against the
// tile's depth extent) and zbin-2d (DEPTHLESS_TILES: the tile's whole column, no depth read; its
// z-bins hold depth). One workgroup per screen tile, sized to the device's subgroup
// (TILE_THREADS): its lanes
//  1. fold the depths of the tile's 2x2 blocks (quadExtent, depth_blocks.glsl) into the nearest
//     and farthest geometry depth, or with transparent spans every pixel's span, and combine them
//     with subgroupMax / subgroupMin;
//  2. build the tile's frustum segment (culling.h), each lane the same one;
//  3. test the lights, each lane every TILE_THREADS-th light (with the coarse pass, every
//     TILE_THREADS-th of its coarse tile's candidates), collecting the passing ones in three
//     mask words (culling.h, lightGridWord), combined with subgroupOr and written by lanes 0-2.
// The masks are those of light_culling.comp's one-slice case bit for bit: the same lights are
// tested against the same segment, whose distances come from the same extreme depths.
//
// Why a kernel of its own: light_culling.comp's 64-invocation workgroups combine through shared
// memory, three barriers and shared atomics per tile, and that fixed cost was most of the pass on
// lavapipe (its workgroups run their subgroups as coroutines switched at every barrier): at
// 1280x720 with no lights, 8.4 ms of shared-memory kernel against 1.4 ms for one subgroup reading
// the same depths (measured, bench/RESULTS.md). One subgroup per tile needs neither, on any device.
// A device whose compute subgroups are smaller than the workgroup (subgroupSize is the default
// size, not a promise) still gets the right masks: the subgroups then combine through shared
// memory (workgroupExtent, workgroupMasks), behind barriers in uniform control flow.
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#include "gpu_types.h"
#include "culling.h"

layout(local_size_x_id = PUNCTUAL_SPEC_TILE_THREADS) in;
layout(constant_id = PUNCTUAL_SPEC_TILE_SIZE) const uint TILE_SIZE = 16u;
layout(constant_id = PUNCTUAL_SPEC_DEPTHLESS_TILES) const bool DEPTHLESS_TILES = false;
layout(constant_id = PUNCTUAL_SPEC_COARSE_TILES) const uint COARSE_TILES = 0u;  // 0: no coarse pass

layout(set = 0, binding = PUNCTUAL_BINDING_FRAME) uniform FrameBlock { GpuFrame frame; };
// The lights' view-space culling shapes (makeCullLight in culling.h, made on the CPU).
layout(std430, set = 0, binding = PUNCTUAL_BINDING_CULL_LIGHTS) readonly buffer CullLightBlock { CullLight frameCullLights[]; };
layout(set = 0, binding = PUNCTUAL_BINDING_DEPTH) uniform sampler2D depthImage;
layout(std430, set = 0, binding = PUNCTUAL_BINDING_LIGHT_GRID) writeonly buffer GridBlock { uint lightGrid[]; };
layout(std430, set = 0, binding = PUNCTUAL_BINDING_COARSE_GRID) readonly buffer CoarseGridBlock { uint coarseGrid[]; };
// The transparent surfaces' depth span per pixel (transparent_depth.frag), when the frame has any
// (frame.lightCounts.w): nearest transparent depth, then (second half) the farthest.
layout(std430, set = 0, binding = PUNCTUAL_BINDING_TRANSPARENT_DEPTH) readonly buffer TransparentDepthBlock {
    uint transparentDepth[];
};

#include "depth_blocks.glsl"

// One slot per subgroup, for workgroups of several subgroups only.
shared uvec4 subgroupResults[PUNCTUAL_MAX_TILE_THREADS];

// (nearest, farthest) depth over the workgroup. Called by every invocation.
vec2 workgroupExtent(vec2 extent) {
    extent = vec2(subgroupMax(extent.x), subgroupMin(extent.y));
    if (gl_NumSubgroups == 1u) return extent;  // uniform over the workgroup
    if (subgroupElect()) subgroupResults[gl_SubgroupID] = uvec4(floatBitsToUint(extent), 0u, 0u);
    barrier();
    for (uint i = 0u; i < gl_NumSubgroups; ++i) {
        vec2 other = uintBitsToFloat(subgroupResults[i].xy);
        extent = vec2(max(extent.x, other.x), min(extent.y, other.y));
    }
    barrier();  // every slot read before workgroupMasks writes them again
    return extent;
}

// The union of the invocations' mask words. Called by every invocation.
uvec3 workgroupMasks(uvec3 masks) {
    masks = subgroupOr(masks);
    if (gl_NumSubgroups == 1u) return masks;
    if (subgroupElect()) subgroupResults[gl_SubgroupID] = uvec4(masks, 0u);
    barrier();
    for (uint i = 0u; i < gl_NumSubgroups; ++i) masks |= subgroupResults[i].xyz;
    return masks;
}

// The bits of a mask word `word` that invocation `lane` of `threads` (a power of two, at most 64)
// tests: candidate 32 word + bit goes to lane (32 word + bit) mod threads, which spreads the
// candidates of any word evenly. For threads <= 32, every threads-th bit from bit `lane`:
// 0xFFFFFFFF / (2^threads - 1) has a one every `threads` bits (8: 0x01010101). For 64, a word's
// 32 candidates go to one half of the lanes.
uint laneBitsOfWord(uint word, uint lane, uint threads) {
    if (threads >= 32u) return (32u * word) % threads == (lane & ~31u) ? 1u << (lane & 31u) : 0u;
    return (0xFFFFFFFFu / ((1u << threads) - 1u)) << lane;
}

// The pixel's geometry span in depth (nearest, farthest) folded into `extent`: a pixel under
// transparent surfaces spans from its nearest transparent depth to its opaque depth (over the
// background, its farthest transparent depth); any other pixel, its opaque depth unless background.
vec2 addPixelSpan(uvec2 pixel, vec2 extent) {
    float depth = texelFetch(depthImage, ivec2(pixel), 0).r;
    uint index = pixel.y * uint(frame.viewport.x) + pixel.x;
    uint nearestBits = transparentDepth[index];
    if (nearestBits != 0u) {
        float farthest = isBackgroundDepth(depth) ? uintBitsToFloat(transparentDepth[uint(frame.viewport.x * frame.viewport.y) + index])
                                                  : depth;
        return vec2(max(extent.x, uintBitsToFloat(nearestBits)), min(extent.y, farthest));
    }
    if (isBackgroundDepth(depth)) return extent;
    return vec2(max(extent.x, depth), min(extent.y, depth));
}

void main() {
    uint lane = gl_LocalInvocationIndex;
    uint threads = gl_WorkGroupSize.x;
    uvec2 tile = gl_WorkGroupID.xy;
    uvec2 viewport = uvec2(frame.viewport.xy);
    uvec2 tileEnd = min((tile + 1u) * TILE_SIZE, viewport);  // one past the tile's last pixel
    vec2 pixelToNdc = 2.0 * frame.viewport.zw;
    vec2 ndcA = vec2(tile * TILE_SIZE) * pixelToNdc - 1.0;
    vec2 ndcB = min(vec2((tile + 1u) * TILE_SIZE), frame.viewport.xy) * pixelToNdc - 1.0;

    // 1-2. The tile's segment: its depth extent, or (DEPTHLESS_TILES) its whole column.
    TileVolume segment;
    bool occupied = true;
    if (DEPTHLESS_TILES) {
        segment = makeTileColumn(min(ndcA, ndcB), max(ndcA, ndcB), frame.depthToView.xy, frame.ndcToView);
    } else {
        vec2 extent = vec2(0.0, 1.0);  // nearest (largest) and farthest (smallest) depth; x = 0: none
        const uint kBlocks = (TILE_SIZE + 1u) / 2u;  // 2x2 blocks a side (an odd size's last is half outside)
        if (frame.lightCounts.w == 0u) {
            for (uint block = lane; block < kBlocks * kBlocks; block += threads) {
                extent = quadExtent(tile * TILE_SIZE + 2u * uvec2(block % kBlocks, block / kBlocks), tileEnd, extent);
            }
        } else {
            for (uint index = lane; index < TILE_SIZE * TILE_SIZE; index += threads) {
                uvec2 pixel = tile * TILE_SIZE + uvec2(index % TILE_SIZE, index / TILE_SIZE);
                if (pixel.x < viewport.x && pixel.y < viewport.y) extent = addPixelSpan(pixel, extent);
            }
        }
        extent = workgroupExtent(extent);
        occupied = extent.x > 0.0;
        // View distance falls monotonically with depth, also as rounded (viewDistanceFromDepth), so
        // the extreme depths give exactly the extreme distances.
        segment = makeTileVolume(min(ndcA, ndcB), max(ndcA, ndcB), viewDistanceFromDepth(extent.x, frame.depthToView.xy),
                                 viewDistanceFromDepth(extent.y, frame.depthToView.xy), frame.ndcToView);
    }

    // 3. The lights against the segment.
    uint spotCount = frame.lightCounts.x;
    uint lightCount = frame.lightCounts.x + frame.lightCounts.y;
    uvec3 masks = uvec3(0u);
    if (occupied && COARSE_TILES == 0u) {
        for (uint light = lane; light < lightCount; light += threads) {
            if (!lightMayTouchTile(frameCullLights[light], segment)) continue;
            uint bit = 1u << lightGridBit(light, spotCount);
            uint word = lightGridWord(light, spotCount);
            masks |= uvec3(word == 0u ? bit : 0u, word == 1u ? bit : 0u, word == 2u ? bit : 0u);
        }
    } else if (occupied) {
        // The candidates: the lights the coarse pass kept for this tile's coarse tile.
        uvec2 coarseTile = tile / COARSE_TILES;
        uint coarseTilesAcross = (frame.lightGrid.y + COARSE_TILES - 1u) / COARSE_TILES;
        uint coarseBase = (coarseTile.y * coarseTilesAcross + coarseTile.x) * PUNCTUAL_GRID_WORDS;
        uvec3 mine = uvec3(coarseGrid[coarseBase] & laneBitsOfWord(0u, lane, threads),
                           coarseGrid[coarseBase + 1u] & laneBitsOfWord(1u, lane, threads),
                           coarseGrid[coarseBase + 2u] & laneBitsOfWord(2u, lane, threads));
        // One loop over the three words, each step the lowest bit of the first word with any,
        // by selects (forward.frag walks its masks so, and why).
        while ((mine.x | mine.y | mine.z) != 0u) {
            uint word = mine.x != 0u ? 0u : (mine.y != 0u ? 1u : 2u);
            uint bits = word == 0u ? mine.x : (word == 1u ? mine.y : mine.z);
            uint bit = 1u << uint(findLSB(bits));
            mine &= ~uvec3(word == 0u ? bit : 0u, word == 1u ? bit : 0u, word == 2u ? bit : 0u);
            if (lightMayTouchTile(frameCullLights[lightGridFirstLight(word, spotCount) + uint(findLSB(bits))], segment)) {
                masks |= uvec3(word == 0u ? bit : 0u, word == 1u ? bit : 0u, word == 2u ? bit : 0u);
            }
        }
    }
    masks = workgroupMasks(masks);

    // 4. The tile's cell, always written (an empty tile's masks are zero).
    uint tileIndex = tile.y * frame.lightGrid.y + tile.x;
    if (lane < PUNCTUAL_GRID_WORDS) {
        lightGrid[tileIndex * PUNCTUAL_GRID_WORDS + lane] = lane == 0u ? masks.x : (lane == 1u ? masks.y : masks.z);
    }
}
