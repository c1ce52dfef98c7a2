// Candidate lists: how the one-subgroup culling kernels (tile_culling.comp, cluster_culling.comp)
// cull a cell past the design notes' 96 lights, and the shared memory and workgroup sums they need
// for it. GLSL only; include after culling.h and the declarations of `frameCullLights` (the
// lights' culling shapes) and `GRID_WORDS` (the words a light-grid cell's masks), with
// GL_KHR_shader_subgroup_arithmetic enabled. subgroup_tiles.glsl includes it; each kernel says in
// its own `CANDIDATE_LISTS` whether it culls so.

// One slot per subgroup, for workgroups of several subgroups only.
shared uvec4 subgroupResults[PUNCTUAL_MAX_TILE_THREADS];

// The cell's mask words in shared memory past one triple (at most 4 KiB, at 16,384 + 16,384
// lights): where its lights come from candidate lists (below), or with index lists gathered
// triple by triple for writeCellList (only tiled-2.5d's masks leave it unused). One
// triple (up to the design notes' 96 lights) stays in every lane's registers, as workgroupMasks
// leaves it: no shared memory, no barrier. (Not `CANDIDATE_LISTS || ...`: glslang 11 emits that
// specialization-constant `||` before its operand's definition, which fails validation.)
const bool kCellListShared = GRID_WORDS > 3u;
shared uint cellListWords[kCellListShared ? GRID_WORDS : 1u];

// Makes cellListWords' writes visible to the workgroup, and keeps them from being overwritten
// before they are read: a subgroup barrier where the workgroup is one subgroup (lavapipe runs a
// workgroup barrier as a coroutine switch), else a workgroup barrier. (Uniform control flow.)
void cellListBarrier() {
    if (!kCellListShared) return;
    if (gl_NumSubgroups == 1u) {
        subgroupMemoryBarrierShared();
        subgroupBarrier();
    } else {
        memoryBarrierShared();
        barrier();
    }
}

// ---- Candidate lists: past one triple of mask words (more than the design notes' 96 lights) ----
// Walking a cell's candidate masks a triple at a time costs every cell GRID_WORDS / 3 rounds of
// light tests and subgroup combines however few candidates the words hold: at 8,192 lights 86
// rounds a tile (and a cluster), each lane testing the few candidates its share of a triple
// holds while the others wait. Instead the lanes compact the candidates' indices into shared
// memory, one mask word a lane per round (an exclusive sum over the workgroup gives each lane its
// place), and then test them every lane-th, every lane busy: the rounds over the words cost a
// load and a count each, and the tests follow the candidates. A kept light sets its bit in the
// cell's words (cellListWords) with a shared atomicOr, so the candidates' order does not matter.
// At 8,192 lights and 1280x720 this took tiled culling from 151 to 89 ms and clustered from 199
// to 112 (bench/RESULTS.md, "fourth part").

// At least one round's candidates (32 a word, a word a lane, at most PUNCTUAL_MAX_TILE_THREADS
// lanes), so that a round always fits an emptied buffer: 8 KiB, with the cell's words at most
// 12 KiB of the 16 KiB every device has.
const uint kCandidateCapacity = 32u * PUNCTUAL_MAX_TILE_THREADS;
shared uint candidateLights[kCellListShared ? kCandidateCapacity : 1u];

// (the sum of `value` over the invocations before this one, in subgroup order; the workgroup's sum)
// (Uniform control flow.)
uvec2 workgroupExclusiveAddAndTotal(uint value) {
    uvec2 sums = uvec2(subgroupExclusiveAdd(value), subgroupAdd(value));
    if (gl_NumSubgroups == 1u) return sums;
    if (subgroupElect()) subgroupResults[gl_SubgroupID] = uvec4(sums.y, 0u, 0u, 0u);
    barrier();
    sums.y = 0u;
    for (uint i = 0u; i < gl_NumSubgroups; ++i) {
        sums.x += i < gl_SubgroupID ? subgroupResults[i].x : 0u;
        sums.y += subgroupResults[i].x;
    }
    barrier();  // every slot read before the next call writes them again
    return sums;
}

// A cell's words cleared before its candidates are tested (testCandidates' barrier orders them).
void clearCellWords(uint lane, uint threads) {
    for (uint word = lane; word < GRID_WORDS; word += threads) cellListWords[word] = 0u;
}

// Tests the buffer's first `count` candidates against `segment`, every `threads`-th from `lane`,
// and sets the bits of those that may touch it. (Uniform control flow.)
void testCandidates(uint count, TileVolume segment, uint lane, uint threads) {
    cellListBarrier();  // the buffer and the cleared words written
    for (uint i = lane; i < count; i += threads) {
        uint light = candidateLights[i];
        if (lightMayTouchTile(frameCullLights[light], segment)) {
            atomicOr(cellListWords[lightGridWord(light)], 1u << lightGridBit(light));
        }
    }
    cellListBarrier();  // the buffer read before it is filled again, the bits set before they are read
}

// Adds the candidates of mask word `word` (`bits`; one word a lane, a round of the workgroup) to
// the buffer that holds `fill` (uniform), testing those first where the round might not fit.
// Returns the buffer's new fill. (Uniform control flow.)
uint addCandidateWord(uint fill, uint word, uint bits, TileVolume segment, uint lane, uint threads) {
    uvec2 place = workgroupExclusiveAddAndTotal(bitCount(bits));
    if (fill + place.y > kCandidateCapacity) {  // (uniform)
        testCandidates(fill, segment, lane, threads);
        fill = 0u;
    }
    uint next = fill + place.x;
    for (; bits != 0u; bits &= bits - 1u) candidateLights[next++] = lightGridFirstLight(word) + uint(findLSB(bits));
    return fill + place.y;
}
