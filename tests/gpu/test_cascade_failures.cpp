// The sun's cascades in the bench's failure study (app/bench_cascade_failures.h): each study's
// measure on a few small frames, showing the failure it is built to find and the setting that
// avoids it. Validation layers on; any message fails.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "bench/bench_cascade_failures.h"
#include "gpu_test_support.h"
#include "scene/outdoor_scene.h"
#include "scene/study_scenes.h"

namespace punctual {
namespace {

using reference::PixelVerdict;

render::RenderSettings cascadeSettings(uint32_t width, uint32_t height, uint32_t resolution, float shadowDistance) {
    render::RenderSettings settings = testing::renderSettings(width, height);
    settings.shadows.resolution = resolution;
    settings.shadows.cascades.shadowDistance = shadowDistance;
    return settings;
}

TEST(CascadeFailures, FlipsAreCountedWhereTheGpuChangesAndTheTruthDoesNot) {
    // Pixel by pixel: a GPU flip alone, a true flip the GPU follows, a true flip the GPU misses, no
    // change, and pixels the sun does not reach in one of the frames (not compared).
    const std::vector<PixelVerdict> before = {PixelVerdict::AgreeLit, PixelVerdict::AgreeLit, PixelVerdict::AgreeShadow,
                                              PixelVerdict::FalseLit, PixelVerdict::NotCompared, PixelVerdict::AgreeLit};
    const std::vector<PixelVerdict> after = {PixelVerdict::FalseShadow, PixelVerdict::AgreeShadow, PixelVerdict::FalseShadow,
                                             PixelVerdict::FalseLit, PixelVerdict::AgreeLit, PixelVerdict::NotCompared};
    const bench::ShimmerCounts counts = bench::countShimmerFlips(before, after);
    EXPECT_EQ(counts.compared, 4u);
    EXPECT_EQ(counts.gpuFlips, 2u);          // pixels 0 and 1
    EXPECT_EQ(counts.truthFlips, 2u);        // pixels 1 and 2
    EXPECT_EQ(counts.unexplainedFlips, 1u);  // pixel 0
    EXPECT_DOUBLE_EQ(counts.unexplainedShare(), 0.25);
}

TEST(CascadeFailures, TheWalkMovesFiveCentimetresAndTurnsATenthOfADegreeAFrame) {
    const Scene scene = study::cascadeFieldScene();
    const std::vector<Camera> path = bench::walkingCameraPath(scene.camera, 30);
    ASSERT_EQ(path.size(), 30u);
    EXPECT_EQ(path.front().view, scene.camera.view);
    for (size_t k = 1; k < path.size(); ++k) {
        const glm::vec3 step = path[k].position() - path[k - 1].position();
        EXPECT_NEAR(glm::length(step), 0.05f, 1e-4f) << k;
        EXPECT_NEAR(step.y, 0.0f, 1e-5f) << k;  // along the ground
        const glm::vec3 before = -glm::vec3(glm::inverse(path[k - 1].view)[2]);
        const glm::vec3 after = -glm::vec3(glm::inverse(path[k].view)[2]);
        EXPECT_NEAR(std::acos(std::min(glm::dot(before, after), 1.0f)), 0.1f * 0.0174533f, 2e-4f) << k;
        EXPECT_FLOAT_EQ(path[k].yfov, scene.camera.yfov);
    }
}

// Without texel snapping the cascades' texels slide over the ground as the camera walks and the
// shadow edges on still receivers flip; with it they stay put (the target: at most a
// tenth of the flips). Seen from the moving camera, Embree's truth flips too.
TEST(CascadeFailures, UnsnappedCascadesShimmerOnStillReceiversSnappedOnesHardlyDo) {
    auto context = testing::makeValidatedContext();
    const Scene scene = study::cascadeFieldScene();
    const reference::EmbreeScene embree(scene);
    const std::vector<Camera> path = bench::walkingCameraPath(scene.camera, 5);
    render::RenderSettings settings = cascadeSettings(320, 180, 512, 200.0f);
    settings.shadows.filter = ShadowFilter::Hardware;
    settings.shadows.cascades.snapToTexels = true;
    const bench::ShimmerCounts snapped =
        bench::measureShimmer(*context, scene, embree, path, bench::ShimmerView::FixedReceivers, settings);
    settings.shadows.cascades.snapToTexels = false;
    const bench::ShimmerCounts unsnapped =
        bench::measureShimmer(*context, scene, embree, path, bench::ShimmerView::FixedReceivers, settings);
    std::printf("[ shimmer ] still receivers: snapped %llu flips, not snapped %llu, of %llu\n",
                static_cast<unsigned long long>(snapped.gpuFlips), static_cast<unsigned long long>(unsnapped.gpuFlips),
                static_cast<unsigned long long>(unsnapped.compared));
    EXPECT_GT(unsnapped.compared, 4u * 20000u);  // four pairs of frames, most of the frame in sunlight
    EXPECT_EQ(snapped.truthFlips, 0u);           // the same receivers every frame
    EXPECT_EQ(unsnapped.truthFlips, 0u);
    EXPECT_GT(unsnapped.gpuFlips, 50u);
    EXPECT_LE(10u * snapped.gpuFlips, unsnapped.gpuFlips);
    EXPECT_EQ(unsnapped.unexplainedFlips, unsnapped.gpuFlips);

    settings.shadows.cascades.snapToTexels = true;
    const std::vector<Camera> shortPath(path.begin(), path.begin() + 3);
    const bench::ShimmerCounts moving =
        bench::measureShimmer(*context, scene, embree, shortPath, bench::ShimmerView::MovingView, settings);
    EXPECT_GT(moving.truthFlips, 50u);  // the view moves: shadow edges cross pixels in Embree's image too
    testing::expectNoValidationMessages(*context);
}

// The seed's culling bias leaves casters deep inside a cascade out of the next one; the soft and
// dither blends read the next cascade in the blend zone and lose those casters' long shadows
// there, while the hard blend reads only the cascade that has them.
TEST(CascadeFailures, BlendsLoseShadowsInTheBlendZoneThatHardKeeps) {
    auto context = testing::makeValidatedContext();
    const Scene scene = study::cascadeSeamScene();
    const reference::EmbreeScene embree(scene);
    const reference::EdgeBand band = reference::EdgeBand::ofScreenPixels(1.0f, scene.camera, 360);
    std::vector<bench::CascadeSeamCounts> seams;
    for (const CascadeBlend blend : {CascadeBlend::Hard, CascadeBlend::Soft, CascadeBlend::Dither}) {
        render::RenderSettings settings = cascadeSettings(640, 360, 1024, 100.0f);
        settings.shadows.cascades.blend = blend;
        const bench::ValidatedFrame frame = bench::renderAndValidate(*context, scene, embree, settings, band);
        ASSERT_TRUE(frame.validation.sun.has_value());
        seams.push_back(bench::cascadeSeamCounts(frame.factors, *frame.validation.sun, frame.plan, settings.shadows.cascades,
                                               scene.camera.view));
        const bench::CascadeSeamCounts& s = seams.back();
        std::printf("[ seams ] %s: split band %.3f%% of %llu, blend zone %.3f%% of %llu, inside %.3f%% of %llu\n",
                    cascadeBlendName(blend), 100.0 * s.splitBand.misclassifiedOutsideBand(),
                    static_cast<unsigned long long>(s.splitBand.comparedOutsideBand), 100.0 * s.blendZone.misclassifiedOutsideBand(),
                    static_cast<unsigned long long>(s.blendZone.comparedOutsideBand), 100.0 * s.inside.misclassifiedOutsideBand(),
                    static_cast<unsigned long long>(s.inside.comparedOutsideBand));
        EXPECT_GT(s.splitBand.compared, 100u);
        EXPECT_GT(s.blendZone.comparedOutsideBand, 2000u);
        EXPECT_GT(s.inside.comparedOutsideBand, 100000u);
    }
    EXPECT_EQ(seams[0].blendZone.falseLitOutsideBand, 0u);
    EXPECT_GT(seams[1].blendZone.misclassifiedOutsideBand(), 0.001);
    EXPECT_GT(seams[2].blendZone.misclassifiedOutsideBand(), 0.001);
    // Outside the blend zones every blend reads the same cascade.
    EXPECT_EQ(seams[1].inside.falseLitOutsideBand, seams[0].inside.falseLitOutsideBand);
    testing::expectNoValidationMessages(*context);
}

// The seed's ratios give the first cascade 20 m of the 200: near the camera its texels are far
// larger than the pixels and thin shadows are lost; the practical scheme (lambda 0.9) splits near
// the camera and keeps them.
TEST(CascadeFailures, PracticalSplitsCutTheNearErrorOfTheSeedRatios) {
    auto context = testing::makeValidatedContext();
    Scene scene = makeOutdoorScene();
    std::erase_if(scene.lights, [](const Light& light) { return light.type != LightType::Directional; });
    const reference::EmbreeScene embree(scene);
    const reference::EdgeBand band = reference::EdgeBand::ofScreenPixels(1.0f, scene.camera, 180);
    const std::vector<float> ends = {5.0f, 1e6f};  // the first five metres, and the rest
    std::vector<std::vector<reference::ShadowCounts>> buckets;
    for (const float lambda : {-1.0f, 0.9f}) {
        render::RenderSettings settings = cascadeSettings(320, 180, 256, 200.0f);
        settings.shadows.cascades.lambda = lambda;
        const bench::ValidatedFrame frame = bench::renderAndValidate(*context, scene, embree, settings, band);
        ASSERT_TRUE(frame.validation.sun.has_value());
        buckets.push_back(bench::sunCountsByViewDepth(frame.factors, *frame.validation.sun, scene.camera.view, ends));
        // Every compared pixel lies in one bucket or the other.
        EXPECT_EQ(buckets.back()[0].compared + buckets.back()[1].compared, frame.validation.sun->counts.compared);
        std::printf("[ perspective ] lambda %.1f: %.3f%% within 5 m, %.3f%% beyond\n", double(lambda),
                    100.0 * buckets.back()[0].misclassifiedOutsideBand(), 100.0 * buckets.back()[1].misclassifiedOutsideBand());
    }
    EXPECT_GT(buckets[0][0].comparedOutsideBand, 10000u);
    EXPECT_GT(buckets[0][0].misclassifiedOutsideBand(), 0.01);
    EXPECT_GT(buckets[0][0].misclassifiedOutsideBand(), 5.0 * buckets[1][0].misclassifiedOutsideBand());
    testing::expectNoValidationMessages(*context);
}

// A deck 16 m up lies in front of the first cascade's near plane: clipped, it casts nothing;
// pancaked by the depth clamp, its shadow is whole.
TEST(CascadeFailures, ClippingLosesTheShadowOfACasterInFrontOfTheNearPlanePancakingKeepsIt) {
    auto context = testing::makeValidatedContext();
    const Scene scene = study::cascadePancakingScene(16.0f);
    const reference::EmbreeScene embree(scene);
    const reference::EdgeBand band = reference::EdgeBand::ofScreenPixels(1.0f, scene.camera, 180);
    std::vector<reference::ShadowCounts> sun;
    for (const bool clamp : {true, false}) {
        render::RenderSettings settings = cascadeSettings(320, 180, 1024, 100.0f);
        settings.shadows.cascades.depthClamp = clamp;
        const bench::ValidatedFrame frame = bench::renderAndValidate(*context, scene, embree, settings, band);
        ASSERT_TRUE(frame.validation.sun.has_value());
        sun.push_back(frame.validation.sun->counts);
    }
    EXPECT_GT(sun[0].comparedOutsideBand, 30000u);
    EXPECT_LT(bench::fraction(sun[0].falseLitOutsideBand, sun[0].comparedOutsideBand), 0.001);
    EXPECT_GT(bench::fraction(sun[1].falseLitOutsideBand, sun[1].comparedOutsideBand), 0.1);
    testing::expectNoValidationMessages(*context);
}

}  // namespace
}  // namespace punctual
