// The sun's cascaded shadows against Embree: a field with casters inside and beyond each split.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "report/validation_report.h"
#include "gpu_test_support.h"
#include "lights/cascade_setup.h"
#include "scene/outdoor_scene.h"
#include "scene/study_scenes.h"
#include "shadow_test_runs.h"

namespace punctual {
namespace {

std::string describe(const reference::ShadowCounts& counts) {
    return "compared " + std::to_string(counts.compared) + ", outside band " + std::to_string(counts.comparedOutsideBand) +
           ", false shadow " + std::to_string(counts.falseShadowOutsideBand) + ", false lit " +
           std::to_string(counts.falseLitOutsideBand) + ", " + std::to_string(100.0 * counts.misclassifiedOutsideBand()) + "%";
}

TEST(Cascades, FieldAgreesWithEmbreeInEveryCascade) {
    auto context = testing::makeValidatedContext();
    const Scene scene = study::cascadeFieldScene();
    ShadowSettings shadows;
    const testing::ShadowRun run =
        testing::renderAndValidateShadows(*context, scene, testing::shadowRenderSettings(320, 180, shadows));
    testing::saveShadowRun("cascades-field", run);
    testing::saveTestImage("cascades-field-cascades", report::cascadeOverlay(run.image, run.factors.sunCascades));
    if (run.validation.sun) {
        testing::saveTestImage("cascades-field-mismatch-sun", report::mismatchMap(run.validation.sun->verdicts, run.validation.sun->inBand,
                                                                                run.validation.width, run.validation.height));
    }
    ASSERT_EQ(run.plan.cascades.count, 4u);
    ASSERT_TRUE(run.validation.sun.has_value());
    const reference::SunShadowValidation& sun = *run.validation.sun;
    std::printf("[ cascades ] sun: %s\n", describe(sun.counts).c_str());
    // Real shadows in every cascade, so that agreement means something.
    std::vector<size_t> shadowed(sun.cascades.size(), 0);
    for (size_t p = 0; p < sun.verdicts.size(); ++p) {
        const uint8_t cascade = run.factors.sunCascades[p];
        if (cascade > 0 && sun.verdicts[p] == reference::PixelVerdict::AgreeShadow) ++shadowed[cascade - 1];
    }
    for (uint32_t i = 0; i < sun.cascades.size(); ++i) {
        EXPECT_GT(shadowed[i], 20u) << "cascade " << i << " shows no shadow to compare";
        std::printf("[ cascades ] cascade %u (to %.1f m, %u texels, %.3f m): %s\n", i, double(run.plan.cascades.splits[i]),
                    run.plan.views[run.plan.cascades.firstView + i].resolution, double(cascadeTexelSize(run.plan, i)),
                    describe(sun.cascades[i]).c_str());
        EXPECT_GT(sun.cascades[i].comparedOutsideBand, 500u) << "cascade " << i;
        EXPECT_LE(sun.cascades[i].misclassifiedOutsideBand(), 0.005) << "cascade " << i;
    }
    std::printf("[ cascades ] split band: %s\n", describe(sun.splitBand).c_str());
    testing::expectNoValidationMessages(*context);
}

}  // namespace
}  // namespace punctual

namespace punctual {
namespace {

// The check can fail: one cascade of 16 texels over the whole 200 m misclassifies far more.
TEST(Cascades, OneCoarseCascadeFailsTheBound) {
    auto context = testing::makeValidatedContext();
    const Scene scene = study::cascadeFieldScene();
    ShadowSettings shadows;
    shadows.resolution = 16;
    shadows.cascades.count = 1;
    const testing::ShadowRun run =
        testing::renderAndValidateShadows(*context, scene, testing::shadowRenderSettings(320, 180, shadows));
    ASSERT_TRUE(run.validation.sun.has_value());
    EXPECT_GT(run.validation.sun->counts.misclassifiedOutsideBand(), 0.005);
    std::printf("[ cascades ] one cascade of 16 texels: %s\n", describe(run.validation.sun->counts).c_str());
    testing::expectNoValidationMessages(*context);
}

}  // namespace
}  // namespace punctual

namespace punctual {
namespace {

// The built-in outdoor street (the target scene) at a test's size: every cascade within
// the 0.5% the issue asks at 1280x720 (bench/RESULTS.md has that measurement).
TEST(Cascades, OutdoorAgreesWithEmbreeInEveryCascade) {
    auto context = testing::makeValidatedContext();
    const Scene scene = makeOutdoorScene();
    const testing::ShadowRun run =
        testing::renderAndValidateShadows(*context, scene, testing::shadowRenderSettings(320, 180, ShadowSettings{}));
    testing::saveShadowRun("cascades-outdoor", run);
    ASSERT_TRUE(run.validation.sun.has_value());
    const reference::SunShadowValidation& sun = *run.validation.sun;
    ASSERT_EQ(sun.cascades.size(), 4u);
    std::printf("[ cascades ] outdoor sun: %s\n", describe(sun.counts).c_str());
    for (uint32_t i = 0; i < 4; ++i) {
        std::printf("[ cascades ] outdoor cascade %u: %s\n", i, describe(sun.cascades[i]).c_str());
        EXPECT_GT(sun.cascades[i].comparedOutsideBand, 100u) << "cascade " << i;
        EXPECT_LE(sun.cascades[i].misclassifiedOutsideBand(), 0.005) << "cascade " << i;
    }
    testing::expectNoValidationMessages(*context);
}

}  // namespace
}  // namespace punctual
