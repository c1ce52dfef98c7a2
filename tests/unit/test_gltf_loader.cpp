// loadGltf on small glTF files written by the tests themselves: geometry, node hierarchy,
// materials and textures, lights, cameras, and the three ways of storing buffers.
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numbers>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <stb_image_write.h>

#include "core/error.h"
#include "core/log.h"
#include "gltf_test_files.h"
#include "scene/gltf_loader.h"
#include "warning_capture.h"

namespace punctual {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

using unit_testing::base64;
using unit_testing::glbFile;
using unit_testing::kFloat;
using unit_testing::kUnsignedShort;
using unit_testing::TempDir;
using unit_testing::writeFile;

// Builds a glTF document and its single binary buffer.
class GltfBuilder {
public:
    json doc = {{"asset", {{"version", "2.0"}}},
                {"scene", 0},
                {"scenes", json::array({json{{"nodes", json::array()}}})},
                {"nodes", json::array()},
                {"meshes", json::array()},
                {"accessors", json::array()},
                {"bufferViews", json::array()}};
    std::vector<unsigned char> bin;

    int view(const void* data, size_t size, size_t stride = 0) {
        while (bin.size() % 4 != 0) bin.push_back(0);
        json v = unit_testing::bufferViewJson(bin.size(), size);
        if (stride != 0) v["byteStride"] = stride;
        const auto* bytes = static_cast<const unsigned char*>(data);
        bin.insert(bin.end(), bytes, bytes + size);
        return push("bufferViews", v);
    }
    int accessor(int bufferView, int componentType, size_t count, const char* type, size_t byteOffset = 0) {
        json a = unit_testing::accessorJson(bufferView, componentType, count, type);
        a["byteOffset"] = byteOffset;
        return push("accessors", a);
    }
    int floats(const std::vector<float>& values, const char* type, size_t components) {
        return accessor(view(values.data(), values.size() * sizeof(float)), kFloat, values.size() / components, type);
    }
    int indices(const std::vector<uint16_t>& values) {
        return accessor(view(values.data(), values.size() * sizeof(uint16_t)), kUnsignedShort, values.size(), "SCALAR");
    }
    int mesh(const json& primitive, const std::string& name = "") {
        json m = {{"primitives", json::array({primitive})}};
        if (!name.empty()) m["name"] = name;
        return push("meshes", m);
    }
    int node(const json& n, bool root = true) {
        const int index = push("nodes", n);
        if (root) doc["scenes"][0]["nodes"].push_back(index);
        return index;
    }
    int light(const json& l) {
        doc["extensionsUsed"] = json::array({"KHR_lights_punctual"});
        return push(doc["extensions"]["KHR_lights_punctual"]["lights"], l);
    }
    int material(const json& m) { return push("materials", m); }

    // The minimal drawable: one triangle in the z = 0 plane, as a root node.
    int triangle() {
        const int positions = floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3);
        return node({{"mesh", mesh({{"attributes", {{"POSITION", positions}}}})}});
    }

    std::string writeGltf(const fs::path& dir, const std::string& name) const {
        json out = doc;
        out["buffers"] = json::array({json{{"uri", name + ".bin"}, {"byteLength", bin.size()}}});
        writeFile(dir / (name + ".bin"), bin);
        writeFile(dir / (name + ".gltf"), out.dump(2));
        return (dir / (name + ".gltf")).string();
    }
    std::string writeDataUri(const fs::path& dir, const std::string& name) const {
        json out = doc;
        out["buffers"] = json::array(
            {json{{"uri", "data:application/octet-stream;base64," + base64(bin)}, {"byteLength", bin.size()}}});
        writeFile(dir / (name + ".gltf"), out.dump());
        return (dir / (name + ".gltf")).string();
    }
    std::string writeGlb(const fs::path& dir, const std::string& fileName) const {
        writeFile(dir / fileName, glbFile(doc, bin));
        return (dir / fileName).string();
    }

private:
    int push(const char* array, const json& value) { return push(doc[array], value); }
    static int push(json& array, const json& value) {
        array.push_back(value);
        return int(array.size()) - 1;
    }
};

using testing::WarningCapture;

void expectVec3Near(const glm::vec3& actual, const glm::vec3& expected, float tolerance = 1e-5f) {
    EXPECT_NEAR(actual.x, expected.x, tolerance);
    EXPECT_NEAR(actual.y, expected.y, tolerance);
    EXPECT_NEAR(actual.z, expected.z, tolerance);
}

// --- geometry -------------------------------------------------------------------------------

TEST(GltfGeometry, IndexedMeshWithoutNormalsGetsFlatNormalsAndUvs) {
    TempDir dir;
    GltfBuilder gltf;
    // A quad folded along its diagonal: two faces with different normals.
    const int positions = gltf.floats({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 1}, "VEC3", 3);
    const int uvs = gltf.floats({0, 0, 1, 0, 1, 1, 0, 1}, "VEC2", 2);
    const int indices = gltf.indices({0, 1, 2, 0, 2, 3});
    gltf.node({{"mesh", gltf.mesh({{"attributes", {{"POSITION", positions}, {"TEXCOORD_0", uvs}}},
                                   {"indices", indices}}, "folded")}});
    const Scene scene = loadGltf(gltf.writeGltf(dir.path(), "quad"));

    ASSERT_EQ(scene.meshes.size(), 1u);
    ASSERT_EQ(scene.objects.size(), 1u);
    EXPECT_EQ(scene.meshes[0].name, "folded");
    EXPECT_EQ(scene.triangleCount(), 2u);
    // De-indexed: each triangle has its own three vertices.
    ASSERT_EQ(scene.vertices.size(), 6u);
    EXPECT_EQ(scene.meshes[0].vertexCount, 6u);
    const uint32_t expectedSource[6] = {0, 1, 2, 0, 2, 3};
    const glm::vec3 sourcePositions[4] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 1}};
    const glm::vec2 sourceUvs[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (size_t i = 0; i < 6; ++i) {
        const Vertex& v = scene.vertices[scene.meshes[0].vertexOffset + scene.indices[i]];
        expectVec3Near(v.position, sourcePositions[expectedSource[i]]);
        EXPECT_FLOAT_EQ(v.uv.x, sourceUvs[expectedSource[i]].x);
        EXPECT_FLOAT_EQ(v.uv.y, sourceUvs[expectedSource[i]].y);
        const glm::vec3 expectedNormal =
            i < 3 ? glm::vec3(0, 0, 1) : glm::normalize(glm::vec3(1, -1, 1));  // cross((1,1,0), (0,1,1))
        expectVec3Near(v.normal, expectedNormal);
    }
    EXPECT_EQ(scene.materials.size(), 1u);
    EXPECT_FALSE(scene.cameraFromFile);
}

TEST(GltfGeometry, LoadedNormalsAreNormalizedAndZeroNormalsRepaired) {
    TempDir dir;
    GltfBuilder gltf;
    const int positions = gltf.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3);
    const int normals = gltf.floats({0, 0, 2, 0, 0, 0, 0, 3, 0}, "VEC3", 3);
    gltf.node({{"mesh", gltf.mesh({{"attributes", {{"POSITION", positions}, {"NORMAL", normals}}}})}});
    const Scene scene = loadGltf(gltf.writeGltf(dir.path(), "normals"));
    ASSERT_EQ(scene.vertices.size(), 3u);  // indexed by generated 0..n-1, not de-indexed
    expectVec3Near(scene.vertices[0].normal, {0, 0, 1});
    expectVec3Near(scene.vertices[1].normal, {0, 0, 1});  // zero -> the face normal
    expectVec3Near(scene.vertices[2].normal, {0, 1, 0});
    EXPECT_EQ(scene.indices, (std::vector<uint32_t>{0, 1, 2}));
}

TEST(GltfGeometry, DegenerateTriangleGetsUpNormal) {
    TempDir dir;
    GltfBuilder gltf;
    const int positions = gltf.floats({0, 0, 0, 1, 1, 1, 2, 2, 2, 0, 0, 0, 1, 0, 0, 0, 0, -1}, "VEC3", 3);
    gltf.node({{"mesh", gltf.mesh({{"attributes", {{"POSITION", positions}}}})}});
    const Scene scene = loadGltf(gltf.writeGltf(dir.path(), "degenerate"));
    ASSERT_EQ(scene.vertices.size(), 6u);
    for (size_t i = 0; i < 3; ++i) expectVec3Near(scene.vertices[i].normal, {0, 1, 0});  // collinear
    for (size_t i = 3; i < 6; ++i) expectVec3Near(scene.vertices[i].normal, {0, 1, 0});  // (1,0,0)x(0,0,-1)
}

TEST(GltfGeometry, ByteStrideAndByteOffsetAreHonoured) {
    TempDir dir;
    GltfBuilder gltf;
    // Interleaved position (12 bytes) + uv (8 bytes) + 4 bytes padding: stride 24.
    std::vector<float> interleaved;
    const float data[3][5] = {{0, 0, 0, 0.25f, 0.5f}, {2, 0, 0, 0.75f, 0.5f}, {0, 3, 0, 0.25f, 1.0f}};
    for (const auto& vertex : data) {
        interleaved.insert(interleaved.end(), vertex, vertex + 5);
        interleaved.push_back(-1.0f);
    }
    const int view = gltf.view(interleaved.data(), interleaved.size() * sizeof(float), 24);
    const int positions = gltf.accessor(view, kFloat, 3, "VEC3", 0);
    const int uvs = gltf.accessor(view, kFloat, 3, "VEC2", 12);
    gltf.node({{"mesh", gltf.mesh({{"attributes", {{"POSITION", positions}, {"TEXCOORD_0", uvs}}}})}});
    const Scene scene = loadGltf(gltf.writeGltf(dir.path(), "stride"));
    ASSERT_EQ(scene.vertices.size(), 3u);
    expectVec3Near(scene.vertices[1].position, {2, 0, 0});
    expectVec3Near(scene.vertices[2].position, {0, 3, 0});
    EXPECT_FLOAT_EQ(scene.vertices[1].uv.x, 0.75f);
    EXPECT_FLOAT_EQ(scene.vertices[2].uv.y, 1.0f);
    expectVec3Near(scene.meshes[0].localBounds.max, {2, 3, 0});
}

TEST(GltfGeometry, NodeHierarchyComposesParentTranslationAndChildRotation) {
    TempDir dir;
    GltfBuilder gltf;
    const int positions = gltf.floats({1, 0, 0, 2, 0, 0, 1, 1, 0}, "VEC3", 3);
    const int mesh = gltf.mesh({{"attributes", {{"POSITION", positions}}}});
    const float s = std::sin(std::numbers::pi_v<float> / 4.0f);
    // Child: +90 degrees about Y (glTF quaternions are x, y, z, w).
    const int child = gltf.node({{"mesh", mesh}, {"rotation", {0.0f, s, 0.0f, s}}}, false);
    gltf.node({{"translation", {10, 0, 0}}, {"children", {child}}});
    const Scene scene = loadGltf(gltf.writeGltf(dir.path(), "hierarchy"));
    ASSERT_EQ(scene.objects.size(), 1u);
    const glm::mat4& model = scene.objects[0].model;
    // (1,0,0) rotated +90 degrees about Y is (0,0,-1); then translated by (10,0,0).
    expectVec3Near(glm::vec3(model * glm::vec4(1, 0, 0, 1)), {10, 0, -1});
    expectVec3Near(glm::vec3(model * glm::vec4(2, 0, 0, 1)), {10, 0, -2});
    expectVec3Near(scene.bounds.min, {10, 0, -2});
    expectVec3Near(scene.bounds.max, {10, 1, -1});
}

TEST(GltfGeometry, PrimitiveInstancedByTwoNodesIsStoredOnce) {
    TempDir dir;
    GltfBuilder gltf;
    const int positions = gltf.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3);
    const int mesh = gltf.mesh({{"attributes", {{"POSITION", positions}}}});
    gltf.node({{"mesh", mesh}, {"name", "left"}});
    gltf.node({{"mesh", mesh}, {"name", "right"}, {"translation", {5, 0, 0}}});
    const Scene scene = loadGltf(gltf.writeGltf(dir.path(), "instances"));
    EXPECT_EQ(scene.meshes.size(), 1u);
    ASSERT_EQ(scene.objects.size(), 2u);
    EXPECT_EQ(scene.objects[0].mesh, scene.objects[1].mesh);
    EXPECT_EQ(scene.objects[1].name, "right");
    EXPECT_FLOAT_EQ(scene.bounds.max.x, 6.0f);
}

TEST(GltfGeometry, NonTrianglePrimitivesAreSkippedWithOneWarning) {
    TempDir dir;
    GltfBuilder gltf;
    gltf.triangle();
    const int positions = gltf.floats({0, 0, 0, 1, 0, 0}, "VEC3", 3);
    const int lines = gltf.mesh({{"attributes", {{"POSITION", positions}}}, {"mode", 1}});
    gltf.node({{"mesh", lines}});
    gltf.node({{"mesh", lines}});
    WarningCapture capture;
    const Scene scene = loadGltf(gltf.writeGltf(dir.path(), "lines"));
    EXPECT_EQ(scene.objects.size(), 1u);
    ASSERT_EQ(capture.warnings.size(), 1u);
    EXPECT_NE(capture.warnings[0].find("LINES"), std::string::npos) << capture.warnings[0];
}

// --- buffers: data URI and GLB ----------------------------------------------------------------

TEST(GltfBuffers, DataUriBufferLoads) {
    TempDir dir;
    GltfBuilder gltf;
    gltf.triangle();
    const Scene scene = loadGltf(gltf.writeDataUri(dir.path(), "embedded"));
    ASSERT_EQ(scene.vertices.size(), 3u);
    expectVec3Near(scene.vertices[2].position, {0, 1, 0});
}

TEST(GltfBuffers, GlbLoadsByExtensionAndByMagic) {
    TempDir dir;
    GltfBuilder gltf;
    gltf.triangle();
    for (const char* name : {"scene.glb", "binary-named.gltf"}) {
        const Scene scene = loadGltf(gltf.writeGlb(dir.path(), name));
        ASSERT_EQ(scene.vertices.size(), 3u) << name;
        expectVec3Near(scene.vertices[1].position, {1, 0, 0});
        EXPECT_EQ(scene.source, (dir.path() / name).string());
    }
}

// --- materials and textures -------------------------------------------------------------------

TEST(GltfMaterials, FactorsAreReadAndPrimitivesWithoutMaterialGetTheDefault) {
    TempDir dir;
    GltfBuilder gltf;
    const int red = gltf.material({{"name", "red"}, {"doubleSided", true},
                                   {"pbrMetallicRoughness", {{"baseColorFactor", {0.8, 0.1, 0.1, 1.0}},
                                                             {"metallicFactor", 0.25}, {"roughnessFactor", 0.75}}}});
    const int plain = gltf.material({{"name", "plain"}});
    const int positions = gltf.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3);
    gltf.node({{"mesh", gltf.mesh({{"attributes", {{"POSITION", positions}}}, {"material", red}})}});
    gltf.node({{"mesh", gltf.mesh({{"attributes", {{"POSITION", positions}}}, {"material", plain}})}});
    gltf.node({{"mesh", gltf.mesh({{"attributes", {{"POSITION", positions}}}})}});
    const Scene scene = loadGltf(gltf.writeGltf(dir.path(), "materials"));
    ASSERT_EQ(scene.materials.size(), 3u);
    ASSERT_EQ(scene.meshes.size(), 3u);
    const Material& first = scene.materials[scene.meshes[0].material];
    EXPECT_EQ(first.name, "red");
    EXPECT_FLOAT_EQ(first.baseColorFactor.r, 0.8f);
    EXPECT_FLOAT_EQ(first.metallic, 0.25f);
    EXPECT_FLOAT_EQ(first.roughness, 0.75f);
    EXPECT_TRUE(first.doubleSided);
    EXPECT_EQ(first.baseColorTexture.image, -1);
    const Material& second = scene.materials[scene.meshes[1].material];  // glTF defaults
    EXPECT_FLOAT_EQ(second.metallic, 1.0f);
    EXPECT_FLOAT_EQ(second.roughness, 1.0f);
    const Material& implicit = scene.materials[scene.meshes[2].material];  // our neutral default
    EXPECT_FLOAT_EQ(implicit.baseColorFactor.g, 1.0f);
    EXPECT_FLOAT_EQ(implicit.metallic, 0.0f);
    EXPECT_FLOAT_EQ(implicit.roughness, 0.5f);
}

// A triangle whose material uses `imageUri` as its baseColorTexture.
std::string texturedTriangle(const TempDir& dir, const std::vector<std::string>& imageUris, int materials = 1) {
    GltfBuilder gltf;
    for (const std::string& uri : imageUris) {
        gltf.doc["images"].push_back({{"uri", uri}});
        gltf.doc["textures"].push_back({{"source", gltf.doc["images"].size() - 1}});
    }
    const int positions = gltf.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3);
    const int uvs = gltf.floats({0, 0, 1, 0, 0, 1}, "VEC2", 2);
    for (int m = 0; m < materials; ++m) {
        std::string name = "m";  // not "m" + to_string(m): GCC 12 warns falsely (-Wrestrict)
        name += std::to_string(m);
        const int material = gltf.material({{"name", name},
                                            {"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.5, 0.5, 1}},
                                                                      {"baseColorTexture", {{"index", 0}}}}}});
        gltf.node({{"mesh", gltf.mesh({{"attributes", {{"POSITION", positions}, {"TEXCOORD_0", uvs}}},
                                       {"material", material}})}});
    }
    return gltf.writeGltf(dir.path(), "textured");
}

TEST(GltfTextures, DecodablePngIsLoadedAsRgba8) {
    TempDir dir;
    const unsigned char pixels[2 * 2 * 4] = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 10, 20, 30, 40};
    ASSERT_NE(stbi_write_png((dir.path() / "checker.png").string().c_str(), 2, 2, 4, pixels, 2 * 4), 0);
    WarningCapture capture;
    const Scene scene = loadGltf(texturedTriangle(dir, {"checker.png"}));
    EXPECT_TRUE(capture.warnings.empty());
    ASSERT_EQ(scene.textures.size(), 1u);
    EXPECT_EQ(scene.textures[0].width, 2u);
    EXPECT_EQ(scene.textures[0].height, 2u);
    EXPECT_EQ(scene.textures[0].rgba, std::vector<uint8_t>(pixels, pixels + sizeof pixels));
    EXPECT_EQ(scene.materials[scene.meshes[0].material].baseColorTexture.image, 0);
}

TEST(GltfTextures, GarbageImageFallsBackToFactorWithOneWarning) {
    TempDir dir;
    writeFile(dir.path() / "garbage.png", std::string("this is not an image at all, just bytes"));
    WarningCapture capture;
    const Scene scene = loadGltf(texturedTriangle(dir, {"garbage.png"}));
    EXPECT_TRUE(scene.textures.empty());
    EXPECT_EQ(scene.materials[0].baseColorTexture.image, -1);
    EXPECT_FLOAT_EQ(scene.materials[0].baseColorFactor.r, 0.5f);
    ASSERT_EQ(capture.warnings.size(), 1u);
    EXPECT_NE(capture.warnings[0].find("garbage.png"), std::string::npos) << capture.warnings[0];
    EXPECT_NE(capture.warnings[0].find("image 0"), std::string::npos) << capture.warnings[0];
    EXPECT_NE(capture.warnings[0].find("textured.gltf"), std::string::npos) << capture.warnings[0];
}

TEST(GltfTextures, MissingImageFallsBackToFactorWithOneWarningEvenWhenSharedByTwoMaterials) {
    TempDir dir;
    WarningCapture capture;
    const Scene scene = loadGltf(texturedTriangle(dir, {"missing.png"}, 2));
    EXPECT_TRUE(scene.textures.empty());
    ASSERT_EQ(scene.materials.size(), 2u);
    EXPECT_EQ(scene.materials[0].baseColorTexture.image, -1);
    EXPECT_EQ(scene.materials[1].baseColorTexture.image, -1);
    ASSERT_EQ(capture.warnings.size(), 1u);
    EXPECT_NE(capture.warnings[0].find("missing.png"), std::string::npos) << capture.warnings[0];
    EXPECT_NE(capture.warnings[0].find("image 0"), std::string::npos) << capture.warnings[0];
}

TEST(GltfTextures, PngInGlbBufferViewAndInDataUriAreDecoded) {
    TempDir dir;
    const unsigned char pixels[2 * 1 * 4] = {1, 2, 3, 255, 200, 100, 50, 255};
    const fs::path pngPath = dir.path() / "strip.png";
    ASSERT_NE(stbi_write_png(pngPath.string().c_str(), 2, 1, 4, pixels, 2 * 4), 0);
    std::ifstream in(pngPath, std::ios::binary);
    const std::vector<unsigned char> png((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    ASSERT_FALSE(png.empty());

    GltfBuilder gltf;
    gltf.doc["images"] = json::array({json{{"bufferView", gltf.view(png.data(), png.size())}, {"mimeType", "image/png"}},
                                      json{{"uri", "data:image/png;base64," + base64(png)}}});
    gltf.doc["textures"] = json::array({json{{"source", 0}}, json{{"source", 1}}});
    const int positions = gltf.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3);
    for (int texture = 0; texture < 2; ++texture) {
        const int material = gltf.material({{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", texture}}}}}});
        gltf.node({{"mesh", gltf.mesh({{"attributes", {{"POSITION", positions}}}, {"material", material}})}});
    }
    WarningCapture capture;
    const Scene scene = loadGltf(gltf.writeGlb(dir.path(), "textured.glb"));
    EXPECT_TRUE(capture.warnings.empty());
    ASSERT_EQ(scene.textures.size(), 2u);
    for (const Texture& texture : scene.textures) {
        EXPECT_EQ(texture.width, 2u);
        EXPECT_EQ(texture.height, 1u);
        EXPECT_EQ(texture.rgba, std::vector<uint8_t>(pixels, pixels + sizeof pixels));
    }
    EXPECT_EQ(scene.materials[0].baseColorTexture.image, 0);
    EXPECT_EQ(scene.materials[1].baseColorTexture.image, 1);
}

// --- lights -----------------------------------------------------------------------------------

TEST(GltfLights, PointLightWithoutRangeGetsDerivedRange) {
    TempDir dir;
    GltfBuilder gltf;
    gltf.triangle();
    const int light = gltf.light({{"type", "point"}, {"name", "bulb"}, {"color", {1.0, 0.5, 0.25}}, {"intensity", 40.0}});
    gltf.node({{"translation", {1, 2, 3}}, {"extensions", {{"KHR_lights_punctual", {{"light", light}}}}}});
    const Scene scene = loadGltf(gltf.writeGltf(dir.path(), "point"));
    ASSERT_EQ(scene.lights.size(), 1u);
    const Light& l = scene.lights[0];
    EXPECT_EQ(l.type, LightType::Point);
    EXPECT_EQ(l.name, "bulb");
    expectVec3Near(l.color, {1.0f, 0.5f, 0.25f});
    EXPECT_FLOAT_EQ(l.intensity, 40.0f);
    expectVec3Near(l.position, {1, 2, 3});
    EXPECT_TRUE(l.rangeDerived);
    EXPECT_FLOAT_EQ(l.range, derivedRange(40.0f, glm::vec3(1.0f, 0.5f, 0.25f)));
}

TEST(GltfLights, SpotLightKeepsRangeAndDefaultsItsCone) {
    TempDir dir;
    GltfBuilder gltf;
    gltf.triangle();
    const int spot = gltf.light({{"type", "spot"}, {"range", 7.5}, {"spot", json::object()}});
    const int narrow = gltf.light({{"type", "spot"}, {"spot", {{"innerConeAngle", 0.1}, {"outerConeAngle", 0.3}}}});
    gltf.node({{"extensions", {{"KHR_lights_punctual", {{"light", spot}}}}}});
    gltf.node({{"extensions", {{"KHR_lights_punctual", {{"light", narrow}}}}}});
    const Scene scene = loadGltf(gltf.writeGltf(dir.path(), "spot"));
    ASSERT_EQ(scene.lights.size(), 2u);
    const Light& l = scene.lights[0];
    EXPECT_EQ(l.type, LightType::Spot);
    expectVec3Near(l.color, {1, 1, 1});
    EXPECT_FLOAT_EQ(l.intensity, 1.0f);
    EXPECT_FLOAT_EQ(l.range, 7.5f);
    EXPECT_FALSE(l.rangeDerived);
    EXPECT_FLOAT_EQ(l.innerConeAngle, 0.0f);
    EXPECT_NEAR(l.outerConeAngle, std::numbers::pi_v<float> / 4.0f, 1e-6f);
    expectVec3Near(l.direction, {0, 0, -1});  // an untransformed node shines down -Z
    EXPECT_FLOAT_EQ(scene.lights[1].innerConeAngle, 0.1f);
    EXPECT_FLOAT_EQ(scene.lights[1].outerConeAngle, 0.3f);
}

TEST(GltfLights, DirectionalLightShinesAlongRotatedNodeMinusZ) {
    TempDir dir;
    GltfBuilder gltf;
    gltf.triangle();
    const int sun = gltf.light({{"type", "directional"}, {"intensity", 3.0}});
    const float half = -std::numbers::pi_v<float> / 4.0f;  // -90 degrees about X
    gltf.node({{"rotation", {std::sin(half), 0.0f, 0.0f, std::cos(half)}},
               {"extensions", {{"KHR_lights_punctual", {{"light", sun}}}}}});
    const Scene scene = loadGltf(gltf.writeGltf(dir.path(), "sun"));
    ASSERT_EQ(scene.lights.size(), 1u);
    EXPECT_EQ(scene.lights[0].type, LightType::Directional);
    EXPECT_FLOAT_EQ(scene.lights[0].intensity, 3.0f);
    expectVec3Near(scene.lights[0].direction, {0, -1, 0});
}

TEST(GltfLights, LightReferencedByTwoNodesGivesTwoLights) {
    TempDir dir;
    GltfBuilder gltf;
    gltf.triangle();
    const int light = gltf.light({{"type", "point"}, {"range", 4.0}});
    gltf.node({{"name", "a"}, {"translation", {-1, 0, 0}}, {"extensions", {{"KHR_lights_punctual", {{"light", light}}}}}});
    const int child = gltf.node({{"name", "b"}, {"extensions", {{"KHR_lights_punctual", {{"light", light}}}}}}, false);
    gltf.node({{"translation", {0, 5, 0}}, {"scale", {2, 2, 2}}, {"children", {child}}});
    const Scene scene = loadGltf(gltf.writeGltf(dir.path(), "twice"));
    ASSERT_EQ(scene.lights.size(), 2u);
    EXPECT_EQ(scene.lights[0].name, "a");  // unnamed lights take their node's name
    expectVec3Near(scene.lights[0].position, {-1, 0, 0});
    expectVec3Near(scene.lights[1].position, {0, 5, 0});
    expectVec3Near(scene.lights[1].direction, {0, 0, -1});  // unit length despite the scale
}

// --- cameras ----------------------------------------------------------------------------------

TEST(GltfCamera, CameraNodeSetsViewAndProjectionParameters) {
    TempDir dir;
    GltfBuilder gltf;
    gltf.triangle();
    gltf.doc["cameras"] = json::array(
        {json{{"type", "perspective"}, {"name", "main"}, {"perspective", {{"yfov", 0.6}, {"znear", 0.1}, {"zfar", 50.0}}}}});
    // Scaled node: the view must ignore the scale.
    gltf.node({{"camera", 0}, {"translation", {0, 2, 10}}, {"scale", {3, 3, 3}}});
    const Scene scene = loadGltf(gltf.writeGltf(dir.path(), "camera"));
    EXPECT_TRUE(scene.cameraFromFile);
    EXPECT_EQ(scene.camera.name, "main");
    EXPECT_FLOAT_EQ(scene.camera.yfov, 0.6f);
    EXPECT_FLOAT_EQ(scene.camera.znear, 0.1f);
    EXPECT_FLOAT_EQ(scene.camera.zfar, 50.0f);
    expectVec3Near(scene.camera.position(), {0, 2, 10});
    EXPECT_NEAR(glm::determinant(glm::mat3(scene.camera.view)), 1.0f, 1e-5f);
    // The camera looks down -Z: the origin is straight ahead, 10 units away, 2 below.
    expectVec3Near(glm::vec3(scene.camera.view * glm::vec4(0, 2, 0, 1)), {0, 0, -10});
}

TEST(GltfCamera, MissingZfarIsDerivedFromSceneBounds) {
    TempDir dir;
    GltfBuilder gltf;
    gltf.triangle();
    gltf.doc["cameras"] = json::array({json{{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.5}}}}});
    gltf.node({{"camera", 0}, {"translation", {0, 0, 100}}});
    const Scene scene = loadGltf(gltf.writeGltf(dir.path(), "infinite"));
    ASSERT_TRUE(scene.cameraFromFile);
    // Farthest corner of the triangle's bounds, (1,1,0) or (0,0,0)-ish, from (0,0,100), x 1.1.
    EXPECT_NEAR(scene.camera.zfar, std::sqrt(1.0f + 1.0f + 100.0f * 100.0f) * 1.1f, 1e-3f);
}

TEST(GltfCamera, OrthographicCameraWarnsAndFallsBackToFittedView) {
    TempDir dir;
    GltfBuilder gltf;
    gltf.triangle();
    gltf.doc["cameras"] = json::array(
        {json{{"type", "orthographic"}, {"orthographic", {{"xmag", 1}, {"ymag", 1}, {"znear", 0.1}, {"zfar", 10}}}}});
    gltf.node({{"camera", 0}});
    WarningCapture capture;
    const Scene scene = loadGltf(gltf.writeGltf(dir.path(), "ortho"));
    EXPECT_FALSE(scene.cameraFromFile);
    ASSERT_EQ(capture.warnings.size(), 1u);
    EXPECT_NE(capture.warnings[0].find("orthographic"), std::string::npos) << capture.warnings[0];
}

TEST(GltfCamera, NoCameraGivesViewFittedToBounds) {
    TempDir dir;
    GltfBuilder gltf;
    gltf.triangle();
    const Scene scene = loadGltf(gltf.writeGltf(dir.path(), "nocamera"));
    EXPECT_FALSE(scene.cameraFromFile);
    const Camera fitted = fitCameraToBounds(scene.bounds);
    expectVec3Near(scene.camera.position(), fitted.position());
    EXPECT_FLOAT_EQ(scene.camera.zfar, fitted.zfar);
}

// --- a real scene -----------------------------------------------------------------------------

TEST(GltfSharedData, CornellBoxLoads) {
    const fs::path path = fs::path(PUNCTUAL_SHARED_DATA_DIR) / "cornell-box" / "cornellBox.gltf";
    if (!fs::exists(path)) GTEST_SKIP() << "shared data not present: " << path;
    const Scene scene = loadGltf(path.string());
    EXPECT_GT(scene.triangleCount(), 0u);
    EXPECT_FALSE(scene.materials.empty());
    EXPECT_TRUE(scene.cameraFromFile);
    EXPECT_FALSE(scene.bounds.empty());
}

}  // namespace
}  // namespace punctual
