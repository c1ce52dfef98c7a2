// Adaptive shadow resolution on the CPU, with answers worked out by hand: the estimator's demand
// for lights whose receivers lie at known distances, the tiers, the atlas packing and the budget.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <tuple>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>

#include "core/error.h"
#include "lights/light_setup.h"
#include "lights/shadow_atlas.h"
#include "lights/shadow_budget.h"
#include "lights/shadow_resolution.h"
#include "lights/shadow_setup.h"
#include "lights/shadow_sizing.h"
#include "metrics/shadow_density.h"
#include "scene/study_scenes.h"
#include "shadow_test_scenes.h"

namespace punctual {
namespace {

// ---- the estimator ----------------------------------------------------------------------------

// The test floor seen straight down (testing::floorSeenFromAbove): 512 x 512 pixels of 0.0390625 m.
constexpr uint32_t kFrame = testing::kFloorFrame;
constexpr float kPixel = testing::kFloorPixel;
using testing::floorSeenFromAbove;

struct Demand {
    ShadowPlan plan;
    std::vector<float> demand;
};

Demand demandOf(const Scene& scene) {
    FrameLights lights = setupFrameLights(scene, scene.camera.view, scene.camera.projection(1.0f));
    Demand result;
    result.plan = planShadows(scene, lights, scene.camera.position(), ShadowSettings{});
    result.demand = shadowViewDemand(result.plan, lights, sampleVisibleReceivers(scene, kFrame, kFrame));
    return result;
}

TEST(ShadowResolution, TheSampleGridSpansTheFrameAtMost320By180) {
    const Scene scene = floorSeenFromAbove();
    const VisibleReceivers small = sampleVisibleReceivers(scene, kFrame, kFrame);
    EXPECT_EQ(small.step, 3u);  // 512 / 3 = 171 rows: within 180
    EXPECT_EQ(small.samples.size(), 171u * 171u) << "the floor fills the frame";
    for (const ReceiverSample& sample : small.samples) {
        ASSERT_NEAR(sample.position.y, 0.0f, 1e-4f);
        ASSERT_NEAR(sample.pixelWorldSize, kPixel, 1e-6f);
        ASSERT_EQ(sample.normal, glm::vec3(0.0f, 1.0f, 0.0f));
    }
    EXPECT_EQ(sampleVisibleReceivers(scene, 1280, 720).step, 4u);
    EXPECT_EQ(sampleVisibleReceivers(scene, 320, 180).step, 1u);
}

TEST(ShadowResolution, ASpotStraightDownNeedsItsHeightTimesItsSpanOverThePixel) {
    Scene scene = floorSeenFromAbove();
    // Outer angle 45 degrees: the frustum spans 2 tan 45 = 2 at unit depth. Every receiver is
    // h deep along the spot's axis, so the demand is h x 2 / pixel: 128 at 2.5 m, 256 at 5 m.
    scene.lights.push_back(study::spotLight(glm::vec3(-4.0f, 2.5f, 0.0f), glm::vec3(0.0f, -1.0f, 0.0f), 8.0f, 10.0f,
                                            glm::radians(30.0f), glm::radians(45.0f)));
    scene.lights.push_back(study::spotLight(glm::vec3(4.0f, 5.0f, 0.0f), glm::vec3(0.0f, -1.0f, 0.0f), 8.0f, 10.0f,
                                            glm::radians(30.0f), glm::radians(45.0f)));
    // Shining up: it reaches nothing the camera sees.
    scene.lights.push_back(study::spotLight(glm::vec3(0.0f, 1.0f, 4.0f), glm::vec3(0.0f, 1.0f, 0.0f), 8.0f, 10.0f,
                                            glm::radians(30.0f), glm::radians(45.0f)));
    const Demand d = demandOf(scene);
    ASSERT_EQ(d.plan.views.size(), 3u);
    EXPECT_NEAR(d.demand[0], 2.5f * 2.0f / kPixel, 0.01f);  // 128
    EXPECT_NEAR(d.demand[1], 5.0f * 2.0f / kPixel, 0.01f);  // 256
    EXPECT_EQ(d.demand[2], 0.0f);
    EXPECT_EQ(shadowTierFor(d.demand[0], 16, 2048), 128u);
    EXPECT_EQ(shadowTierFor(d.demand[1], 16, 2048), 256u);
    EXPECT_EQ(shadowTierFor(d.demand[2], 16, 2048), 0u) << "a view whose receivers are not visible gets nothing";
}

TEST(ShadowResolution, APointLightsFacesNeedWhatTheirOwnReceiversNeed) {
    Scene scene = floorSeenFromAbove();
    // 4 m above the floor, range 4.4 m: it reaches the floor within sqrt(4.4^2 - 16) = 1.83 m of
    // the point below it, all on the -Y face (the direction's largest component is -y there), every
    // receiver 4 m deep along -Y: 4 x 2 / pixel = 204.8, tier 256. The other faces see no floor.
    scene.lights.push_back(study::pointLight(glm::vec3(0.0f, 4.0f, 0.0f), 4.4f, 10.0f));
    const Demand d = demandOf(scene);
    ASSERT_EQ(d.plan.views.size(), 6u);
    for (uint32_t face = 0; face < 6; ++face) {
        if (face == 3) {
            EXPECT_NEAR(d.demand[face], 4.0f * 2.0f / kPixel, 0.01f);
            EXPECT_EQ(shadowTierFor(d.demand[face], 16, 2048), 256u);
        } else {
            EXPECT_EQ(d.demand[face], 0.0f) << "face " << face;
        }
    }
}

TEST(ShadowDensity, TexelsPerPixelAreTheResolutionOverTheDemand) {
    Scene scene = floorSeenFromAbove();
    // The 128-demand spot of the test above, at a fixed 256 texels: 2 texels per pixel wherever
    // it reaches; nothing outside its cone. At auto resolution it gets its tier, 128: 1.
    scene.lights.push_back(study::spotLight(glm::vec3(-4.0f, 2.5f, 0.0f), glm::vec3(0.0f, -1.0f, 0.0f), 8.0f, 10.0f,
                                            glm::radians(30.0f), glm::radians(45.0f)));
    for (const auto& [resolution, expected] : {std::pair{256u, 2.0f}, std::pair{ShadowSettings::kAutoResolution, 1.0f}}) {
        FrameLights lights = setupFrameLights(scene, scene.camera.view, scene.camera.projection(1.0f));
        ShadowSettings settings;
        settings.resolution = resolution;
        ShadowPlan plan = planShadows(scene, lights, scene.camera.position(), settings);
        sizeShadowViews(plan, scene, lights, scene.camera.position(), kFrame, kFrame, settings, ShadowMemoryLimits{});
        ASSERT_TRUE(plan.views[0].rendered());
        const ShadowDensityImage image = computeShadowDensity(scene, lights, plan, kFrame, kFrame);
        size_t reached = 0;
        for (uint32_t y = 0; y < kFrame; ++y) {
            for (uint32_t x = 0; x < kFrame; ++x) {
                const float density = image.density[size_t(y) * kFrame + x];
                // The floor point under pixel (x, y): 20 m across 512 pixels, centred on the origin.
                const float fx = (float(x) + 0.5f) * kPixel - 10.0f;
                const float fz = (float(y) + 0.5f) * kPixel - 10.0f;
                const float fromAxis = std::hypot(fx + 4.0f, fz);  // cone radius at the floor: 2.5 m
                if (std::abs(fromAxis - 2.5f) < 0.1f) continue;  // the rim, either way
                if (fromAxis < 2.5f) {
                    ++reached;
                    ASSERT_NEAR(density, expected, 1e-3f) << x << ", " << y;
                } else {
                    ASSERT_EQ(density, 0.0f) << x << ", " << y;
                }
            }
        }
        EXPECT_GT(reached, 10000u);
    }
    // The legend's picture: the frame 1:1 with a strip below.
    FrameLights lights = setupFrameLights(scene, scene.camera.view, scene.camera.projection(1.0f));
    ShadowPlan plan = planShadows(scene, lights, scene.camera.position(), ShadowSettings{});
    sizeShadowViews(plan, scene, lights, scene.camera.position(), 64, 64, ShadowSettings{}, ShadowMemoryLimits{});
    const ImageRgba8 picture = renderShadowDensity(computeShadowDensity(scene, lights, plan, 64, 64), "density");
    EXPECT_GE(picture.width, 64u);
    EXPECT_GT(picture.height, 64u);
}

TEST(ShadowResolution, SurfacesFacingAwayFromTheLightNeedNothing) {
    Scene scene = floorSeenFromAbove();
    // Below the floor's top, shining up: the floor's visible side faces away from it.
    scene.lights.push_back(study::spotLight(glm::vec3(0.0f, -0.05f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f), 8.0f, 10.0f,
                                            glm::radians(30.0f), glm::radians(45.0f)));
    EXPECT_EQ(demandOf(scene).demand[0], 0.0f);
}

TEST(ShadowResolution, TiersAreTheNearestPowerOfTwoInLogScale) {
    EXPECT_EQ(shadowTierFor(0.0f, 16, 2048), 0u);
    EXPECT_EQ(shadowTierFor(1.0f, 16, 2048), 16u);  // clamped up to the smallest tier
    EXPECT_EQ(shadowTierFor(1000.0f, 16, 2048), 1024u);
    EXPECT_EQ(shadowTierFor(1448.0f, 16, 2048), 1024u);  // below 1024 sqrt 2 = 1448.15
    EXPECT_EQ(shadowTierFor(1449.0f, 16, 2048), 2048u);
    EXPECT_EQ(shadowTierFor(724.0f, 16, 2048), 512u);  // below 512 sqrt 2 = 724.08
    EXPECT_EQ(shadowTierFor(1e9f, 16, 2048), 2048u);  // clamped down to the largest
}

// With half an octave of hysteresis a tier of 1024 goes up as soon as the nearest tier is finer,
// and down only once the demand falls below 1024 / 2^1 = 512 (the nearest-tier band alone: 724).
// Without a previous tier or hysteresis, the nearest tier.
TEST(ShadowResolution, HysteresisGoesUpAtOnceAndDownLate) {
    EXPECT_EQ(shadowTierWithHysteresis(1500.0f, 1024, 0.5f, 16, 2048), 2048u);  // up at once
    EXPECT_EQ(shadowTierWithHysteresis(1448.0f, 1024, 0.5f, 16, 2048), 1024u);  // the nearest is 1024 itself
    EXPECT_EQ(shadowTierWithHysteresis(700.0f, 1024, 0.5f, 16, 2048), 1024u);   // nearest 512: held
    EXPECT_EQ(shadowTierWithHysteresis(512.0f, 1024, 0.5f, 16, 2048), 1024u);   // the band's edge
    EXPECT_EQ(shadowTierWithHysteresis(511.0f, 1024, 0.5f, 16, 2048), 512u);
    EXPECT_EQ(shadowTierWithHysteresis(400.0f, 1024, 1.0f, 16, 2048), 1024u);   // a whole octave more: held to 362
    EXPECT_EQ(shadowTierWithHysteresis(300.0f, 1024, 1.0f, 16, 2048), 256u);
    EXPECT_EQ(shadowTierWithHysteresis(700.0f, 1024, 0.0f, 16, 2048), 512u);    // no hysteresis
    EXPECT_EQ(shadowTierWithHysteresis(700.0f, 0, 0.5f, 16, 2048), 512u);       // no previous tier
    EXPECT_EQ(shadowTierWithHysteresis(0.0f, 1024, 0.5f, 16, 2048), 0u);        // no receiver: no storage
    EXPECT_EQ(shadowTierWithHysteresis(700.0f, 4096, 0.5f, 16, 2048), 512u);    // a tier out of range is not kept
}

// ---- the atlas --------------------------------------------------------------------------------

TEST(ShadowAtlas, SquaresFillShelvesLargestFirst) {
    // 1.75 Mi texels in all. Width 1024: a shelf for the 1024, one for the two 512s, one for the
    // four 256s: 1024 x 1792 = 1.75 Mi, nothing empty (width 2048 would take 2 Mi).
    const AtlasLayout layout = packShadowAtlas({256, 1024, 512, 0, 512, 256, 256, 256}, 16384);
    EXPECT_EQ(layout.width, 1024u);
    EXPECT_EQ(layout.height, 1792u);
    auto rect = [&](size_t i) { return std::tuple(layout.rects[i].x, layout.rects[i].y, layout.rects[i].size); };
    EXPECT_EQ(rect(1), std::tuple(0u, 0u, 1024u));
    EXPECT_EQ(rect(2), std::tuple(0u, 1024u, 512u));
    EXPECT_EQ(rect(4), std::tuple(512u, 1024u, 512u));
    EXPECT_EQ(rect(0), std::tuple(0u, 1536u, 256u));
    EXPECT_EQ(rect(5), std::tuple(256u, 1536u, 256u));
    EXPECT_EQ(rect(6), std::tuple(512u, 1536u, 256u));
    EXPECT_EQ(rect(7), std::tuple(768u, 1536u, 256u));
    EXPECT_EQ(rect(3), std::tuple(0u, 0u, 0u)) << "no storage";
}

TEST(ShadowAtlas, SmallerSquaresFillABlockInZOrder) {
    // Width 1024 (2.5 Mi texels; 2048 would take 3 Mi): shelves of 1024, 1024 and 512; the 512's
    // shelf has a second block of 512 at x = 512, where the four 256s go in Z order.
    const AtlasLayout layout = packShadowAtlas({1024, 1024, 512, 256, 256, 256, 256}, 16384);
    EXPECT_EQ(layout.width, 1024u);
    EXPECT_EQ(layout.height, 2560u);
    auto corner = [&](size_t i) { return std::pair(layout.rects[i].x, layout.rects[i].y); };
    EXPECT_EQ(corner(2), std::pair(0u, 2048u));
    EXPECT_EQ(corner(3), std::pair(512u, 2048u));
    EXPECT_EQ(corner(4), std::pair(768u, 2048u));
    EXPECT_EQ(corner(5), std::pair(512u, 2304u));
    EXPECT_EQ(corner(6), std::pair(768u, 2304u));
}

TEST(ShadowAtlas, TheWidthWithTheFewestTexelsWins) {
    // One 1024 and four 256s (1.25 Mi texels): at width 2048 the 256s share the 1024's shelf and
    // leave 0.75 Mi texels empty; at width 1024 they take a shelf of their own, 1024 x 1280, with
    // nothing empty.
    const AtlasLayout layout = packShadowAtlas({1024, 256, 256, 256, 256}, 16384);
    EXPECT_EQ(layout.width, 1024u);
    EXPECT_EQ(layout.height, 1280u);
    EXPECT_EQ(layout.rects[4].x, 768u);
    EXPECT_EQ(layout.rects[4].y, 1024u);
    EXPECT_EQ(packShadowAtlas({}, 16384).texels(), 0u);
    EXPECT_EQ(packShadowAtlas({0, 0}, 16384).texels(), 0u);
}

TEST(ShadowAtlas, RandomSquaresNeverOverlapAndWasteLessThanTheLargest) {
    std::mt19937 random(7);
    for (int trial = 0; trial < 200; ++trial) {
        std::vector<uint32_t> sizes(1 + random() % 80);
        uint64_t area = 0;
        uint32_t largest = 0;
        for (uint32_t& size : sizes) {
            size = random() % 8 == 0 ? 0u : 16u << (random() % 8);
            area += uint64_t(size) * size;
            largest = std::max(largest, size);
        }
        const AtlasLayout layout = packShadowAtlas(sizes, 1u << 30);
        EXPECT_GE(layout.texels(), area);
        if (largest > 0) {
            EXPECT_LT(layout.texels(), area + uint64_t(largest) * largest);
        }
        for (size_t a = 0; a < sizes.size(); ++a) {
            const AtlasRect& ra = layout.rects[a];
            ASSERT_EQ(ra.size, sizes[a]);
            ASSERT_LE(ra.x + ra.size, layout.width);
            ASSERT_LE(ra.y + ra.size, layout.height);
            for (size_t b = a + 1; b < sizes.size(); ++b) {
                const AtlasRect& rb = layout.rects[b];
                const bool apart = ra.size == 0 || rb.size == 0 || ra.x + ra.size <= rb.x || rb.x + rb.size <= ra.x ||
                                   ra.y + ra.size <= rb.y || rb.y + rb.size <= ra.y;
                ASSERT_TRUE(apart) << "trial " << trial << ": squares " << a << " and " << b << " overlap";
            }
        }
    }
}

TEST(ShadowAtlas, ShelvesStayWithinTheDevicesSideOrFail) {
    // Five 1024s within 4096: width 1024 stacks five shelves (5120, too tall); 2048 takes three
    // shelves of two (2048 x 3072 = 6 Mi), 4096 two shelves of four (4096 x 2048 = 8 Mi): 2048.
    // Within 2048, neither width fits.
    const AtlasLayout layout = packShadowAtlas({1024, 1024, 1024, 1024, 1024}, 4096);
    EXPECT_EQ(layout.width, 2048u);
    EXPECT_EQ(layout.height, 3072u);
    EXPECT_TRUE(shadowAtlasFits({1024, 1024, 1024, 1024, 1024}, 4096));
    EXPECT_FALSE(shadowAtlasFits({1024, 1024, 1024, 1024, 1024}, 2048));
    EXPECT_THROW(packShadowAtlas({1024, 1024, 1024, 1024, 1024}, 2048), Error);
    EXPECT_THROW(packShadowAtlas({1000}, 2048), Error) << "not a power of two";
}

// ---- the budget -------------------------------------------------------------------------------

TEST(ShadowBudget, TheLeastImportantLightGivesUpResolutionFirst) {
    // Light B (rank 0) has views 2, 3 at 512; light A (rank 1) views 0, 1 at 1024. At 16 bits:
    // shelves of 1024, 1024 and 512 in a 1024-wide atlas, 1024 x 2560 x 2 bytes = 5 MiB. A budget
    // of 4 MiB halves A's views: four 512s, 512 x 2048 x 2 bytes = 2 MiB.
    ShadowBudgetLimits limits;
    limits.bytes = 4ull << 20;
    limits.bytesName = "--shadow-budget 4";
    limits.texelBytes = 2;
    const ShadowAllocation allocation = fitShadowBudget({1024, 1024, 512, 512}, {1, 1, 0, 0}, limits);
    EXPECT_EQ(allocation.resolutions, (std::vector<uint32_t>{512, 512, 512, 512}));
    EXPECT_EQ(allocation.bytes, 2ull << 20);
    ASSERT_EQ(allocation.reductions.size(), 2u);
    EXPECT_EQ(allocation.reductions[0].view, 0u);
    EXPECT_EQ(allocation.reductions[0].demanded, 1024u);
    EXPECT_EQ(allocation.reductions[0].granted, 512u);
    EXPECT_EQ(allocation.reductions[1].view, 1u);
    EXPECT_EQ(allocation.limitName, "--shadow-budget 4");
}

TEST(ShadowBudget, WithinTheBudgetNothingIsReduced) {
    ShadowBudgetLimits limits;
    limits.bytes = 5ull << 20;
    const ShadowAllocation allocation = fitShadowBudget({1024, 1024, 512, 512}, {1, 1, 0, 0}, limits);
    EXPECT_EQ(allocation.resolutions, (std::vector<uint32_t>{1024, 1024, 512, 512}));
    EXPECT_TRUE(allocation.reductions.empty());
    EXPECT_EQ(allocation.limitName, "");
}

TEST(ShadowBudget, RoundsHalveEachLightOnceBeforeAnyTwice) {
    // Three lights of one 1024 view each, 2 MiB a view at 16 bits: 6 MiB. A budget of 2 MiB:
    // round 1 halves C (1024 x 2560: 5 MiB), then B (a shelf of 1024 and one of two 512s: 3 MiB),
    // then A (three 512s stacked, 512 x 1536 x 2 bytes = 1.5 MiB: fits).
    ShadowBudgetLimits limits;
    limits.bytes = 2ull << 20;
    const ShadowAllocation allocation = fitShadowBudget({1024, 1024, 1024}, {0, 1, 2}, limits);
    EXPECT_EQ(allocation.resolutions, (std::vector<uint32_t>{512, 512, 512}));
    EXPECT_EQ(allocation.bytes, 512ull * 1536 * 2);
}

TEST(ShadowBudget, ABudgetEvenTheSmallestTiersExceedIsOneClearError) {
    ShadowBudgetLimits limits;
    limits.bytes = 512;
    limits.bytesName = "--shadow-budget 1";
    try {
        fitShadowBudget({1024, 512}, {0, 1}, limits);
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()),
                  "--shadow-budget 1: the shadow views need 1.0 KiB even at 16^2 texels each, more than 0.5 KiB "
                  "(or larger than 16384^2 texels)");
    }
}

}  // namespace
}  // namespace punctual
