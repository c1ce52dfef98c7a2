// Materials on the GPU against the Embree reference: alpha-masked casters (the checkerboard
// shadow), alpha-masked surfaces, emission, single-sided faces, mipmaps, samplers, texture
// transforms and the second texture coordinate set.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include <glm/gtc/matrix_transform.hpp>

#include "gpu_test_support.h"
#include "reference/reference_renderer.h"
#include "reference_agreement.h"
#include "reference_test_support.h"
#include "scene/study_scenes.h"
#include "material_test_scenes.h"
#include "shadow_test_runs.h"

namespace punctual {
namespace {

using reference::PixelVerdict;
using reference::ReferenceRenderer;
using reference::SurfaceHit;
using study::addQuad;
using testing::checkerTexture;
using testing::lookAt;
using testing::matte;

// ---- alpha-masked casters: the checkerboard shadow ----------------------------------------------

constexpr glm::vec3 kSpotPosition{0.0f, 4.0f, 0.0f};
constexpr float kCardHeight = 1.5f;
constexpr float kCardHalf = 1.0f;
constexpr uint32_t kChecks = 4;  // checks along each side of the card

// A floor, a 2 x 2 m card 1.5 m above it whose base colour is a 4 x 4 checkerboard with alpha 1
// and 0 (alphaMode `mode`, cutoff 0.5), and a spot straight above it. The card's shadow on the
// floor is the card scaled by 4 / (4 - 1.5) = 1.6: 3.2 m wide, checks 0.8 m wide.
Scene checkerCardScene(AlphaMode mode) {
    Scene scene;
    scene.source = "masked checker card";
    scene.materials.push_back(matte("floor", glm::vec3(0.6f)));
    Material card = matte("card", glm::vec3(0.9f, 0.5f, 0.2f));
    card.alphaMode = mode;
    card.alphaCutoff = 0.5f;
    card.doubleSided = true;
    card.baseColorTexture.image = 0;
    card.baseColorTexture.sampler.magFilter = TextureFilter::Nearest;
    scene.materials.push_back(card);
    scene.textures.push_back(checkerTexture(8, 8 / kChecks, glm::u8vec4(255, 255, 255, 0)));
    study::addBox(scene, glm::vec3(0.0f, -0.1f, 0.0f), glm::vec3(20.0f, 0.2f, 20.0f), 0);
    addQuad(scene, "card", glm::vec3(0.0f, kCardHeight, 0.0f), glm::vec3(1, 0, 0), glm::vec3(0, 0, 1), kCardHalf,
            kCardHalf, 1);
    scene.lights.push_back(study::spotLight(kSpotPosition, glm::vec3(0, -1, 0), 12.0f, 60.0f, glm::radians(50.0f),
                                            glm::radians(60.0f)));
    lookAt(scene, glm::vec3(0.0f, 7.0f, 4.0f), glm::vec3(0.0f, 0.0f, 0.3f), 0.9f);
    scene.computeBounds();
    return scene;
}

// Which check of the card the ray from the spot to a floor point crosses, and whether that check
// is opaque; nullopt for points whose ray misses the card or passes within 15% of a check's
// edge (the shadow map's texels and filter blur there).
std::optional<bool> checkUnder(glm::vec3 floorPoint) {
    const float t = (kSpotPosition.y - kCardHeight) / (kSpotPosition.y - floorPoint.y);
    const glm::vec3 onCard = kSpotPosition + t * (floorPoint - kSpotPosition);
    const glm::vec2 uv = (glm::vec2(onCard.x, onCard.z) + kCardHalf) / (2.0f * kCardHalf) * float(kChecks);
    if (uv.x < 0.0f || uv.y < 0.0f || uv.x >= float(kChecks) || uv.y >= float(kChecks)) return std::nullopt;
    const glm::vec2 inCheck = glm::fract(uv);
    if (glm::any(glm::lessThan(inCheck, glm::vec2(0.15f))) || glm::any(glm::greaterThan(inCheck, glm::vec2(0.85f))))
        return std::nullopt;
    return (int(uv.x) + int(uv.y)) % 2 == 0;  // texture check (0, 0) is the opaque kind
}

struct CheckerShadow {
    size_t opaquePixels = 0, opaqueDark = 0;
    size_t clearPixels = 0, clearDark = 0;
};

CheckerShadow checkerShadowOnTheFloor(const testing::ShadowRun& run) {
    CheckerShadow result;
    const ShadowFactorImage& factors = run.factors;
    for (size_t i = 0; i < size_t(factors.width) * factors.height; ++i) {
        if (!factors.covered[i] || factors.positions[i].y > 0.01f) continue;  // the floor's top only
        const std::optional<bool> opaque = checkUnder(factors.positions[i]);
        const uint8_t factor = factors.factors[i * factors.slots];
        if (!opaque || factor == PUNCTUAL_SHADOW_FACTOR_NOT_REACHED) continue;
        const bool dark = factor < 127;
        if (*opaque) {
            ++result.opaquePixels;
            result.opaqueDark += dark;
        } else {
            ++result.clearPixels;
            result.clearDark += dark;
        }
    }
    return result;
}

TEST(AlphaMaskedCasters, ACheckerCardCastsACheckerShadowThatEmbreeAgreesWith) {
    auto context = testing::makeValidatedContext();
    ShadowSettings shadows;
    const testing::ShadowRun run = testing::renderAndValidateShadows(
        *context, checkerCardScene(AlphaMode::Mask), testing::shadowRenderSettings(320, 240, shadows));
    testing::saveShadowRun("masked-checker-card", run);
    const CheckerShadow shadow = checkerShadowOnTheFloor(run);
    // The shadow's 16 checks cover a 3.2 m square of the floor (0.8 m each; their cores, 0.56 m, count).
    ASSERT_GT(shadow.opaquePixels, 1000u);
    ASSERT_GT(shadow.clearPixels, 1000u);
    EXPECT_GT(double(shadow.opaqueDark) / double(shadow.opaquePixels), 0.99) << "opaque checks must shadow";
    EXPECT_LT(double(shadow.clearDark) / double(shadow.clearPixels), 0.01) << "clear checks must let light through";
    // Embree tests alpha too (its filter functions): the GPU agrees with it outside the edge band.
    ASSERT_EQ(run.validation.lights.size(), 1u);
    const reference::ShadowCounts& counts = run.validation.lights[0].counts;
    ASSERT_GT(counts.comparedOutsideBand, 20000u);
    EXPECT_LT(counts.misclassifiedOutsideBand(), 0.002) << counts.falseShadowOutsideBand << " false shadow, "
                                                        << counts.falseLitOutsideBand << " false lit";
    testing::expectNoValidationMessages(*context);
}

TEST(AlphaMaskedCasters, TheSameCardOpaqueCastsASolidShadow) {
    // The control: without MASK the clear checks shadow too, so the test above can fail.
    auto context = testing::makeValidatedContext();
    const testing::ShadowRun run = testing::renderAndValidateShadows(
        *context, checkerCardScene(AlphaMode::Opaque), testing::shadowRenderSettings(320, 240, ShadowSettings{}));
    const CheckerShadow shadow = checkerShadowOnTheFloor(run);
    ASSERT_GT(shadow.clearPixels, 1000u);
    EXPECT_GT(double(shadow.clearDark) / double(shadow.clearPixels), 0.99);
    EXPECT_LT(run.validation.lights[0].counts.misclassifiedOutsideBand(), 0.002) << "Embree sees the opaque card too";
    testing::expectNoValidationMessages(*context);
}

TEST(AlphaMaskedCasters, ThePointLightsCubeAndTheSunsCascadesTestAlphaToo) {
    auto context = testing::makeValidatedContext();
    Scene scene = checkerCardScene(AlphaMode::Mask);
    scene.lights = {study::pointLight(kSpotPosition, 12.0f, 60.0f), study::sunLight(glm::vec3(0.2f, -1.0f, 0.1f), 3.0f)};
    const testing::ShadowRun run =
        testing::renderAndValidateShadows(*context, scene, testing::shadowRenderSettings(320, 240, ShadowSettings{}));
    testing::saveShadowRun("masked-checker-card-point-sun", run);
    ASSERT_EQ(run.validation.lights.size(), 1u);
    const reference::ShadowCounts& point = run.validation.lights[0].counts;
    ASSERT_GT(point.comparedOutsideBand, 20000u);
    EXPECT_LT(point.misclassifiedOutsideBand(), 0.005);
    ASSERT_TRUE(run.validation.sun.has_value());
    const reference::ShadowCounts& sun = run.validation.sun->counts;
    ASSERT_GT(sun.comparedOutsideBand, 20000u);
    EXPECT_LT(sun.misclassifiedOutsideBand(), 0.005);
    // Were the cube faces or the cascades drawn without the alpha test, the clear checks' light
    // (Embree: lit) would be dark on the GPU: several percent of the compared pixels.
    testing::expectNoValidationMessages(*context);
}

// ---- the camera's view of materials ---------------------------------------------------------------

TEST(MaterialImages, MaskedSurfacesMatchTheReference) {
    auto context = testing::makeValidatedContext();
    Scene scene = checkerCardScene(AlphaMode::Mask);
    scene.lights = {study::sunLight(glm::vec3(0.3f, -1.0f, -0.2f), 3.0f)};
    const testing::GpuFrame gpu = testing::renderGpu(*context, scene, 240, 180);
    const ReferenceRenderer reference(scene, testing::unshadowed(240, 180));
    std::vector<SurfaceHit> hits;
    const ImageRgba8 image = reference.render(nullptr, &hits);
    // The floor shows through the clear checks in both.
    size_t floorThroughCard = 0;
    for (const SurfaceHit& hit : hits) floorThroughCard += hit.hit && hit.object == 0 && std::abs(hit.position.x) < 0.9f &&
                                                           std::abs(hit.position.z) < 0.6f;
    EXPECT_GT(floorThroughCard, 500u);
    testing::expectAgreement(testing::compare(gpu.image, gpu.depth, gpu.projection, image, hits, "materials-masked"),
                             "masked card");
    testing::expectNoValidationMessages(*context);
}

// An emissive quad (factor x strength, times an emissive texture read through TEXCOORD_1 and a
// KHR_texture_transform), a single-sided quad seen from behind, a double-sided one seen from
// behind, and a mirrored single-sided one, all under a dim sun.
Scene materialPanelsScene() {
    Scene scene;
    scene.source = "material panels";
    scene.materials.push_back(matte("floor", glm::vec3(0.5f)));
    Material glow = matte("glow", glm::vec3(0.1f));
    glow.emissiveFactor = glm::vec3(1.0f, 0.6f, 0.3f);
    glow.emissiveStrength = 2.0f;
    glow.emissiveTexture.image = 0;
    glow.emissiveTexture.texCoord = 1;
    glow.emissiveTexture.transform.rotation = 0.4f;
    glow.emissiveTexture.transform.scale = glm::vec2(1.5f, 2.0f);
    glow.emissiveTexture.transform.offset = glm::vec2(0.25f, 0.1f);
    glow.emissiveTexture.sampler.wrapU = TextureWrap::MirroredRepeat;
    scene.materials.push_back(glow);
    Material singleSided = matte("single-sided", glm::vec3(0.8f, 0.2f, 0.2f));
    scene.materials.push_back(singleSided);
    Material doubleSided = matte("double-sided", glm::vec3(0.2f, 0.8f, 0.2f));
    doubleSided.doubleSided = true;
    scene.materials.push_back(doubleSided);
    scene.textures.push_back(checkerTexture(16, 4, glm::u8vec4(40, 90, 200, 255)));
    study::addBox(scene, glm::vec3(0.0f, -0.1f, 0.0f), glm::vec3(12.0f, 0.2f, 12.0f), 0);
    // Facing the camera (+Z): u = +X, v = +Y.
    addQuad(scene, "glow", glm::vec3(-1.6f, 1.0f, 0.0f), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), 0.7f, 0.7f, 1, 2.0f);
    // Facing away (-Z): u = -X, v = +Y. Single-sided: invisible; double-sided: seen from behind.
    addQuad(scene, "away single", glm::vec3(0.0f, 1.0f, 0.0f), glm::vec3(-1, 0, 0), glm::vec3(0, 1, 0), 0.6f, 0.7f, 2);
    addQuad(scene, "away double", glm::vec3(1.5f, 1.0f, 0.0f), glm::vec3(-1, 0, 0), glm::vec3(0, 1, 0), 0.6f, 0.7f, 3);
    // Mirrored by their transforms (x -> -x), which turns their winding clockwise: glTF then takes
    // the clockwise side as the front, so each still faces where its normal points. Facing away
    // (wound with normal -Z): culled; facing the camera: drawn.
    const glm::mat4 mirror = glm::scale(glm::mat4(1.0f), glm::vec3(-1.0f, 1.0f, 1.0f));
    addQuad(scene, "mirrored away", glm::vec3(-1.6f, 1.0f, -2.0f), glm::vec3(-1, 0, 0), glm::vec3(0, 1, 0), 0.7f,
            0.5f, 2, 1.0f, mirror);
    addQuad(scene, "mirrored facing", glm::vec3(-0.2f, 0.3f, -1.0f), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), 0.4f,
            0.25f, 2, 1.0f, mirror);
    scene.lights = {study::sunLight(glm::vec3(0.2f, -1.0f, -0.4f), 1.0f)};
    lookAt(scene, glm::vec3(0.0f, 2.0f, 5.0f), glm::vec3(0.0f, 0.8f, 0.0f), 0.9f);
    scene.computeBounds();
    return scene;
}

TEST(MaterialImages, EmissionSidednessAndTextureTransformsMatchTheReference) {
    auto context = testing::makeValidatedContext();
    const Scene scene = materialPanelsScene();
    const testing::GpuFrame gpu = testing::renderGpu(*context, scene, 240, 160);
    const ReferenceRenderer reference(scene, testing::unshadowed(240, 160));
    std::vector<SurfaceHit> hits;
    const ImageRgba8 image = reference.render(nullptr, &hits);
    size_t byObject[6] = {};
    for (const SurfaceHit& hit : hits)
        if (hit.hit) ++byObject[hit.object];
    EXPECT_GT(byObject[1], 1000u) << "the emissive panel is in view";
    EXPECT_EQ(byObject[2], 0u) << "a single-sided panel seen from behind is not drawn";
    EXPECT_GT(byObject[3], 1000u) << "a double-sided one is";
    EXPECT_EQ(byObject[4], 0u) << "a mirrored single-sided panel facing away is not drawn";
    EXPECT_GT(byObject[5], 150u) << "a mirrored single-sided panel facing the camera is";
    // Emission dominates the dim sun: the panel is bright in both images.
    size_t bright = 0;
    for (size_t i = 0; i < hits.size(); ++i)
        if (hits[i].hit && hits[i].object == 1) bright += image.pixels[4 * i] > 150;
    EXPECT_GT(bright, byObject[1] / 2);
    testing::expectAgreement(testing::compare(gpu.image, gpu.depth, gpu.projection, image, hits, "materials-panels"),
                             "panels");
    testing::expectNoValidationMessages(*context);
}

// ---- mipmaps ----------------------------------------------------------------------------------------

// A floor textured with a fine checkerboard (1-texel checks, 128 texels repeated 24 times across
// 24 m), seen at a grazing angle, so that most of it is minified by 4x to 100x.
Scene receedingCheckerScene(bool mipmaps) {
    Scene scene;
    scene.source = "receding checker";
    Material floor = matte("checker floor", glm::vec3(1.0f));
    floor.baseColorTexture.image = 0;
    floor.baseColorTexture.sampler.mipmaps = mipmaps;
    scene.materials.push_back(floor);
    scene.textures.push_back(checkerTexture(128, 1, glm::u8vec4(0, 0, 0, 255)));
    addQuad(scene, "floor", glm::vec3(0.0f, 0.0f, -10.0f), glm::vec3(1, 0, 0), glm::vec3(0, 0, -1), 12.0f, 12.0f, 0,
            24.0f);
    scene.lights = {study::sunLight(glm::vec3(0.0f, -1.0f, 0.0f), 2.0f)};
    lookAt(scene, glm::vec3(0.0f, 1.5f, 2.0f), glm::vec3(0.0f, 0.0f, -8.0f), 0.9f);
    scene.computeBounds();
    return scene;
}

// The spread of the image's values over the far half of the floor (rows above the frame's
// middle that hit it): the standard deviation of the red channel.
double farFloorSpread(const ImageRgba8& image, const std::vector<SurfaceHit>& hits) {
    double sum = 0.0, sumSquares = 0.0;
    size_t count = 0;
    for (uint32_t y = 0; y < image.height; ++y)
        for (uint32_t x = 0; x < image.width; ++x) {
            const SurfaceHit& hit = hits[size_t(y) * image.width + x];
            if (!hit.hit || hit.position.z > -10.0f) continue;
            const double value = image.at(x, y)[0];
            sum += value;
            sumSquares += value * value;
            ++count;
        }
    if (count < 100) return -1.0;
    const double mean = sum / double(count);
    return std::sqrt(std::max(sumSquares / double(count) - mean * mean, 0.0));
}

TEST(Mipmaps, MinifiedTexturesAreFilteredAndMatchTheReference) {
    auto context = testing::makeValidatedContext();
    const Scene scene = receedingCheckerScene(true);
    const testing::GpuFrame gpu = testing::renderGpu(*context, scene, 240, 160);
    const ReferenceRenderer reference(scene, testing::unshadowed(240, 160));
    std::vector<SurfaceHit> hits;
    const ImageRgba8 image = reference.render(nullptr, &hits);
    // The far floor is an even grey in both: its 1-texel checks average out in the mip chain.
    const double gpuSpread = farFloorSpread(gpu.image, hits);
    const double referenceSpread = farFloorSpread(image, hits);
    EXPECT_GE(gpuSpread, 0.0);
    EXPECT_LT(gpuSpread, 8.0);
    EXPECT_LT(referenceSpread, 8.0);
    // The level of detail comes from the GPU's 2x2 quad differences and from the reference's ray
    // differentials: close, not equal, so a few codes of tolerance where levels blend.
    const testing::Agreement agreement =
        testing::compare(gpu.image, gpu.depth, gpu.projection, image, hits, "materials-mipmaps", 6);
    EXPECT_GE(agreement.withinFraction(), 0.99) << agreement.pixels - agreement.within << " pixels differ";
    testing::expectNoValidationMessages(*context);
}

TEST(Mipmaps, WithoutMipmapsTheSameFloorAliases) {
    // The control: glTF's minFilter LINEAR (no mipmaps) reads level 0 only, and the far floor
    // shows the checks' aliasing, so the test above can fail.
    auto context = testing::makeValidatedContext();
    const Scene scene = receedingCheckerScene(false);
    const testing::GpuFrame gpu = testing::renderGpu(*context, scene, 240, 160);
    const ReferenceRenderer reference(scene, testing::unshadowed(240, 160));
    std::vector<SurfaceHit> hits;
    const ImageRgba8 image = reference.render(nullptr, &hits);
    EXPECT_GT(farFloorSpread(gpu.image, hits), 20.0);
    EXPECT_GT(farFloorSpread(image, hits), 20.0);
    testing::expectNoValidationMessages(*context);
}

}  // namespace
}  // namespace punctual
