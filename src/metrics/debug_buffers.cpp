#include "metrics/debug_buffers.h"

#include <algorithm>
#include <bit>
#include <cstring>

#include "core/check.h"
#include "gpu_types.h"

namespace punctual {

uint64_t lightStatsBytes(uint32_t width, uint32_t height, uint32_t listCells, uint32_t gridWords) {
    return (uint64_t(width) * height * PUNCTUAL_LIGHT_STATS_BLOCKS * PUNCTUAL_LIGHT_STATS_PIXEL_WORDS +
            uint64_t(listCells) * gridWords) *
           4;
}

uint64_t shadowFactorBytes(uint32_t width, uint32_t height) {
    return uint64_t(width) * height * (PUNCTUAL_SHADOW_DEBUG_SURFACE_WORDS + PUNCTUAL_SHADOW_DEBUG_FACTOR_WORDS) * 4;
}

LightStatsImage decodeLightStats(const std::vector<uint8_t>& bytes, uint32_t width, uint32_t height, uint32_t listCells,
                                 uint32_t gridWords) {
    PUNCTUAL_CHECK(bytes.size() >= lightStatsBytes(width, height, listCells, gridWords), "light statistics buffer too small");
    const size_t pixels = size_t(width) * height;
    std::vector<uint32_t> words(lightStatsBytes(width, height, listCells, gridWords) / sizeof(uint32_t));
    std::memcpy(words.data(), bytes.data(), words.size() * sizeof(uint32_t));
    const auto at = [&](uint32_t block, size_t pixel) {
        return &words[gpu::lightStatsWord(block, uint32_t(pixels), uint32_t(pixel), 0u)];
    };
    LightStatsImage stats;
    stats.width = width;
    stats.height = height;
    stats.tested.resize(pixels);
    stats.affecting.resize(pixels);
    stats.shadowLookups.resize(pixels);
    stats.shadowTaps.resize(pixels);
    stats.covered.resize(pixels);
    stats.methodLuminance.resize(pixels);
    stats.bruteLuminance.resize(pixels);
    stats.transparentTested.resize(pixels);
    stats.transparentAffecting.resize(pixels);
    stats.transparentFragments.resize(pixels);
    stats.transparentMissingLight.resize(pixels);
    stats.listCells.resize(pixels);
    for (size_t i = 0; i < pixels; ++i) {
        const uint32_t* list = at(PUNCTUAL_LIGHT_STATS_LIST, i);
        stats.listCells[i] = list[PUNCTUAL_LIGHT_STATS_LIST_CELL];
        stats.tested[i] = list[PUNCTUAL_LIGHT_STATS_LIST_TESTED];
    }
    stats.cellReachingLights.resize(listCells);
    for (uint32_t cell = 0; cell < listCells; ++cell) {
        const uint32_t* mask = &words[gpu::lightStatsCellWord(uint32_t(pixels), gridWords, cell, 0u)];
        uint32_t lights = 0;
        for (uint32_t w = 0; w < gridWords; ++w) lights += uint32_t(std::popcount(mask[w]));
        stats.cellReachingLights[cell] = lights;
    }
    for (size_t i = 0; i < pixels; ++i) {
        const uint32_t* t = at(PUNCTUAL_LIGHT_STATS_TRANSPARENT, i);
        stats.transparentTested[i] = t[PUNCTUAL_LIGHT_STATS_TESTED];
        stats.transparentAffecting[i] = t[PUNCTUAL_LIGHT_STATS_REACHING];
        stats.transparentFragments[i] = t[PUNCTUAL_LIGHT_STATS_FRAGMENTS];
        stats.transparentMissingLight[i] = t[PUNCTUAL_LIGHT_STATS_MISSING];
    }
    for (size_t i = 0; i < pixels; ++i) {
        const uint32_t* w = at(PUNCTUAL_LIGHT_STATS_OPAQUE, i);
        const uint32_t work = w[PUNCTUAL_LIGHT_STATS_WORK];
        const uint32_t reaching = w[PUNCTUAL_LIGHT_STATS_REACHING];
        stats.covered[i] = (reaching & PUNCTUAL_LIGHT_STATS_COVERED) ? uint8_t{1} : uint8_t{0};  // every shaded pixel
        stats.shadowLookups[i] = gpu::unpackShadowLookups(work);
        stats.shadowTaps[i] = gpu::unpackShadowTaps(work);
        stats.affecting[i] = reaching & ~PUNCTUAL_LIGHT_STATS_COVERED;
        std::memcpy(&stats.methodLuminance[i], &w[PUNCTUAL_LIGHT_STATS_LUMINANCE], sizeof(float));
        std::memcpy(&stats.bruteLuminance[i], &w[PUNCTUAL_LIGHT_STATS_BRUTE_LUMINANCE], sizeof(float));
    }
    return stats;
}

ShadowFactorImage decodeShadowFactors(const std::vector<uint8_t>& bytes, uint32_t width, uint32_t height,
                                      uint32_t slots, bool sun) {
    PUNCTUAL_CHECK(bytes.size() >= shadowFactorBytes(width, height), "shadow factor buffer too small");
    PUNCTUAL_CHECK(slots <= PUNCTUAL_MAX_SHADOWED_LIGHTS, "more shadow slots than the buffer holds");
    const size_t pixels = size_t(width) * height;
    ShadowFactorImage image;
    image.width = width;
    image.height = height;
    image.slots = slots;
    image.positions.resize(pixels);
    image.normals.resize(pixels);
    image.covered.resize(pixels);
    image.factors.resize(pixels * image.slots);
    if (sun) {
        image.sunFactors.resize(pixels);
        image.sunCascades.resize(pixels);
    }
    const auto* words = reinterpret_cast<const uint32_t*>(bytes.data());
    for (size_t i = 0; i < pixels; ++i) {
        const uint32_t* surface = words + i * PUNCTUAL_SHADOW_DEBUG_SURFACE_WORDS;
        std::memcpy(&image.positions[i], surface, sizeof(glm::vec3));
        std::memcpy(&image.normals[i], surface + 4, sizeof(glm::vec3));
        image.covered[i] = surface[3] != 0 ? uint8_t{1} : uint8_t{0};
        const auto* factors = reinterpret_cast<const uint8_t*>(words + pixels * PUNCTUAL_SHADOW_DEBUG_SURFACE_WORDS +
                                                               i * PUNCTUAL_SHADOW_DEBUG_FACTOR_WORDS);
        // Uncovered pixels were cleared to 0: report them as not reached.
        for (uint32_t slot = 0; slot < image.slots; ++slot) {
            image.factors[i * image.slots + slot] = image.covered[i] ? factors[slot] : uint8_t{255};
        }
        if (sun) {
            image.sunFactors[i] = image.covered[i] ? factors[PUNCTUAL_SUN_SHADOW_SLOT] : uint8_t{255};
            image.sunCascades[i] = image.covered[i] ? uint8_t(surface[7]) : uint8_t{0};
        }
    }
    return image;
}

}  // namespace punctual
