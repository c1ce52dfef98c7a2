#include "lights/shadow_budget.h"

#include <algorithm>
#include <cstdio>

#include "core/error.h"

namespace punctual {

std::string describeBytes(uint64_t bytes) {
    const char* units[] = {"KiB", "MiB", "GiB"};
    int unit = 2;
    while (unit > 0 && double(bytes) < 0.1 * double(1ull << (10 * (unit + 1)))) --unit;
    char text[32];
    std::snprintf(text, sizeof(text), "%.1f %s", double(bytes) / double(1ull << (10 * (unit + 1))), units[unit]);
    return text;
}

ShadowAllocation fitShadowBudget(const std::vector<uint32_t>& demanded, const std::vector<uint32_t>& lightRank,
                                 const ShadowBudgetLimits& limits) {
    ShadowAllocation allocation;
    allocation.resolutions = demanded;
    std::vector<uint32_t>& resolutions = allocation.resolutions;
    auto bytesOf = [&](const std::vector<uint32_t>& sizes) -> uint64_t {
        if (!shadowAtlasFits(sizes, limits.maxSide)) return UINT64_MAX;
        return packShadowAtlas(sizes, limits.maxSide).texels() * limits.texelBytes;
    };
    // The lights present, least important first.
    std::vector<uint32_t> ranks = lightRank;
    std::sort(ranks.begin(), ranks.end());
    ranks.erase(std::unique(ranks.begin(), ranks.end()), ranks.end());
    std::reverse(ranks.begin(), ranks.end());

    uint64_t bytes = bytesOf(resolutions);
    while (bytes > limits.bytes) {
        bool lowered = false;
        for (uint32_t rank : ranks) {
            bool lightLowered = false;
            for (size_t v = 0; v < resolutions.size(); ++v) {
                if (lightRank[v] != rank || resolutions[v] <= limits.minTier) continue;
                resolutions[v] /= 2;
                lightLowered = true;
            }
            if (!lightLowered) continue;
            lowered = true;
            bytes = bytesOf(resolutions);
            if (bytes <= limits.bytes) break;
        }
        if (!lowered) {
            std::vector<uint32_t> smallest = demanded;
            for (uint32_t& size : smallest) size = size > 0 ? limits.minTier : 0;
            const uint64_t need = uint64_t(packShadowAtlas(smallest, UINT32_MAX).texels()) * limits.texelBytes;
            throw Error(limits.bytesName, "the shadow views need " + describeBytes(need) + " even at " +
                                              std::to_string(limits.minTier) + "^2 texels each, more than " +
                                              describeBytes(limits.bytes) + " (or larger than " +
                                              std::to_string(limits.maxSide) + "^2 texels)");
        }
    }
    allocation.atlas = packShadowAtlas(resolutions, limits.maxSide);
    allocation.bytes = allocation.atlas.texels() * limits.texelBytes;
    for (uint32_t v = 0; v < resolutions.size(); ++v) {
        if (resolutions[v] < demanded[v]) allocation.reductions.push_back({v, demanded[v], resolutions[v]});
    }
    if (!allocation.reductions.empty()) allocation.limitName = limits.bytesName;
    return allocation;
}

}  // namespace punctual
