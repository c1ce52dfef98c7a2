// Known answers for the z-bin method's bins (src/lights/z_bins.h), computed by hand: the depth
// order of the lights, each bin's range of sorted indices and its mask in packed order.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "lights/z_bins.h"

namespace punctual {
namespace {

// A camera with near 0.1 and far 100: depth = a / D - b with a = f n / (f - n), b = n / (f - n)
// (culling.h), 1 at the near plane and 0 at the far one.
const glm::vec2 kDepthToView(100.0f * 0.1f / 99.9f, 0.1f / 99.9f);

gpu::CullLight lightAt(float distance, float radius) {
    gpu::CullLight light{};
    light.cosOuter = -1.0f;  // a point light: its extent is its sphere's
    light.sphereCenter = glm::vec3(0.0f, 0.0f, -distance);
    light.sphereRadius = radius;
    return light;
}

// The bin a pixel at view distance `distance` reads: its range and its mask's words.
struct Bin {
    uint32_t range = 0;
    std::vector<uint32_t> mask;
    uint32_t word(uint32_t w) const { return w < mask.size() ? mask[w] : 0u; }
};

Bin binAt(const ZBins& bins, float distance) {
    const uint32_t b = zBinOfDepth(bins.gpu, gpu::depthFromViewDistance(distance, kDepthToView));
    return {bins.gpu.binRange[b], std::vector<uint32_t>(bins.binMask(b), bins.binMask(b) + bins.gridWords)};
}

uint32_t first(const Bin& bin) { return bin.range & 0xFFFFu; }
uint32_t last(const Bin& bin) { return bin.range >> 16; }

TEST(ZBins, LightsAreSortedByTheirNearestExtent) {
    // Packed: spot 0 at 10..14, spot 1 at 2..4, point 2 at 5..9 (spotCount 2). Nearest ends 10, 2, 5.
    const ZBins bins = buildZBins({lightAt(12.0f, 2.0f), lightAt(3.0f, 1.0f), lightAt(7.0f, 2.0f)}, kDepthToView);
    EXPECT_EQ(bins.sortedLights, (std::vector<uint32_t>{1, 2, 0}));
}

TEST(ZBins, EachLightsRankIsItsPlaceInDepthOrder) {
    // Sorted 1, 2, 0 (as above): ranks 2, 0, 1 for packed 0, 1, 2, two 16-bit ranks a word:
    // word 0 = rank(0) | rank(1) << 16 = 0x00000002, word 1 = rank(2) = 1.
    const ZBins bins = buildZBins({lightAt(12.0f, 2.0f), lightAt(3.0f, 1.0f), lightAt(7.0f, 2.0f)}, kDepthToView);
    EXPECT_EQ(bins.rankWords, (std::vector<uint32_t>{0x00000002u, 0x00000001u}));
    // A light is in a bin's mask exactly where its rank is in the bin's range: the index lists'
    // test stands for the mask's bit.
    for (uint32_t b = 0; b < PUNCTUAL_ZBIN_COUNT; ++b) {
        for (uint32_t light = 0; light < 3; ++light) {
            const uint32_t rank = gpu::lightListEntry(bins.rankWords[light / 2], light);
            const bool inRange = rank >= (bins.gpu.binRange[b] & 0xFFFFu) && rank <= (bins.gpu.binRange[b] >> 16);
            EXPECT_EQ(inRange, (bins.binMask(b)[0] >> light & 1u) != 0u) << "bin " << b << " light " << light;
        }
    }
    EXPECT_EQ(bins.bytes(true), sizeof(gpu::GpuZBins) + 2 * sizeof(uint32_t));
}

TEST(ZBins, StartsRunFromTheNearPlaneThroughTheLightsExtentLogarithmically) {
    // Extents 2..4 and 8..32 (nearest 2, farthest 32): bin s >= 1 starts at 2 x 16^(s / 64), so bin
    // 16 starts at 2 x 16^(1/4) = 4, bin 32 at 8 and bin 48 at 16.
    const ZBins bins = buildZBins({lightAt(3.0f, 1.0f), lightAt(20.0f, 12.0f)}, kDepthToView);
    EXPECT_EQ(bins.gpu.binStartDepth[0], 1.0f);
    EXPECT_NEAR(gpu::viewDistanceFromDepth(bins.gpu.binStartDepth[1], kDepthToView), 2.0f * std::pow(16.0f, 1.0f / 64.0f), 1e-3f);
    EXPECT_NEAR(gpu::viewDistanceFromDepth(bins.gpu.binStartDepth[16], kDepthToView), 4.0f, 1e-3f);
    EXPECT_NEAR(gpu::viewDistanceFromDepth(bins.gpu.binStartDepth[32], kDepthToView), 8.0f, 1e-3f);
    EXPECT_NEAR(gpu::viewDistanceFromDepth(bins.gpu.binStartDepth[48], kDepthToView), 16.0f, 2e-3f);
    for (uint32_t s = 1; s < PUNCTUAL_ZBIN_COUNT; ++s) EXPECT_LE(bins.gpu.binStartDepth[s], bins.gpu.binStartDepth[s - 1]);
}

TEST(ZBins, EachBinHoldsTheRangeOfSortedLightsOverlappingIt) {
    // Sorted: A (2..4, packed 1), B (3..6, packed 0), C (8..32, packed 2, a point; spotCount 2).
    // Bins (starts as above with nearest 2, farthest 32): distances 2..4 are bins 0..15, 4..8 are
    // bins 16..31, 8..32 bins 32..63. A spans bins 0..16 at most, B 7..26 or so, C 32..63.
    const ZBins bins = buildZBins({lightAt(4.5f, 1.5f), lightAt(3.0f, 1.0f), lightAt(20.0f, 12.0f)}, kDepthToView);
    ASSERT_EQ(bins.sortedLights, (std::vector<uint32_t>{1, 0, 2}));
    // A pixel at distance 3.5 is inside A and B: its bin's range is sorted 0..1, mask lights 0 and 1.
    const Bin both = binAt(bins, 3.5f);
    EXPECT_EQ(first(both), 0u);
    EXPECT_EQ(last(both), 1u);
    EXPECT_EQ(both.word(0), 0x3u);
    // At 5 only B: range 1..1.
    const Bin onlyB = binAt(bins, 5.0f);
    EXPECT_EQ(first(onlyB), 1u);
    EXPECT_EQ(last(onlyB), 1u);
    EXPECT_EQ(onlyB.word(0), 0x1u);  // packed light 0
    // At 7, in the gap: empty.
    const Bin gap = binAt(bins, 7.0f);
    EXPECT_GT(first(gap), last(gap));
    EXPECT_EQ(gap.word(0), 0u);
    // At 30, C alone: bit 2 (packed 2, the first point: one bit per light, culling.h).
    const Bin onlyC = binAt(bins, 30.0f);
    EXPECT_EQ(first(onlyC), 2u);
    EXPECT_EQ(last(onlyC), 2u);
    EXPECT_EQ(onlyC.word(0), 0x4u);
}

TEST(ZBins, ARangeAlsoHoldsTheSortedLightsBetweenItsEnds) {
    // The scheme's looseness: A 2..40 (a long extent), B 5..6, C 10..12, sorted A, B, C. A bin at
    // distance 11 meets A and C, so its range is 0..2 and holds B too, which does not reach it.
    const ZBins bins = buildZBins({lightAt(21.0f, 19.0f), lightAt(5.5f, 0.5f), lightAt(11.0f, 1.0f)}, kDepthToView);
    ASSERT_EQ(bins.sortedLights, (std::vector<uint32_t>{0, 1, 2}));
    const Bin bin = binAt(bins, 11.0f);
    EXPECT_EQ(first(bin), 0u);
    EXPECT_EQ(last(bin), 2u);
    EXPECT_EQ(bin.word(0), 0x7u);
}

TEST(ZBins, EveryDistanceInsideALightFindsItInItsBin) {
    // Losslessness over many lights: every distance inside a light's extent lands in a bin whose
    // mask holds that light.
    std::vector<gpu::CullLight> lights;
    for (int i = 0; i < 40; ++i) lights.push_back(lightAt(0.5f + 2.3f * float(i % 17), 0.2f + 0.9f * float(i % 5)));
    const ZBins bins = buildZBins(lights, kDepthToView);
    size_t checked = 0;
    for (uint32_t light = 0; light < lights.size(); ++light) {
        const float centre = -lights[light].sphereCenter.z;
        for (int k = 0; k <= 50; ++k) {
            // From just inside the near end to just inside the far end (never before the near plane).
            const float d = std::max(centre - lights[light].sphereRadius * 0.999f +
                                         lights[light].sphereRadius * 1.998f * float(k) / 50.0f,
                                     0.11f);
            const Bin bin = binAt(bins, d);
            EXPECT_NE(bin.word(gpu::lightGridWord(light)) & (1u << gpu::lightGridBit(light)), 0u) << light << " at " << d;
            ++checked;
        }
    }
    EXPECT_EQ(checked, 40u * 51u);
}

TEST(ZBins, NoLightsMakeEmptyBins) {
    const ZBins bins = buildZBins({}, kDepthToView);
    ASSERT_EQ(bins.gridWords, 1u);
    for (uint32_t b = 0; b < PUNCTUAL_ZBIN_COUNT; ++b) {
        EXPECT_EQ(bins.binMask(b)[0], 0u);
        EXPECT_GT(bins.gpu.binRange[b] & 0xFFFFu, bins.gpu.binRange[b] >> 16);  // empty
    }
}

}  // namespace
}  // namespace punctual
