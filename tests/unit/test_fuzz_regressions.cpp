// Inputs the fuzzers (tests/fuzz) crashed on, each now a clean punctual::Error, and the bugs
// behind them written out as small cases.
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/log.h"
#include "gltf_test_files.h"
#include "scene/gltf_loader.h"

namespace punctual {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using unit_testing::TempDir;
using unit_testing::writeFile;

std::vector<unsigned char> readBytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The message of the punctual::Error loading `path` throws; fails the test for anything else.
std::string loadErrorOf(const std::string& path) {
    try {
        loadGltf(path);
    } catch (const Error& error) {
        return error.what();
    } catch (const std::exception& other) {
        ADD_FAILURE() << path << ": not a punctual::Error: " << other.what();
        return {};
    }
    ADD_FAILURE() << path << ": loaded";
    return {};
}

// Every file in tests/fuzz/regressions/gltf, run as the fuzzer ran it: alone in an empty folder
// (its relative URIs resolve there) as input.gltf.
TEST(FuzzRegressions, EveryGltfInputFailsWithOneClearLine) {
    const fs::path folder = fs::path(PUNCTUAL_FUZZ_REGRESSIONS_DIR) / "gltf";
    size_t count = 0;
    for (const auto& entry : fs::directory_iterator(folder)) {
        TempDir dir;
        const std::string path = (dir.path() / "input.gltf").string();
        writeFile(path, readBytes(entry.path()));
        const std::string message = loadErrorOf(path);
        EXPECT_EQ(message.rfind(path + ": ", 0), 0u) << entry.path() << ": " << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << entry.path() << ": " << message;
        ++count;
    }
    EXPECT_GT(count, 0u);
}

// One triangle whose buffer (and, with `image`, whose base-colour texture) has the URI given.
json triangleWithUris(const std::string& bufferUri, const std::string& imageUri = "") {
    json doc = {{"asset", {{"version", "2.0"}}},
                {"scenes", {{{"nodes", {0}}}}},
                {"nodes", {{{"mesh", 0}}}},
                {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}}}}}}}}},
                {"accessors", {unit_testing::accessorJson(0, unit_testing::kFloat, 3, "VEC3")}},
                {"bufferViews", {unit_testing::bufferViewJson(0, 36)}},
                {"buffers", {{{"uri", bufferUri}, {"byteLength", 36}}}}};
    if (!imageUri.empty()) {
        doc["meshes"][0]["primitives"][0]["material"] = 0;
        doc["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
        doc["textures"] = {{{"source", 0}}};
        doc["images"] = {{{"uri", imageUri}}};
    }
    return doc;
}

void writeTriangleBin(const fs::path& path) {
    const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    writeFile(path, positions, sizeof positions);
}

// Found by the fuzzer as a URI decoding to ".": tinygltf's file reader takes a directory's size
// to be 2^63 - 1 bytes and threw std::bad_alloc, an internal error instead of a clear one.
TEST(FuzzRegressions, BufferUriThatIsADirectoryIsAClearError) {
    TempDir dir;
    fs::create_directory(dir.path() / "textures");
    const std::string path = (dir.path() / "scene.gltf").string();
    writeFile(path, triangleWithUris("textures").dump());
    EXPECT_EQ(loadErrorOf(path), path + ": buffer 0: 'textures' cannot be read (a directory, not a regular file)");
}

// The same reader serves images, which may fail without failing the load: the texture falls back
// to the material's factor with one warning.
TEST(FuzzRegressions, ImageUriThatIsADirectoryFallsBackWithAWarning) {
    TempDir dir;
    fs::create_directory(dir.path() / "albedo.png");
    writeTriangleBin(dir.path() / "triangle.bin");
    const std::string path = (dir.path() / "scene.gltf").string();
    writeFile(path, triangleWithUris("triangle.bin", "albedo.png").dump());
    std::vector<std::string> warnings;
    const log::Sink previous =
        log::setSink([&](const std::string&, const std::string& message) { warnings.push_back(message); });
    Scene scene;
    EXPECT_NO_THROW(scene = loadGltf(path));
    log::setSink(previous);
    EXPECT_EQ(scene.triangleCount(), 1u);
    EXPECT_EQ(warnings.size(), 1u);
}

}  // namespace
}  // namespace punctual
