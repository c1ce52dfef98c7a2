#version 450
// Tile culling for the methods with one depth extent per tile: tiled and zbin (culled against the
// tile's depth extent), tiled-2.5d (DEPTH_MASK: that, then Harada's depth mask) and zbin-2d
// (DEPTHLESS_TILES: the tile's whole column, no depth read; its z-bins hold depth). One workgroup
// per screen tile, sized to the device's subgroup (TILE_THREADS): its lanes
//  1. fold the depths of the tile's 2x2 blocks (quadExtent, depth_blocks.glsl) into the nearest
//     and farthest geometry depth, or with transparent spans every pixel's span, and combine them
//     with subgroupMax / subgroupMin;
//  2. build the tile's frustum segment (culling.h), each lane the same one;
//  3. test the lights, each lane its share of the candidates (laneCandidates: the frame's lights,
//     or with the coarse pass its coarse tile's), collecting the passing ones in mask words
//     (culling.h, lightGridWord), three at a time (steps 3-4 loop over the cell's triples);
//  3b. DEPTH_MASK: read the blocks again for the 32 depth cells of the tile's extent that its
//     pixels occupy (each cell with the columns and rows of its blocks, in the lane's registers),
//     then visit the occupied cells nearest first: each gets its frustum segment (cut to its
//     blocks' rectangle, combined over the workgroup) and each lane keeps those of its lights
//     whose depth cells include it and whose shapes meet its segment (until none is left to keep);
//  4. combine the masks with subgroupOr; lanes 0-2 write them (index lists: gather them, and
//     after the last triple the first subgroup writes the tile's list, writeCellList).
// Past the design notes' 96 lights (more than one triple), all but tiled-2.5d do steps 3-4 from
// candidate lists instead (candidate_lists.glsl): the lanes compact the candidates' indices, test
// them every lane-th and set the kept ones' bits in shared memory, which is then written.
// The masks are those of light_culling.comp's one-slice case bit for bit: the same lights are
// tested against the same segments, whose distances come from the same extreme depths, with the
// same cells and rectangles.
//
// Why a kernel of its own: light_culling.comp's 64-invocation workgroups combine through shared
// memory, three barriers and shared atomics per tile, and that fixed cost was most of the pass on
// lavapipe (its workgroups run their subgroups as coroutines switched at every barrier): at
// 1280x720 with no lights, 8.4 ms of shared-memory kernel against 1.4 ms for one subgroup reading
// the same depths (measured, bench/RESULTS.md). One subgroup per tile needs neither, on any device.
// A device whose compute subgroups are smaller than the workgroup (subgroupSize is the default
// size, not a promise) still gets the right masks: the subgroups then combine through shared
// memory (workgroupExtent, workgroupMasks in subgroup_tiles.glsl), behind barriers in uniform
// control flow. Clustered has a kernel of the same kind, cluster_culling.comp. Tiled-2.5d ran the
// shared-memory kernel until it had a path here: 12.5 ms of culling on lavapipe at 1280x720
// (bench/RESULTS.md).
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#include "gpu_types.h"
#include "culling.h"

layout(local_size_x_id = PUNCTUAL_SPEC_TILE_THREADS) in;
layout(constant_id = PUNCTUAL_SPEC_TILE_SIZE) const uint TILE_SIZE = 16u;
// The method's culling flags (culling.h, its table row's cullFlags), as constant bools.
layout(constant_id = PUNCTUAL_SPEC_CULL_FLAGS) const uint CULL_FLAGS = 0u;
const bool DEPTH_MASK = (CULL_FLAGS & PUNCTUAL_CULL_DEPTH_MASK) != 0u;            // tiled-2.5d
const bool DEPTHLESS_TILES = (CULL_FLAGS & PUNCTUAL_CULL_DEPTHLESS_TILES) != 0u;  // zbin-2d
layout(constant_id = PUNCTUAL_SPEC_COARSE_TILES) const uint COARSE_TILES = 0u;  // 0: no coarse pass
layout(constant_id = PUNCTUAL_SPEC_GRID_WORDS) const uint GRID_WORDS = 3u;  // words a light-grid cell

layout(set = 0, binding = PUNCTUAL_BINDING_FRAME) uniform FrameBlock { GpuFrame frame; };
// The lights' view-space culling shapes (makeCullLight in culling.h, made on the CPU).
layout(std430, set = 0, binding = PUNCTUAL_BINDING_CULL_LIGHTS) readonly buffer CullLightBlock { CullLight frameCullLights[]; };
layout(set = 0, binding = PUNCTUAL_BINDING_DEPTH) uniform sampler2D depthImage;
layout(std430, set = 0, binding = PUNCTUAL_BINDING_LIGHT_GRID) writeonly buffer GridBlock { uint lightGrid[]; };
layout(std430, set = 0, binding = PUNCTUAL_BINDING_COARSE_GRID) readonly buffer CoarseGridBlock { uint coarseGrid[]; };
// The transparent surfaces' depth span per pixel (transparent_depth.frag), when the frame has any
// (frame.transparentSpans): nearest transparent depth, then (second half) the farthest.
layout(std430, set = 0, binding = PUNCTUAL_BINDING_TRANSPARENT_DEPTH) readonly buffer TransparentDepthBlock {
    uint transparentDepth[];
};

// Past the design notes' 96 lights a tile's candidates are compacted and tested as a list
// (candidate_lists.glsl); tiled-2.5d's per-cell tests keep the triples.
const bool CANDIDATE_LISTS = GRID_WORDS > 3u && !DEPTH_MASK;

#include "depth_blocks.glsl"
#include "light_lists.glsl"
#include "subgroup_tiles.glsl"

// ---- the steps (main below). Functions cost nothing here: drivers inline them, and none takes an
// array (GLSL copies arrays passed by value: culling.h, PUNCTUAL_CLUSTER_SLICE_OF_DEPTH); the
// 2.5D step's per-block array lives inside its function.

const uint kBlocks = (TILE_SIZE + 1u) / 2u;  // 2x2 blocks a side (an odd size's last is half outside)
// A lane's rounds of blocks in tiles of at most 32 pixels (16 blocks a side, 4 lanes at least).
const uint kMaxBlockRounds = 16u * 16u / 4u;

// 1. This lane's share of the tile's nearest (largest) and farthest (smallest) depth, x = 0 for
//    none: its 2x2 blocks (quadExtent), or with transparent spans (`spans`) its pixels' spans.
vec2 laneDepthExtent(uvec2 tile, uvec2 tileEnd, uvec2 viewport, uint lane, uint threads, bool spans) {
    vec2 extent = vec2(0.0, 1.0);
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
    return extent;
}

// 3b. Tiled-2.5d: of this lane's lights that passed the tile (`masks`, triple `triple`), those
//     whose depth cells meet an occupied cell of the tile's extent `distances` (Harada's depth
//     mask) whose segment their shapes meet (culling.h, makeDepthCellVolume). The cells come from
//     the depths again for each triple with lights left to test (one at the design notes' 96):
//     found once per tile for every triple, they took a private array outside this function,
//     which lavapipe keeps in memory: the pass 12.1 -> 14.5 ms at 1280x720 (A/B, 3 rounds).
//     Called in uniform control flow.
uvec3 lightsMeetingOccupiedCells(uvec3 masks, uint triple, uvec2 tile, uvec2 tileEnd, uvec2 viewport, uint lane, uint threads,
                                 bool spans, vec2 distances, vec2 ndcMin, vec2 ndcMax, vec2 pixelToNdc) {
    float maskNear = distances.x;
    float maskScale = depthMaskScale(distances.x, distances.y);
    // The cells this lane's pixels occupy, and each of its blocks' cells (tiles of at most 32
    // pixels without spans, for the cells' rectangles below). The blocks' array is indexed by
    // the round, the same in every lane: each lane's columns and rows kept per cell, an index
    // differing between lanes, made lavapipe (which runs the lanes as one vector) scatter to
    // memory, 1-1.5 ms more of the pass (A/B, 3 rounds).
    uint laneCells = 0u;
    uint blockCells[kMaxBlockRounds];
    bool rects = !spans && TILE_SIZE <= 32u;
    if (!spans) {
        uint blockRound = 0u;
        for (uint block = lane; block < kBlocks * kBlocks; block += threads, ++blockRound) {
            uint cells = quadDepthCells(tile * TILE_SIZE + 2u * uvec2(block % kBlocks, block / kBlocks), tileEnd, maskNear, maskScale);
            laneCells |= cells;
            if (rects) blockCells[blockRound] = cells;
        }
    } else {
        // A pixel under transparent surfaces occupies every cell from its span's near end to
        // its far end.
        for (uint index = lane; index < TILE_SIZE * TILE_SIZE; index += threads) {
            uvec2 pixel = tile * TILE_SIZE + uvec2(index % TILE_SIZE, index / TILE_SIZE);
            if (pixel.x >= viewport.x || pixel.y >= viewport.y) continue;
            vec2 span = pixelSpan(pixel);
            if (span.x == 0.0) continue;  // background
            laneCells |= depthMaskBits(depthMaskCell(viewDistanceFromDepth(span.x, frame.depthToView.xy), maskNear, maskScale),
                                       depthMaskCell(viewDistanceFromDepth(span.y, frame.depthToView.xy), maskNear, maskScale));
        }
    }
    uint tileCells = workgroupMasks(uvec3(laneCells, 0u, 0u)).x;
    uvec3 unkept = masks;  // this lane's lights that passed the tile and meet no cell yet
    masks = uvec3(0u);
    for (uint cells = tileCells; cells != 0u; cells &= cells - 1u) {  // (uniform)
        uint cell = uint(findLSB(cells));
        // The rectangle of the cell's blocks: each of a block's cells gets the whole block's.
        uvec2 columnsRows = uvec2(0u);
        uint blockRound = 0u;
        for (uint block = lane; rects && block < kBlocks * kBlocks; block += threads, ++blockRound) {
            if ((blockCells[blockRound] & (1u << cell)) == 0u) continue;
            uvec2 local = 2u * uvec2(block % kBlocks, block / kBlocks);  // the block's top-left pixel in the tile
            uvec2 corner = tile * TILE_SIZE + local;
            uvec2 last = local + uvec2(corner.x + 1u < tileEnd.x ? 1u : 0u, corner.y + 1u < tileEnd.y ? 1u : 0u);
            columnsRows |= uvec2(depthMaskBits(local.x, last.x), depthMaskBits(local.y, last.y));
        }
        uvec3 combined = workgroupMasks(uvec3(columnsRows, any(notEqual(unkept, uvec3(0u))) ? 1u : 0u));
        if (combined.z == 0u) break;  // every lane's lights are decided (uniform)
        vec4 rect = rects ? columnsRowsRectNdc(tile * TILE_SIZE, combined.x, combined.y, pixelToNdc)
                          : vec4(ndcMin, ndcMax);
        TileVolume cellSegment = makeDepthCellVolume(rect.xy, rect.zw, cell, maskNear, distances.y, frame.ndcToView);
        uvec3 kept = lightsMeetingDepthCell(unkept, triple, cellSegment, cell, maskNear, maskScale);
        masks |= kept;
        unkept &= ~kept;
    }
    return masks;
}

// Steps 3 to 4 for triple `triple` of the tile's mask words (subgroup_tiles.glsl), in main's
// variables: a macro, so that the one-triple case needs no loop (below).
#define PUNCTUAL_CULL_WORD_TRIPLE(triple)                                                                               \
    {                                                                                                                   \
        /* 3. The lights against the segment: this lane's share of the candidates. */                                  \
        uvec3 masks = occupied ? lightsMeetingSegment(laneCandidates(tile, COARSE_TILES, lane, threads, triple), triple, segment) \
                               : uvec3(0u);                                                                             \
        /* 3b. Tiled-2.5d. (A tile none of whose lights passed reads no depth again.) */                                \
        bool anyPassed = DEPTH_MASK && occupied &&                                                                      \
                         workgroupMasks(uvec3(any(notEqual(masks, uvec3(0u))) ? 1u : 0u, 0u, 0u)).x != 0u;              \
        if (anyPassed) { /* (uniform) */                                                                                \
            masks = lightsMeetingOccupiedCells(masks, triple, tile, tileEnd, viewport, lane, threads, spans, distances, \
                                               ndcMin, ndcMax, pixelToNdc);                                             \
        }                                                                                                               \
        /* 4. The tile's cell, always written (an empty tile's masks are zero). */                                      \
        cellTriple = workgroupMasks(masks);                                                                             \
        writeCellTriple(cellBase, triple, cellTriple, lane);                                                            \
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
    vec2 ndcMin = min(ndcA, ndcB);
    vec2 ndcMax = max(ndcA, ndcB);

    // 1-2. The tile's segment: its depth extent, or (DEPTHLESS_TILES) its whole column.
    TileVolume segment;
    bool occupied = true;
    bool spans = frame.transparentSpans != 0u;  // transparent spans: read pixel by pixel
    vec2 distances = vec2(0.0);  // the tile's nearest and farthest view distance
    if (DEPTHLESS_TILES) {
        segment = makeTileColumn(ndcMin, ndcMax, frame.depthToView.xy, frame.ndcToView);
    } else {
        vec2 extent = workgroupExtent(laneDepthExtent(tile, tileEnd, viewport, lane, threads, spans));
        occupied = extent.x > 0.0;
        // View distance falls monotonically with depth, also as rounded (viewDistanceFromDepth), so
        // the extreme depths give exactly the extreme distances.
        distances = vec2(viewDistanceFromDepth(extent.x, frame.depthToView.xy), viewDistanceFromDepth(extent.y, frame.depthToView.xy));
        segment = makeTileVolume(ndcMin, ndcMax, distances.x, distances.y, frame.ndcToView);
    }

    uint tileIndex = tile.y * frame.lightGrid.y + tile.x;
    uint cellBase = tileIndex * GRID_WORDS;
    if (CANDIDATE_LISTS) {
        // 3-4. The candidates, compacted and tested as a list; the tile's cell from their bits.
        clearCellWords(lane, threads);
        uint fill = 0u;
        for (uint first = 0u; occupied && first < GRID_WORDS; first += threads) {  // (uniform)
            uint word = first + lane;
            fill = addCandidateWord(fill, word, candidateWord(tile, COARSE_TILES, word), segment, lane, threads);
        }
        testCandidates(fill, segment, lane, threads);
        writeCellFromWords(tileIndex, cellBase, lane, threads);
        return;
    }
    uvec3 cellTriple;  // the last triple of the tile's masks (index lists of one triple: all of them)
    if (GRID_WORDS <= 3u) {
        // Up to the design notes' 96 lights: one triple, with no loop around it (measured on
        // lavapipe: the one-trip loop cost tiled-2.5d's pass 20%, 12.1 -> 14.7 ms at 1280x720).
        PUNCTUAL_CULL_WORD_TRIPLE(0u)
    } else {
        for (uint triple = 0u; triple < (GRID_WORDS + 2u) / 3u; ++triple) PUNCTUAL_CULL_WORD_TRIPLE(triple)  // (uniform)
    }
    if (INDEX_LISTS) writeCellList(tileIndex, cellTriple);  // (uniform)
}
