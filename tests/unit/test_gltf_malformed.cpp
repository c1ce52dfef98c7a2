// loadGltf on broken files: each must throw punctual::Error naming the file and the problem,
// never crash, hang or read out of bounds.
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "scene/gltf_loader.h"

namespace punctual {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

class TempDir {
public:
    TempDir() {
        const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
        path_ = fs::temp_directory_path() /
                ("punctual-gltf-" + std::to_string(::getpid()) + "-" + test->test_suite_name() + "-" + test->name());
        fs::remove_all(path_);
        fs::create_directories(path_);
    }
    ~TempDir() {
        std::error_code ignored;
        fs::remove_all(path_, ignored);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    const fs::path& path() const { return path_; }

private:
    fs::path path_;
};

void writeFile(const fs::path& path, const void* data, size_t size) {
    std::ofstream out(path, std::ios::binary);
    out.write(static_cast<const char*>(data), static_cast<std::streamsize>(size));
}

void appendU32(std::vector<unsigned char>& out, uint32_t value) {
    for (int shift = 0; shift < 32; shift += 8) out.push_back(static_cast<unsigned char>(value >> shift));
}

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
               {"accessors", {{{"bufferView", 0}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}},
                              {{"bufferView", 1}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}}}},
               {"bufferViews", {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", sizeof positions}},
                                {{"buffer", 0}, {"byteOffset", sizeof positions}, {"byteLength", sizeof indices}}}},
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
        if (writeBin) writeFile(dir / "scene.bin", bin.data(), bin.size());
        const std::string text = doc.dump(2);
        writeFile(dir / "scene.gltf", text.data(), text.size());
        return (dir / "scene.gltf").string();
    }

    std::vector<unsigned char> glb() const {
        json out = doc;
        out["buffers"] = {{{"byteLength", bin.size()}}};
        std::string text = out.dump();
        while (text.size() % 4 != 0) text += ' ';
        std::vector<unsigned char> payload = bin;
        while (payload.size() % 4 != 0) payload.push_back(0);
        std::vector<unsigned char> file;
        appendU32(file, 0x46546C67);
        appendU32(file, 2);
        appendU32(file, uint32_t(12 + 8 + text.size() + 8 + payload.size()));
        appendU32(file, uint32_t(text.size()));
        appendU32(file, 0x4E4F534A);
        file.insert(file.end(), text.begin(), text.end());
        appendU32(file, uint32_t(payload.size()));
        appendU32(file, 0x004E4942);
        file.insert(file.end(), payload.begin(), payload.end());
        return file;
    }
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

TEST(GltfMalformed, ValidBaseFileLoads) {
    TempDir dir;
    EXPECT_EQ(loadGltf(QuadFile().write(dir.path())).triangleCount(), 2u);
}

TEST(GltfMalformed, NonexistentFile) {
    TempDir dir;
    expectLoadError((dir.path() / "nothing-here.gltf").string(), "no such file");
}

TEST(GltfMalformed, TruncatedJson) {
    TempDir dir;
    const std::string text = QuadFile().doc.dump(2);
    const fs::path path = dir.path() / "half.gltf";
    writeFile(path, text.data(), text.size() / 2);
    expectLoadError(path.string(), "cannot parse JSON");
}

TEST(GltfMalformed, MissingBinFile) {
    TempDir dir;
    QuadFile quad;
    quad.doc["buffers"][0]["uri"] = "missing.bin";
    expectLoadError(quad.write(dir.path()), "buffer 0: 'missing.bin' cannot be read");
}

TEST(GltfMalformed, AccessorCountPastTheEndOfItsView) {
    TempDir dir;
    QuadFile quad;
    quad.doc["accessors"][0]["count"] = 1000;
    expectLoadError(quad.write(dir.path()), "accessor 0 reads past the end of buffer view 0");
}

TEST(GltfMalformed, AccessorByteOffsetPastTheEndOfItsView) {
    TempDir dir;
    QuadFile quad;
    quad.doc["accessors"][1]["byteOffset"] = 4;
    expectLoadError(quad.write(dir.path()), "reads past the end");
}

TEST(GltfMalformed, BufferViewPastTheEndOfItsBuffer) {
    TempDir dir;
    QuadFile quad;
    quad.doc["bufferViews"][1]["byteLength"] = 4096;
    quad.doc["accessors"][1]["count"] = 2048;
    expectLoadError(quad.write(dir.path()), "buffer view 1 reads past the end of buffer 0");
}

TEST(GltfMalformed, NanPosition) {
    TempDir dir;
    QuadFile quad;
    quad.setPosition(2, 1, std::numeric_limits<float>::quiet_NaN());
    expectLoadError(quad.write(dir.path()), "mesh 'quad' primitive 0: position 2 is not finite");
}

TEST(GltfMalformed, InfinitePosition) {
    TempDir dir;
    QuadFile quad;
    quad.setPosition(3, 0, std::numeric_limits<float>::infinity());
    expectLoadError(quad.write(dir.path()), "position 3 is not finite");
}

TEST(GltfMalformed, NanNormalAndTexcoord) {
    TempDir dir;
    QuadFile quad;
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
    quad.doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", normalOffset}, {"byteLength", sizeof normals}});
    quad.doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", uvOffset}, {"byteLength", sizeof uvs}});
    quad.doc["accessors"].push_back({{"bufferView", 2}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}});
    quad.doc["accessors"].push_back({{"bufferView", 3}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}});
    quad.doc["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = 2;
    expectLoadError(quad.write(dir.path()), "normal 2 is not finite");
    quad.doc["meshes"][0]["primitives"][0]["attributes"].erase("NORMAL");
    quad.doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = 3;
    expectLoadError(quad.write(dir.path()), "texture coordinate 3 is not finite");
}

TEST(GltfMalformed, UnsupportedRequiredExtension) {
    TempDir dir;
    QuadFile quad;
    quad.doc["extensionsUsed"] = {"KHR_draco_mesh_compression"};
    quad.doc["extensionsRequired"] = {"KHR_draco_mesh_compression"};
    expectLoadError(quad.write(dir.path()), "KHR_draco_mesh_compression");
}

TEST(GltfMalformed, IndexNotLessThanVertexCount) {
    TempDir dir;
    QuadFile quad;
    quad.setIndex(4, 4);
    expectLoadError(quad.write(dir.path()), "index 4 is 4, out of range for 4 vertices");
}

TEST(GltfMalformed, IndexCountNotMultipleOfThree) {
    TempDir dir;
    QuadFile quad;
    quad.doc["accessors"][1]["count"] = 5;
    expectLoadError(quad.write(dir.path()), "not a whole number of triangles");
}

TEST(GltfMalformed, BadAccessorIndex) {
    TempDir dir;
    QuadFile quad;
    quad.doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 7;
    expectLoadError(quad.write(dir.path()), "accessor 7");
}

TEST(GltfMalformed, SparseAccessorIsRejected) {
    TempDir dir;
    QuadFile quad;
    quad.doc["accessors"][0]["sparse"] = {{"count", 1},
                                          {"indices", {{"bufferView", 1}, {"componentType", 5123}}},
                                          {"values", {{"bufferView", 0}}}};
    expectLoadError(quad.write(dir.path()), "sparse");
}

TEST(GltfMalformed, NodeCycle) {
    TempDir dir;
    QuadFile quad;
    quad.doc["nodes"].push_back({{"children", {2}}});
    quad.doc["nodes"].push_back({{"children", {1}}});
    quad.doc["scenes"][0]["nodes"].push_back(1);
    expectLoadError(quad.write(dir.path()), "node 1 is its own ancestor");
}

TEST(GltfMalformed, BadNodeIndices) {
    TempDir dir;
    QuadFile quad;
    quad.doc["nodes"][0]["children"] = {42};
    expectLoadError(quad.write(dir.path()), "child 42, which does not exist");
    quad.doc["nodes"][0].erase("children");
    quad.doc["scenes"][0]["nodes"] = {-3};
    expectLoadError(quad.write(dir.path()), "node -3");
    quad.doc["scenes"][0]["nodes"] = {0};
    quad.doc["nodes"][0]["mesh"] = 5;
    expectLoadError(quad.write(dir.path()), "mesh 5");
}

TEST(GltfMalformed, NoTrianglesToDraw) {
    TempDir dir;
    QuadFile quad;
    quad.doc["meshes"][0]["primitives"][0]["mode"] = 1;  // LINES
    expectLoadError(quad.write(dir.path()), "no triangle meshes to draw");
}

TEST(GltfMalformed, NegativeLightRange) {
    TempDir dir;
    QuadFile quad;
    quad.addLight({{"type", "point"}, {"range", -2.0}});
    expectLoadError(quad.write(dir.path()), "invalid range");
}

TEST(GltfMalformed, InnerConeNotLessThanOuter) {
    TempDir dir;
    QuadFile quad;
    quad.addLight({{"type", "spot"}, {"spot", {{"innerConeAngle", 0.5}, {"outerConeAngle", 0.5}}}});
    expectLoadError(quad.write(dir.path()), "cone angles");
}

TEST(GltfMalformed, OuterConeBeyondHalfPi) {
    TempDir dir;
    QuadFile quad;
    quad.addLight({{"type", "spot"}, {"spot", {{"outerConeAngle", 2.0}}}});
    expectLoadError(quad.write(dir.path()), "cone angles");
}

TEST(GltfMalformed, NegativeIntensity) {
    TempDir dir;
    QuadFile quad;
    quad.addLight({{"type", "point"}, {"intensity", -1.0}});
    expectLoadError(quad.write(dir.path()), "intensity");
}

TEST(GltfMalformed, UnknownLightTypeAndMistypedProperty) {
    TempDir dir;
    QuadFile quad;
    quad.addLight({{"type", "area"}});
    expectLoadError(quad.write(dir.path()), "unknown type 'area'");
    QuadFile mistyped;
    mistyped.addLight({{"type", "point"}, {"range", "far"}});
    expectLoadError(mistyped.write(dir.path()), "'range' is not a number");
    QuadFile spotless;
    spotless.addLight({{"type", "spot"}});
    expectLoadError(spotless.write(dir.path()), "light 0 is a spot light without a 'spot' object");
}

TEST(GltfMalformed, BinFileOfTheWrongSize) {
    TempDir dir;
    QuadFile quad;
    quad.doc["buffers"][0]["byteLength"] = 64;
    expectLoadError(quad.write(dir.path()), "buffer 0: 'scene.bin' has 60 bytes but the buffer's byteLength is 64");
}

TEST(GltfMalformed, TruncatedGlb) {
    TempDir dir;
    const std::vector<unsigned char> glb = QuadFile().glb();
    const fs::path whole = dir.path() / "whole.glb";
    writeFile(whole, glb.data(), glb.size());
    EXPECT_EQ(loadGltf(whole.string()).triangleCount(), 2u);
    const fs::path cut = dir.path() / "cut.glb";
    writeFile(cut, glb.data(), glb.size() - 10);
    expectLoadError(cut.string(), "truncated");
}

TEST(GltfMalformed, ImageBufferViewOutsideItsBuffer) {
    TempDir dir;
    QuadFile quad;
    quad.doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", 40}, {"byteLength", 100000}});
    quad.doc["images"] = {{{"bufferView", 2}, {"mimeType", "image/png"}}};
    const std::vector<unsigned char> glb = quad.glb();
    const fs::path path = dir.path() / "image.glb";
    writeFile(path, glb.data(), glb.size());
    expectLoadError(path.string(), "image 0: buffer view 2 lies outside buffer 0");
}

// Every prefix of a valid file must fail cleanly: no crash, no hang, always punctual::Error.
TEST(GltfMalformed, EveryTruncationIsAnError) {
    TempDir dir;
    const QuadFile quad;
    const std::vector<unsigned char> glb = quad.glb();
    const std::string text = quad.doc.dump();
    writeFile(dir.path() / "scene.bin", quad.bin.data(), quad.bin.size());
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
