// loadGltf on broken files: each must throw punctual::Error naming the file and the problem,
// never crash, hang or read out of bounds.
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "gltf_test_files.h"
#include "scene/gltf_loader.h"

namespace punctual {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

using unit_testing::accessorJson;
using unit_testing::bufferViewJson;
using unit_testing::kFloat;
using unit_testing::kUnsignedShort;
using unit_testing::TempDir;
using unit_testing::writeFile;

// A valid glTF with one indexed quad (4 vertices, 6 uint16 indices) in "scene.bin"; tests break
// one thing in `doc` or `bin` and write it.
struct QuadFile {
    json doc;
    std::vector<unsigned char> bin;

    QuadFile() {
        const float positions[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
        const uint16_t indices[6] = {0, 1, 2, 0, 2, 3};
        bin.resize(sizeof positions + sizeof indices);
        std::memcpy(bin.data(), positions, sizeof positions);
        std::memcpy(bin.data() + sizeof positions, indices, sizeof indices);
        doc = {{"asset", {{"version", "2.0"}}},
               {"scene", 0},
               {"scenes", {{{"nodes", {0}}}}},
               {"nodes", {{{"mesh", 0}, {"name", "quad"}}}},
               {"meshes", {{{"name", "quad"}, {"primitives", {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}}}}}}},
               {"accessors", {accessorJson(0, kFloat, 4, "VEC3"), accessorJson(1, kUnsignedShort, 6, "SCALAR")}},
               {"bufferViews", {bufferViewJson(0, sizeof positions), bufferViewJson(sizeof positions, sizeof indices)}},
               {"buffers", {{{"uri", "scene.bin"}, {"byteLength", bin.size()}}}}};
    }

    void setPosition(size_t vertex, size_t component, float value) {
        std::memcpy(bin.data() + (vertex * 3 + component) * sizeof(float), &value, sizeof value);
    }
    void setIndex(size_t i, uint16_t value) {
        std::memcpy(bin.data() + 12 * sizeof(float) + i * sizeof(uint16_t), &value, sizeof value);
    }
    void addLight(const json& light) {
        doc["extensionsUsed"] = {"KHR_lights_punctual"};
        doc["extensions"]["KHR_lights_punctual"]["lights"].push_back(light);
        doc["nodes"].push_back({{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
        doc["scenes"][0]["nodes"].push_back(doc["nodes"].size() - 1);
    }

    std::string write(const fs::path& dir, bool writeBin = true) const {
        if (writeBin) writeFile(dir / "scene.bin", bin);
        writeFile(dir / "scene.gltf", doc.dump(2));
        return (dir / "scene.gltf").string();
    }

    std::vector<unsigned char> glb() const { return unit_testing::glbFile(doc, bin); }
};

// Loading `path` throws punctual::Error whose message names the file and contains `keyword`.
void expectLoadError(const std::string& path, const std::string& keyword) {
    EXPECT_THROW(
        {
            try {
                loadGltf(path);
            } catch (const Error& e) {
                const std::string message = e.what();
                EXPECT_NE(message.find(path), std::string::npos) << message;
                EXPECT_NE(message.find(keyword), std::string::npos) << "expected '" << keyword << "' in: " << message;
                EXPECT_EQ(message.find('\n'), std::string::npos) << "not one line: " << message;
                throw;
            }
        },
        Error);
}

// Each test gets a fresh directory and a valid QuadFile to break.
class GltfMalformed : public ::testing::Test {
protected:
    // Writes `quad` and expects loading it to fail with `keyword` in the message.
    void expectQuadLoadError(const std::string& keyword) const { expectLoadError(quad.write(dir.path()), keyword); }

    TempDir dir;
    QuadFile quad;
};

TEST_F(GltfMalformed, ValidBaseFileLoads) {
    EXPECT_EQ(loadGltf(quad.write(dir.path())).triangleCount(), 2u);
}

TEST_F(GltfMalformed, NonexistentFile) {
    expectLoadError((dir.path() / "nothing-here.gltf").string(), "no such file");
}

TEST_F(GltfMalformed, TruncatedJson) {
    const std::string text = quad.doc.dump(2);
    const fs::path path = dir.path() / "half.gltf";
    writeFile(path, text.data(), text.size() / 2);
    expectLoadError(path.string(), "cannot parse JSON");
}

TEST_F(GltfMalformed, MissingBinFile) {
    quad.doc["buffers"][0]["uri"] = "missing.bin";
    expectQuadLoadError("buffer 0: 'missing.bin' cannot be read");
}

TEST_F(GltfMalformed, AccessorCountPastTheEndOfItsView) {
    quad.doc["accessors"][0]["count"] = 1000;
    expectQuadLoadError("accessor 0 reads past the end of buffer view 0");
}

TEST_F(GltfMalformed, AccessorByteOffsetPastTheEndOfItsView) {
    quad.doc["accessors"][1]["byteOffset"] = 4;
    expectQuadLoadError("reads past the end");
}

TEST_F(GltfMalformed, BufferViewPastTheEndOfItsBuffer) {
    quad.doc["bufferViews"][1]["byteLength"] = 4096;
    quad.doc["accessors"][1]["count"] = 2048;
    expectQuadLoadError("buffer view 1 reads past the end of buffer 0");
}

TEST_F(GltfMalformed, NanPosition) {
    quad.setPosition(2, 1, std::numeric_limits<float>::quiet_NaN());
    expectQuadLoadError("mesh 'quad' primitive 0: position 2 is not finite");
}

TEST_F(GltfMalformed, InfinitePosition) {
    quad.setPosition(3, 0, std::numeric_limits<float>::infinity());
    expectQuadLoadError("position 3 is not finite");
}

TEST_F(GltfMalformed, NanNormalAndTexcoord) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float normals[12] = {0, 0, 1, 0, 0, 1, 0, nan, 1, 0, 0, 1};
    const float uvs[8] = {0, 0, 1, 0, 1, 1, nan, 1};
    const size_t normalOffset = quad.bin.size();
    quad.bin.insert(quad.bin.end(), reinterpret_cast<const unsigned char*>(normals),
                    reinterpret_cast<const unsigned char*>(normals) + sizeof normals);
    const size_t uvOffset = quad.bin.size();
    quad.bin.insert(quad.bin.end(), reinterpret_cast<const unsigned char*>(uvs),
                    reinterpret_cast<const unsigned char*>(uvs) + sizeof uvs);
    quad.doc["buffers"][0]["byteLength"] = quad.bin.size();
    quad.doc["bufferViews"].push_back(bufferViewJson(normalOffset, sizeof normals));
    quad.doc["bufferViews"].push_back(bufferViewJson(uvOffset, sizeof uvs));
    quad.doc["accessors"].push_back(accessorJson(2, kFloat, 4, "VEC3"));
    quad.doc["accessors"].push_back(accessorJson(3, kFloat, 4, "VEC2"));
    quad.doc["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = 2;
    expectQuadLoadError("normal 2 is not finite");
    quad.doc["meshes"][0]["primitives"][0]["attributes"].erase("NORMAL");
    quad.doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = 3;
    expectQuadLoadError("texture coordinate 3 is not finite");
}

TEST_F(GltfMalformed, UnsupportedRequiredExtension) {
    quad.doc["extensionsUsed"] = {"KHR_draco_mesh_compression"};
    quad.doc["extensionsRequired"] = {"KHR_draco_mesh_compression"};
    expectQuadLoadError("KHR_draco_mesh_compression");
}

TEST_F(GltfMalformed, IndexNotLessThanVertexCount) {
    quad.setIndex(4, 4);
    expectQuadLoadError("index 4 is 4, out of range for 4 vertices");
}

TEST_F(GltfMalformed, IndexCountNotMultipleOfThree) {
    quad.doc["accessors"][1]["count"] = 5;
    expectQuadLoadError("not a whole number of triangles");
}

TEST_F(GltfMalformed, BadAccessorIndex) {
    quad.doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 7;
    expectQuadLoadError("accessor 7");
}

TEST_F(GltfMalformed, SparseAccessorIsRejected) {
    quad.doc["accessors"][0]["sparse"] = {{"count", 1},
                                          {"indices", {{"bufferView", 1}, {"componentType", kUnsignedShort}}},
                                          {"values", {{"bufferView", 0}}}};
    expectQuadLoadError("sparse");
}

TEST_F(GltfMalformed, NodeCycle) {
    quad.doc["nodes"].push_back({{"children", {2}}});
    quad.doc["nodes"].push_back({{"children", {1}}});
    quad.doc["scenes"][0]["nodes"].push_back(1);
    expectQuadLoadError("node 1 is its own ancestor");
}

TEST_F(GltfMalformed, BadNodeIndices) {
    quad.doc["nodes"][0]["children"] = {42};
    expectQuadLoadError("child 42, which does not exist");
    quad.doc["nodes"][0].erase("children");
    quad.doc["scenes"][0]["nodes"] = {-3};
    expectQuadLoadError("node -3");
    quad.doc["scenes"][0]["nodes"] = {0};
    quad.doc["nodes"][0]["mesh"] = 5;
    expectQuadLoadError("mesh 5");
}

TEST_F(GltfMalformed, NoTrianglesToDraw) {
    quad.doc["meshes"][0]["primitives"][0]["mode"] = 1;  // LINES
    expectQuadLoadError("no triangle meshes to draw");
}

TEST_F(GltfMalformed, NegativeLightRange) {
    quad.addLight({{"type", "point"}, {"range", -2.0}});
    expectQuadLoadError("invalid range");
}

TEST_F(GltfMalformed, InnerConeNotLessThanOuter) {
    quad.addLight({{"type", "spot"}, {"spot", {{"innerConeAngle", 0.5}, {"outerConeAngle", 0.5}}}});
    expectQuadLoadError("cone angles");
}

TEST_F(GltfMalformed, OuterConeBeyondHalfPi) {
    quad.addLight({{"type", "spot"}, {"spot", {{"outerConeAngle", 2.0}}}});
    expectQuadLoadError("cone angles");
}

TEST_F(GltfMalformed, NegativeIntensity) {
    quad.addLight({{"type", "point"}, {"intensity", -1.0}});
    expectQuadLoadError("intensity");
}

TEST_F(GltfMalformed, UnknownLightTypeAndMistypedProperty) {
    quad.addLight({{"type", "area"}});
    expectQuadLoadError("unknown type 'area'");
    QuadFile mistyped;
    mistyped.addLight({{"type", "point"}, {"range", "far"}});
    expectLoadError(mistyped.write(dir.path()), "'range' is not a number");
    QuadFile spotless;
    spotless.addLight({{"type", "spot"}});
    expectLoadError(spotless.write(dir.path()), "light 0 is a spot light without a 'spot' object");
}

TEST_F(GltfMalformed, BinFileOfTheWrongSize) {
    quad.doc["buffers"][0]["byteLength"] = 64;
    expectQuadLoadError("buffer 0: 'scene.bin' has 60 bytes but the buffer's byteLength is 64");
}

TEST_F(GltfMalformed, TruncatedGlb) {
    const std::vector<unsigned char> glb = quad.glb();
    const fs::path whole = dir.path() / "whole.glb";
    writeFile(whole, glb);
    EXPECT_EQ(loadGltf(whole.string()).triangleCount(), 2u);
    const fs::path cut = dir.path() / "cut.glb";
    writeFile(cut, glb.data(), glb.size() - 10);
    expectLoadError(cut.string(), "truncated");
}

TEST_F(GltfMalformed, ImageBufferViewOutsideItsBuffer) {
    quad.doc["bufferViews"].push_back(bufferViewJson(40, 100000));
    quad.doc["images"] = {{{"bufferView", 2}, {"mimeType", "image/png"}}};
    const fs::path path = dir.path() / "image.glb";
    writeFile(path, quad.glb());
    expectLoadError(path.string(), "image 0: buffer view 2 lies outside buffer 0");
}

// Every prefix of a valid file must fail cleanly: no crash, no hang, always punctual::Error.
TEST_F(GltfMalformed, EveryTruncationIsAnError) {
    const std::vector<unsigned char> glb = quad.glb();
    const std::string text = quad.doc.dump();
    writeFile(dir.path() / "scene.bin", quad.bin);
    const fs::path glbPath = dir.path() / "cut.glb";
    const fs::path gltfPath = dir.path() / "cut.gltf";
    for (size_t length = 0; length < glb.size(); length += 7) {
        writeFile(glbPath, glb.data(), length);
        EXPECT_THROW(loadGltf(glbPath.string()), Error) << "GLB cut at " << length;
    }
    for (size_t length = 0; length + 1 < text.size(); length += 13) {
        writeFile(gltfPath, text.data(), length);
        EXPECT_THROW(loadGltf(gltfPath.string()), Error) << "JSON cut at " << length;
    }
}

}  // namespace
}  // namespace punctual
