// The statistics variant's shadow work counters (gpu_types.h packPixelWork): every filtered
// shadow read and the taps it issued, per pixel. They are what the bench reports beside the
// times, so they must count what the shader does, on any device.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "gpu_test_support.h"
#include "metrics/culling_stats.h"
#include "render/renderer.h"
#include "scene/default_scene.h"

namespace punctual {
namespace {

using render::LightListMethod;

LightStatsImage pixelWork(vk::Context& context, const Scene& scene, LightListMethod method, const ShadowSettings& shadows) {
    render::RenderSettings settings = testing::renderSettings(192, 108);
    settings.method = method;
    settings.shadows = shadows;
    settings.collectLightStats = true;
    render::Renderer renderer(context, scene, settings);
    renderer.render(1, 0);
    return renderer.readLightStats();
}

TEST(PixelWork, NoShadowsTakeNoLookups) {
    auto context = testing::makeValidatedContext();
    ShadowSettings off;
    off.enabled = false;
    const LightStatsImage stats = pixelWork(*context, makeDefaultScene(), LightListMethod::Brute, off);
    size_t covered = 0;
    for (size_t i = 0; i < stats.covered.size(); ++i) {
        if (!stats.covered[i]) continue;
        ++covered;
        EXPECT_EQ(stats.shadowLookups[i], 0u) << i;
        EXPECT_EQ(stats.shadowTaps[i], 0u) << i;
    }
    EXPECT_GT(covered, 1000u);  // something was looked at
    testing::expectNoValidationMessages(*context);
}

// Each filtered read issues the filter's taps (lights/shadow_filters.h: hardware compares for
// the footprints, samples for the disk), and a pixel reads at most once per light that reaches
// it, plus twice for the sun (its blend zone reads two cascades; the hall has no sun).
TEST(PixelWork, EveryLookupIssuesTheFiltersTaps) {
    auto context = testing::makeValidatedContext();
    const Scene scene = makeDefaultScene();
    // One filter of each kernel (shadow_kernels.h): the first in the table.
    std::set<uint32_t> kernels;
    for (const ShadowFilterInfo& filter : kShadowFilters) {
        if (!kernels.insert(filter.kernel.value).second) continue;
        ShadowSettings shadows;
        shadows.filter = filter.value;
        SCOPED_TRACE(filter.name);
        const LightStatsImage stats = pixelWork(*context, scene, LightListMethod::Brute, shadows);
        uint64_t lookups = 0;
        uint64_t taps = 0;
        for (size_t i = 0; i < stats.covered.size(); ++i) {
            if (!stats.covered[i]) continue;
            EXPECT_LE(stats.shadowLookups[i], stats.affecting[i] + 2u) << i;
            EXPECT_EQ(stats.shadowTaps[i], stats.shadowLookups[i] * shadows.filterTaps()) << i;
            lookups += stats.shadowLookups[i];
            taps += stats.shadowTaps[i];
        }
        EXPECT_GT(lookups, 10000u);  // the hall's lights are shadowed: most pixels read several
        EXPECT_EQ(taps, lookups * shadows.filterTaps());
    }
    testing::expectNoValidationMessages(*context);
}

// Culling is lossless, and a light that does not reach a pixel takes no lookup there: the light
// grid methods' lists make exactly the reads brute force makes, pixel by pixel, while testing
// fewer lights.
TEST(PixelWork, CulledMethodsReadTheShadowsBruteForceReads) {
    auto context = testing::makeValidatedContext();
    const Scene scene = makeDefaultScene();
    const ShadowSettings shadows;
    const LightStatsImage brute = pixelWork(*context, scene, LightListMethod::Brute, shadows);
    for (LightListMethod method : render::gridMethods()) {
        SCOPED_TRACE(render::methodName(method));
        const LightStatsImage culled = pixelWork(*context, scene, method, shadows);
        size_t compared = 0;
        for (size_t i = 0; i < brute.covered.size(); ++i) {
            if (!brute.covered[i]) continue;
            ++compared;
            EXPECT_EQ(culled.shadowLookups[i], brute.shadowLookups[i]) << i;
            EXPECT_EQ(culled.shadowTaps[i], brute.shadowTaps[i]) << i;
        }
        EXPECT_GT(compared, 1000u);
        EXPECT_LT(computeCullingStats(culled).testedPerPixel, computeCullingStats(brute).testedPerPixel);
    }
    testing::expectNoValidationMessages(*context);
}

}  // namespace
}  // namespace punctual
