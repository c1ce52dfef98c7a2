#version 450
// Tiled and clustered light culling. One workgroup per screen tile:
//  1. every pixel of the tile reads the prepass depth; pixels with geometry record their view
//     distance into the min/max of their depth slice (shared atomics). Tiled culling is the case
//     SLICE_COUNT = 1: one slice spanning the tile's own min..max depth. A pixel with transparent
//     surfaces in front records its whole depth span, into every slice the span crosses.
//  2. the occupied slices are listed, each with its frustum segment bounded by the distances of
//     the pixels really in it and, for tiles of up to 32 pixels without transparent spans, by the
//     rectangle of their columns and rows (computed once per slice, not per light);
//  3. each (occupied slice, light) pair is tested: the light's conservative shapes against the
//     segment (for the lights whose depth extent meets the tile's). Empty slices test nothing, and
//     a light reaching only the foreground of a tile never lands in a slice that holds only
//     background.
//  4. the masks (one bit per light, culling.h) of every occupied slice are written out.
// Steps 3-4 take the lights a chunk at a time (up to 8 mask words, 256 lights), so that shared
// memory holds one chunk's lights whatever the capacity; at the design notes' 96 the one chunk is
// all of them. Index lists (light_lists.glsl): a cell's list needs its count before its first
// entry, so with several chunks steps 3-4 run twice, the first time counting each cell's lights
// (then each list's words are claimed), the second writing them; with one chunk, once.
// Tiled with DEPTH_MASK (--culling tiled-2.5d) adds Harada's 2.5D test to step 3: the tile's
// 32-cell depth mask (culling.h) is built from its pixels once their min..max extent is known,
// and a light that passed the tile test is kept only if its depth cells meet an occupied one
// whose frustum segment its shapes meet (culling.h, makeDepthCellVolume), each cell's segment cut
// to the rectangle of its pixels as the slices' are.
// DEPTHLESS_TILES (--culling zbin-2d): the tile's mask is two-dimensional, every light that meets
// the tile's side planes anywhere between the near and far planes, and no depth is read at all:
// the z-bins (lights/z_bins.h, built on the CPU) hold depth, and forward.frag ANDs the two masks.
// (--culling zbin builds its tile masks as tiled does, within the tile's depth extent.)
// Tiled, tiled-2.5d, zbin and zbin-2d run tile_culling.comp instead, clustered cluster_culling.comp
// (one subgroup a tile, no shared-memory atomics) where the device has compute subgroup
// arithmetic; this kernel serves them on devices without it and with --subgroup-tiles off, and
// writes the same masks (tests/gpu/test_culling.cpp).
// COARSE_TILES > 0: the coarse pass (coarse_culling.comp) has culled the lights to this tile's
// big tile, and steps 1-3 test only those (the candidates), listed while the depths are read.
#extension GL_GOOGLE_include_directive : require
#include "gpu_types.h"
#include "culling.h"

// TILE_THREADS invocations a tile, the device's subgroup size (at most 64): each folds the depths of
// every TILE_THREADS-th 2x2 block in registers and touches shared memory only when its slice
// changes, which keeps the shared atomics (the cost that dominates this pass on CPU drivers) few.
// One subgroup a workgroup also makes the barriers cheap where they cost most: lavapipe runs a
// workgroup's subgroups as coroutines switched at every barrier, and 64 invocations (8 of its
// subgroups) took the clustered pass 34.9 ms at 1280x720, one subgroup 20.2 (A/B, bench/RESULTS.md).
layout(local_size_x_id = PUNCTUAL_SPEC_TILE_THREADS) in;
layout(constant_id = PUNCTUAL_SPEC_TILE_SIZE) const uint TILE_SIZE = 16u;
layout(constant_id = PUNCTUAL_SPEC_SLICE_COUNT) const uint SLICE_COUNT = 1u;
// The method's culling flags (culling.h, its table row's cullFlags), as constant bools.
layout(constant_id = PUNCTUAL_SPEC_CULL_FLAGS) const uint CULL_FLAGS = 0u;
const bool DEPTH_MASK = (CULL_FLAGS & PUNCTUAL_CULL_DEPTH_MASK) != 0u;            // tiled-2.5d
const bool DEPTHLESS_TILES = (CULL_FLAGS & PUNCTUAL_CULL_DEPTHLESS_TILES) != 0u;  // zbin-2d
layout(constant_id = PUNCTUAL_SPEC_COARSE_TILES) const uint COARSE_TILES = 0u;  // 0: no coarse pass
layout(constant_id = PUNCTUAL_SPEC_GRID_WORDS) const uint GRID_WORDS = 3u;  // words a light-grid cell
// A chunk's words and lights. 8 words: the chunk's culling shapes take 12 KiB of shared memory, the
// whole kernel about 22 KiB with 32 slices (GPUs give 32-64 KiB; Vulkan promises 16).
const uint kChunkWords = GRID_WORDS < 8u ? GRID_WORDS : 8u;
const uint kChunkLights = 32u * kChunkWords;

layout(set = 0, binding = PUNCTUAL_BINDING_FRAME) uniform FrameBlock { GpuFrame frame; };
// The lights' view-space culling shapes, made once per frame on the CPU (makeCullLight in
// culling.h) rather than by every workgroup.
layout(std430, set = 0, binding = PUNCTUAL_BINDING_CULL_LIGHTS) readonly buffer CullLightBlock { CullLight frameCullLights[]; };
layout(set = 0, binding = PUNCTUAL_BINDING_DEPTH) uniform sampler2D depthImage;
layout(std430, set = 0, binding = PUNCTUAL_BINDING_LIGHT_GRID) writeonly buffer GridBlock { uint lightGrid[]; };
layout(std430, set = 0, binding = PUNCTUAL_BINDING_COARSE_GRID) readonly buffer CoarseGridBlock { uint coarseGrid[]; };
layout(std430, set = 0, binding = PUNCTUAL_BINDING_DEPTH_RANGE) readonly buffer DepthRangeBlock { GpuDepthRange depthRange; };  // (its slices' lights unread here)
// The transparent surfaces' depth span per pixel (transparent_depth.frag), when the frame has
// any (frame.transparentSpans): a pixel then shades every depth from its opaque surface (or, over
// the background, its farthest transparent one) to its nearest transparent one.
layout(std430, set = 0, binding = PUNCTUAL_BINDING_TRANSPARENT_DEPTH) readonly buffer TransparentDepthBlock {
    uint transparentDepth[];
};

#include "depth_blocks.glsl"
#include "light_lists.glsl"

const uint kThreads = gl_WorkGroupSize.x;

shared uint sliceMinDistance[SLICE_COUNT];  // float bits of view distances (positive: bits sort like values)
shared uint sliceMaxDistance[SLICE_COUNT];
// Clustered and tiled-2.5d, tiles of at most 32 pixels, no transparent spans: the columns and rows
// of the tile (bit i: the tile's pixel column or row i) where each slice (clustered) or depth cell
// (tiled-2.5d) has pixels. Its frustum segment then spans only that rectangle of the tile: a slice
// or cell holding an object's edge is a sliver.
const uint kRectCells = DEPTH_MASK ? PUNCTUAL_DEPTH_MASK_CELLS : SLICE_COUNT;
shared uint cellColumns[kRectCells];
shared uint cellRows[kRectCells];
shared uint sliceMasks[SLICE_COUNT * kChunkWords];  // the chunk's words of each slice's masks
shared uint candidateCount;  // COARSE_TILES: the chunk's lights of this tile's coarse tile
shared uint candidateLights[kChunkLights];
shared float sliceStart[SLICE_COUNT];  // copy of depthRange.sliceStartDepth for the pixel loop
shared uint occupiedCount;
shared uint tileLightCount;  // lights passing the whole-tile step (clustered: its depth; tested per slice)
shared uint tileLights[kChunkLights];
// Clustered: the shapes of the lights whose depth extent meets the tile's, read again per slice.
// (Tiled reads each light once, straight from the buffer.)
shared CullLight tileLightShapes[kChunkLights];
shared TileVolume tileVolume;
shared uint tileMinDistance;  // float bits: the extent of all the tile's pixels
shared uint tileMaxDistance;
shared uint occupiedSlices[SLICE_COUNT];
shared TileVolume occupiedVolumes[SLICE_COUNT];
shared uint tileDepthMask;  // DEPTH_MASK: the occupied cells of the tile's depth extent
// Index lists, per written cell (a list slot: tiled's one cell, clustered's occupied slices in
// occupiedSlices order), each kept by one thread: the cell's lights counted so far, its list's
// start, the entries written and the last of them.
const uint kListSlots = INDEX_LISTS ? SLICE_COUNT : 1u;
shared uint slotCount[kListSlots];
shared uint slotStart[kListSlots];
shared uint slotWritten[kListSlots];
shared uint slotLast[kListSlots];
shared TileVolume cellVolumes[DEPTH_MASK ? PUNCTUAL_DEPTH_MASK_CELLS : 1u];  // DEPTH_MASK: each cell's segment

// The chunk of lights steps 3-4 take: its first mask word, and its words (kChunkWords, fewer in
// the last chunk).
uint chunkFirstWord = 0u;
uint chunkWords = kChunkWords;

// Marks packed light `light` (of the chunk) in the masks of `slice` (culling.h, lightGridWord).
void setLightBit(uint slice, uint light) {
    uint word = lightGridWord(light) - chunkFirstWord;
    atomicOr(sliceMasks[slice * kChunkWords + word], 1u << lightGridBit(light));
}

// Pixels read four at a time: a 2x2 block per gather (quadExtent, depth_blocks.glsl).
const uint kBlocks = (TILE_SIZE + 1u) / 2u;  // blocks a side of a tile (an odd size's last is half outside)

// A thread's run of pixels in one slice: their distances' extent and (tiles of at most 32 pixels)
// the columns and rows they cover, kept in registers and flushed to shared memory when the slice
// changes (the shared atomics are per run, not per block).
struct SliceRun {
    uint slice;  // 0xFFFFFFFF: no run yet
    uint minBits;
    uint maxBits;
    uint columns;
    uint rows;
};

void flushSliceRun(SliceRun run) {
    if (run.slice == 0xFFFFFFFFu) return;
    atomicMin(sliceMinDistance[run.slice], run.minBits);
    atomicMax(sliceMaxDistance[run.slice], run.maxBits);
    if (TILE_SIZE <= 32u) {
        atomicOr(cellColumns[run.slice], run.columns);
        atomicOr(cellRows[run.slice], run.rows);
    }
}

// The run extended by pixels of `slice` at distances [minBits, maxBits] covering tile-local
// columns first.x .. last.x and rows first.y .. last.y, or flushed and restarted with them.
SliceRun addToSliceRun(SliceRun run, uint slice, uint minBits, uint maxBits, uvec2 first, uvec2 last) {
    uint columns = TILE_SIZE <= 32u ? depthMaskBits(first.x, last.x) : 0u;
    uint rows = TILE_SIZE <= 32u ? depthMaskBits(first.y, last.y) : 0u;
    if (slice == run.slice) {
        return SliceRun(slice, min(run.minBits, minBits), max(run.maxBits, maxBits), run.columns | columns, run.rows | rows);
    }
    flushSliceRun(run);
    return SliceRun(slice, minBits, maxBits, columns, rows);
}

// Marks the tile-local pixel columns first.x .. last.x and rows first.y .. last.y as holding
// pixels of slice or depth cell `cell` (cellColumns, cellRows; tiles of at most 32 pixels).
void markCellRect(uint cell, uvec2 first, uvec2 last) {
    if (TILE_SIZE > 32u) return;
    atomicOr(cellColumns[cell], depthMaskBits(first.x, last.x));
    atomicOr(cellRows[cell], depthMaskBits(first.y, last.y));
}

// The NDC rectangle (min corner in xy, max corner in zw) of cell `cell`'s marked pixels, from its
// first column's left edge to its last column's right edge, cut at the viewport.
vec4 cellRectNdc(uvec2 tile, uint cell, vec2 pixelToNdc) {
    return columnsRowsRectNdc(tile * TILE_SIZE, cellColumns[cell], cellRows[cell], pixelToNdc);
}

// One pixel at `depth` (tile-local position `local`) into the run, in its slice (the search
// forward.frag makes); background pixels add nothing.
SliceRun addPixelToSliceRun(SliceRun run, float depth, uvec2 local) {
    if (isBackgroundDepth(depth)) return run;
    uint slice;
    PUNCTUAL_CLUSTER_SLICE_OF_DEPTH(slice, depth, sliceStart, SLICE_COUNT);
    uint bits = floatBitsToUint(viewDistanceFromDepth(depth, frame.depthToView.xy));
    return addToSliceRun(run, slice, bits, bits, local, local);
}

// ---- the steps, in order (main below). Each runs on every invocation of the workgroup, striding
// over its items; main puts the barriers between them. Functions cost nothing here: every driver
// inlines them, and none takes an array (GLSL copies arrays passed by value: culling.h,
// PUNCTUAL_CLUSTER_SLICE_OF_DEPTH). Measured on lavapipe against the one long main: no change
// (bench/RESULTS.md, "Every variant from one table, second part").

// The chunk's shared state, cleared.
void clearChunkState(uint thread) {
    for (uint i = thread; i < SLICE_COUNT * kChunkWords; i += kThreads) sliceMasks[i] = 0u;
    if (thread == 0u) {
        tileLightCount = 0u;
        candidateCount = 0u;
    }
}

// The tile's shared state, cleared.
void clearTileState(uint thread) {
    for (uint i = thread; i < SLICE_COUNT; i += kThreads) {
        sliceMinDistance[i] = 0x7F7FFFFFu;  // FLT_MAX
        sliceMaxDistance[i] = 0u;
    }
    for (uint i = thread; i < kRectCells; i += kThreads) {
        cellColumns[i] = 0u;
        cellRows[i] = 0u;
    }
    for (uint i = thread; i < SLICE_COUNT; i += kThreads) sliceStart[i] = depthRange.sliceStartDepth[i];
    for (uint i = thread; i < kListSlots; i += kThreads) {
        slotCount[i] = 0u;
        slotWritten[i] = 0u;
    }
    if (thread == 0u) {
        occupiedCount = 0u;
        tileMinDistance = 0x7F7FFFFFu;
        tileMaxDistance = 0u;
        tileDepthMask = 0u;
    }
    clearChunkState(thread);
}

// 0. The candidates: the chunk's lights the coarse pass kept for this tile's coarse tile (in any
//    order: the masks this kernel writes do not depend on it).
void listCandidates(uvec2 tile, uint thread, uint lightCount) {
    uvec2 coarseTile = tile / COARSE_TILES;
    uint coarseTilesAcross = (frame.lightGrid.y + COARSE_TILES - 1u) / COARSE_TILES;
    uint coarseBase = (coarseTile.y * coarseTilesAcross + coarseTile.x) * GRID_WORDS;
    uint chunkEnd = min(lightCount, lightGridFirstLight(chunkFirstWord + chunkWords));
    for (uint light = lightGridFirstLight(chunkFirstWord) + thread; light < chunkEnd; light += kThreads) {
        if ((coarseGrid[coarseBase + lightGridWord(light)] & (1u << lightGridBit(light))) != 0u) {
            candidateLights[atomicAdd(candidateCount, 1u)] = light;
        }
    }
}

// 1, tiled without transparent spans (the common case): the tile's nearest and farthest depths,
// folded first and divided once: view distance falls monotonically with depth, also as rounded
// (viewDistanceFromDepth), so the extreme depths give exactly the extreme distances. It reads the
// depths four at a time, a 2x2 block per gather (quadExtent). Measured on lavapipe at 1280x720
// with no lights: 27 ms before, 10 ms after.
void foldTileExtent(uvec2 tile, uvec2 tileEnd, uint thread) {
    vec2 extent = vec2(0.0, 1.0);  // nearest (largest) and farthest (smallest) geometry depth; x = 0: none
    for (uint block = thread; block < kBlocks * kBlocks; block += kThreads) {
        extent = quadExtent(tile * TILE_SIZE + 2u * uvec2(block % kBlocks, block / kBlocks), tileEnd, extent);
    }
    if (extent.x > 0.0) {
        atomicMin(sliceMinDistance[0], floatBitsToUint(viewDistanceFromDepth(extent.x, frame.depthToView.xy)));
        atomicMax(sliceMaxDistance[0], floatBitsToUint(viewDistanceFromDepth(extent.y, frame.depthToView.xy)));
    }
}

// 1, clustered without transparent spans: 2x2 blocks too. A block whose nearest and farthest
// depths fall in one slice (slices are monotone in depth, so all four do) adds its extreme
// distances to that slice with two searches and two divisions instead of four each; a block
// across a slice boundary adds its pixels one by one. (Measured on lavapipe, default scene at
// 1280x720: the clustered culling pass 13% faster, A/B under load.) `threadMin`/`threadMax`: the
// extent of this invocation's pixels (the tile-level test).
void addClusterBlocks(uvec2 tile, uvec2 tileEnd, uint thread, inout uint threadMin, inout uint threadMax) {
    SliceRun run = SliceRun(0xFFFFFFFFu, 0xFFFFFFFFu, 0u, 0u, 0u);
    for (uint block = thread; block < kBlocks * kBlocks; block += kThreads) {
        uvec2 local = 2u * uvec2(block % kBlocks, block / kBlocks);  // the block's top-left pixel in the tile
        uvec2 corner = tile * TILE_SIZE + local;
        vec2 extent = quadExtent(corner, tileEnd, vec2(0.0, 1.0));
        if (extent.x == 0.0) continue;  // background only, or past the viewport
        uint nearSlice, farSlice;
        PUNCTUAL_CLUSTER_SLICE_OF_DEPTH(nearSlice, extent.x, sliceStart, SLICE_COUNT);
        PUNCTUAL_CLUSTER_SLICE_OF_DEPTH(farSlice, extent.y, sliceStart, SLICE_COUNT);
        uint nearBits = floatBitsToUint(viewDistanceFromDepth(extent.x, frame.depthToView.xy));
        uint farBits = floatBitsToUint(viewDistanceFromDepth(extent.y, frame.depthToView.xy));
        threadMin = min(threadMin, nearBits);
        threadMax = max(threadMax, farBits);
        bool right = corner.x + 1u < tileEnd.x;
        bool below = corner.y + 1u < tileEnd.y;
        if (nearSlice == farSlice) {
            // (The whole block: a background pixel in it only widens the rectangle.)
            run = addToSliceRun(run, nearSlice, nearBits, farBits, local, local + uvec2(right ? 1u : 0u, below ? 1u : 0u));
            continue;
        }
        vec4 quad = textureGather(depthImage, (vec2(corner) + 1.0) * frame.viewport.zw);
        run = addPixelToSliceRun(run, quad.w, local);
        if (right) run = addPixelToSliceRun(run, quad.z, local + uvec2(1u, 0u));
        if (below) run = addPixelToSliceRun(run, quad.x, local + uvec2(0u, 1u));
        if (right && below) run = addPixelToSliceRun(run, quad.y, local + uvec2(1u, 1u));
    }
    flushSliceRun(run);
}

// 1, frames with transparent spans: pixel by pixel. A pixel with transparent surfaces in front
// adds its whole depth span to every slice the span crosses.
void addPixels(uvec2 tile, uvec2 viewport, uint thread, inout uint threadMin, inout uint threadMax) {
    uint runSlice = 0xFFFFFFFFu;  // the slice of the current run of this thread's pixels
    uint runMin = 0xFFFFFFFFu;
    uint runMax = 0u;
    for (uint tilePixel = thread; tilePixel < TILE_SIZE * TILE_SIZE; tilePixel += kThreads) {
        uvec2 pixel = tile * TILE_SIZE + uvec2(tilePixel % TILE_SIZE, tilePixel / TILE_SIZE);
        if (pixel.x >= viewport.x || pixel.y >= viewport.y) continue;
        float depth = texelFetch(depthImage, ivec2(pixel), 0).r;
        if (frame.transparentSpans != 0u) {
            uint index = pixel.y * viewport.x + pixel.x;
            uint nearestBits = transparentDepth[index];
            if (nearestBits != 0u) {
                float nearest = uintBitsToFloat(nearestBits);
                float farthest = isBackgroundDepth(depth) ? uintBitsToFloat(transparentDepth[viewport.x * viewport.y + index])
                                                          : depth;
                uint nearSlice, farSlice;
                PUNCTUAL_CLUSTER_SLICE_OF_DEPTH(nearSlice, nearest, sliceStart, SLICE_COUNT);
                PUNCTUAL_CLUSTER_SLICE_OF_DEPTH(farSlice, farthest, sliceStart, SLICE_COUNT);
                // Each crossed slice gets the part of the span inside it: from its start (or the
                // span's near end) to the next slice's start (or the span's far end).
                for (uint slice = nearSlice; slice <= farSlice; ++slice) {
                    float top = slice == nearSlice ? nearest : sliceStart[slice];
                    float bottom = slice == farSlice ? farthest : sliceStart[slice + 1u];
                    atomicMin(sliceMinDistance[slice], floatBitsToUint(viewDistanceFromDepth(top, frame.depthToView.xy)));
                    atomicMax(sliceMaxDistance[slice], floatBitsToUint(viewDistanceFromDepth(bottom, frame.depthToView.xy)));
                }
                threadMin = min(threadMin, floatBitsToUint(viewDistanceFromDepth(nearest, frame.depthToView.xy)));
                threadMax = max(threadMax, floatBitsToUint(viewDistanceFromDepth(farthest, frame.depthToView.xy)));
                continue;
            }
        }
        if (isBackgroundDepth(depth)) continue;  // nothing to shade
        // The pixel's slice: the same search as pixelGridCell() in forward.frag (culling.h),
        // so both pick the same slice.
        uint slice;
        PUNCTUAL_CLUSTER_SLICE_OF_DEPTH(slice, depth, sliceStart, SLICE_COUNT);
        uint distanceBits = floatBitsToUint(viewDistanceFromDepth(depth, frame.depthToView.xy));
        threadMin = min(threadMin, distanceBits);
        threadMax = max(threadMax, distanceBits);
        if (slice != runSlice) {
            if (runSlice != 0xFFFFFFFFu) {
                atomicMin(sliceMinDistance[runSlice], runMin);
                atomicMax(sliceMaxDistance[runSlice], runMax);
            }
            runSlice = slice;
            runMin = distanceBits;
            runMax = distanceBits;
        } else {
            runMin = min(runMin, distanceBits);
            runMax = max(runMax, distanceBits);
        }
    }
    if (runSlice != 0xFFFFFFFFu) {
        atomicMin(sliceMinDistance[runSlice], runMin);
        atomicMax(sliceMaxDistance[runSlice], runMax);
    }
}

// 1b, DEPTH_MASK: the cells of the tile's extent [maskNear, maskNear + 32 / maskScale] that its
// pixels occupy, each pixel (or a transparent span, every cell from its near to its far end) read
// again now that the extent is known. The same distances as step 1, so every pixel lies inside
// the extent. Blocks mark each of their cells' rectangles (folded tiles).
void markOccupiedCells(uvec2 tile, uvec2 tileEnd, uvec2 viewport, uint thread, bool foldDepths, float maskNear,
                       float maskScale) {
    uint threadMask = 0u;
    for (uint block = thread; foldDepths && block < kBlocks * kBlocks; block += kThreads) {
        uvec2 local = 2u * uvec2(block % kBlocks, block / kBlocks);  // the block's top-left pixel in the tile
        uvec2 corner = tile * TILE_SIZE + local;
        uint cells = quadDepthCells(corner, tileEnd, maskNear, maskScale);
        threadMask |= cells;
        // Each of the block's cells gets the whole block's rectangle.
        uvec2 last = local + uvec2(corner.x + 1u < tileEnd.x ? 1u : 0u, corner.y + 1u < tileEnd.y ? 1u : 0u);
        for (; cells != 0u; cells &= cells - 1u) markCellRect(uint(findLSB(cells)), local, last);
    }
    for (uint tilePixel = thread; !foldDepths && tilePixel < TILE_SIZE * TILE_SIZE; tilePixel += kThreads) {
        uvec2 pixel = tile * TILE_SIZE + uvec2(tilePixel % TILE_SIZE, tilePixel / TILE_SIZE);
        if (pixel.x >= viewport.x || pixel.y >= viewport.y) continue;
        float depth = texelFetch(depthImage, ivec2(pixel), 0).r;
        if (frame.transparentSpans != 0u) {
            uint index = pixel.y * viewport.x + pixel.x;
            uint nearestBits = transparentDepth[index];
            if (nearestBits != 0u) {
                float farthest = isBackgroundDepth(depth) ? uintBitsToFloat(transparentDepth[viewport.x * viewport.y + index])
                                                          : depth;
                float top = viewDistanceFromDepth(uintBitsToFloat(nearestBits), frame.depthToView.xy);
                float bottom = viewDistanceFromDepth(farthest, frame.depthToView.xy);
                threadMask |= depthMaskBits(depthMaskCell(top, maskNear, maskScale),
                                            depthMaskCell(bottom, maskNear, maskScale));
                continue;
            }
        }
        if (isBackgroundDepth(depth)) continue;
        threadMask |= 1u << depthMaskCell(viewDistanceFromDepth(depth, frame.depthToView.xy), maskNear, maskScale);
    }
    if (threadMask != 0u) atomicOr(tileDepthMask, threadMask);
}

// 1b, DEPTH_MASK: each occupied cell's frustum segment, for step 3's per-cell tests: the rectangle
// of the cell's pixels where marked, else the whole tile ([ndcMin, ndcMax]).
void makeCellVolumes(uvec2 tile, uint thread, bool foldDepths, float maskNear, vec2 ndcMin, vec2 ndcMax,
                     vec2 pixelToNdc) {
    for (uint cell = thread; cell < PUNCTUAL_DEPTH_MASK_CELLS; cell += kThreads) {
        if ((tileDepthMask & (1u << cell)) == 0u) continue;  // an unoccupied cell is never tested
        bool marked = foldDepths && TILE_SIZE <= 32u && cellColumns[cell] != 0u;
        vec4 rect = marked ? cellRectNdc(tile, cell, pixelToNdc) : vec4(ndcMin, ndcMax);
        cellVolumes[cell] = makeDepthCellVolume(rect.xy, rect.zw, cell, maskNear, uintBitsToFloat(sliceMaxDistance[0]),
                                                frame.ndcToView);
    }
}

// 2, clustered: lists the occupied slices with their frustum segments (each cut to the rectangle
// of its pixels where marked, else the whole tile [ndcMin, ndcMax]), and the whole tile's.
void listOccupiedSlices(uvec2 tile, uint thread, bool clusterBlocks, vec2 ndcMin, vec2 ndcMax, vec2 pixelToNdc) {
    for (uint slice = thread; slice < SLICE_COUNT; slice += kThreads) {
        if (sliceMaxDistance[slice] == 0u) continue;  // no pixel in this slice
        uint index = atomicAdd(occupiedCount, 1u);
        occupiedSlices[index] = slice;
        vec4 rect = clusterBlocks && TILE_SIZE <= 32u ? cellRectNdc(tile, slice, pixelToNdc) : vec4(ndcMin, ndcMax);
        occupiedVolumes[index] = makeTileVolume(rect.xy, rect.zw, uintBitsToFloat(sliceMinDistance[slice]),
                                                uintBitsToFloat(sliceMaxDistance[slice]), frame.ndcToView);
    }
    if (thread == 0u && tileMaxDistance != 0u) {
        tileVolume = makeTileVolume(ndcMin, ndcMax, uintBitsToFloat(tileMinDistance), uintBitsToFloat(tileMaxDistance),
                                    frame.ndcToView);
    }
}

// 3. Every candidate light against the tile's whole depth extent, `wholeTile` (for tiled, the only
//    test; tiled-2.5d then asks for an occupied depth cell the light meets). For clustered, a
//    light is kept where it meets an occupied slice's segment, each tested in testSlices; here
//    only the lights whose depth extent meets the tile's are listed for them (the rest would fail
//    every slice's test at its first step, lightDepthMeetsSegment).
void testCandidates(uint thread, uint lightCount, TileVolume wholeTile, float maskNear, float maskScale) {
    uint firstLight = lightGridFirstLight(chunkFirstWord);
    uint candidates = COARSE_TILES > 0u ? candidateCount : min(lightCount - firstLight, 32u * chunkWords);
    for (uint k = thread; k < candidates; k += kThreads) {
        uint light = COARSE_TILES > 0u ? candidateLights[k] : firstLight + k;
        CullLight shape = frameCullLights[light];
        if (SLICE_COUNT == 1u ? !lightMayTouchTile(shape, wholeTile) : !lightDepthMeetsSegment(lightDistanceExtent(shape), wholeTile)) {
            continue;
        }
        if (DEPTH_MASK && SLICE_COUNT == 1u) {
            // Harada's test, then the light's own shapes against each occupied cell it spans.
            uint cells = lightDepthMask(shape, maskNear, maskScale) & tileDepthMask;
            bool meets = false;
            while (cells != 0u && !meets) {
                uint cell = uint(findLSB(cells));
                cells &= cells - 1u;
                meets = lightMayTouchTile(shape, cellVolumes[cell]);
            }
            if (!meets) continue;
        }
        if (SLICE_COUNT == 1u) {
            setLightBit(0u, light);
        } else {
            uint index = atomicAdd(tileLightCount, 1u);
            tileLights[index] = light;
            tileLightShapes[index] = shape;
        }
    }
}

// 3, clustered: each (occupied slice, listed light) pair.
void testSlices(uint thread) {
    for (uint job = thread; job < occupiedCount * tileLightCount; job += kThreads) {
        uint index = job / tileLightCount;
        uint passed = job - index * tileLightCount;
        if (lightMayTouchTile(tileLightShapes[passed], occupiedVolumes[index])) {
            setLightBit(occupiedSlices[index], tileLights[passed]);
        }
    }
}

// 4. The chunk's words of this tile's cells: cell = tile index * SLICE_COUNT + slice. Only
//    occupied cells: a pixel only ever reads the cell of its own slice, which its depth occupies,
//    so the other cells are never read and need no clearing. (Tiled: the one cell, always.)
void writeTileCells(uvec2 tile, uint thread) {
    uint tileIndex = tile.y * frame.lightGrid.y + tile.x;
    if (SLICE_COUNT == 1u) {
        for (uint word = thread; word < chunkWords; word += kThreads) {
            lightGrid[tileIndex * GRID_WORDS + chunkFirstWord + word] = sliceMasks[word];
        }
    } else {
        for (uint i = thread; i < occupiedCount * chunkWords; i += kThreads) {
            uint slice = occupiedSlices[i / chunkWords];
            uint word = i % chunkWords;
            lightGrid[(tileIndex * SLICE_COUNT + slice) * GRID_WORDS + chunkFirstWord + word] = sliceMasks[slice * kChunkWords + word];
        }
    }
}

// 4, index lists: the chunk's words of each list slot's cell (the slice of tiled's one slot is 0),
//    each slot by one thread, the same every chunk and pass. `counting`: the chunk's lights are
//    added to the cell's count, and after the last chunk (`lastChunk`) its list's words are claimed
//    and its header written; `writing`: the chunk's lights are written into its list, in order.
//    (One pass with one chunk does all three.) Serial per cell: the fallback kernel's lists are a
//    matter of correctness, not speed.
void writeTileLists(uvec2 tile, uint thread, bool counting, bool lastChunk, bool writing) {
    uint tileIndex = tile.y * frame.lightGrid.y + tile.x;
    uint slots = SLICE_COUNT == 1u ? 1u : occupiedCount;
    for (uint slot = thread; slot < slots; slot += kThreads) {
        uint slice = SLICE_COUNT == 1u ? 0u : occupiedSlices[slot];
        if (counting) {
            uint count = slotCount[slot];
            for (uint word = 0u; word < chunkWords; ++word) count += bitCount(sliceMasks[slice * kChunkWords + word]);
            slotCount[slot] = count;
            if (lastChunk) {
                slotStart[slot] = claimLightList(count);
                slotLast[slot] = count;  // entry 0
                lightGrid[tileIndex * SLICE_COUNT + slice] = slotStart[slot];
            }
        }
        uint start = slotStart[slot];
        if (!writing || start >= PUNCTUAL_LIGHT_LIST_OVERFLOW) continue;
        uint entry = slotWritten[slot];
        uint last = slotLast[slot];
        for (uint word = 0u; word < chunkWords; ++word) {
            for (uint bits = sliceMasks[slice * kChunkWords + word]; bits != 0u; bits &= bits - 1u) {
                uint light = lightGridFirstLight(chunkFirstWord + word) + uint(findLSB(bits));
                writeLightListEntry(start, ++entry, last, light, slotCount[slot]);
                last = light;
            }
        }
        slotWritten[slot] = entry;
        slotLast[slot] = last;
    }
}

// Steps 3-4 over the lights, a chunk at a time; with index lists over several chunks, a counting
// pass, then a writing pass (see the top). The first chunk's state was cleared, and its candidates
// listed, with the depths. Called in uniform control flow (barriers).
void cullChunks(uvec2 tile, uint thread, uint lightCount, bool occupied, TileVolume wholeTile, float maskNear,
                float maskScale) {
    uint listPasses = INDEX_LISTS && GRID_WORDS > kChunkWords ? 2u : 1u;
    for (uint listPass = 0u; listPass < listPasses; ++listPass) {
        for (chunkFirstWord = 0u; chunkFirstWord < GRID_WORDS; chunkFirstWord += kChunkWords) {
            chunkWords = min(kChunkWords, GRID_WORDS - chunkFirstWord);
            if (chunkFirstWord > 0u || listPass > 0u) {
                barrier();  // the last chunk's masks written out
                clearChunkState(thread);
                barrier();
                if (COARSE_TILES > 0u) {
                    listCandidates(tile, thread, lightCount);
                    barrier();
                }
            }
            // 3. The chunk's lights: against the whole tile, then (clustered) against each occupied slice.
            if (occupied) testCandidates(thread, lightCount, wholeTile, maskNear, maskScale);
            if (SLICE_COUNT > 1u) {
                barrier();
                testSlices(thread);
            }
            barrier();

            // 4. The tile's cells out (the chunk's words).
            if (INDEX_LISTS) {
                writeTileLists(tile, thread, listPass == 0u, chunkFirstWord + kChunkWords >= GRID_WORDS,
                               listPass + 1u == listPasses);
            } else {
                writeTileCells(tile, thread);
            }
        }
    }
}

void main() {
    uint thread = gl_LocalInvocationIndex;
    uint lightCount = frame.spotCount + frame.pointCount;
    uvec2 tile = gl_WorkGroupID.xy;
    chunkWords = min(kChunkWords, GRID_WORDS);
    clearTileState(thread);
    barrier();
    if (COARSE_TILES > 0u) listCandidates(tile, thread, lightCount);  // the first chunk's

    // 1. Depth extent of each slice in this tile: the tile folded (tiled), blocks (clustered),
    //    or pixel by pixel (transparent spans); none for depthless tiles.
    uvec2 viewport = uvec2(frame.viewport.xy);
    uvec2 tileEnd = min((tile + 1u) * TILE_SIZE, viewport);  // one past the tile's last pixel
    bool foldDepths = SLICE_COUNT == 1u && !DEPTHLESS_TILES && frame.transparentSpans == 0u;
    bool clusterBlocks = SLICE_COUNT > 1u && !DEPTHLESS_TILES && frame.transparentSpans == 0u;
    uint threadMin = 0xFFFFFFFFu;  // all of this thread's pixels (clustered: the tile-level test)
    uint threadMax = 0u;
    if (foldDepths) foldTileExtent(tile, tileEnd, thread);
    if (clusterBlocks) addClusterBlocks(tile, tileEnd, thread, threadMin, threadMax);
    if (!foldDepths && !clusterBlocks && !DEPTHLESS_TILES) addPixels(tile, viewport, thread, threadMin, threadMax);
    if (SLICE_COUNT > 1u && threadMax != 0u) {
        atomicMin(tileMinDistance, threadMin);
        atomicMax(tileMaxDistance, threadMax);
    }
    barrier();

    // 1b. DEPTH_MASK: the occupied cells of the tile's extent, and their segments.
    float maskNear = uintBitsToFloat(sliceMinDistance[0]);
    float maskScale = depthMaskScale(maskNear, uintBitsToFloat(sliceMaxDistance[0]));
    vec2 pixelToNdc = 2.0 * frame.viewport.zw;
    vec2 ndcA = vec2(tile * TILE_SIZE) * pixelToNdc - 1.0;
    vec2 ndcB = min(vec2((tile + 1u) * TILE_SIZE), frame.viewport.xy) * pixelToNdc - 1.0;
    vec2 ndcMin = min(ndcA, ndcB);
    vec2 ndcMax = max(ndcA, ndcB);
    if (DEPTH_MASK && SLICE_COUNT == 1u && sliceMaxDistance[0] != 0u) {
        markOccupiedCells(tile, tileEnd, viewport, thread, foldDepths, maskNear, maskScale);
        barrier();
        makeCellVolumes(tile, thread, foldDepths, maskNear, ndcMin, ndcMax, pixelToNdc);
    }
    if (DEPTH_MASK) barrier();

    // 2. Tiled (one slice): every thread makes the tile's segment itself, which costs less than a
    //    barrier (zbin-2d: the tile's whole column, the bins holding depth). Clustered: the
    //    occupied slices are listed with their segments, and the whole tile's.
    bool occupied = SLICE_COUNT == 1u && (DEPTHLESS_TILES || sliceMaxDistance[0] != 0u);
    TileVolume wholeTile;
    if (SLICE_COUNT == 1u) {
        wholeTile = DEPTHLESS_TILES ? makeTileColumn(ndcMin, ndcMax, frame.depthToView.xy, frame.ndcToView)
                                    : makeTileVolume(ndcMin, ndcMax, uintBitsToFloat(sliceMinDistance[0]),
                                                     uintBitsToFloat(sliceMaxDistance[0]), frame.ndcToView);
    } else {
        listOccupiedSlices(tile, thread, clusterBlocks, ndcMin, ndcMax, pixelToNdc);
        barrier();
        occupied = occupiedCount > 0u;
        wholeTile = tileVolume;
    }

    cullChunks(tile, thread, lightCount, occupied, wholeTile, maskNear, maskScale);
}
