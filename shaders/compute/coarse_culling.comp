#version 450
// The coarse light-culling pass (HDRP's "big tile" prepass): one workgroup per coarse tile of
// COARSE_TILES x COARSE_TILES fine tiles (64x64 pixels at the default 16-pixel tiles), testing
// every light against the tile's frustum column from the near plane to the far plane. No depth is
// read: the pass costs one light test per (coarse tile, light), a sixteenth of the fine tests it
// saves, and the fine kernel (light_culling.comp) then tests only the lights of its coarse tile.
//
// Lossless: each test is conservative against the true shapes (culling.h), so a light that
// reaches any pixel of a fine tile meets that pixel's frustum segment, which lies inside the
// coarse column, and passes here. The fine kernel only ever drops lights, never adds them.
#extension GL_GOOGLE_include_directive : require
#include "gpu_types.h"
#include "culling.h"

// Sized to the device's subgroup, as the fine kernels (LightGridLayout::tileThreads): lavapipe runs
// a workgroup's subgroups as coroutines switched at every barrier, so one subgroup a workgroup makes
// its two barriers cheap there, and on a GPU a big tile's light tests (96 at the design notes' caps)
// fill a subgroup.
layout(local_size_x_id = PUNCTUAL_SPEC_TILE_THREADS) in;
layout(constant_id = PUNCTUAL_SPEC_TILE_SIZE) const uint TILE_SIZE = 16u;
layout(constant_id = PUNCTUAL_SPEC_COARSE_TILES) const uint COARSE_TILES = 4u;  // fine tiles a side
layout(constant_id = PUNCTUAL_SPEC_GRID_WORDS) const uint GRID_WORDS = 3u;  // words a light-grid cell

layout(set = 0, binding = PUNCTUAL_BINDING_FRAME) uniform FrameBlock { GpuFrame frame; };
layout(std430, set = 0, binding = PUNCTUAL_BINDING_CULL_LIGHTS) readonly buffer CullLightBlock { CullLight frameCullLights[]; };
layout(std430, set = 0, binding = PUNCTUAL_BINDING_COARSE_GRID) writeonly buffer CoarseGridBlock { uint coarseGrid[]; };

shared uint coarseMask[GRID_WORDS];  // 4 bytes per 32 lights: 1 KiB at 8192
shared TileVolume column;

void main() {
    uint thread = gl_LocalInvocationIndex;
    uvec2 coarseTile = gl_WorkGroupID.xy;
    for (uint word = thread; word < GRID_WORDS; word += gl_WorkGroupSize.x) coarseMask[word] = 0u;
    if (thread == 0u) {
        // The column's screen rectangle, cut at the viewport as the fine tiles are.
        uint side = TILE_SIZE * COARSE_TILES;
        vec2 pixelToNdc = 2.0 * frame.viewport.zw;
        vec2 ndcA = vec2(coarseTile * side) * pixelToNdc - 1.0;
        vec2 ndcB = min(vec2((coarseTile + 1u) * side), frame.viewport.xy) * pixelToNdc - 1.0;
        column = makeTileColumn(min(ndcA, ndcB), max(ndcA, ndcB), frame.depthToView.xy, frame.ndcToView);
    }
    barrier();
    uint lightCount = frame.spotCount + frame.pointCount;
    for (uint light = thread; light < lightCount; light += gl_WorkGroupSize.x) {
        if (!lightMayTouchTile(frameCullLights[light], column)) continue;
        atomicOr(coarseMask[lightGridWord(light)], 1u << lightGridBit(light));
    }
    barrier();
    uint coarseTilesAcross = (uint(frame.viewport.x) + TILE_SIZE * COARSE_TILES - 1u) / (TILE_SIZE * COARSE_TILES);
    uint base = (coarseTile.y * coarseTilesAcross + coarseTile.x) * GRID_WORDS;
    for (uint word = thread; word < GRID_WORDS; word += gl_WorkGroupSize.x) coarseGrid[base + word] = coarseMask[word];
}
