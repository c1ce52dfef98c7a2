#pragma once
// The z-bin method's bins, built on the CPU each frame (URP Forward+, after Drobot, "Improved
// culling for tiled and clustered rendering", SIGGRAPH 2017):
//   1. each light's view-distance extent is culling.h's lightDistanceExtent (its shapes,
//      already widened by the culling margin), nearest end first;
//   2. the lights are sorted by that nearest end (ties by packed index: deterministic);
//   3. PUNCTUAL_ZBIN_COUNT logarithmic bins between the nearest and the farthest light extent
//      each hold the [first, last] range of sorted indices of the lights overlapping them;
//   4. each bin's range is expanded into a packed-order light mask (the grid's words), so
//      the forward pass ANDs its tile's mask with its bin's and walks the set bits in packed
//      order, the brute-force loop's order: bit-identical to brute force.
// A range is looser than the exact set of lights in a bin (it also holds the sorted lights
// between its ends that miss the bin): that is the scheme's trade, two words a bin instead of a
// mask, and what the bench measures.
//
// Why the CPU: the lights already pass through it every frame (packing, view transform); sorting
// the design notes' 96 and filling 64 bins is a few microseconds (8,192: about a millisecond),
// where a GPU pass would cost a dispatch, a barrier and a sort. URP builds its bins on the CPU too
// (Burst jobs).
#include <cstdint>
#include <vector>

#include "culling.h"
#include "gpu_types.h"

namespace punctual {

struct ZBins {
    gpu::GpuZBins gpu{};
    uint32_t gridWords = 1;              // words a bin's mask: gpu::gridWordsOf(the lights)
    std::vector<uint32_t> binMasks;      // PUNCTUAL_ZBIN_COUNT x gridWords: bin b's mask at b x gridWords
    std::vector<uint32_t> sortedLights;  // packed indices in depth order (nearest extent first)
    // Each packed light's place in sortedLights, 16 bits each, two a word (light L in the low half
    // of word L / 2 when L is even: zBinRankOf): with index lists, the forward pass keeps a light of
    // its cell's list where its rank lies in its bin's range, as Drobot's bins are read, instead of
    // ANDing a mask.
    std::vector<uint32_t> rankWords;

    const uint32_t* binMask(uint32_t bin) const { return &binMasks[size_t(bin) * gridWords]; }
    // The GPU buffer (PUNCTUAL_BINDING_ZBINS): the header `gpu`, then binMasks (or, for
    // `indexLists`, rankWords).
    uint64_t bytes(bool indexLists = false) const {
        return sizeof(gpu::GpuZBins) + (indexLists ? rankWords.size() : binMasks.size()) * sizeof(uint32_t);
    }
};

// `cullLights` in packed order, `depthToView` the camera's (a, b) of viewDistanceFromDepth.
// Deterministic.
ZBins buildZBins(const std::vector<gpu::CullLight>& cullLights, glm::vec2 depthToView);

// The bin of a (reversed) depth: the stored-start search the forward pass makes.
uint32_t zBinOfDepth(const gpu::GpuZBins& bins, float depth);

}  // namespace punctual
