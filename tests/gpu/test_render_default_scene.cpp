// The default scene rendered through the whole brute-force frame: lit, deterministic, and
// without validation messages; its lights overlap as a many-light scene should.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/check.h"
#include "culling.h"
#include "gpu_test_support.h"
#include "lights/light_setup.h"
#include "render/renderer.h"
#include "scene/default_scene.h"
#include "shading.h"

namespace punctual {
namespace {

render::RenderSettings smallSettings() { return testing::renderSettings(320, 180); }

TEST(RenderDefaultScene, IsLitDeterministicAndValidationClean) {
    auto context = testing::makeValidatedContext();
    const Scene scene = makeDefaultScene();

    render::Renderer first(*context, scene, smallSettings());
    const render::FrameResult a = first.render(2);
    render::Renderer second(*context, scene, smallSettings());
    const render::FrameResult b = second.render(1);

    ASSERT_EQ(a.image.width, 320u);
    ASSERT_EQ(a.image.height, 180u);
    // Lit: most of the frame shows lit geometry, and the average brightness is mid-range, not
    // black and not blown out.
    EXPECT_GT(testing::fractionBrighterThan(a.image, 20), 0.6);
    const double luma = testing::meanLuma(a.image);
    EXPECT_GT(luma, 0.2);
    EXPECT_LT(luma, 0.85);
    // Bit-identical across frames and across renderer instances.
    EXPECT_TRUE(a.image.pixels == b.image.pixels);
    EXPECT_EQ(first.lights().spotCount, 64u);
    EXPECT_EQ(first.lights().pointCount, 32u);
    EXPECT_GT(a.medianMs.of("forward"), 0.0);
    EXPECT_GE(a.medianMs.total, a.medianMs.of("depth") + a.medianMs.of("forward"));
    testing::expectNoValidationMessages(*context);
}

// Every pass of the frame is timed under its own name, in frame order, and a pass with no work
// (culling under brute force) reports 0. Asking for a debug output the settings did not request
// is a caller's bug: an internal error, not a user error.
TEST(RenderDefaultScene, TimesEveryPassByNameAndRejectsUnrequestedDebugOutputs) {
    auto context = testing::makeValidatedContext();
    const Scene scene = makeDefaultScene();
    render::RenderSettings settings = smallSettings();
    settings.method = render::LightListMethod::Brute;
    render::Renderer renderer(*context, scene, settings);
    const render::FrameResult result = renderer.render(1);
    const std::vector<std::string> names = {"depth",   "transparent_depth", "culling", "shadows",
                                            "forward", "transparent",       "tonemap"};
    EXPECT_EQ(renderer.passNames(), names);
    ASSERT_EQ(result.medianMs.passes.size(), names.size());
    double sum = 0.0;
    for (size_t i = 0; i < names.size(); ++i) {
        EXPECT_EQ(result.medianMs.passes[i].first, names[i]);
        sum += result.medianMs.passes[i].second;
    }
    EXPECT_EQ(result.medianMs.of("culling"), 0.0);  // brute force culls nothing
    EXPECT_EQ(result.medianMs.of("transparent_depth"), 0.0);  // the hall has nothing transparent
    EXPECT_EQ(result.medianMs.of("transparent"), 0.0);
    EXPECT_GT(result.medianMs.of("shadows"), 0.0);
    EXPECT_EQ(result.medianMs.of("no such pass"), 0.0);
    EXPECT_GE(result.medianMs.total, sum * 0.999);  // the passes lie inside the frame
    EXPECT_THROW(renderer.readLightStats(), InternalError);
    EXPECT_THROW(renderer.readShadowFactors(), InternalError);
    testing::expectNoValidationMessages(*context);
}

// On average at least 4 lights reach each lit pixel of the default view, so that no culling
// method wins merely because lights are small. Positions come from the GPU's own depth buffer.
TEST(RenderDefaultScene, AtLeastFourLightsReachEachLitPixelOnAverage) {
    auto context = testing::makeValidatedContext();
    const Scene scene = makeDefaultScene();
    render::Renderer renderer(*context, scene, smallSettings());
    renderer.render(1);
    const std::vector<float> depth = renderer.readDepth();
    const glm::mat4 inverseViewProjection = glm::inverse(renderer.projection() * renderer.view());
    const FrameLights& lights = renderer.lights();

    size_t litPixels = 0;
    size_t reaching = 0;
    const uint32_t width = renderer.settings().width;
    const uint32_t height = renderer.settings().height;
    for (uint32_t y = 0; y < height; ++y) {
        for (uint32_t x = 0; x < width; ++x) {
            const float d = depth[size_t(y) * width + x];
            if (gpu::isBackgroundDepth(d)) continue;  // background (the clear value)
            const glm::vec4 ndc((float(x) + 0.5f) / float(width) * 2.0f - 1.0f,
                                (float(y) + 0.5f) / float(height) * 2.0f - 1.0f, d, 1.0f);
            const glm::vec4 world = inverseViewProjection * ndc;
            const glm::vec3 position = glm::vec3(world) / world.w;
            size_t count = 0;
            for (const gpu::GpuPunctualLight& light : lights.packed) {
                if (gpu::punctualAttenuation(light, position) > 0.0f) ++count;
            }
            if (count > 0) {
                ++litPixels;
                reaching += count;
            }
        }
    }
    ASSERT_GT(litPixels, size_t(width) * height / 2);
    const double average = double(reaching) / double(litPixels);
    EXPECT_GE(average, 4.0) << "average lights per lit pixel";
    testing::expectNoValidationMessages(*context);
}

}  // namespace
}  // namespace punctual
