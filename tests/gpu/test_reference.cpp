// The Embree reference as a ruler for the GPU: the two images agree wherever they must (all but
// silhouette pixels), and the check can fail. The reference's own tests (conventions, analytic
// visibility, determinism) need no GPU and are in tests/unit/test_reference.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>

#include <glm/gtc/matrix_transform.hpp>

#include "culling.h"
#include "culling_test_scenes.h"
#include "gpu_test_support.h"
#include "reference/reference_renderer.h"
#include "reference_agreement.h"
#include "reference_test_support.h"
#include "render/renderer.h"
#include "scene/default_scene.h"
#include "scene/gltf_loader.h"
#include "scene/study_scenes.h"

namespace punctual {
namespace {

using reference::ReferenceRenderer;
using reference::SurfaceHit;
using testing::Agreement;
using testing::compare;
using testing::expectAgreement;
using testing::GpuFrame;
using testing::greyMaterial;
using testing::renderGpu;
using testing::unshadowed;

// ---- the reference against the GPU ------------------------------------------------------------
// (Agreement, compare, renderGpu and expectAgreement: reference_agreement.h)

TEST(ReferenceImage, MatchesGpuBruteForceOnTheDefaultScene) {
    auto context = testing::makeValidatedContext();
    const Scene scene = makeDefaultScene();
    for (const auto& [width, height] : {std::pair<uint32_t, uint32_t>{320, 180}, {237, 161}}) {
        const std::string size = std::to_string(width) + "x" + std::to_string(height);
        const GpuFrame gpu = renderGpu(*context, scene, width, height);
        const ReferenceRenderer reference(scene, unshadowed(width, height));
        std::vector<SurfaceHit> hits;
        const ImageRgba8 image = reference.render(nullptr, &hits);
        EXPECT_GT(testing::fractionBrighterThan(image, 20), 0.6) << "a black frame would prove nothing";
        expectAgreement(compare(gpu.image, gpu.depth, gpu.projection, image, hits, "reference-default-" + size), size);

        // The check can fail: 10% more exposure in the reference breaks it.
        const ReferenceRenderer wrong(scene, unshadowed(width, height, 1.1f));
        const Agreement bad = compare(gpu.image, gpu.depth, gpu.projection, wrong.render(), hits, "reference-wrong-" + size);
        EXPECT_LT(bad.withinFraction(), 0.999) << size;
        EXPECT_GT(bad.offSilhouette, 0u) << size;
    }
    testing::expectNoValidationMessages(*context);
}

// A room seen from inside (every wall is a back face of a double-sided material, its normal must
// turn to the viewer on both paths), with a mirrored single-sided box (negative determinant: its world winding is reversed) and a
// rotated, non-uniformly scaled one (the inverse-transpose normal matrix matters).
TEST(ReferenceImage, MatchesGpuOnBackFacesAndMirroredObjects) {
    Scene scene;
    scene.source = "room";
    scene.materials.push_back(greyMaterial());
    scene.materials.back().doubleSided = true;  // the room's walls are seen from inside; the mirrored box is single-sided
    Material metal = greyMaterial();
    metal.baseColorFactor = glm::vec4(0.9f, 0.6f, 0.3f, 1.0f);
    metal.metallic = 1.0f;
    metal.roughness = 0.35f;
    scene.materials.push_back(metal);
    study::addBox(scene, glm::vec3(0.0f, 3.0f, 0.0f), glm::vec3(12.0f, 6.0f, 12.0f));
    Object mirrored;
    mirrored.mesh = appendBoxMesh(scene, "mirrored", glm::vec3(1.5f, 1.0f, 2.0f), 1);
    mirrored.model = glm::scale(glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(-2.0f, 1.0f, -1.0f)), 0.6f,
                                            glm::vec3(0.0f, 1.0f, 0.0f)),
                                glm::vec3(-1.0f, 1.0f, 1.0f));
    scene.objects.push_back(mirrored);
    Object squashed = mirrored;
    squashed.mesh = appendBoxMesh(scene, "squashed", glm::vec3(1.0f), 0);
    squashed.model = glm::scale(glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(2.0f, 1.2f, -2.0f)), 0.8f,
                                            glm::normalize(glm::vec3(1.0f, 1.0f, 0.0f))),
                                glm::vec3(2.5f, 0.7f, 1.2f));
    scene.objects.push_back(squashed);
    scene.lights.push_back(study::pointLight(glm::vec3(1.0f, 4.5f, 2.0f), 14.0f, 60.0f));
    scene.lights.push_back(testing::withColor(
        study::spotLight(glm::vec3(-3.0f, 5.0f, 3.0f), glm::vec3(0.3f, -1.0f, -0.6f), 14.0f, 120.0f, 0.3f, 0.6f),
        glm::vec3(0.4f, 0.7f, 1.0f)));
    scene.camera.view = glm::lookAtRH(glm::vec3(0.5f, 2.5f, 5.5f), glm::vec3(0.0f, 1.5f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f));
    scene.camera.zfar = 40.0f;
    scene.computeBounds();

    auto context = testing::makeValidatedContext();
    const GpuFrame gpu = renderGpu(*context, scene, 240, 160);
    const ReferenceRenderer reference(scene, unshadowed(240, 160));
    std::vector<SurfaceHit> hits;
    const ImageRgba8 image = reference.render(nullptr, &hits);
    size_t backFaces = 0;
    for (const SurfaceHit& hit : hits) backFaces += hit.backFace;
    EXPECT_GT(backFaces, hits.size() / 2) << "the room's inside must fill most of the frame";
    EXPECT_GT(testing::meanLuma(image), 0.1);
    expectAgreement(compare(gpu.image, gpu.depth, gpu.projection, image, hits, "reference-room"), "room");
    testing::expectNoValidationMessages(*context);
}

// A 2 x 2 m quad in the XZ plane with a 4 x 4 texture repeated twice across it (UVs 0..2:
// REPEAT wrapping and bilinear filtering across the wrap are both visible), a tinted base-colour
// factor, a sun from the side, and a camera looking down at it at an angle.
std::string writeTexturedQuad(const testing::TempFolder& folder) {
    ImageRgba8 texture;
    texture.width = 4;
    texture.height = 4;
    for (uint32_t i = 0; i < 16; ++i) {
        texture.pixels.insert(texture.pixels.end(), {uint8_t(80 + 55 * (i % 4)), uint8_t(240 - 40 * (i / 4)),
                                                     uint8_t(i % 2 ? 230 : 90), 255});
    }
    const std::string gltf = R"({
  "asset": {"version": "2.0"},
  "extensionsUsed": ["KHR_lights_punctual"],
  "extensions": {"KHR_lights_punctual": {"lights": [{"type": "directional", "intensity": 2.5}]}},
  "scene": 0,
  "scenes": [{"nodes": [0, 1, 2]}],
  "nodes": [
    {"mesh": 0},
    {"camera": 0, "translation": [0.4, 1.6, 1.9], "rotation": [-0.3826834, 0, 0, 0.9238795]},
    {"extensions": {"KHR_lights_punctual": {"light": 0}}, "rotation": [-0.5, 0.3, 0.1, 0.8062258]}
  ],
  "cameras": [{"type": "perspective", "perspective": {"yfov": 0.9, "znear": 0.1, "zfar": 10}}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3, "material": 0}]}],
  "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "baseColorFactor": [1, 0.9, 0.8, 1],
                 "metallicFactor": 0, "roughnessFactor": 0.6}}],
  "textures": [{"source": 0}],
  "images": [{"uri": "data:image/png;base64,)" + testing::base64(encodePng(texture)) + R"("}],)" +
                             testing::quadGltfBuffers({0, 2, 2, 2, 2, 0, 0, 0}) + "\n}";
    const std::string path = folder.file("quad.gltf");
    std::ofstream(path) << gltf;
    return path;
}

TEST(ReferenceImage, MatchesGpuOnATexturedGltfQuadUnderTheSun) {
    testing::TempFolder folder;
    const Scene scene = loadGltf(writeTexturedQuad(folder));
    ASSERT_EQ(scene.textures.size(), 1u);
    auto context = testing::makeValidatedContext();
    const GpuFrame gpu = renderGpu(*context, scene, 200, 150);
    const ReferenceRenderer reference(scene, unshadowed(200, 150));
    ASSERT_EQ(reference.lights().directionalCount, 1u);
    std::vector<SurfaceHit> hits;
    const ImageRgba8 image = reference.render(nullptr, &hits);
    EXPECT_GT(testing::fractionBrighterThan(image, 40), 0.3) << "the quad must fill much of the frame, lit";
    expectAgreement(compare(gpu.image, gpu.depth, gpu.projection, image, hits, "reference-textured-quad"), "quad");
    testing::expectNoValidationMessages(*context);
}

}  // namespace
}  // namespace punctual
