// loadGltf on broken files: each must throw punctual::Error naming the file and the problem,
// never crash, hang or read out of bounds.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <future>
#include <limits>
#include <optional>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/image.h"
#include "core/log.h"
#include "gltf_test_files.h"
#include "scene/gltf_loader.h"
#include "warning_capture.h"

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
    // Gives the quad a material whose base colour texture is `image` (a glTF image object).
    void addBaseColorImage(const json& image) {
        doc["images"] = {image};
        doc["textures"] = {{{"source", 0}}};
        doc["materials"] = {{{"name", "textured"}, {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
        doc["meshes"][0]["primitives"][0]["material"] = 0;
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
    quad.doc["extensionsUsed"] = {"KHR_texture_basisu"};
    quad.doc["extensionsRequired"] = {"KHR_texture_basisu"};
    expectQuadLoadError("requires the glTF extension KHR_texture_basisu, which is not supported");
}

TEST_F(GltfMalformed, UnsupportedRequiredExtensionsAreAllNamedBesideSupportedOnes) {
    quad.doc["extensionsUsed"] = {"KHR_mesh_quantization", "EXT_unknown_a", "KHR_draco_mesh_compression", "EXT_unknown_b"};
    quad.doc["extensionsRequired"] = quad.doc["extensionsUsed"];
    expectQuadLoadError("requires the glTF extensions EXT_unknown_a, EXT_unknown_b, which are not supported");
}

TEST_F(GltfMalformed, SupportedRequiredExtensionsLoad) {
    quad.doc["extensionsUsed"] = {"KHR_mesh_quantization", "KHR_draco_mesh_compression", "EXT_meshopt_compression",
                                  "KHR_lights_punctual"};
    quad.doc["extensionsRequired"] = quad.doc["extensionsUsed"];
    EXPECT_EQ(loadGltf(quad.write(dir.path())).triangleCount(), 2u);
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

// ---- files a URI names that are not regular files ----------------------------------------------

using testing::WarningCapture;

struct LoadOutcome {
    std::optional<std::string> error;  // what loadGltf threw, if it threw
    std::vector<std::string> warnings;
    std::optional<Scene> scene;
};

// loadGltf(path) on another thread, waiting at most 30 s. Opening a FIFO for reading blocks
// until a writer appears: if the load is still running by then, the test becomes that writer
// for `fifo` (which ends the blocked open or read) and fails, rather than hang the suite.
LoadOutcome loadInBoundedTime(const std::string& path, const fs::path& fifo = {}) {
    WarningCapture capture;
    LoadOutcome outcome;
    auto load = std::async(std::launch::async, [&path, &outcome]() {
        try {
            outcome.scene = loadGltf(path);
        } catch (const Error& e) {
            outcome.error = e.what();
        } catch (const std::exception& e) {
            outcome.error = std::string("internal error: ") + e.what();
        }
    });
    if (load.wait_for(std::chrono::seconds(30)) != std::future_status::ready) {
        ADD_FAILURE() << path << ": still loading after 30 s";
        while (!fifo.empty() && load.wait_for(std::chrono::milliseconds(100)) != std::future_status::ready) {
            const int writer = ::open(fifo.c_str(), O_WRONLY | O_NONBLOCK);
            if (writer >= 0) ::close(writer);
        }
    }
    load.get();
    outcome.warnings = capture.warnings;
    return outcome;
}

// The load failed with one line naming the scene file and containing `keyword`.
void expectError(const LoadOutcome& outcome, const std::string& path, const std::string& keyword) {
    ASSERT_TRUE(outcome.error.has_value()) << path << " loaded without an error";
    const std::string& message = *outcome.error;
    EXPECT_EQ(message.rfind(path + ": ", 0), 0u) << message;
    EXPECT_NE(message.find(keyword), std::string::npos) << "expected '" << keyword << "' in: " << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << "not one line: " << message;
}

constexpr const char* kFolder = "a directory, not a regular file";
constexpr const char* kFifo = "a named pipe (FIFO), not a regular file";

TEST_F(GltfMalformed, BufferUriNamingAFolderIsRefused) {
    fs::create_directory(dir.path() / "sub");
    // Plain and percent-encoded ("%2E" is '.', "%2F" is '/').
    for (const std::string uri : {".", "..", "sub", "%2E", "%2e%2E", "sub%2F"}) {
        quad.doc["buffers"][0]["uri"] = uri;
        const std::string path = quad.write(dir.path(), false);
        expectError(loadInBoundedTime(path), path, "buffer 0: '" + uri + "' cannot be read (" + kFolder + ")");
    }
}

TEST_F(GltfMalformed, BufferUriNamingAFifoIsRefusedWithoutOpeningIt) {
    const fs::path fifo = dir.path() / "pipe.bin";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    for (const std::string uri : {"pipe.bin", "pipe%2Ebin"}) {
        quad.doc["buffers"][0]["uri"] = uri;
        const std::string path = quad.write(dir.path(), false);
        const auto start = std::chrono::steady_clock::now();
        expectError(loadInBoundedTime(path, fifo), path, "buffer 0: '" + uri + "' cannot be read (" + kFifo + ")");
        EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5));
    }
}

TEST_F(GltfMalformed, BufferUriNamingADeviceIsRefused) {
    fs::create_symlink("/dev/zero", dir.path() / "zero.bin");
    quad.doc["buffers"][0]["uri"] = "zero.bin";
    const std::string path = quad.write(dir.path(), false);
    expectError(loadInBoundedTime(path), path, "buffer 0: 'zero.bin' cannot be read (a device, not a regular file)");
}

TEST_F(GltfMalformed, GlbBufferUrisNamingAFolderOrFifoAreRefused) {
    const fs::path fifo = dir.path() / "pipe.bin";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    const fs::path glb = dir.path() / "scene.glb";
    writeFile(glb, unit_testing::glbFile(quad.doc, quad.bin, json::array({{{"uri", "."}, {"byteLength", 4}}})));
    expectError(loadInBoundedTime(glb.string()), glb.string(), std::string("buffer 1: '.' cannot be read (") + kFolder);
    writeFile(glb, unit_testing::glbFile(quad.doc, quad.bin, json::array({{{"uri", "pipe%2Ebin"}, {"byteLength", 4}}})));
    expectError(loadInBoundedTime(glb.string(), fifo), glb.string(),
                std::string("buffer 1: 'pipe%2Ebin' cannot be read (") + kFifo);
}

// Images are not needed to draw (their materials fall back to the base colour factor, as for a
// missing image): one warning naming the scene, the image's URI and the problem.
TEST_F(GltfMalformed, ImageUriNamingAFolderOrFifoWarnsOnceAndFallsBack) {
    const fs::path fifo = dir.path() / "pipe.png";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    struct Case {
        std::string uri;
        const char* problem;
        bool binary;
    };
    for (const Case& c : {Case{".", kFolder, false}, Case{"%2E%2E", kFolder, true}, Case{"pipe.png", kFifo, false},
                          Case{"pipe%2Epng", kFifo, true}}) {
        QuadFile textured;
        textured.addBaseColorImage({{"uri", c.uri}});
        std::string path = (dir.path() / "textured.glb").string();
        if (c.binary) writeFile(path, textured.glb());
        else path = textured.write(dir.path());
        const LoadOutcome outcome = loadInBoundedTime(path, fifo);
        ASSERT_FALSE(outcome.error) << *outcome.error;
        ASSERT_EQ(outcome.warnings.size(), 1u) << c.uri;
        const std::string& warning = outcome.warnings[0];
        EXPECT_EQ(warning.rfind(path + ": ", 0), 0u) << warning;
        EXPECT_NE(warning.find("image 0 '" + c.uri + "' cannot be read (" + c.problem + ")"), std::string::npos) << warning;
        EXPECT_TRUE(outcome.scene->textures.empty());
        EXPECT_EQ(outcome.scene->materials[0].baseColorTexture.image, -1);
    }
}

TEST_F(GltfMalformed, SceneFileThatIsAFolderOrFifoIsRefused) {
    const fs::path folder = dir.path() / "folder.gltf";
    fs::create_directory(folder);
    expectError(loadInBoundedTime(folder.string()), folder.string(), std::string("cannot be read (") + kFolder);
    const fs::path fifo = dir.path() / "pipe.glb";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    expectError(loadInBoundedTime(fifo.string(), fifo), fifo.string(), std::string("cannot be read (") + kFifo);
}

// A relative URI is relative to the glTF file: tinygltf also looks in the current folder, which
// would read a file the scene never named.
TEST_F(GltfMalformed, RelativeUriIsNeverLookedUpInTheCurrentFolder) {
    fs::create_directory(dir.path() / "models");
    quad.doc["buffers"][0]["uri"] = "elsewhere.bin";
    quad.write(dir.path() / "models", false);
    writeFile(dir.path() / "elsewhere.bin", quad.bin);
    const fs::path previous = fs::current_path();
    fs::current_path(dir.path());
    const LoadOutcome outcome = loadInBoundedTime("models/scene.gltf");
    fs::current_path(previous);
    expectError(outcome, "models/scene.gltf", "buffer 0: 'elsewhere.bin' cannot be read (no such file)");
}

// ---- light ranges -----------------------------------------------------------------------------------

// KHR_lights_punctual: "range ... must be > 0". An absent range is infinite, and tinygltf reads
// it as 0, so a written 0 used to mean infinite too.
TEST_F(GltfMalformed, LightRangeZeroIsRejectedNamingTheLight) {
    quad.addLight({{"type", "point"}, {"name", "lamp"}, {"range", 0}});
    expectQuadLoadError("light 0 'lamp' has an invalid range 0 (KHR_lights_punctual requires range > 0");
    for (const char* type : {"spot", "directional"}) {
        QuadFile other;
        json light = {{"type", type}, {"range", 0.0}};
        if (std::string(type) == "spot") light["spot"] = json::object();
        other.addLight(light);
        expectLoadError(other.write(dir.path()), "light 0 has an invalid range 0");
    }
    QuadFile negative;
    negative.addLight({{"type", "spot"}, {"spot", json::object()}, {"range", -1e-30}});
    expectLoadError(negative.write(dir.path()), "light 0 has an invalid range -1e-30");
}

TEST_F(GltfMalformed, LightRangeNanIsAJsonError) {
    quad.addLight({{"type", "point"}, {"range", 12345}});
    std::string text = quad.doc.dump();
    text.replace(text.find("12345"), 5, "NaN");  // JSON has no NaN: nlohmann would write null
    writeFile(dir.path() / "scene.bin", quad.bin);
    writeFile(dir.path() / "scene.gltf", text);
    expectLoadError((dir.path() / "scene.gltf").string(), "cannot parse JSON");
}

TEST_F(GltfMalformed, HugeLightRangesAreKeptOrInfinite) {
    quad.addLight({{"type", "point"}, {"intensity", 4.0}, {"range", 1e30}});
    Scene scene = loadGltf(quad.write(dir.path()));
    ASSERT_EQ(scene.lights.size(), 1u);
    EXPECT_EQ(scene.lights[0].range, 1e30f);
    EXPECT_FALSE(scene.lights[0].rangeDerived);
    // Beyond what a float holds: infinite, as if absent. Beyond a double, the JSON parser
    // refuses the number.
    for (const char* huge : {"1e300", "1e400"}) {
        QuadFile far;
        far.addLight({{"type", "point"}, {"intensity", 4.0}, {"range", 12345}});
        std::string text = far.doc.dump();
        text.replace(text.find("12345"), 5, huge);
        writeFile(dir.path() / "scene.bin", far.bin);
        const fs::path path = dir.path() / "scene.gltf";
        writeFile(path, text);
        if (std::string(huge) == "1e400") {
            expectLoadError(path.string(), "cannot parse JSON: number overflow parsing '1e400'");
            continue;
        }
        scene = loadGltf(path.string());
        ASSERT_EQ(scene.lights.size(), 1u);
        EXPECT_TRUE(scene.lights[0].rangeDerived);
        EXPECT_EQ(scene.lights[0].range, derivedRange(4.0f, glm::vec3(1.0f)));
    }
}

// ---- textures larger than the frame can use -----------------------------------------------------

TEST_F(GltfMalformed, TextureOverTheLimitIsDownscaledOnLoadWithOneWarning) {
    ImageRgba8 wide;
    wide.width = 300;
    wide.height = 100;
    wide.pixels.assign(size_t(300) * 100 * 4, 200);
    writeFile(dir.path() / "wide.png", encodePng(wide));
    quad.addBaseColorImage({{"uri", "wide.png"}});
    const std::string path = quad.write(dir.path());

    WarningCapture capture;
    const Scene full = loadGltf(path);
    ASSERT_EQ(full.textures.size(), 1u);
    EXPECT_EQ(full.textures[0].width, 300u);
    EXPECT_TRUE(capture.warnings.empty());

    GltfLoadOptions options;
    options.textureLimit = {64, "a test's limit"};
    const Scene fitted = loadGltf(path, options);
    ASSERT_EQ(fitted.textures.size(), 1u);
    EXPECT_EQ(fitted.textures[0].width, 64u);
    EXPECT_EQ(fitted.textures[0].height, 21u);  // 100 x 64 / 300 = 21.3
    EXPECT_EQ(fitted.textures[0].rgba, std::vector<uint8_t>(size_t(64) * 21 * 4, 200));  // a flat colour stays
    ASSERT_EQ(capture.warnings.size(), 1u);
    EXPECT_EQ(capture.warnings[0], path + ": image 0 'wide.png' is 300x100 texels; downscaled to 64x21 "
                                          "(a test's limit)");
}

// Issue 30's third hardening round: each of these used to crash, read gigabytes, or say the wrong thing.

TEST_F(GltfMalformed, DeeplyNestedJsonIsRefusedBeforeTheParserRecursesIntoIt) {
    // 15,000 levels once overflowed the stack inside tinygltf's JSON conversion (SIGSEGV).
    const std::string deep = "{\"asset\": {\"version\": \"2.0\"}, \"extras\": " + std::string(15000, '[') +
                             std::string(15000, ']') + "}";
    writeFile(dir.path() / "deep.gltf", deep);
    expectLoadError((dir.path() / "deep.gltf").string(), "nests more than 128 levels");
    // Brackets inside strings do not count, and 128 levels are still read.
    quad.doc["extras"] = {{"text", std::string(5000, '[')}};
    json nested = json::array();
    for (int level = 0; level < 120; ++level) nested = json::array({nested});
    quad.doc["extras"]["nested"] = nested;
    EXPECT_EQ(loadGltf(quad.write(dir.path())).triangleCount(), 2u);
}

TEST_F(GltfMalformed, AFileThatCannotBeGltfIsRefusedFromItsFirstBytes) {
    // A sparse 3 GB file of zeros: refused at byte 0 without reading it (it would take seconds and
    // 3 GB of memory to read whole).
    const fs::path zeros = dir.path() / "zeros.gltf";
    writeFile(zeros, std::string());
    fs::resize_file(zeros, 3ull << 30);
    const auto started = std::chrono::steady_clock::now();
    expectLoadError(zeros.string(), "JSON text must start with '{' but byte 0 is 0x00");
    EXPECT_LT(std::chrono::steady_clock::now() - started, std::chrono::seconds(5)) << "the file was read whole";
    writeFile(dir.path() / "blank.gltf", std::string("  \n\t  "));
    expectLoadError((dir.path() / "blank.gltf").string(), "empty or only whitespace");
    // A UTF-8 byte order mark and whitespace before the '{' are fine.
    quad.write(dir.path());
    writeFile(dir.path() / "bom.gltf", "\xEF\xBB\xBF\n  " + quad.doc.dump());
    EXPECT_EQ(loadGltf((dir.path() / "bom.gltf").string()).triangleCount(), 2u);
}

TEST_F(GltfMalformed, OnlyGltfVersionTwoIsRead) {
    quad.doc["asset"]["version"] = "3.0";
    expectQuadLoadError("glTF version 3.0 is not supported (punctual reads 2.x)");
    quad.doc["asset"]["version"] = "two";
    expectQuadLoadError("asset.version 'two' is not <major>.<minor>");
    quad.doc["asset"]["version"] = "2.1";  // a newer minor version is compatible by the spec's rules
    EXPECT_EQ(loadGltf(quad.write(dir.path())).triangleCount(), 2u);
    quad.doc["asset"]["minVersion"] = "2.1";
    expectQuadLoadError("asset.minVersion '2.1' needs a newer loader");
    quad.doc["asset"] = json::object();
    expectQuadLoadError("asset.version is missing");
}

TEST_F(GltfMalformed, ANodeWithBothAMatrixAndTrsIsRefused) {
    quad.doc["nodes"][0]["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 5, 0, 0, 1};
    quad.doc["nodes"][0]["translation"] = {1, 2, 3};
    expectQuadLoadError("node 0 has both a matrix and a translation");
}

TEST_F(GltfMalformed, ADataUriOfTheWrongLengthNamesBothLengths) {
    // 48 bytes of base64 ("AAAA" is 3 bytes) where byteLength says 60.
    quad.doc["buffers"][0]["uri"] = "data:application/octet-stream;base64," + std::string(64, 'A');
    quad.doc["buffers"][0]["byteLength"] = 60;
    expectQuadLoadError("buffer 0: its data URI holds 48 bytes but its byteLength is 60");
    quad.doc["buffers"][0]["uri"] = "data:application/octet-stream;base64," + std::string(62, 'A') + "==";
    expectQuadLoadError("holds 46 bytes");
    quad.doc["buffers"][0]["uri"] = "data:application/octet-stream;base64,AAA";
    expectQuadLoadError("has 3 characters, not a multiple of 4");
    // The right length of text that is not base64: tinygltf's message, with the URI cut short.
    quad.doc["buffers"][0]["uri"] = "data:application/octet-stream;base64," + std::string(2000, '!');
    quad.doc["buffers"][0]["byteLength"] = 1500;
    try {
        loadGltf(quad.write(dir.path()));
        ADD_FAILURE() << "text that is not base64 was accepted";
    } catch (const Error& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("data:application/octet-stream;base64,!!!... (2037 characters)"), std::string::npos)
            << message;
        EXPECT_LT(message.size(), 300u) << message;
    }
}

TEST_F(GltfMalformed, ABrightLightWithoutARangeIsNotBlamedForItsRange) {
    quad.addLight({{"type", "point"}, {"intensity", 1e37}});
    expectQuadLoadError("no range and an intensity of 1e+37 cd, too large to derive a cut-off radius");
}

TEST_F(GltfMalformed, APointLightOnAZeroScaleNodeKeepsItsPosition) {
    quad.addLight({{"type", "point"}, {"intensity", 10.0}, {"range", 5.0}});
    quad.doc["nodes"].back()["translation"] = {1.0, 2.0, 3.0};
    quad.doc["nodes"].back()["scale"] = {0.0, 0.0, 0.0};
    const Scene scene = loadGltf(quad.write(dir.path()));
    ASSERT_EQ(scene.lights.size(), 1u);
    EXPECT_EQ(scene.lights[0].position, glm::vec3(1.0f, 2.0f, 3.0f));
    EXPECT_EQ(scene.lights[0].direction, glm::vec3(0.0f, 0.0f, -1.0f));  // none to lose: the default
    // A spot has a direction to lose.
    quad.doc["extensions"]["KHR_lights_punctual"]["lights"][0] = {
        {"type", "spot"}, {"intensity", 10.0}, {"range", 5.0}, {"spot", json::object()}};
    expectQuadLoadError("has a degenerate direction");
}

TEST_F(GltfMalformed, MorphTargetsAreAppliedAtTheirDefaultWeights) {
    // One target moving every vertex by (0, 0, 2), and its NORMAL unused. Weight 0 (the default)
    // draws the base quad; the mesh's weight 0.25 moves it by 0.5; a node's weight overrides.
    const float deltas[12] = {0, 0, 2, 0, 0, 2, 0, 0, 2, 0, 0, 2};
    const size_t offset = quad.bin.size();
    quad.bin.resize(offset + sizeof deltas);
    std::memcpy(quad.bin.data() + offset, deltas, sizeof deltas);
    quad.doc["buffers"][0]["byteLength"] = quad.bin.size();
    quad.doc["bufferViews"].push_back(bufferViewJson(offset, sizeof deltas));
    quad.doc["accessors"].push_back(accessorJson(2, kFloat, 4, "VEC3"));
    quad.doc["meshes"][0]["primitives"][0]["targets"] = {{{"POSITION", 2}}};
    const auto zOf = [&](const Scene& scene) {
        float lowest = 1e9f, highest = -1e9f;
        for (const Vertex& v : scene.vertices) {
            lowest = std::min(lowest, v.position.z);
            highest = std::max(highest, v.position.z);
        }
        EXPECT_EQ(lowest, highest);
        return lowest;
    };
    EXPECT_EQ(zOf(loadGltf(quad.write(dir.path()))), 0.0f);  // no weights: 0
    quad.doc["meshes"][0]["weights"] = {0.25};
    EXPECT_EQ(zOf(loadGltf(quad.write(dir.path()))), 0.5f);
    quad.doc["nodes"][0]["weights"] = {1.0};
    EXPECT_EQ(zOf(loadGltf(quad.write(dir.path()))), 2.0f);
    // A sparse target is not read: one warning, the base shape.
    quad.doc["accessors"][2].erase("bufferView");
    quad.doc["accessors"][2]["sparse"] = {{"count", 1}, {"indices", {{"bufferView", 1}, {"componentType", 5123}}},
                                          {"values", {{"bufferView", 2}}}};
    WarningCapture capture;
    const Scene sparse = loadGltf(quad.write(dir.path()));
    ASSERT_EQ(capture.warnings.size(), 1u);
    EXPECT_NE(capture.warnings[0].find("1 weighted morph target(s) use sparse accessors"), std::string::npos);
}

TEST_F(GltfMalformed, ABufferFileLargerThanItsByteLengthIsRefusedUnread) {
    quad.bin.resize(quad.bin.size() + 1000);  // byteLength stays 60
    expectQuadLoadError("buffer 0: 'scene.bin' cannot be read (1060 bytes, more than the buffer's byteLength 60)");
}

}  // namespace
}  // namespace punctual
