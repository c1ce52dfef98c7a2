// glTF scenes through the whole frame: a textured quad under a directional light, seen from the
// file's camera, and the Cornell box from ../shared/data when it is there.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/image.h"
#include "gpu_test_support.h"
#include "reference/reference_renderer.h"
#include "reference_test_support.h"
#include "render/renderer.h"
#include "scene/gltf_loader.h"
#include "scene/light_generator.h"

namespace punctual {
namespace {

// A 2 x 2 m quad in the XZ plane, textured red on its left half (-X) and green on its right,
// lit from straight above by a 2 lux directional light, seen from a camera 3 m above it.
std::string writeTexturedQuad(const testing::TempFolder& folder) {
    ImageRgba8 texture;
    // 8 x 1 texels, red then green: bilinear filtering and repeat wrapping blend only near the
    // middle and the edges, so a quarter of the way in from either side the colour is pure.
    texture.width = 8;
    texture.height = 1;
    for (int i = 0; i < 8; ++i) {
        const uint8_t red = i < 4 ? 255 : 0;
        texture.pixels.insert(texture.pixels.end(), {red, uint8_t(255 - red), 0, 255});
    }
    const std::string png = encodePng(texture);
    const std::string gltf = R"({
  "asset": {"version": "2.0"},
  "extensionsUsed": ["KHR_lights_punctual"],
  "extensions": {"KHR_lights_punctual": {"lights": [{"type": "directional", "intensity": 2.0}]}},
  "scene": 0,
  "scenes": [{"nodes": [0, 1, 2]}],
  "nodes": [
    {"mesh": 0},
    {"camera": 0, "translation": [0, 3, 0], "rotation": [-0.70710678, 0, 0, 0.70710678]},
    {"extensions": {"KHR_lights_punctual": {"light": 0}}, "rotation": [-0.70710678, 0, 0, 0.70710678]}
  ],
  "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1, "zfar": 10}}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3, "material": 0}]}],
  "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0, "roughnessFactor": 1}}],
  "textures": [{"source": 0, "sampler": 0}],
  "samplers": [{"magFilter": 9728, "minFilter": 9728}],
  "images": [{"uri": "data:image/png;base64,)" + testing::base64(png) + R"("}],)" +
                             testing::quadGltfBuffers({0, 1, 1, 1, 1, 0, 0, 0}) + "\n}";
    const std::string path = folder.file("quad.gltf");
    std::ofstream(path) << gltf;
    return path;
}

TEST(RenderGltf, TexturedQuadUnderDirectionalLightFromTheFilesCamera) {
    testing::TempFolder folder;
    const Scene scene = loadGltf(writeTexturedQuad(folder));
    ASSERT_EQ(scene.textures.size(), 1u);
    ASSERT_TRUE(scene.cameraFromFile);
    auto context = testing::makeValidatedContext();
    render::Renderer renderer(*context, scene, testing::renderSettings(64, 64));
    const ImageRgba8 image = renderer.render(1, 0).image;
    testing::saveTestImage("gltf-textured-quad", image);
    EXPECT_EQ(renderer.lights().directionalCount, 1u);

    // Left of centre is red, right of centre green (the texture), both clearly lit by the sun;
    // the corners beyond the quad stay black.
    const uint8_t* left = image.at(16, 32);
    const uint8_t* right = image.at(48, 32);
    EXPECT_GT(left[0], 80);
    EXPECT_LT(left[1], 10);
    EXPECT_GT(right[1], 80);
    EXPECT_LT(right[0], 10);
    const uint8_t* corner = image.at(0, 0);
    EXPECT_EQ(corner[0] + corner[1] + corner[2], 0);
    testing::expectNoValidationMessages(*context);
}

TEST(RenderGltf, CornellBoxWithGeneratedLights) {
    const std::string path = std::string(PUNCTUAL_SHARED_DATA_DIR) + "/cornell-box/cornellBox.gltf";
    if (!std::filesystem::exists(path)) GTEST_SKIP() << "no " << path << " (../shared/data is absent)";
    Scene scene = loadGltf(path);
    // Its own light is an emissive cube: seen (CornellBoxShowsItsEmissiveLamp), but emission
    // lights nothing else, so generated spot and point lights light the box.
    replaceLights(scene, 8, 4, 3);
    auto context = testing::makeValidatedContext();
    render::RenderSettings settings = testing::renderSettings(160, 160);
    render::Renderer tiled(*context, scene, settings);
    const ImageRgba8 image = tiled.render(1, 0).image;
    testing::saveTestImage("gltf-cornell-box", image);
    EXPECT_GT(testing::fractionBrighterThan(image, 20), 0.1);
    settings.method = render::LightListMethod::Brute;
    render::Renderer brute(*context, scene, settings);
    EXPECT_TRUE(brute.render(1, 0).image.pixels == image.pixels);
    testing::expectNoValidationMessages(*context);
}

TEST(RenderGltf, CornellBoxShowsItsEmissiveLamp) {
    const std::string path = std::string(PUNCTUAL_SHARED_DATA_DIR) + "/cornell-box/cornellBox.gltf";
    if (!std::filesystem::exists(path)) GTEST_SKIP() << "no " << path << " (../shared/data is absent)";
    const Scene scene = loadGltf(path);
    auto context = testing::makeValidatedContext();
    render::RenderSettings settings = testing::renderSettings(200, 150);
    render::Renderer renderer(*context, scene, settings);
    const ImageRgba8 image = renderer.render(1, 0).image;
    testing::saveTestImage("gltf-cornell-box-lamp", image);
    // The lamp's pixels, found by the reference's primary rays: its material emits (factor 10).
    const reference::ReferenceRenderer reference(scene, testing::unshadowed(200, 150));
    size_t lampPixels = 0, lampWhite = 0;
    for (uint32_t y = 0; y < image.height; ++y)
        for (uint32_t x = 0; x < image.width; ++x) {
            const reference::SurfaceHit hit = reference.traceSurface(x, y);
            if (!hit.hit) continue;
            const Material& material = scene.materials[scene.meshes[scene.objects[hit.object].mesh].material];
            if (material.emission() == glm::vec3(0.0f)) continue;
            ++lampPixels;
            const uint8_t* rgb = image.at(x, y);
            lampWhite += rgb[0] >= 240 && rgb[1] >= 240 && rgb[2] >= 240;
        }
    ASSERT_GT(lampPixels, 20u) << "the lamp is in the file's view";
    EXPECT_GT(double(lampWhite) / double(lampPixels), 0.9) << "an emission of 10 saturates to white";
    testing::expectNoValidationMessages(*context);
}

}  // namespace
}  // namespace punctual
