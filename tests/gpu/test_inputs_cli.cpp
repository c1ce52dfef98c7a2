// Inputs at their extremes, through the command line and the renderer: URIs that name folders
// and FIFOs, light ranges the spec forbids, textures larger than the device or the frame can use,
// generated lights around a small closed model, frames no light reaches, and the exit status of
// each kind of failure.
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <sys/wait.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/log.h"
#include "gpu_test_support.h"
#include "render/renderer.h"
#include "scene/gltf_loader.h"
#include "warning_capture.h"

namespace punctual {
namespace {

namespace fs = std::filesystem;
using testing::cat;
using testing::quoted;
using testing::RunResult;

// runPunctual under `timeout`, so a run that blocks (on a FIFO) fails the test with status 124
// instead of hanging the suite.
RunResult runBounded(const testing::TempFolder& folder, const std::string& args) {
    const std::string out = folder.file("stdout.txt");
    const std::string err = folder.file("stderr.txt");
    const std::string command =
        cat("timeout 120 ", quoted(PUNCTUAL_BINARY), " ", args, " >", quoted(out), " 2>", quoted(err));
    const int status = std::system(command.c_str());
    RunResult result;
    result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    result.out = testing::readText(out);
    result.err = testing::readText(err);
    return result;
}

using testing::WarningCapture;

// What a test scene holds besides its geometry (all optional).
struct SceneParts {
    std::string lights;          // the KHR_lights_punctual "lights" array, e.g. R"([{"type": "point"}])"
    std::string lightNode;       // that light's node, e.g. R"({"translation": [0, 3, 0]})" (not empty)
    std::string baseColorImage;  // the URI of the quad's base-colour image
    std::string bufferUri;       // an external URI for the quad's buffer instead of its data URI
};

// A 2 x 2 m quad at y = 0 under a camera 3 m above it (the layout of test_render_gltf.cpp).
std::string writeQuad(const testing::TempFolder& folder, const std::string& name, const SceneParts& parts) {
    std::string buffers = testing::quadGltfBuffers({0, 1, 1, 1, 1, 0, 0, 0});
    if (!parts.bufferUri.empty()) {
        const size_t start = buffers.find("data:");
        buffers.replace(start, buffers.find('"', start) - start, parts.bufferUri);
    }
    std::string nodes = R"({"mesh": 0}, {"camera": 0, "translation": [0, 3, 0], "rotation": [-0.70710678, 0, 0, 0.70710678]})";
    std::string sceneNodes = "0, 1";
    std::string extensions;
    if (!parts.lights.empty()) {
        extensions = cat(R"("extensionsUsed": ["KHR_lights_punctual"], "extensions": {"KHR_lights_punctual": {"lights": )",
                         parts.lights, "}},");
        std::string node = parts.lightNode;  // an object with at least one member
        node.insert(1, R"("extensions": {"KHR_lights_punctual": {"light": 0}}, )");
        nodes += ", " + node;
        sceneNodes += ", 2";
    }
    std::string material = R"({"pbrMetallicRoughness": {"metallicFactor": 0}})";
    std::string images;
    if (!parts.baseColorImage.empty()) {
        material = R"({"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0}})";
        images = cat(R"("textures": [{"source": 0}], "images": [{"uri": ")", parts.baseColorImage, R"("}],)");
    }
    const std::string gltf = cat(R"({"asset": {"version": "2.0"}, )", extensions, R"("scene": 0, "scenes": [{"nodes": [)",
                                 sceneNodes, R"(]}], "nodes": [)", nodes, R"(],
  "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1, "zfar": 10}}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3, "material": 0}]}],
  "materials": [)",
                                 material, "], ", images, buffers, "\n}");
    const std::string path = folder.file(name);
    std::ofstream(path) << gltf;
    return path;
}

const char* kSun = R"([{"type": "directional", "intensity": 2.0}])";
const char* kSunNode = R"({"rotation": [-0.70710678, 0, 0, 0.70710678]})";

// A closed 1 m cube (12 triangles, its normals computed by the loader), with no camera: the
// loader fits one to it. `lights` as in SceneParts, its node at `lightPosition`.
std::string writeCube(const testing::TempFolder& folder, const std::string& name, const std::string& lights = "",
                      const std::string& lightPosition = "[0, 0, 0]") {
    std::string bytes;
    for (int corner = 0; corner < 8; ++corner) {
        const float p[3] = {(corner & 1) ? 0.5f : -0.5f, (corner & 2) ? 0.5f : -0.5f, (corner & 4) ? 0.5f : -0.5f};
        bytes.append(reinterpret_cast<const char*>(p), sizeof p);
    }
    const uint16_t indices[36] = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4,
                                  2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
    bytes.append(reinterpret_cast<const char*>(indices), sizeof indices);
    std::string extensions;
    std::string lightNode;
    if (!lights.empty()) {
        extensions = cat(R"("extensionsUsed": ["KHR_lights_punctual"], "extensions": {"KHR_lights_punctual": {"lights": )",
                         lights, "}},");
        lightNode = cat(R"(, {"translation": )", lightPosition, R"(, "extensions": {"KHR_lights_punctual": {"light": 0}}})");
    }
    const std::string gltf = cat(R"({"asset": {"version": "2.0"}, )", extensions, R"( "scene": 0, "scenes": [{"nodes": [)",
                                 lights.empty() ? "0" : "0, 1", R"(]}], "nodes": [{"mesh": 0})", lightNode, R"(],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
  "buffers": [{"byteLength": 168, "uri": "data:application/octet-stream;base64,)",
                                 testing::base64(bytes), R"("}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 96}, {"buffer": 0, "byteOffset": 96, "byteLength": 72}],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 8, "type": "VEC3", "min": [-0.5, -0.5, -0.5], "max": [0.5, 0.5, 0.5]},
    {"bufferView": 1, "componentType": 5123, "count": 36, "type": "SCALAR"}
  ]
})");
    const std::string path = folder.file(name);
    std::ofstream(path) << gltf;
    return path;
}

bool anyLitPixel(const ImageRgba8& image) {
    for (size_t i = 0; i < image.pixels.size(); i += 4)
        if (image.pixels[i] != 0 || image.pixels[i + 1] != 0 || image.pixels[i + 2] != 0) return true;
    return false;
}

// README, "Exit status": 0 success, 1 a user error, 2 no or an unknown command, 3 a bug. No input
// provokes 3 (one that did would be a bug to fix), so it is not tested here.
TEST(CliInputs, ExitStatusSaysWhichKindOfFailure) {
    testing::TempFolder folder;
    RunResult run = runBounded(folder, "");
    EXPECT_EQ(run.exitCode, 2);
    EXPECT_NE(run.err.find("usage: punctual <command>"), std::string::npos) << run.err;
    run = runBounded(folder, "frobnicate");
    EXPECT_EQ(run.exitCode, 2);
    EXPECT_EQ(run.err, "punctual: error: unknown command 'frobnicate' (try punctual help)\n");
    EXPECT_EQ(runBounded(folder, "help").exitCode, 0);
    EXPECT_EQ(runBounded(folder, "render --help").exitCode, 0);
    run = runBounded(folder, "render --size 0x5");
    EXPECT_EQ(run.exitCode, 1);
    testing::expectOneClearError(run, "--size 0x5", "--size");
    run = runBounded(folder, cat("render ", quoted(folder.path())));
    EXPECT_EQ(run.exitCode, 1);
    testing::expectOneClearError(run, "a folder as the scene", "a directory, not a regular file");
}

TEST(CliInputs, BufferUrisNamingFoldersOrFifosFailCleanlyAndAtOnce) {
    testing::TempFolder folder;
    std::filesystem::create_directory(folder.file("sub"));
    ASSERT_EQ(::mkfifo(folder.file("pipe.bin").c_str(), 0600), 0);
    const std::string png = folder.file("out.png");
    for (const auto& [uri, problem] : std::vector<std::pair<std::string, std::string>>{
             {".", "a directory, not a regular file"},
             {"%2E%2E", "a directory, not a regular file"},
             {"sub", "a directory, not a regular file"},
             {"pipe.bin", "a named pipe (FIFO), not a regular file"},
             {"pipe%2Ebin", "a named pipe (FIFO), not a regular file"}}) {
        SceneParts parts;
        parts.bufferUri = uri;
        const std::string scene = writeQuad(folder, "scene.gltf", parts);
        const RunResult run = runBounded(folder, cat("render ", quoted(scene), " --size 32x32 --out ", quoted(png)));
        EXPECT_EQ(run.exitCode, 1) << uri << ": " << run.err;  // not 3 (std::bad_alloc), not 124 (blocked)
        testing::expectOneClearError(run, uri, cat(scene, ": buffer 0: '", uri, "' cannot be read (", problem, ")"));
        EXPECT_FALSE(std::filesystem::exists(png)) << uri;
    }
}

TEST(CliInputs, LightRangeZeroFailsCleanly) {
    testing::TempFolder folder;
    SceneParts parts;
    parts.lights = R"([{"type": "point", "name": "lamp", "range": 0}])";
    parts.lightNode = R"({"translation": [0, 1, 0]})";
    const std::string scene = writeQuad(folder, "scene.gltf", parts);
    const std::string png = folder.file("out.png");
    const RunResult run = runBounded(folder, cat("render ", quoted(scene), " --size 32x32 --out ", quoted(png)));
    EXPECT_EQ(run.exitCode, 1);
    testing::expectOneClearError(run, "range 0", cat(scene, ": light 0 'lamp' has an invalid range 0"));
    EXPECT_FALSE(std::filesystem::exists(png));
}

// 16385 texels is over lavapipe's maxImageDimension2D (16384), and over what a 160x120 frame can
// use: fitted when loaded, so the upload stays valid, with one warning.
TEST(CliInputs, TextureLargerThanTheFrameCanUseIsDownscaledWithOneWarning) {
    testing::TempFolder folder;
    ImageRgba8 big;
    big.width = 16385;
    big.height = 2;
    big.pixels.assign(size_t(big.width) * big.height * 4, 255);
    std::ofstream(folder.file("big.png"), std::ios::binary) << encodePng(big);
    SceneParts parts;
    parts.lights = kSun;
    parts.lightNode = kSunNode;
    parts.baseColorImage = "big.png";
    const std::string scene = writeQuad(folder, "scene.gltf", parts);
    const std::string png = folder.file("out.png");
    const RunResult run =
        runBounded(folder, cat("render ", quoted(scene), " --validate --size 160x120 --out ", quoted(png)));
    ASSERT_EQ(run.exitCode, 0) << run.err;
    EXPECT_EQ(run.err, cat("punctual: warning: ", scene,
                           ": image 0 'big.png' is 16385x2 texels; downscaled to 256x1 (enough for a "
                           "160x120 frame)\n"));
    const ImageRgba8 image = readPng(png);
    const uint8_t* centre = image.at(80, 60);
    EXPECT_GT(centre[0], 80);  // the white texture, lit by the sun
}

// Without the frame's limit (a scene loaded by a program, not the command line), the upload
// itself fits a texture to the device, whatever the device's limit is.
TEST(CliInputs, TextureLargerThanTheDeviceAllowsIsFittedAtUpload) {
    testing::TempFolder folder;
    auto context = testing::makeValidatedContext();
    const uint32_t limit = context->properties().limits.maxImageDimension2D;
    ImageRgba8 big;
    big.width = limit + 1;
    big.height = 2;
    big.pixels.assign(size_t(big.width) * big.height * 4, 255);
    std::ofstream(folder.file("big.png"), std::ios::binary) << encodePng(big);
    SceneParts parts;
    parts.lights = kSun;
    parts.lightNode = kSunNode;
    parts.baseColorImage = "big.png";
    const Scene scene = loadGltf(writeQuad(folder, "scene.gltf", parts));
    ASSERT_EQ(scene.textures.size(), 1u);
    ASSERT_EQ(scene.textures[0].width, limit + 1);
    WarningCapture capture;
    render::Renderer renderer(*context, scene, testing::renderSettings(64, 64));
    const ImageRgba8 image = renderer.render(1, 0).image;
    ASSERT_EQ(capture.warnings.size(), 1u);
    EXPECT_NE(capture.warnings[0].find(cat("is ", limit + 1, "x2 texels; downscaled to ", limit, "x2 (the device's limit, "
                                           "maxImageDimension2D = ", limit, ")")),
              std::string::npos)
        << capture.warnings[0];
    EXPECT_GT(image.at(32, 32)[0], 80);
    testing::expectNoValidationMessages(*context);
}

// The generated lights used to fall inside the model's bounds, i.e. inside it: a black image.
TEST(CliInputs, GeneratedLightsLightASmallClosedModel) {
    testing::TempFolder folder;
    const std::string scene = writeCube(folder, "cube.gltf");
    const std::string png = folder.file("out.png");
    const RunResult run =
        runBounded(folder, cat("render ", quoted(scene), " --validate --size 96x72 --lights 4,4 --out ", quoted(png)));
    ASSERT_EQ(run.exitCode, 0) << run.err;
    EXPECT_EQ(run.err, "");  // in particular, no "the image is black" warning
    EXPECT_TRUE(anyLitPixel(readPng(png)));
}

TEST(CliInputs, FrameNoLightReachesWarnsInOneLine) {
    testing::TempFolder folder;
    const std::string png = folder.file("out.png");
    const std::string unlit = writeCube(folder, "unlit.gltf");
    RunResult run = runBounded(folder, cat("render ", quoted(unlit), " --validate --size 64x48 --out ", quoted(png)));
    ASSERT_EQ(run.exitCode, 0) << run.err;
    EXPECT_EQ(run.err, cat("punctual: warning: ", unlit,
                           ": the image is black: the scene has no lights, not even a directional one (add some with "
                           "--lights S,P)\n"));
    EXPECT_FALSE(anyLitPixel(readPng(png)));

    const std::string inside = writeCube(folder, "inside.gltf", R"([{"type": "point", "intensity": 10}])", "[0, 0, 0]");
    run = runBounded(folder, cat("render ", quoted(inside), " --validate --size 64x48 --out ", quoted(png)));
    ASSERT_EQ(run.exitCode, 0) << run.err;
    EXPECT_EQ(run.err, cat("punctual: warning: ", inside,
                           ": the image is black: none of the scene's 1 light(s) reaches a surface the camera sees\n"));

    const std::string outside = writeCube(folder, "outside.gltf", R"([{"type": "point", "intensity": 10}])", "[1, 2, 3]");
    run = runBounded(folder, cat("render ", quoted(outside), " --validate --size 64x48 --out ", quoted(png)));
    ASSERT_EQ(run.exitCode, 0) << run.err;
    EXPECT_EQ(run.err, "");
    EXPECT_TRUE(anyLitPixel(readPng(png)));
}

// No output may replace a file the run reads, however it is spelt (issue 30: `--out s.gltf`
// replaced the scene, `--out tex.png` a texture, validate's reference.png a texture of that name).
// Each run fails in one line before any work, and every input is left byte for byte.
TEST(CliInputs, NoOutputReplacesAFileTheRunReads) {
    testing::TempFolder folder;
    fs::create_directories(folder.file("out"));
    ImageRgba8 texture;
    texture.width = texture.height = 4;
    texture.pixels.assign(4 * 4 * 4, 180);
    const std::string png = encodePng(texture);
    std::ofstream(folder.file("tex.png"), std::ios::binary) << png;
    std::ofstream(folder.file("out/reference.png"), std::ios::binary) << png;
    SceneParts parts;
    parts.lights = kSun;
    parts.lightNode = kSunNode;
    parts.baseColorImage = "tex.png";
    const std::string scene = writeQuad(folder, "s.gltf", parts);
    parts.baseColorImage = "out/reference.png";
    const std::string sceneB = writeQuad(folder, "b.gltf", parts);
    const std::string sceneBytes = testing::readText(scene);
    fs::create_symlink("s.gltf", folder.file("link.png"));
    fs::create_hard_link(scene, folder.file("hard.png"));

    for (const std::string& out : {folder.file("link.png"), folder.file("hard.png"), folder.file("out/../tex.png")}) {
        const std::string args = cat("render ", quoted(scene), " --size 32x18 --out ", quoted(out));
        const RunResult run = runBounded(folder, args);
        testing::expectOneClearError(run, args, "is an input of this run");
        EXPECT_EQ(run.exitCode, 1) << args;
        EXPECT_EQ(run.out, "") << args << ": the command rendered before refusing";
    }
    const std::string stats = cat("render ", quoted(scene), " --size 32x18 --stats ", quoted(folder.file("s.gltf")));
    testing::expectOneClearError(runBounded(folder, stats), stats, "punctual writes JSON there");
    const std::string validate = cat("validate ", quoted(sceneB), " --size 32x18 --out-dir ", quoted(folder.file("out")));
    testing::expectOneClearError(runBounded(folder, validate), validate, "is an input of this run");

    EXPECT_EQ(testing::readText(scene), sceneBytes) << "the scene changed";
    EXPECT_EQ(testing::readText(folder.file("tex.png")), png) << "the texture changed";
    EXPECT_EQ(testing::readText(folder.file("out/reference.png")), png) << "validate's texture changed";
    testing::expectNothingLeftBehind(folder, "every refused run", {"s.gltf", "b.gltf", "tex.png", "link.png", "hard.png", "out"});
    // The same scene renders to a file of its own.
    const std::string fine = cat("render ", quoted(scene), " --size 32x18 --out ", quoted(folder.file("frame.png")));
    EXPECT_EQ(runBounded(folder, fine).exitCode, 0) << fine;
}

// A field of view too narrow for float precision is refused in one line (issue 30: yfov 1e-8 drew
// half the frame black while Embree saw it lit; 1e-12 drew all of it black, with a false warning).
TEST(CliInputs, AFieldOfViewTooNarrowForFloatsIsRefused) {
    testing::TempFolder folder;
    SceneParts parts;
    parts.lights = kSun;
    parts.lightNode = kSunNode;
    const std::string scene = writeQuad(folder, "narrow.gltf", parts);
    std::string text = testing::readText(scene);
    const size_t yfov = text.find("\"yfov\": 0.8");
    ASSERT_NE(yfov, std::string::npos);
    for (const char* narrow : {"1e-8", "1e-12"}) {
        std::string changed = text;
        changed.replace(yfov, std::strlen("\"yfov\": 0.8"), cat("\"yfov\": ", narrow));
        std::ofstream(scene) << changed;
        for (const char* command : {"render", "reference"}) {
            const std::string args = cat(command, " ", quoted(scene), " --size 160x120 --out ", quoted(folder.file("x.png")));
            testing::expectOneClearError(runBounded(folder, args), args, "is too narrow for float precision at 120 rows");
        }
    }
    // The narrowest it accepts at 120 rows renders a lit frame (the quad fills it).
    std::string changed = text;
    changed.replace(yfov, std::strlen("\"yfov\": 0.8"), "\"yfov\": 0.002");
    std::ofstream(scene) << changed;
    const std::string args = cat("render ", quoted(scene), " --size 160x120 --out ", quoted(folder.file("x.png")));
    ASSERT_EQ(runBounded(folder, args).exitCode, 0) << args;
    EXPECT_TRUE(anyLitPixel(readPng(folder.file("x.png"))));
}

}  // namespace
}  // namespace punctual
