#include "lights/z_bins.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace punctual {
namespace {

// A light's view-distance extent: its bounding sphere's, never nearer than 0.
struct Extent {
    float nearest;
    float farthest;
};

Extent extentOf(const gpu::CullLight& light) {
    const glm::vec2 extent = gpu::lightDistanceExtent(light);
    return {std::max(extent.x, 0.0f), extent.y};
}

}  // namespace

uint32_t zBinOfDepth(const gpu::GpuZBins& bins, float depth) {
    return gpu::clusterSliceOfDepth(depth, bins.binStartDepth, PUNCTUAL_ZBIN_COUNT);
}

ZBins buildZBins(const std::vector<gpu::CullLight>& cullLights, glm::vec2 depthToView) {
    ZBins bins;
    const uint32_t count = uint32_t(cullLights.size());
    bins.gridWords = gpu::gridWordsOf(count);
    bins.binMasks.assign(size_t(PUNCTUAL_ZBIN_COUNT) * bins.gridWords, 0u);
    std::vector<Extent> extents;
    for (const gpu::CullLight& light : cullLights) extents.push_back(extentOf(light));
    bins.sortedLights.resize(count);
    std::iota(bins.sortedLights.begin(), bins.sortedLights.end(), 0u);
    std::stable_sort(bins.sortedLights.begin(), bins.sortedLights.end(),
                     [&](uint32_t a, uint32_t b) { return extents[a].nearest < extents[b].nearest; });

    // Bin starts: bin 0 from the near plane (depth 1); bins 1 .. N-1 start at logarithmically
    // spaced distances between the nearest and the farthest light extent, so that every bin can
    // hold lights: D_s = near (far / near)^(s / N), as the cluster slices (sliceStartDepth), and
    // stored as depths so the forward pass compares depths exactly. Depths nearer than D_1 fall in
    // bin 0 and farther than the last start in the last bin; the lights are binned by the same
    // search, so a light whose extent holds a pixel's distance holds its bin too (the search is
    // monotone in depth, and depthFromViewDistance in distance).
    float nearest = 0.0f, farthest = 0.0f;
    if (count > 0) {
        nearest = extents[bins.sortedLights.front()].nearest;
        for (const Extent& e : extents) farthest = std::max(farthest, e.farthest);
    }
    // A light around the camera reaches distance 0: bins start from a small share of the extent
    // instead (a logarithm needs a positive start); nearer depths are bin 0's.
    nearest = std::max(nearest, farthest * 1e-4f);
    bins.gpu.binStartDepth[0] = 1.0f;
    for (uint32_t s = 1; s < PUNCTUAL_ZBIN_COUNT; ++s) {
        const float distance =
            count > 0 ? gpu::sliceStartDistance(s, nearest, farthest, PUNCTUAL_ZBIN_COUNT) : 0.0f;
        // No lights: every start at depth 1, all depths in the last bin, which is empty.
        bins.gpu.binStartDepth[s] = count > 0 ? std::min(gpu::depthFromViewDistance(distance, depthToView), 1.0f) : 1.0f;
        // Starts must not rise (rounding of pow on nearly equal distances): keep them falling.
        bins.gpu.binStartDepth[s] = std::min(bins.gpu.binStartDepth[s], bins.gpu.binStartDepth[s - 1]);
    }

    // Ranges of sorted indices per bin: first > last is empty.
    std::vector<uint32_t> first(PUNCTUAL_ZBIN_COUNT, UINT32_MAX), last(PUNCTUAL_ZBIN_COUNT, 0u);
    for (uint32_t i = 0; i < count; ++i) {
        const Extent& e = extents[bins.sortedLights[i]];
        // Reversed depth: the nearest end has the larger depth, the lower bin.
        const uint32_t nearBin = zBinOfDepth(bins.gpu, gpu::depthFromViewDistance(std::max(e.nearest, 1e-30f), depthToView));
        const uint32_t farBin = zBinOfDepth(bins.gpu, gpu::depthFromViewDistance(e.farthest, depthToView));
        for (uint32_t b = nearBin; b <= farBin; ++b) {
            first[b] = std::min(first[b], i);
            last[b] = std::max(last[b], i);
        }
    }
    bins.rankWords.assign(std::max<size_t>((count + 1) / 2, 1), 0u);
    for (uint32_t i = 0; i < count; ++i) {
        const uint32_t light = bins.sortedLights[i];
        bins.rankWords[light / 2] |= i << (16 * (light % 2));
    }
    for (uint32_t b = 0; b < PUNCTUAL_ZBIN_COUNT; ++b) {
        uint32_t* words = &bins.binMasks[size_t(b) * bins.gridWords];
        if (first[b] <= last[b]) {
            for (uint32_t i = first[b]; i <= last[b]; ++i) {
                const uint32_t light = bins.sortedLights[i];
                words[gpu::lightGridWord(light)] |= 1u << gpu::lightGridBit(light);
            }
            bins.gpu.binRange[b] = first[b] | (last[b] << 16);  // 16-bit indices (PUNCTUAL_MAX_LIGHT_CAPACITY)
        } else {
            bins.gpu.binRange[b] = 1u;  // first 1 > last 0: empty
        }
    }
    return bins;
}

}  // namespace punctual
