// Transparent (alphaMode BLEND) surfaces: composited back to front over the opaque image as the
// reference composites them, lit by lossless light lists (tiled and clustered stay bit-identical
// to brute force even where a light reaches a pane but not the wall behind it), and casting
// shadows as --transparent-shadows says, which Embree's shadow rays follow.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "gpu_test_support.h"
#include "metrics/culling_stats.h"
#include "material_test_scenes.h"
#include "reference/reference_renderer.h"
#include "reference_agreement.h"
#include "reference_test_support.h"
#include "render/renderer.h"
#include "scene/study_scenes.h"
#include "shadow_test_runs.h"

namespace punctual {
namespace {

using reference::ReferenceRenderer;
using reference::SurfaceHit;
using render::LightListMethod;
using study::addQuad;
using testing::lookAt;
using testing::matte;

Scene glassPanesScene() { return study::glassPanesScene(9.0f); }  // the wall 12 m away

render::RenderSettings settingsFor(LightListMethod method) {
    render::RenderSettings settings = testing::renderSettings(256, 160);
    settings.method = method;
    settings.shadows.enabled = false;
    return settings;
}

ImageRgba8 renderImage(vk::Context& context, const Scene& scene, const render::RenderSettings& settings) {
    render::Renderer renderer(context, scene, settings);
    return renderer.render(1, 0).image;
}

size_t differingPixels(const ImageRgba8& a, const ImageRgba8& b) {
    size_t count = 0;
    for (size_t i = 0; i < a.pixels.size(); i += 4)
        count += a.pixels[i] != b.pixels[i] || a.pixels[i + 1] != b.pixels[i + 1] || a.pixels[i + 2] != b.pixels[i + 2];
    return count;
}

TEST(Transparency, CulledMethodsStayBitIdenticalToBruteForceOnGlassBeforeAFarWall) {
    auto context = testing::makeValidatedContext();
    const Scene scene = glassPanesScene();
    const ImageRgba8 brute = renderImage(*context, scene, settingsFor(LightListMethod::Brute));
    testing::saveTestImage("transparency-glass-brute", brute);
    for (const LightListMethod method : render::gridMethods()) {
        const ImageRgba8 culled = renderImage(*context, scene, settingsFor(method));
        EXPECT_EQ(differingPixels(culled, brute), 0u) << methodInfo(method).name;
    }
    testing::expectNoValidationMessages(*context);
}

TEST(Transparency, WithTheOpaqueDepthAloneTiledCullingMissesTheGlasssLights) {
    // The control: the kernels fed the opaque depth only (as before the transparent span) cull the
    // lights that reach the panes but not the wall, so the test above can fail.
    auto context = testing::makeValidatedContext();
    const Scene scene = glassPanesScene();
    const ImageRgba8 brute = renderImage(*context, scene, settingsFor(LightListMethod::Brute));
    for (const LightListMethod method : render::gridMethods()) {
        // A culling that reads no depth (zbin-2d: its bins hold depth, per fragment) has nothing to miss.
        if (!gpu::cullFlagsReadDepth(methodInfo(method).cullFlags)) continue;
        render::RenderSettings settings = settingsFor(method);
        settings.opaqueCullingDepth = true;
        EXPECT_GT(differingPixels(renderImage(*context, scene, settings), brute), 200u) << methodInfo(method).name;
    }
    testing::expectNoValidationMessages(*context);
}

TEST(Transparency, LightStatisticsCountTransparentFragmentsAndTheLightsTheyMiss) {
    auto context = testing::makeValidatedContext();
    const Scene scene = glassPanesScene();
    for (const bool opaqueDepthOnly : {false, true}) {
        render::RenderSettings settings = settingsFor(LightListMethod::Tiled);
        settings.collectLightStats = true;
        settings.opaqueCullingDepth = opaqueDepthOnly;
        render::Renderer renderer(*context, scene, settings);
        const CullingStats stats = computeCullingStats(renderer.readLightStats());
        // Both panes cover about a tenth of the frame; where they overlap a pixel has two fragments.
        EXPECT_GT(stats.transparentFragments, 3000u);
        EXPECT_GT(stats.transparentAffectingPerFragment, 0.5);
        if (opaqueDepthOnly) {
            EXPECT_GT(stats.transparentFragmentsMissingLight, 200u) << "the control: the wall's depth alone culls them";
        } else {
            EXPECT_EQ(stats.transparentFragmentsMissingLight, 0u);
            EXPECT_EQ(stats.pixelsMissingLight, 0u);
        }
    }
    testing::expectNoValidationMessages(*context);
}

TEST(Transparency, PanesCompositeOverTheWallAsTheReferenceComposites) {
    auto context = testing::makeValidatedContext();
    const Scene scene = glassPanesScene();
    const testing::GpuFrame gpu = testing::renderGpu(*context, scene, 256, 160);
    const ReferenceRenderer reference(scene, testing::unshadowed(256, 160));
    std::vector<SurfaceHit> hits;
    const ImageRgba8 image = reference.render(nullptr, &hits);
    // The primary hits are the wall everywhere (the panes are passed), and the panes tint it: the
    // pixels through the blue pane are bluer than red, through the amber one redder than blue.
    size_t wallHits = 0;
    for (const SurfaceHit& hit : hits) wallHits += hit.hit && hit.object == 0;
    EXPECT_EQ(wallHits, hits.size());
    const uint8_t* throughBlue = gpu.image.at(60, 80);
    EXPECT_GT(throughBlue[2], throughBlue[0]);
    testing::expectAgreement(
        testing::compare(gpu.image, gpu.depth, gpu.projection, image, hits, "transparency-panes"), "panes");
    testing::expectNoValidationMessages(*context);
}

// ---- shadows of transparent casters ----------------------------------------------------------------

// A floor, a 2 x 2 m pane 1.5 m above it whose alpha is a checkerboard of 0.25 and 0.75, and a
// spot straight above.
Scene translucentCardScene() {
    Scene scene;
    scene.source = "translucent checker card";
    scene.materials.push_back(matte("floor", glm::vec3(0.6f)));
    Material card = matte("card", glm::vec3(0.9f, 0.5f, 0.2f));
    card.alphaMode = AlphaMode::Blend;
    card.doubleSided = true;
    card.baseColorTexture.image = 0;
    card.baseColorTexture.sampler.magFilter = TextureFilter::Nearest;
    scene.materials.push_back(card);
    Texture texture = testing::checkerTexture(8, 2, glm::u8vec4(255, 255, 255, 64));
    for (size_t i = 3; i < texture.rgba.size(); i += 4) texture.rgba[i] = texture.rgba[i] == 255 ? 191 : 64;
    scene.textures.push_back(texture);  // alpha 0.75 and 0.25 (levels 1.. are not read: magnified)
    study::addBox(scene, glm::vec3(0.0f, -0.1f, 0.0f), glm::vec3(20.0f, 0.2f, 20.0f), 0);
    addQuad(scene, "card", glm::vec3(0.0f, 1.5f, 0.0f), glm::vec3(1, 0, 0), glm::vec3(0, 0, 1), 1.0f, 1.0f, 1);
    scene.lights.push_back(study::spotLight(glm::vec3(0.0f, 4.0f, 0.0f), glm::vec3(0, -1, 0), 12.0f, 60.0f,
                                            glm::radians(50.0f), glm::radians(60.0f)));
    lookAt(scene, glm::vec3(0.0f, 7.0f, 4.0f), glm::vec3(0.0f, 0.0f, 0.3f), 0.9f);
    scene.computeBounds();
    return scene;
}

struct ModeRun {
    reference::ShadowCounts counts;
    size_t darkFloorPixels = 0;  // floor pixels the GPU shadows, under the card's shadow square
};

ModeRun runMode(vk::Context& context, TransparentShadows mode) {
    ShadowSettings shadows;
    shadows.transparent = mode;
    const testing::ShadowRun run =
        testing::renderAndValidateShadows(context, translucentCardScene(), testing::shadowRenderSettings(320, 240, shadows));
    testing::saveShadowRun(std::string("transparent-shadows-") + transparentShadowsName(mode), run);
    ModeRun result;
    result.counts = run.validation.lights.at(0).counts;
    const ShadowFactorImage& factors = run.factors;
    for (size_t i = 0; i < size_t(factors.width) * factors.height; ++i) {
        const glm::vec3 p = factors.positions[i];
        // The card's shadow from 4 m up: 1.6x the card, |x|, |z| < 1.6 on the floor.
        if (!factors.covered[i] || p.y > 0.01f || std::abs(p.x) > 1.5f || std::abs(p.z) > 1.5f) continue;
        const uint8_t factor = factors.factors[i * factors.slots];
        result.darkFloorPixels += factor != PUNCTUAL_SHADOW_FACTOR_NOT_REACHED && factor < 127;
    }
    return result;
}

TEST(TransparentShadows, EachModeCastsWhatItSaysAndEmbreeAgrees) {
    auto context = testing::makeValidatedContext();
    const ModeRun on = runMode(*context, TransparentShadows::On);
    const ModeRun clip = runMode(*context, TransparentShadows::Clip);
    const ModeRun dither = runMode(*context, TransparentShadows::Dither);
    const ModeRun off = runMode(*context, TransparentShadows::Off);
    // on: the whole square dark; clip: the 0.75 checks (half); off: none; dither: coverage ~ alpha,
    // which the tent filter turns into the 0.75 checks dark and the 0.25 ones lit.
    ASSERT_GT(on.darkFloorPixels, 5000u);
    EXPECT_NEAR(double(clip.darkFloorPixels) / double(on.darkFloorPixels), 0.5, 0.08);
    EXPECT_NEAR(double(dither.darkFloorPixels) / double(on.darkFloorPixels), 0.5, 0.15);
    EXPECT_EQ(off.darkFloorPixels, 0u);
    // Embree's shadow rays follow the same mode: the GPU agrees outside the edge band.
    for (const auto& [name, run] : {std::pair<const char*, const ModeRun&>{"on", on}, {"clip", clip}, {"off", off}}) {
        ASSERT_GT(run.counts.comparedOutsideBand, 20000u) << name;
        EXPECT_LT(run.counts.misclassifiedOutsideBand(), 0.003) << name;
    }
    // Dither's noise breaks the shadow into texels that the filter only partly averages out.
    EXPECT_LT(dither.counts.misclassifiedOutsideBand(), 0.05);
    testing::expectNoValidationMessages(*context);
}

}  // namespace
}  // namespace punctual
