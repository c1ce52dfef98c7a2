// The scenes in data/ load, render bit-identically with every conservative light list, and cast
// shadows that agree with Embree.
#include <gtest/gtest.h>

#include "gpu_test_support.h"
#include "reference/embree_scene.h"
#include "reference/shadow_validation.h"
#include "render/renderer.h"
#include "scene/gltf_loader.h"

namespace punctual {
namespace {

TEST(ShippedScenes, SmallRoomRendersAndItsShadowsValidate) {
    const Scene scene = loadGltf(std::string(PUNCTUAL_DATA_DIR) + "/small-room.gltf");
    EXPECT_TRUE(scene.cameraFromFile);
    EXPECT_EQ(scene.objects.size(), 4u);
    ASSERT_EQ(scene.lights.size(), 5u);
    EXPECT_TRUE(scene.lights[4].rangeDerived);  // the green point light has no range

    auto context = testing::makeValidatedContext();
    render::RenderSettings settings;
    settings.width = 160;
    settings.height = 90;
    settings.shadows.resolution = 512;
    settings.method = render::LightListMethod::Brute;
    settings.collectShadowFactors = true;
    render::Renderer brute(*context, scene, settings);
    const ImageRgba8 image = brute.render(1, 0).image;
    EXPECT_GT(testing::fractionBrighterThan(image, 20), 0.3);
    EXPECT_EQ(brute.shadowPlan().shadowedSpots, 3u);
    EXPECT_EQ(brute.shadowPlan().shadowedPoints, 2u);

    const reference::EmbreeScene embree(scene);
    const reference::ShadowValidation validation = reference::validateShadows(
        embree, brute.readShadowFactors(), brute.lights(), brute.shadowPlan());
    EXPECT_GT(validation.overall.compared, 5000u);
    EXPECT_LE(validation.overall.misclassifiedOutsideBand(), 0.01);

    for (render::LightListMethod method : render::gridMethods()) {
        settings.method = method;
        settings.collectShadowFactors = false;
        render::Renderer culled(*context, scene, settings);
        EXPECT_TRUE(culled.render(1, 0).image.pixels == image.pixels) << render::methodName(method);
    }
    testing::expectNoValidationMessages(*context);
}

}  // namespace
}  // namespace punctual
