// What the one-subgroup-a-tile culling kernels (tile_culling.comp, cluster_culling.comp) share:
// combining a workgroup's values with subgroup operations, spreading a tile's candidate lights over
// the lanes, reading a pixel's depth span and testing a set of lights against a frustum segment.
// GLSL only; include after culling.h, light_lists.glsl and the declarations of `frame` (GpuFrame),
// `depthImage`, `transparentDepth`, `frameCullLights` and `GRID_WORDS` (the words a light-grid
// cell's masks), with GL_KHR_shader_subgroup_arithmetic enabled.
//
// Light masks travel three words at a time (a triple: words 3 triple .. 3 triple + 2; words past
// GRID_WORDS are 0): the kernels loop over a cell's triples, one at the design notes' 96 lights.
// Past one triple they cull from candidate lists instead (candidate_lists.glsl, which this
// includes), tiled-2.5d excepted: its per-cell tests take the triples' masks.
//
// A workgroup is one subgroup on the devices these kernels are sized for (LightGridLayout::
// tileThreads is the device's subgroup size), and then needs no shared memory and no barrier. A
// device whose compute subgroups come out smaller (the size is the default, not a promise) still
// gets the right answers: the subgroups then combine through shared memory, behind barriers,
// which is why every function here that combines must be called in uniform control flow.

#include "candidate_lists.glsl"

// (nearest, farthest) depth over the workgroup: the largest x and the smallest y.
vec2 workgroupExtent(vec2 extent) {
    extent = vec2(subgroupMax(extent.x), subgroupMin(extent.y));
    if (gl_NumSubgroups == 1u) return extent;  // uniform over the workgroup
    if (subgroupElect()) subgroupResults[gl_SubgroupID] = uvec4(floatBitsToUint(extent), 0u, 0u);
    barrier();
    for (uint i = 0u; i < gl_NumSubgroups; ++i) {
        vec2 other = uintBitsToFloat(subgroupResults[i].xy);
        extent = vec2(max(extent.x, other.x), min(extent.y, other.y));
    }
    barrier();  // every slot read before the next call writes them again
    return extent;
}

// The largest value over the workgroup.
float workgroupMax(float value) {
    value = subgroupMax(value);
    if (gl_NumSubgroups == 1u) return value;
    if (subgroupElect()) subgroupResults[gl_SubgroupID] = uvec4(floatBitsToUint(value), 0u, 0u, 0u);
    barrier();
    for (uint i = 0u; i < gl_NumSubgroups; ++i) value = max(value, uintBitsToFloat(subgroupResults[i].x));
    barrier();  // every slot read before the next call writes them again
    return value;
}

// The union of the invocations' mask words.
uvec3 workgroupMasks(uvec3 masks) {
    masks = subgroupOr(masks);
    if (gl_NumSubgroups == 1u) return masks;
    if (subgroupElect()) subgroupResults[gl_SubgroupID] = uvec4(masks, 0u);
    barrier();
    for (uint i = 0u; i < gl_NumSubgroups; ++i) masks |= subgroupResults[i].xyz;
    barrier();  // every slot read before the next call writes them again
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

// Word `word` of the masks (culling.h, lightGridWord) of the tile's candidate lights: with the
// coarse pass (coarseTiles > 0), those its big tile kept; else all of the frame's lights. Then
// (laneCandidates) the part of triple `triple` that lane `lane` of `threads` tests.
uint candidateWord(uvec2 tile, uint coarseTiles, uint word) {
    if (word >= GRID_WORDS) return 0u;
    if (coarseTiles == 0u) return allLightsWord(word, frame.spotCount + frame.pointCount);
    uvec2 coarseTile = tile / coarseTiles;
    uint coarseTilesAcross = (frame.lightGrid.y + coarseTiles - 1u) / coarseTiles;
    return coarseGrid[(coarseTile.y * coarseTilesAcross + coarseTile.x) * GRID_WORDS + word];
}

uint laneCandidateWord(uvec2 tile, uint coarseTiles, uint lane, uint threads, uint word) {
    return candidateWord(tile, coarseTiles, word) & laneBitsOfWord(word, lane, threads);
}

uvec3 laneCandidates(uvec2 tile, uint coarseTiles, uint lane, uint threads, uint triple) {
    return uvec3(laneCandidateWord(tile, coarseTiles, lane, threads, 3u * triple),
                 laneCandidateWord(tile, coarseTiles, lane, threads, 3u * triple + 1u),
                 laneCandidateWord(tile, coarseTiles, lane, threads, 3u * triple + 2u));
}

// The lights of `lights` (triple `triple` of a mask) whose shapes may touch `segment` (culling.h)
// and, for a `cell` other than kAnyDepthCell, whose depth cells (lightDepthMask, the tile's mask of
// near distance `maskNear` and `maskScale`) include it: tiled-2.5d's per-cell test. One loop over
// the three words, each step the lowest bit of the first word with any, by selects (forward.frag
// walks its masks so, and why).
const uint kAnyDepthCell = 0xFFFFFFFFu;
uvec3 lightsMeetingDepthCell(uvec3 lights, uint triple, TileVolume segment, uint cell, float maskNear, float maskScale) {
    uvec3 meeting = uvec3(0u);
    while ((lights.x | lights.y | lights.z) != 0u) {
        uint word = lights.x != 0u ? 0u : (lights.y != 0u ? 1u : 2u);
        uint bits = word == 0u ? lights.x : (word == 1u ? lights.y : lights.z);
        uint bit = 1u << uint(findLSB(bits));
        uvec3 wordBit = uvec3(word == 0u ? bit : 0u, word == 1u ? bit : 0u, word == 2u ? bit : 0u);
        lights &= ~wordBit;
        CullLight shape = frameCullLights[lightGridFirstLight(3u * triple + word) + uint(findLSB(bits))];
        bool spansCell = cell == kAnyDepthCell || (lightDepthMask(shape, maskNear, maskScale) & (1u << cell)) != 0u;
        if (spansCell && lightMayTouchTile(shape, segment)) meeting |= wordBit;
    }
    return meeting;
}

// The lights of `lights` whose shapes may touch `segment`, whatever their depth cells.
uvec3 lightsMeetingSegment(uvec3 lights, uint triple, TileVolume segment) {
    return lightsMeetingDepthCell(lights, triple, segment, kAnyDepthCell, 0.0, 0.0);
}

// Writes triple `triple` of a cell's masks (lanes 0-2, the words before GRID_WORDS): at `cellBase`
// of lightGrid, or with index lists past one triple into cellListWords.
void writeCellTriple(uint cellBase, uint triple, uvec3 masks, uint lane) {
    uint word = 3u * triple + lane;
    if (lane < 3u && word < GRID_WORDS) {
        uint bits = lane == 0u ? masks.x : (lane == 1u ? masks.y : masks.z);
        if (!INDEX_LISTS) {
            lightGrid[cellBase + word] = bits;
        } else if (kCellListShared) {
            cellListWords[word] = bits;
        }
    }
}

// Word `word` of the cell's masks, for writeCellList: from cellListWords, or from `onlyTriple`,
// the cell's one triple.
uint cellListWord(uvec3 onlyTriple, uint word) {
    if (word >= GRID_WORDS) return 0u;
    if (!kCellListShared) return word == 0u ? onlyTriple.x : (word == 1u ? onlyTriple.y : onlyTriple.z);
    return cellListWords[word];
}

// Index lists: cell `cell`'s list (light_lists.glsl) from its mask words (cellListWord). The first
// subgroup writes it, each lane every `lanes`-th word of the masks: a sum over the lanes gives the
// count, one lane claims the list's words, and per round of words an exclusive sum gives each
// word's first entry, so the lanes write disjoint words of the list. A word of the list holds two
// entries: a lane whose first light is an odd entry pairs it with the entry before, the last light
// of the nearest earlier word with any (an exclusive max over the lanes, since lights ascend with
// the words), or the count for the list's first light. `onlyTriple`: the cell's masks where they
// are one triple (cellListWord). Called in uniform control flow (cellListBarrier).
void writeCellList(uint cell, uvec3 onlyTriple) {
    cellListBarrier();
    if (gl_SubgroupID == 0u) {
        uint lanes = subgroupAdd(1u);
        uint lane = subgroupExclusiveAdd(1u);
        uint count = 0u;
        for (uint word = lane; word < GRID_WORDS; word += lanes) count += bitCount(cellListWord(onlyTriple, word));
        count = subgroupAdd(count);
        uint start = subgroupMax(subgroupElect() ? claimLightList(count) : 0u);
        if (subgroupElect()) lightGrid[cell] = start;
        uint before = count;  // the entry before the next round's first
        uint written = 0u;    // entries 1 .. written are placed
        for (uint first = 0u; start < PUNCTUAL_LIGHT_LIST_OVERFLOW && first < GRID_WORDS; first += lanes) {  // (uniform)
            uint word = first + lane;
            uint bits = cellListWord(onlyTriple, word);
            uint lastPlusOne = bits != 0u ? lightGridFirstLight(word) + uint(findMSB(bits)) + 1u : 0u;
            uint entry = written + subgroupExclusiveAdd(bitCount(bits));  // the entry before this word's first
            uint earlier = subgroupExclusiveMax(lastPlusOne);
            uint previous = earlier != 0u ? earlier - 1u : before;
            written += subgroupAdd(bitCount(bits));
            uint roundLast = subgroupMax(lastPlusOne);
            if (roundLast != 0u) before = roundLast - 1u;
            for (; bits != 0u; bits &= bits - 1u) {
                uint light = lightGridFirstLight(word) + uint(findLSB(bits));
                writeLightListEntry(start, ++entry, previous, light, count);
                previous = light;
            }
        }
    }
    cellListBarrier();
}

// Writes the cell's words (cellListWords, after testCandidates): its masks at `cellBase` of
// lightGrid, or (index lists) cell `cell`'s list. (Uniform control flow.)
void writeCellFromWords(uint cell, uint cellBase, uint lane, uint threads) {
    if (INDEX_LISTS) {
        writeCellList(cell, uvec3(0u));
    } else {
        for (uint word = lane; word < GRID_WORDS; word += threads) lightGrid[cellBase + word] = cellListWords[word];
    }
}

// The geometry a pixel shades, as a depth span (nearest, farthest): a pixel under transparent
// surfaces spans from its nearest transparent depth to its opaque depth (over the background, its
// farthest transparent depth); any other pixel its opaque depth alone; a background pixel nothing,
// (0, 2), which max() and min() pass over.
vec2 pixelSpan(uvec2 pixel) {
    float depth = texelFetch(depthImage, ivec2(pixel), 0).r;
    uint index = pixel.y * uint(frame.viewport.x) + pixel.x;
    uint nearestBits = frame.transparentSpans != 0u ? transparentDepth[index] : 0u;
    if (nearestBits != 0u) {
        float farthest = isBackgroundDepth(depth) ? uintBitsToFloat(transparentDepth[uint(frame.viewport.x * frame.viewport.y) + index])
                                                  : depth;
        return vec2(uintBitsToFloat(nearestBits), farthest);
    }
    return isBackgroundDepth(depth) ? vec2(0.0, 2.0) : vec2(depth);
}
