// The glTF loader's materials beyond the metallic-roughness factors: alphaMode and alphaCutoff,
// emission (factor, texture, KHR_materials_emissive_strength), samplers, texture coordinate sets,
// KHR_texture_transform, EXT_texture_webp and the mip chains made at load.
#include <cstring>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <stb_image_write.h>
#include <webp/encode.h>

#include "core/error.h"
#include "gltf_test_files.h"
#include "scene/gltf_loader.h"
#include "warning_capture.h"

namespace punctual {
namespace {

using nlohmann::json;
using testing::WarningCapture;
using unit_testing::TempDir;

// One triangle (POSITION, TEXCOORD_0, TEXCOORD_1) drawn with `material`, in a file that also has
// the given images, textures and samplers; written as `name`.gltf with an embedded buffer.
std::string writeTriangle(const TempDir& dir, const json& material, const json& images = json::array(),
                          const json& textures = json::array(), const json& samplers = json::array(),
                          const json& extensionsRequired = json::array()) {
    const float data[] = {0, 0, 0, 1, 0, 0, 0, 1, 0,  // positions
                          0, 0, 1, 0, 0, 1,           // TEXCOORD_0
                          0.5f, 0.5f, 1, 0.5f, 0.5f, 1};  // TEXCOORD_1
    std::vector<unsigned char> bytes(sizeof data);
    std::memcpy(bytes.data(), data, sizeof data);
    json doc = {{"asset", {{"version", "2.0"}}},
                {"scene", 0},
                {"scenes", {{{"nodes", {0}}}}},
                {"nodes", {{{"mesh", 0}}}},
                {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 1}, {"TEXCOORD_1", 2}}},
                                               {"material", 0}}}}}}},
                {"materials", {material}},
                {"buffers", {{{"byteLength", bytes.size()},
                              {"uri", "data:application/octet-stream;base64," + unit_testing::base64(bytes)}}}},
                {"bufferViews", {unit_testing::bufferViewJson(0, 36), unit_testing::bufferViewJson(36, 24),
                                 unit_testing::bufferViewJson(60, 24)}},
                {"accessors", {unit_testing::accessorJson(0, unit_testing::kFloat, 3, "VEC3"),
                               unit_testing::accessorJson(1, unit_testing::kFloat, 3, "VEC2"),
                               unit_testing::accessorJson(2, unit_testing::kFloat, 3, "VEC2")}}};
    doc["accessors"][0]["min"] = {0, 0, 0};
    doc["accessors"][0]["max"] = {1, 1, 0};
    if (!images.empty()) doc["images"] = images;
    if (!textures.empty()) doc["textures"] = textures;
    if (!samplers.empty()) doc["samplers"] = samplers;
    if (!extensionsRequired.empty()) {
        doc["extensionsRequired"] = extensionsRequired;
        doc["extensionsUsed"] = extensionsRequired;
    }
    const std::filesystem::path path = dir.path() / "triangle.gltf";
    unit_testing::writeFile(path, doc.dump());
    return path.string();
}

// A PNG of `width` x `height` RGBA texels as a data URI.
std::string pngUri(uint32_t width, uint32_t height, const std::vector<unsigned char>& rgba) {
    std::vector<unsigned char> png;
    stbi_write_png_to_func(
        [](void* context, void* data, int size) {
            auto* out = static_cast<std::vector<unsigned char>*>(context);
            out->insert(out->end(), static_cast<unsigned char*>(data), static_cast<unsigned char*>(data) + size);
        },
        &png, int(width), int(height), 4, rgba.data(), int(width * 4));
    return "data:image/png;base64," + unit_testing::base64(png);
}

std::vector<unsigned char> solid(uint32_t texels, std::vector<unsigned char> rgba) {
    std::vector<unsigned char> out;
    for (uint32_t i = 0; i < texels; ++i) out.insert(out.end(), rgba.begin(), rgba.end());
    return out;
}

TEST(GltfMaterialModes, AlphaModesAndCutoffAreRead) {
    TempDir dir;
    Scene scene = loadGltf(writeTriangle(dir, {{"alphaMode", "MASK"}, {"alphaCutoff", 0.25}, {"doubleSided", true}}));
    EXPECT_EQ(scene.materials[0].alphaMode, AlphaMode::Mask);
    EXPECT_FLOAT_EQ(scene.materials[0].alphaCutoff, 0.25f);
    EXPECT_TRUE(scene.materials[0].doubleSided);
    scene = loadGltf(writeTriangle(dir, {{"alphaMode", "MASK"}}));
    EXPECT_FLOAT_EQ(scene.materials[0].alphaCutoff, 0.5f);  // the spec's default
    EXPECT_FALSE(scene.materials[0].doubleSided);
    scene = loadGltf(writeTriangle(dir, {{"alphaMode", "BLEND"}}));
    EXPECT_EQ(scene.materials[0].alphaMode, AlphaMode::Blend);
    scene = loadGltf(writeTriangle(dir, json::object()));
    EXPECT_EQ(scene.materials[0].alphaMode, AlphaMode::Opaque);
}

TEST(GltfMaterialModes, UnknownAlphaModeIsAnErrorNamingIt) {
    TempDir dir;
    try {
        loadGltf(writeTriangle(dir, {{"name", "glass"}, {"alphaMode", "ADDITIVE"}}));
        FAIL() << "expected an error";
    } catch (const Error& error) {
        const std::string message = error.what();
        EXPECT_NE(message.find("glass"), std::string::npos) << message;
        EXPECT_NE(message.find("ADDITIVE"), std::string::npos) << message;
    }
}

TEST(GltfEmission, FactorStrengthAndTextureAreRead) {
    TempDir dir;
    const json images = {{{"uri", pngUri(2, 2, solid(4, {255, 128, 0, 255}))}}};
    const json textures = {{{"source", 0}}};
    const Scene scene = loadGltf(writeTriangle(
        dir,
        {{"emissiveFactor", {1.0, 0.5, 0.25}},
         {"emissiveTexture", {{"index", 0}, {"texCoord", 1}}},
         {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 40.0}}}}}},
        images, textures, json::array(), {"KHR_materials_emissive_strength"}));
    const Material& material = scene.materials[0];
    EXPECT_EQ(material.emission(), glm::vec3(40.0f, 20.0f, 10.0f));
    ASSERT_TRUE(material.emissiveTexture.present());
    EXPECT_EQ(material.emissiveTexture.texCoord, 1u);
    ASSERT_EQ(scene.textures.size(), 1u);  // the emissive image is decoded too
    EXPECT_EQ(scene.textures[0].rgba[1], 128);
}

TEST(GltfEmission, FactorsAboveOneAreKeptAsTheCornellBoxWritesThem) {
    TempDir dir;
    const Scene scene = loadGltf(writeTriangle(dir, {{"emissiveFactor", {10.0, 10.0, 10.0}}}));
    EXPECT_EQ(scene.materials[0].emission(), glm::vec3(10.0f));
}

TEST(GltfEmission, NegativeStrengthIsAnError) {
    TempDir dir;
    EXPECT_THROW(loadGltf(writeTriangle(
                     dir, {{"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", -1.0}}}}}})),
                 Error);
}

TEST(GltfSamplers, FiltersAndWrapsBecomeTheSamplersTheyName) {
    TempDir dir;
    const json images = {{{"uri", pngUri(4, 4, solid(16, {9, 9, 9, 255}))}}};
    const json textures = {{{"source", 0}, {"sampler", 0}}};
    const json samplers = {{{"magFilter", 9728}, {"minFilter", 9984}, {"wrapS", 33071}, {"wrapT", 33648}}};
    const Scene scene = loadGltf(writeTriangle(dir, {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}},
                                               images, textures, samplers));
    const TextureSampler& sampler = scene.materials[0].baseColorTexture.sampler;
    EXPECT_EQ(sampler.magFilter, TextureFilter::Nearest);
    EXPECT_EQ(sampler.minFilter, TextureFilter::Nearest);
    EXPECT_EQ(sampler.mipFilter, TextureFilter::Nearest);
    EXPECT_TRUE(sampler.mipmaps);
    EXPECT_EQ(sampler.wrapU, TextureWrap::ClampToEdge);
    EXPECT_EQ(sampler.wrapV, TextureWrap::MirroredRepeat);
    // The texture got its mip chain: 4x4, 2x2, 1x1.
    ASSERT_EQ(scene.textures[0].levelCount(), 3u);
    EXPECT_EQ(scene.textures[0].mipLevels[1].width, 1u);
}

TEST(GltfSamplers, MinFilterWithoutMipmapsReadsLevelZeroOnly) {
    TempDir dir;
    const json images = {{{"uri", pngUri(2, 2, solid(4, {9, 9, 9, 255}))}}};
    const json textures = {{{"source", 0}, {"sampler", 0}}};
    const json samplers = {{{"minFilter", 9729}}};
    const Scene scene = loadGltf(writeTriangle(dir, {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}},
                                               images, textures, samplers));
    EXPECT_FALSE(scene.materials[0].baseColorTexture.sampler.mipmaps);
    EXPECT_EQ(scene.materials[0].baseColorTexture.sampler.wrapU, TextureWrap::Repeat);  // the default
}

TEST(GltfSamplers, InvalidWrapModeIsAnErrorNamingTheSampler) {
    TempDir dir;
    const json images = {{{"uri", pngUri(2, 2, solid(4, {9, 9, 9, 255}))}}};
    const json textures = {{{"source", 0}, {"sampler", 0}}};
    const json samplers = {{{"wrapS", 12345}}};
    try {
        loadGltf(writeTriangle(dir, {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}, images,
                               textures, samplers));
        FAIL() << "expected an error";
    } catch (const Error& error) {
        EXPECT_NE(std::string(error.what()).find("sampler 0"), std::string::npos) << error.what();
    }
}

TEST(GltfTextureTransform, OffsetRotationScaleAndTexCoordOverrideAreRead) {
    TempDir dir;
    const json images = {{{"uri", pngUri(2, 2, solid(4, {9, 9, 9, 255}))}}};
    const json textures = {{{"source", 0}}};
    const json info = {{"index", 0},
                       {"texCoord", 0},
                       {"extensions",
                        {{"KHR_texture_transform",
                          {{"offset", {0.5, -0.25}}, {"rotation", 1.5}, {"scale", {2.0, 4.0}}, {"texCoord", 1}}}}}};
    const Scene scene = loadGltf(writeTriangle(dir, {{"pbrMetallicRoughness", {{"baseColorTexture", info}}}}, images,
                                               textures, json::array(), {"KHR_texture_transform"}));
    const TextureRef& ref = scene.materials[0].baseColorTexture;
    EXPECT_EQ(ref.transform.offset, glm::vec2(0.5f, -0.25f));
    EXPECT_FLOAT_EQ(ref.transform.rotation, 1.5f);
    EXPECT_EQ(ref.transform.scale, glm::vec2(2.0f, 4.0f));
    EXPECT_EQ(ref.texCoord, 1u);
    // TEXCOORD_1 is loaded with the vertices.
    EXPECT_EQ(scene.vertices[1].uv1, glm::vec2(1.0f, 0.5f));
}

TEST(GltfTextureTransform, NonNumericScaleIsAnError) {
    TempDir dir;
    const json images = {{{"uri", pngUri(2, 2, solid(4, {9, 9, 9, 255}))}}};
    const json textures = {{{"source", 0}}};
    const json info = {{"index", 0}, {"extensions", {{"KHR_texture_transform", {{"scale", {"two", 1}}}}}}};
    EXPECT_THROW(loadGltf(writeTriangle(dir, {{"pbrMetallicRoughness", {{"baseColorTexture", info}}}}, images, textures)),
                 Error);
}

TEST(GltfTextureTransform, ThirdTextureCoordinateSetWarnsAndUsesTheFactor) {
    TempDir dir;
    const json images = {{{"uri", pngUri(2, 2, solid(4, {9, 9, 9, 255}))}}};
    const json textures = {{{"source", 0}}};
    WarningCapture capture;
    const Scene scene = loadGltf(writeTriangle(
        dir, {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}, {"texCoord", 2}}}}}}, images, textures));
    EXPECT_FALSE(scene.materials[0].baseColorTexture.present());
    ASSERT_EQ(capture.warnings.size(), 1u);
    EXPECT_NE(capture.warnings[0].find("TEXCOORD_2"), std::string::npos) << capture.warnings[0];
}

TEST(GltfWebp, WebpImagesDecodeThroughTheExtension) {
    TempDir dir;
    // A lossless 2x2 WebP made by libwebp's own encoder; the PNG fallback is a different colour,
    // so the test sees which image was used.
    const std::vector<unsigned char> rgba = {10, 20, 30, 255, 40, 50, 60, 255, 70, 80, 90, 255, 100, 110, 120, 255};
    uint8_t* encoded = nullptr;
    const size_t size = WebPEncodeLosslessRGBA(rgba.data(), 2, 2, 8, &encoded);
    ASSERT_GT(size, 0u);
    const std::vector<unsigned char> webp(encoded, encoded + size);
    WebPFree(encoded);
    // A file beside the scene: tinygltf 2.7 takes data URIs only for the image types it knows.
    unit_testing::writeFile(dir.path() / "texture.webp", webp);
    const json images = {{{"uri", pngUri(2, 2, solid(4, {255, 0, 0, 255}))}}, {{"uri", "texture.webp"}}};
    const json textures = {{{"source", 0}, {"extensions", {{"EXT_texture_webp", {{"source", 1}}}}}}};
    WarningCapture capture;
    const Scene scene = loadGltf(writeTriangle(dir, {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}},
                                               images, textures, json::array(), {"EXT_texture_webp"}));
    EXPECT_TRUE(capture.warnings.empty()) << capture.warnings.front();
    ASSERT_EQ(scene.textures.size(), 1u);
    EXPECT_EQ(scene.textures[0].rgba, rgba);
}

TEST(GltfWebp, CorruptWebpFallsBackToThePngSource) {
    TempDir dir;
    const std::vector<unsigned char> broken = {'R', 'I', 'F', 'F', 40, 0, 0, 0, 'W', 'E', 'B', 'P', 'V', 'P', '8', 'L', 1, 2, 3};
    unit_testing::writeFile(dir.path() / "broken.webp", broken);
    const json images = {{{"uri", pngUri(1, 1, {255, 0, 0, 255})}}, {{"uri", "broken.webp"}}};
    const json textures = {{{"source", 0}, {"extensions", {{"EXT_texture_webp", {{"source", 1}}}}}}};
    const Scene scene = loadGltf(writeTriangle(dir, {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}},
                                               images, textures));
    ASSERT_EQ(scene.textures.size(), 1u);
    EXPECT_EQ(scene.textures[0].rgba, (std::vector<uint8_t>{255, 0, 0, 255}));
}

TEST(GltfExtensions, RequiredExtensionsWeReadAreAccepted) {
    TempDir dir;
    EXPECT_NO_THROW(loadGltf(writeTriangle(dir, json::object(), json::array(), json::array(), json::array(),
                                           {"KHR_texture_transform", "KHR_materials_emissive_strength",
                                            "EXT_texture_webp"})));
    try {
        loadGltf(writeTriangle(dir, json::object(), json::array(), json::array(), json::array(),
                               {"KHR_materials_volume"}));
        FAIL() << "expected an error";
    } catch (const Error& error) {
        EXPECT_NE(std::string(error.what()).find("KHR_materials_volume"), std::string::npos) << error.what();
    }
}

}  // namespace
}  // namespace punctual
