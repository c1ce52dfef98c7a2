// Virtual shadow pages on the CPU (shaders/shared/shadow_pages.h, lights/virtual_pages.h): the
// addressing with answers worked out by hand, and the page demand of lights whose receivers lie at
// known depths on the test floor seen from above.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "lights/light_setup.h"
#include "lights/shadow_setup.h"
#include "lights/virtual_pages.h"
#include "scene/default_scene.h"
#include "scene/study_scenes.h"
#include "shadow_pages.h"
#include "shadow_test_scenes.h"

namespace punctual {
namespace {

TEST(VirtualPages, LevelsRunFromTheVirtualSizeDownToOnePage) {
    EXPECT_EQ(gpu::virtualShadowLevels(16384, 128), 8u);  // 16384, 8192, ..., 128
    EXPECT_EQ(gpu::virtualShadowLevels(4096, 32), 8u);    // 4096 .. 32
    EXPECT_EQ(gpu::virtualShadowLevels(256, 256), 1u);
    EXPECT_EQ(gpu::virtualShadowPagesAcross(0, 16384, 128), 128u);
    EXPECT_EQ(gpu::virtualShadowPagesAcross(3, 16384, 128), 16u);
    EXPECT_EQ(gpu::virtualShadowPagesAcross(7, 16384, 128), 1u);
    // 128^2 + 64^2 + 32^2 + 16^2 + 8^2 + 4^2 + 2^2 + 1 pages.
    EXPECT_EQ((VirtualPageLayout{16384, 128}.pagesPerView()), 21845u);
}

TEST(VirtualPages, ALevelIsTheNearestInLogScaleToTheNeed) {
    // Levels of 16384 / 128: 16384, 8192, 4096, 2048, 1024, 512, 256, 128 texels a side.
    EXPECT_EQ(gpu::virtualShadowLevel(1000.0f, 16384, 8), 4u);  // 1024
    EXPECT_EQ(gpu::virtualShadowLevel(724.0f, 16384, 8), 5u);   // below 512 sqrt 2 = 724.08: 512
    EXPECT_EQ(gpu::virtualShadowLevel(725.0f, 16384, 8), 4u);   // above it: 1024
    EXPECT_EQ(gpu::virtualShadowLevel(10.0f, 16384, 8), 7u);    // below the coarsest: the coarsest
    EXPECT_EQ(gpu::virtualShadowLevel(1e6f, 16384, 8), 0u);     // past the finest: the finest
    EXPECT_EQ(gpu::virtualShadowLevel(16384.0f, 16384, 8), 0u);
}

// Hysteresis (--shadow-hysteresis H): the finer level may be kept while the need stays above its
// midpoint with the nearest / 2^H. Level 4 of 16384 is 1024 texels; its midpoint with level 3 is
// 1024 sqrt 2 = 1448.15. H = 1/2: kept above 1448.15 / sqrt 2 = 1024.0; H = 1: above 724.08, the
// nearest band's whole (its lower midpoint): a level's band is one octave wide; H = 0: never.
TEST(VirtualPages, HysteresisMayKeepTheFinerLevelWithinHOctaves) {
    const float half = std::exp2(0.5f);
    EXPECT_FALSE(gpu::virtualShadowMayKeepFiner(1000.0f, 4, half));  // 1414.2 < 1448.15
    EXPECT_TRUE(gpu::virtualShadowMayKeepFiner(1030.0f, 4, half));   // 1456.6 > 1448.15
    EXPECT_TRUE(gpu::virtualShadowMayKeepFiner(725.0f, 4, 2.0f));    // 1450 > 1448.15
    EXPECT_FALSE(gpu::virtualShadowMayKeepFiner(1448.0f, 4, 1.0f));  // the nearest's need is below the midpoint
    EXPECT_FALSE(gpu::virtualShadowMayKeepFiner(1e6f, 0, 4.0f));     // nothing finer than level 0
    // Coarsening moves the level, never past the coarsest.
    EXPECT_EQ(gpu::virtualShadowCoarsened(4, 2), 6u);
    EXPECT_EQ(gpu::virtualShadowCoarsened(8, 3), PUNCTUAL_VIRTUAL_SHADOW_LEVELS - 1u);
}

TEST(VirtualPages, APageIsTheCellUnderTheUvAtItsLevel) {
    EXPECT_EQ(gpu::virtualShadowPage(glm::vec2(0.5f, 0.25f), 0, 16384, 128), glm::uvec2(64, 32));
    EXPECT_EQ(gpu::virtualShadowPage(glm::vec2(0.5f, 0.25f), 6, 16384, 128), glm::uvec2(1, 0));  // 2 across
    EXPECT_EQ(gpu::virtualShadowPage(glm::vec2(1.0f, 1.0f), 0, 16384, 128), glm::uvec2(127, 127));
    EXPECT_EQ(gpu::virtualShadowPage(glm::vec2(-0.1f, 2.0f), 0, 16384, 128), glm::uvec2(0, 127));  // clamped
    // Level 0's pages first, row by row; level 1 after its 128^2, level 2 after 64^2 more.
    EXPECT_EQ(gpu::virtualShadowPageIndex(glm::uvec2(3, 2), 0, 16384, 128), 2u * 128u + 3u);
    EXPECT_EQ(gpu::virtualShadowPageIndex(glm::uvec2(0, 0), 1, 16384, 128), 16384u);
    EXPECT_EQ(gpu::virtualShadowPageIndex(glm::uvec2(1, 1), 2, 16384, 128), 16384u + 4096u + 32u + 1u);
    EXPECT_EQ(gpu::virtualShadowPageIndex(glm::uvec2(0, 0), 7, 16384, 128), 21844u);  // the last
}

TEST(VirtualPages, AFilterNearAPageBorderNeedsTheNeighbour) {
    // Level 0 of 4096 / 32: 128 pages across. UV 0.25 is texel 1024, the border between pages 31
    // and 32: a footprint of 2.5 texels reaches both; at texel 1040 (page 32's middle) only 32.
    const float texel = 1.0f / 4096.0f;
    EXPECT_EQ(gpu::virtualShadowFootprintPages(glm::vec2(0.25f, 1040.0f * texel), 2.5f, 0, 4096, 32),
              glm::uvec4(31, 32, 32, 32));
    EXPECT_EQ(gpu::virtualShadowFootprintPages(glm::vec2(1040.0f * texel), 2.5f, 0, 4096, 32), glm::uvec4(32, 32, 32, 32));
    EXPECT_EQ(gpu::virtualShadowFootprintPages(glm::vec2(1040.0f * texel), 0.0f, 0, 4096, 32), glm::uvec4(32, 32, 32, 32));
    // Clamped at the map's edges: the corner's footprint stays on the first and last pages.
    EXPECT_EQ(gpu::virtualShadowFootprintPages(glm::vec2(0.0f, 1.0f), 2.5f, 0, 4096, 32), glm::uvec4(0, 127, 0, 127));
    // At the coarsest level (one page) every footprint is that page.
    EXPECT_EQ(gpu::virtualShadowFootprintPages(glm::vec2(0.5f), 100.0f, 7, 4096, 32), glm::uvec4(0, 0, 0, 0));
}

// The floor seen from above, lit by `lights`, planned (no sizing: the views' spans are their own).
VirtualPageEstimate floorEstimate(const std::vector<Light>& extraLights, float texelsPerPixel,
                                  const std::vector<VirtualPageLayout>& layouts, ShadowPlan* planOut = nullptr) {
    Scene scene = testing::floorSeenFromAbove();
    for (const Light& light : extraLights) scene.lights.push_back(light);
    FrameLights lights = setupFrameLights(scene, scene.camera.view, scene.camera.projection(1.0f));
    ShadowSettings settings;  // tent5: a reach of 2.5 texels
    settings.texelsPerPixel = texelsPerPixel;
    const ShadowPlan plan = planShadows(scene, lights, scene.camera.position(), settings);
    if (planOut) *planOut = plan;
    return estimateVirtualPages(scene, lights, plan, testing::kFloorFrame, testing::kFloorFrame, settings, layouts);
}

// Pixels of the floor frame inside a disk of `radius` around floor point (cx, 0, cz), and those
// within `rim` of its edge (either way: the cone test's rounding decides them).
std::pair<uint64_t, uint64_t> pixelsInDisk(float cx, float cz, float radius, float rim) {
    uint64_t inside = 0;
    uint64_t onRim = 0;
    for (uint32_t y = 0; y < testing::kFloorFrame; ++y) {
        for (uint32_t x = 0; x < testing::kFloorFrame; ++x) {
            const float fx = (float(x) + 0.5f) * testing::kFloorPixel - 10.0f;
            const float fz = (float(y) + 0.5f) * testing::kFloorPixel - 10.0f;
            const float fromAxis = std::hypot(fx - cx, fz - cz);
            inside += fromAxis < radius ? 1 : 0;
            onRim += std::abs(fromAxis - radius) < rim ? 1 : 0;
        }
    }
    return {inside, onRim};
}

TEST(VirtualPages, SpotsStraightDownMarkTheLevelOfTheirHeightAndThePagesUnderTheirDisk) {
    // Outer angle 45 degrees: a spot h above the floor reaches a disk of radius h, every receiver
    // h deep along its axis, so it needs h x 2 / pixel texels (shadow_resolution.h): 128 at 2.5 m,
    // 256 at 5 m. Its view spans the disk's square, 2h a side.
    const std::vector<Light> spots = {
        study::spotLight(glm::vec3(-4.0f, 2.5f, 0.0f), glm::vec3(0.0f, -1.0f, 0.0f), 8.0f, 10.0f, glm::radians(30.0f),
                         glm::radians(45.0f)),
        study::spotLight(glm::vec3(4.0f, 5.0f, 0.0f), glm::vec3(0.0f, -1.0f, 0.0f), 8.0f, 10.0f, glm::radians(30.0f),
                         glm::radians(45.0f))};
    // 4096 / 128: levels 4096, 2048, 1024, 512, 256, 128 (5); 128 is one page, 256 two across.
    const std::vector<VirtualPageLayout> layouts = {{4096, 128}, {4096, 32}};
    ShadowPlan plan;
    const VirtualPageEstimate estimate = floorEstimate(spots, 1.0f, layouts, &plan);
    ASSERT_EQ(plan.views.size(), 2u);
    ASSERT_FALSE(plan.views[0].casters.empty());  // the floor: both views have a map
    ASSERT_FALSE(plan.views[1].casters.empty());

    // A shaded pair per pixel of each disk (radii 2.5 and 5 m, apart: x <= -1.5 and x >= -1).
    const auto [small, smallRim] = pixelsInDisk(-4.0f, 0.0f, 2.5f, 1e-3f);
    const auto [large, largeRim] = pixelsInDisk(4.0f, 0.0f, 5.0f, 1e-3f);
    EXPECT_GE(estimate.shadedPairs + smallRim + largeRim, small + large);
    EXPECT_LE(estimate.shadedPairs, small + large + smallRim + largeRim);
    EXPECT_GT(small, 12000u);  // pi 2.5^2 / pixel^2 = 12,868

    // 128 texels: level 5, its one page; 256: level 4, 2 x 2 pages, all under the disk.
    const VirtualPageDemand& big = estimate.layouts[0];
    EXPECT_EQ(big.markedPerLevel, (std::vector<uint64_t>{0, 0, 0, 0, 4, 1}));
    EXPECT_EQ(big.viewsWithPages, 2u);
    EXPECT_EQ(big.physicalBytes(2), 5u * 128u * 128u * 2u);
    EXPECT_EQ(big.pageTableBytes(), 2u * big.layout.pagesPerView() * 4u);
    EXPECT_EQ(big.usedLevelsPageTableBytes(), (1u + 4u) * 4u);  // one view's level 5, the other's level 4
    EXPECT_EQ(big.pairsCoarserThanAsked, 0u);
    // 32-texel pages: level 5 is 4 across (a disk inscribed in the view meets all 16: the corner
    // page's inner corner is sqrt(2) / 4 of the side, 0.35, from the centre, inside the radius
    // 0.5), level 4 is 8 across (the 4 corner pages' inner corners are 0.53 away: outside).
    const VirtualPageDemand& fine = estimate.layouts[1];
    ASSERT_EQ(fine.markedPerLevel.size(), 8u);
    EXPECT_EQ(fine.markedPerLevel[5], 16u);
    EXPECT_EQ(fine.markedPerLevel[4], 64u - 4u);
    EXPECT_EQ(fine.markedPages(), 76u);
    // No receiver lies within the filter's 2.5 texels of an unmarked page (the nearest are 5 or
    // more texels from the corner pages), so the footprints add none.
    EXPECT_EQ(fine.centrePages, fine.markedPages());
    EXPECT_EQ(big.centrePages, big.markedPages());

    // Two texels a pixel ask twice the resolution: a level finer each.
    const VirtualPageEstimate doubled = floorEstimate(spots, 2.0f, {{4096, 128}});
    EXPECT_EQ(doubled.layouts[0].markedPerLevel, (std::vector<uint64_t>{0, 0, 0, 16, 4, 0}));
    EXPECT_EQ(doubled.shadedPairs, estimate.shadedPairs);
}

TEST(VirtualPages, APointLightMarksTheFaceItsReceiversFallOn) {
    // 4 m above the floor, range 4.4 m: a disk of radius 1.83 m on the -Y face, 4 m deep: 204.8
    // texels, nearest level 256 (shadow_resolution's test). The disk is centred on the face, where
    // four pages of that level meet: all four are marked, and no other face has any.
    const std::vector<Light> point = {study::pointLight(glm::vec3(0.0f, 4.0f, 0.0f), 4.4f, 10.0f)};
    ShadowPlan plan;
    const VirtualPageEstimate estimate = floorEstimate(point, 1.0f, {{4096, 128}}, &plan);
    ASSERT_EQ(plan.views.size(), 6u);
    EXPECT_EQ(estimate.layouts[0].markedPerLevel, (std::vector<uint64_t>{0, 0, 0, 0, 4, 0}));
    EXPECT_EQ(estimate.layouts[0].viewsWithPages, 1u);
    const auto [inside, rim] = pixelsInDisk(0.0f, 0.0f, std::sqrt(4.4f * 4.4f - 16.0f), 2e-3f);
    EXPECT_GE(estimate.shadedPairs + rim, inside);
    EXPECT_LE(estimate.shadedPairs, inside + rim);
}

TEST(VirtualPages, SmallerPagesMarkMoreOfThemAndNeverMoreTexels) {
    // Halving the page cuts every marked page into four, of which only those a receiver needs stay
    // marked: more pages, no more texels (the levels do not change while the needs stay above the
    // coarsest page). On the default hall at 320x180.
    Scene scene = makeDefaultScene();
    FrameLights lights = setupFrameLights(scene, scene.camera.view, scene.camera.projection(320.0f / 180.0f));
    const ShadowPlan plan = planShadows(scene, lights, scene.camera.position(), ShadowSettings{});
    const std::vector<VirtualPageLayout> layouts = {{16384, 256}, {16384, 128}, {16384, 64}, {16384, 32}};
    const VirtualPageEstimate estimate = estimateVirtualPages(scene, lights, plan, 320, 180, ShadowSettings{}, layouts);
    EXPECT_GT(estimate.shadedPairs, 320u * 180u);  // several shadowed lights a pixel
    for (size_t i = 1; i < layouts.size(); ++i) {
        EXPECT_GT(estimate.layouts[i].markedPages(), estimate.layouts[i - 1].markedPages()) << layouts[i].pageSize;
        EXPECT_LE(estimate.layouts[i].physicalBytes(2), estimate.layouts[i - 1].physicalBytes(2)) << layouts[i].pageSize;
        EXPECT_EQ(estimate.layouts[i].viewsWithPages, estimate.layouts[0].viewsWithPages);
    }
    // The filters' footprints never take pages away, and with 32-texel pages they add some (at
    // this size most views need one page of 128 or 256 at their level, which holds every footprint).
    for (const VirtualPageDemand& demand : estimate.layouts) EXPECT_GE(demand.markedPages(), demand.centrePages);
    EXPECT_GT(estimate.layouts.back().markedPages(), estimate.layouts.back().centrePages);
}

}  // namespace
}  // namespace punctual
