#version 450
// Clustered light culling with one subgroup a tile (the device's subgroup size, TILE_THREADS), no
// shared-memory atomics and, where the workgroup is one subgroup, no barriers. Its lanes
//  1. fold the depths of the tile's 2x2 blocks (quadExtent, depth_blocks.glsl; with transparent
//     spans, every pixel's span) into the tile's nearest and farthest depth, combined with
//     subgroupMax / subgroupMin; each takes its share of the candidate lights (laneCandidates);
//  2. walk the occupied slices nearest first: the slice of the tile's nearest depth, then each
//     time the slice of the nearest depth past the last one (one search each; empty slices are
//     never read). Each pass reads the tile's blocks again: the depths inside the slice, (lo, hi],
//     give its nearest and farthest depth and the columns and rows of its pixels, each combined
//     over the workgroup. The slice gets its frustum segment (cut to that rectangle of the tile);
//     each lane tests its candidates whose depth extent meets the slice's (sliceLights, listed by
//     depth_range.comp) against it, and the masks are combined with subgroupOr and written (index
//     lists: gathered, then written as the cell's list, writeCellList). Past the design notes' 96
//     lights, from candidate lists instead (candidate_lists.glsl): the slice's candidates
//     compacted, tested every lane-th, their bits set in shared memory and written.
// A light is kept in a cluster where its shapes meet the cluster's segment (culling.h,
// lightMayTouchTile). There is no whole-tile test first: on the default scene it changed no list
// (the coarse pass and the slices' depth lists already keep the tests to lights near the tile), and
// it cost lavapipe 1.1 ms of the pass's 8 (bench/RESULTS.md).
// The masks are those light_culling.comp writes, bit for bit (tests/gpu/test_culling.cpp): the
// same lights against the same segments, whose distances come from the same extreme depths (view
// distance falls monotonically with depth, also as rounded), with the same rectangles: a block
// whose geometry lies in one slice gives it the whole block, a block across slices gives each its
// own pixels. The slices written are the occupied ones, as there.
//
// Why: light_culling.comp finds each pixel's slice with two searches a block (more for blocks
// across a boundary) and gathers each slice's extent with shared-memory atomics; on lavapipe at
// 1280x720 that made clustered culling 4.7x tiled's (bench/RESULTS.md). Here a pixel's slice is
// never searched: within the uniform slice loop, two comparisons with the slice's bounds tell
// whether it lies inside, and the extents are subgroup reductions. The depths are read once more
// per occupied slice, which the texture cache serves.
// A slice's bounds come from depth_range.comp (its last subgroup), which makes them non-increasing, so that "inside
// slice s" (sliceStart[s] >= depth > sliceStart[s + 1]) is exactly what the search in forward.frag
// (PUNCTUAL_CLUSTER_SLICE_OF_DEPTH) picks.
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#include "gpu_types.h"
#include "culling.h"

layout(local_size_x_id = PUNCTUAL_SPEC_TILE_THREADS) in;
layout(constant_id = PUNCTUAL_SPEC_TILE_SIZE) const uint TILE_SIZE = 16u;
layout(constant_id = PUNCTUAL_SPEC_SLICE_COUNT) const uint SLICE_COUNT = 16u;
layout(constant_id = PUNCTUAL_SPEC_COARSE_TILES) const uint COARSE_TILES = 0u;  // 0: no coarse pass
layout(constant_id = PUNCTUAL_SPEC_GRID_WORDS) const uint GRID_WORDS = 3u;  // words a light-grid cell

layout(set = 0, binding = PUNCTUAL_BINDING_FRAME) uniform FrameBlock { GpuFrame frame; };
// The lights' view-space culling shapes (makeCullLight in culling.h, made on the CPU).
layout(std430, set = 0, binding = PUNCTUAL_BINDING_CULL_LIGHTS) readonly buffer CullLightBlock { CullLight frameCullLights[]; };
layout(set = 0, binding = PUNCTUAL_BINDING_DEPTH) uniform sampler2D depthImage;
layout(std430, set = 0, binding = PUNCTUAL_BINDING_LIGHT_GRID) writeonly buffer GridBlock { uint lightGrid[]; };
layout(std430, set = 0, binding = PUNCTUAL_BINDING_COARSE_GRID) readonly buffer CoarseGridBlock { uint coarseGrid[]; };
layout(std430, set = 0, binding = PUNCTUAL_BINDING_DEPTH_RANGE) readonly buffer DepthRangeBlock {
    GpuDepthRange depthRange;
    uint sliceLights[];  // per slice, GRID_WORDS mask words (depth_range.comp)
};
// The transparent surfaces' depth span per pixel (transparent_depth.frag), when the frame has any
// (frame.transparentSpans): nearest transparent depth, then (second half) the farthest.
layout(std430, set = 0, binding = PUNCTUAL_BINDING_TRANSPARENT_DEPTH) readonly buffer TransparentDepthBlock {
    uint transparentDepth[];
};

// Past the design notes' 96 lights a cluster's candidates are compacted and tested as a list
// (candidate_lists.glsl).
const bool CANDIDATE_LISTS = GRID_WORDS > 3u;

#include "depth_blocks.glsl"
#include "light_lists.glsl"
#include "subgroup_tiles.glsl"

const uint kBlocks = (TILE_SIZE + 1u) / 2u;  // 2x2 blocks a side (an odd size's last is half outside)

// A slice's part of the tile as one lane sees it: the nearest and farthest depth of its pixels in
// the slice (x = 0: none) and (tiles of at most 32 pixels) the tile-local columns and rows they
// cover, one bit each.
struct SlicePart {
    vec2 extent;
    uvec2 columnsRows;
    float beyond;  // the nearest depth of its geometry past the slice (0: none)
};

// `part` widened by the pixels of the 2x2 block at tile-local `local` whose depths lie in
// (lo, hi]: one gather, the pixels past `tileEnd` and the background left out (quadExtent's
// conventions). A block whose geometry all lies in the slice adds its whole rectangle, one across
// a slice boundary only its pixels inside (light_culling.comp's rule).
SlicePart addBlockToSlice(SlicePart part, uvec2 tile, uvec2 local, uvec2 tileEnd, float lo, float hi) {
    uvec2 corner = tile * TILE_SIZE + local;
    if (corner.x >= tileEnd.x || corner.y >= tileEnd.y) return part;
    vec4 quad = textureGather(depthImage, (vec2(corner) + 1.0) * frame.viewport.zw);
    bool right = corner.x + 1u < tileEnd.x;
    bool below = corner.y + 1u < tileEnd.y;
    // Order of the gather: x (0,1), y (1,1), z (1,0), w (0,0) from the corner.
    bvec4 inTile = bvec4(below, right && below, right, true);
    bvec4 geometry = bvec4(inTile.x && !isBackgroundDepth(quad.x), inTile.y && !isBackgroundDepth(quad.y),
                           inTile.z && !isBackgroundDepth(quad.z), inTile.w && !isBackgroundDepth(quad.w));
    bvec4 inside = bvec4(geometry.x && quad.x > lo && quad.x <= hi, geometry.y && quad.y > lo && quad.y <= hi,
                         geometry.z && quad.z > lo && quad.z <= hi, geometry.w && quad.w > lo && quad.w <= hi);
    vec4 past = vec4(geometry.x && quad.x <= lo ? quad.x : 0.0, geometry.y && quad.y <= lo ? quad.y : 0.0,
                     geometry.z && quad.z <= lo ? quad.z : 0.0, geometry.w && quad.w <= lo ? quad.w : 0.0);
    part.beyond = max(part.beyond, max(max(past.x, past.y), max(past.z, past.w)));
    if (!any(inside)) return part;
    const float kNone = 2.0;  // above any depth: min() ignores it
    vec4 nearest = vec4(inside.x ? quad.x : 0.0, inside.y ? quad.y : 0.0, inside.z ? quad.z : 0.0, inside.w ? quad.w : 0.0);
    vec4 farthest = vec4(inside.x ? quad.x : kNone, inside.y ? quad.y : kNone, inside.z ? quad.z : kNone, inside.w ? quad.w : kNone);
    part.extent = vec2(max(part.extent.x, max(max(nearest.x, nearest.y), max(nearest.z, nearest.w))),
                       min(part.extent.y, min(min(farthest.x, farthest.y), min(farthest.z, farthest.w))));
    if (TILE_SIZE <= 32u) {
        bool whole = inside == geometry;
        uvec2 last = local + uvec2(right ? 1u : 0u, below ? 1u : 0u);
        uint columns = whole ? depthMaskBits(local.x, last.x)
                             : ((inside.w || inside.x) ? 1u << local.x : 0u) | ((inside.z || inside.y) ? 1u << (local.x + 1u) : 0u);
        uint rows = whole ? depthMaskBits(local.y, last.y)
                          : ((inside.w || inside.z) ? 1u << local.y : 0u) | ((inside.x || inside.y) ? 1u << (local.y + 1u) : 0u);
        part.columnsRows |= uvec2(columns, rows);
    }
    return part;
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
    vec2 tileMin = min(ndcA, ndcB);
    vec2 tileMax = max(ndcA, ndcB);
    bool spans = frame.transparentSpans != 0u;  // transparent spans: read pixel by pixel

    // 1. The tile's extent.
    vec2 extent = vec2(0.0, 1.0);  // nearest (largest) and farthest (smallest) depth; x = 0: none
    if (!spans) {
        for (uint block = lane; block < kBlocks * kBlocks; block += threads) {
            extent = quadExtent(tile * TILE_SIZE + 2u * uvec2(block % kBlocks, block / kBlocks), tileEnd, extent);
        }
    } else {
        for (uint index = lane; index < TILE_SIZE * TILE_SIZE; index += threads) {
            uvec2 pixel = tile * TILE_SIZE + uvec2(index % TILE_SIZE, index / TILE_SIZE);
            if (pixel.x >= viewport.x || pixel.y >= viewport.y) continue;
            vec2 span = pixelSpan(pixel);
            extent = vec2(max(extent.x, span.x), min(extent.y, span.y));
        }
    }
    extent = workgroupExtent(extent);
    if (extent.x == 0.0) return;  // no geometry: no cell of this tile is read (uniform)
    vec2 toView = frame.depthToView.xy;

    // 2. The occupied slices, nearest first: the nearest depth's, then each time the slice of the
    //    nearest depth past the last one (one search each; slices with no pixel are never read).
    uint slice;
    PUNCTUAL_CLUSTER_SLICE_OF_DEPTH(slice, extent.x, depthRange.sliceStartDepth, SLICE_COUNT);
    uint tileIndex = tile.y * frame.lightGrid.y + tile.x;
    while (true) {
        // Depths inside the slice: (lo, hi]. The first slice has no upper bound, the last none
        // but the background's.
        float hi = slice == 0u ? 2.0 : depthRange.sliceStartDepth[slice];
        float lo = slice + 1u < SLICE_COUNT ? depthRange.sliceStartDepth[slice + 1u] : PUNCTUAL_DEPTH_CLEAR;
        SlicePart part = SlicePart(vec2(0.0, 2.0), uvec2(0u), 0.0);
        if (!spans) {
            for (uint block = lane; block < kBlocks * kBlocks; block += threads) {
                part = addBlockToSlice(part, tile, 2u * uvec2(block % kBlocks, block / kBlocks), tileEnd, lo, hi);
            }
        } else {
            // A span crossing slices gives each its part: from the slice's start (or the span's
            // near end) to the next slice's start (or the span's far end). The rectangle is the
            // whole tile's.
            for (uint index = lane; index < TILE_SIZE * TILE_SIZE; index += threads) {
                uvec2 pixel = tile * TILE_SIZE + uvec2(index % TILE_SIZE, index / TILE_SIZE);
                if (pixel.x >= viewport.x || pixel.y >= viewport.y) continue;
                vec2 span = pixelSpan(pixel);
                if (span.x > lo && span.y <= hi) {
                    part.extent = vec2(max(part.extent.x, min(span.x, hi)), min(part.extent.y, max(span.y, lo)));
                }
                // A span reaching past the slice occupies the next one (depth lo is its start) or,
                // wholly past it, the one of its near end.
                if (span.y <= lo) part.beyond = max(part.beyond, min(span.x, lo));
            }
        }
        // Every slice visited is occupied: the first holds the tile's nearest depth, each next one
        // the nearest depth past the last.
        vec2 sliceExtent = workgroupExtent(part.extent);
        // The rectangle of the slice's pixels (tiles of at most 32 pixels without spans), else the tile.
        vec4 rect = vec4(tileMin, tileMax);
        if (!spans && TILE_SIZE <= 32u) {
            uvec2 columnsRows = workgroupMasks(uvec3(part.columnsRows, 0u)).xy;
            rect = columnsRowsRectNdc(tile * TILE_SIZE, columnsRows.x, columnsRows.y, pixelToNdc);
        }
        TileVolume segment = makeTileVolume(rect.xy, rect.zw, viewDistanceFromDepth(sliceExtent.x, toView),
                                            viewDistanceFromDepth(sliceExtent.y, toView), frame.ndcToView);
        // Only the lights whose depth extent meets the slice's (depth_range.comp) can pass; the
        // masks go three words at a time (subgroup_tiles.glsl).
        uint cellBase = (tileIndex * SLICE_COUNT + slice) * GRID_WORDS;
        if (CANDIDATE_LISTS) {
            clearCellWords(lane, threads);
            uint fill = 0u;
            for (uint first = 0u; first < GRID_WORDS; first += threads) {  // (uniform)
                uint word = first + lane;
                uint bits = word < GRID_WORDS ? candidateWord(tile, COARSE_TILES, word) & sliceLights[slice * GRID_WORDS + word]
                                              : 0u;
                fill = addCandidateWord(fill, word, bits, segment, lane, threads);
            }
            testCandidates(fill, segment, lane, threads);
            writeCellFromWords(tileIndex * SLICE_COUNT + slice, cellBase, lane, threads);
        } else {
            uvec3 cellTriple;  // the last triple of the cell's masks (index lists of one triple: all of them)
            for (uint triple = 0u; triple < (GRID_WORDS + 2u) / 3u; ++triple) {  // (uniform)
                uint word = slice * GRID_WORDS + 3u * triple;
                uvec3 lights = laneCandidates(tile, COARSE_TILES, lane, threads, triple) &
                               uvec3(sliceLights[word], 3u * triple + 1u < GRID_WORDS ? sliceLights[word + 1u] : 0u,
                                     3u * triple + 2u < GRID_WORDS ? sliceLights[word + 2u] : 0u);
                cellTriple = workgroupMasks(lightsMeetingSegment(lights, triple, segment));
                writeCellTriple(cellBase, triple, cellTriple, lane);
            }
            if (INDEX_LISTS) writeCellList(tileIndex * SLICE_COUNT + slice, cellTriple);  // (uniform)
        }
        float beyond = workgroupMax(part.beyond);
        if (beyond == 0.0) break;  // (uniform)
        PUNCTUAL_CLUSTER_SLICE_OF_DEPTH(slice, beyond, depthRange.sliceStartDepth, SLICE_COUNT);
    }
}
