// Known answers for the culling statistics (metrics/culling_stats.h) on hand-built images.
#include <gtest/gtest.h>

#include <bit>
#include <vector>

#include "gpu_types.h"
#include "metrics/culling_stats.h"

namespace punctual {
namespace {

// An image of `pixels` opaque pixels, each given its reaching lights (a mask over lights 0..31 of
// the first grid word), its list cell and the lights its method tested. Each cell's reaching
// lights are the union of its covered pixels' masks, as forward.frag gathers them.
struct PixelSpec {
    uint32_t reaching;  // bit i: light i reaches the pixel
    uint32_t cell;
    uint32_t tested;
    bool covered = true;
};

LightStatsImage imageOf(const std::vector<PixelSpec>& pixels) {
    LightStatsImage image;
    image.width = uint32_t(pixels.size());
    image.height = 1;
    for (const PixelSpec& p : pixels) {
        image.covered.push_back(p.covered ? 1 : 0);
        image.tested.push_back(p.tested);
        image.affecting.push_back(uint32_t(std::popcount(p.reaching)));
        image.methodLuminance.push_back(1.0f);
        image.bruteLuminance.push_back(1.0f);
        image.listCells.push_back(p.cell);
    }
    std::vector<uint32_t> unions;
    for (const PixelSpec& p : pixels) {
        if (p.cell >= unions.size()) unions.resize(p.cell + 1, 0u);
        if (p.covered) unions[p.cell] |= p.reaching;
    }
    for (const uint32_t lights : unions) image.cellReachingLights.push_back(uint32_t(std::popcount(lights)));
    return image;
}

TEST(CullingStats, TheFloorTestsEachCellsUnionOfReachingLightsAtEachOfItsPixels) {
    // Cell 7: one pixel reached by light 0, one by light 1: the exact list {0, 1}, 2 tests each.
    // Cell 9: one pixel reached by lights 0 and 2: {0, 2}, 2 tests. The uncovered pixel of cell 9
    // (reaching 3, which a background pixel cannot really have) counts nowhere. Reaching 1 + 1 + 2
    // = 4 lights; the floor tests 2 + 2 + 2 = 6: 1.5. The method tested 3 + 3 + 2 = 8: 2.0.
    const CullingStats stats = computeCullingStats(imageOf({{0b001u, 7u, 3u},
                                                           {0b010u, 7u, 3u},
                                                           {0b101u, 9u, 2u},
                                                           {0b1000u, 9u, 5u, false}}));
    EXPECT_EQ(stats.coveredPixels, 3u);
    EXPECT_DOUBLE_EQ(stats.efficiency, 2.0);
    EXPECT_DOUBLE_EQ(stats.floorEfficiency, 1.5);
}

TEST(CullingStats, OneCellPerPixelIsAPerfectFloorAndOneCellForAllIsBruteForcesUnion) {
    const std::vector<PixelSpec> perPixel = {{0b01u, 0u, 2u}, {0b10u, 1u, 2u}, {0b11u, 2u, 2u}};
    EXPECT_DOUBLE_EQ(computeCullingStats(imageOf(perPixel)).floorEfficiency, 1.0);
    // The same pixels in one cell: each tests both lights, 6 tests for 4 reaching.
    const std::vector<PixelSpec> oneCell = {{0b01u, 0u, 2u}, {0b10u, 0u, 2u}, {0b11u, 0u, 2u}};
    EXPECT_DOUBLE_EQ(computeCullingStats(imageOf(oneCell)).floorEfficiency, 1.5);
}

TEST(CullingStats, TheFloorTestsTheCellsGatheredLightsWhateverTheirWords) {
    // 3 lights reach one pixel of cell 4 (say in three grid words; the GPU counted the cell's
    // union: debug buffers' decoding), none the other: the floor tests 3 at each pixel, 6.
    LightStatsImage image = imageOf({{0u, 4u, 3u}, {0u, 4u, 3u}});
    image.affecting[0] = 3;
    image.cellReachingLights[4] = 3;
    EXPECT_DOUBLE_EQ(computeCullingStats(image).floorEfficiency, 2.0);
}

TEST(CullingStats, AnImageWithoutMasksHasNoFloor) {
    LightStatsImage image = imageOf({{0b1u, 0u, 1u}});
    image.listCells.clear();
    EXPECT_EQ(computeCullingStats(image).floorEfficiency, 0.0);
}

}  // namespace
}  // namespace punctual
