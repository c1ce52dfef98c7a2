// The procedural rooms scene on the GPU: it renders lit, tiled and clustered light lists give
// brute force's image bit for bit, and per-view object culling draws fewer objects than the scene
// has while leaving the image unchanged against drawing every object. On the command line,
// --scene-triangles sizes it, its stats report the drawn geometry and memory, and a bad size, or a
// size for a scene of fixed size, fails with one line naming the option.
#include <gtest/gtest.h>

#include <string>

#include <nlohmann/json.hpp>

#include "gpu_test_support.h"
#include "render/renderer.h"
#include "scene/rooms_scene.h"

namespace punctual {
namespace {

using render::LightListMethod;
using testing::quoted;
using testing::readText;
using testing::RunResult;
using testing::runPunctual;

// 20k triangles: two rooms, enough that some objects are behind the camera.
const Scene& smallRooms() {
    static const Scene scene = makeRoomsScene(20'000);
    return scene;
}

render::RenderSettings settingsFor(LightListMethod method, bool shadows) {
    render::RenderSettings settings = testing::renderSettings(192, 108);
    settings.method = method;
    settings.shadows.enabled = shadows;
    return settings;
}

size_t differingPixels(const ImageRgba8& a, const ImageRgba8& b) {
    size_t count = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i) count += a.pixels[i] != b.pixels[i];
    return count;
}

TEST(RoomsScene, TiledAndClusteredMatchBruteForceBitForBit) {
    auto context = testing::makeValidatedContext();
    render::Renderer bruteRenderer(*context, smallRooms(), settingsFor(LightListMethod::Brute, true));
    const ImageRgba8 brute = bruteRenderer.render(1, 0).image;
    testing::saveTestImage("rooms-brute", brute);
    EXPECT_GT(testing::meanLuma(brute), 0.05);  // lit, not black
    for (const LightListMethod method : {LightListMethod::Tiled, LightListMethod::Clustered}) {
        render::Renderer renderer(*context, smallRooms(), settingsFor(method, true));
        EXPECT_EQ(differingPixels(renderer.render(1, 0).image, brute), 0u) << render::methodName(method);
    }
    testing::expectNoValidationMessages(*context);
}

TEST(RoomsScene, FrustumCullingDrawsFewerObjectsAndLeavesTheImageUnchanged) {
    auto context = testing::makeValidatedContext();
    const Scene& scene = smallRooms();
    for (const LightListMethod method : {LightListMethod::Brute, LightListMethod::Tiled}) {
        render::RenderSettings everything = settingsFor(method, true);
        everything.cullObjectsToView = false;
        render::Renderer all(*context, scene, everything);
        render::Renderer culled(*context, scene, settingsFor(method, true));
        EXPECT_EQ(all.cameraDraws().objectsInView, scene.objects.size());
        EXPECT_EQ(all.cameraDraws().triangles, scene.triangleCount());
        EXPECT_LT(culled.cameraDraws().objectsInView, scene.objects.size());
        EXPECT_GT(culled.cameraDraws().objectsInView, 0u);
        EXPECT_LT(culled.cameraDraws().triangles, scene.triangleCount());
        EXPECT_EQ(culled.cameraDraws().depthDraws + culled.cameraDraws().transparentDraws,
                  culled.cameraDraws().objectsInView);  // no BLEND objects here: every one in the prepass
        EXPECT_EQ(differingPixels(culled.render(1, 0).image, all.render(1, 0).image), 0u) << render::methodName(method);
        // Each shadow view draws no more than its casters; a point light's face at most all objects.
        const render::ShadowDraws shadows = culled.shadowDraws();
        EXPECT_GT(shadows.total, 0u);
        EXPECT_LE(shadows.maxPerView, scene.objects.size());
        EXPECT_GT(culled.deviceMemoryBytes(), scene.vertices.size() * sizeof(Vertex));
    }
    testing::expectNoValidationMessages(*context);
}

TEST(RoomsScene, RendersFromTheCommandLineWithGeometryAndMemoryStats) {
    testing::TempFolder folder;
    const std::string png = folder.file("rooms.png");
    const std::string json = folder.file("stats.json");
    const RunResult run = runPunctual(folder, "render --scene rooms --scene-triangles 20k --validate --size 160x90 --out " +
                                                  quoted(png) + " --stats " + quoted(json));
    ASSERT_EQ(run.exitCode, 0) << run.err;
    EXPECT_EQ(run.err, "");
    const ImageRgba8 image = readPng(png);
    testing::saveTestImage("scene_cli_rooms", image);
    EXPECT_GT(testing::meanLuma(image), 0.05);
    EXPECT_LT(testing::fractionBrighterThan(image, 250), 0.05);
    const nlohmann::json stats = nlohmann::json::parse(readText(json));
    EXPECT_EQ(stats["scene"].get<std::string>(), rooms_scene::kSource);
    const nlohmann::json& geometry = stats["geometry"];
    EXPECT_EQ(geometry["triangles"].get<uint64_t>(), rooms_scene::layoutFor(20'000).triangles);
    EXPECT_EQ(geometry["triangles_instanced"].get<uint64_t>(), geometry["triangles"].get<uint64_t>());
    EXPECT_LT(geometry["objects_in_view"].get<uint64_t>(), geometry["objects"].get<uint64_t>());
    EXPECT_LT(geometry["camera_triangles"].get<uint64_t>(), geometry["triangles"].get<uint64_t>());
    EXPECT_EQ(geometry["camera_draws"]["depth"].get<uint64_t>(), geometry["objects_in_view"].get<uint64_t>());
    EXPECT_GT(geometry["shadow_draws"]["total"].get<uint64_t>(), 0u);
    EXPECT_GT(geometry["shadow_draws"]["max_per_view"].get<uint64_t>(), 0u);
    EXPECT_GT(stats["memory"]["peak_rss_bytes"].get<uint64_t>(), 1u << 20);
    EXPECT_GT(stats["memory"]["device_bytes"].get<uint64_t>(), 1u << 10);
    EXPECT_EQ(stats["lights"]["in_scene"].get<int>(), 97);  // 64 spots, 32 points, the sun
}

TEST(RoomsScene, BadSizesFailWithOneLineNamingTheOption) {
    testing::TempFolder folder;
    const std::string png = quoted(folder.file("x.png"));
    const std::string range = "--scene-triangles: expected a triangle count from 10k to 10M";
    for (const std::string size : {"5k", "20M", "abc", "2.5", "-1", "1e3", "100kk", "k"}) {
        const std::string args = "render --scene rooms --scene-triangles " + size + " --out " + png;
        const RunResult run = runPunctual(folder, args);
        testing::expectOneClearError(run, args, range);
        EXPECT_EQ(run.exitCode, 1) << args;
        testing::expectNothingLeftBehind(folder, args);
    }
    for (const std::string& args : {"render --scene hall --scene-triangles 20k --out " + png,
                                   "render --scene-triangles 20k --out " + png,
                                   "render some.gltf --scene-triangles 20k --out " + png}) {
        const RunResult run = runPunctual(folder, args);
        testing::expectOneClearError(run, args, "--scene-triangles: sizes only --scene rooms");
        EXPECT_EQ(run.exitCode, 1) << args;
    }
    const RunResult missing = runPunctual(folder, "render --scene rooms --scene-triangles --out " + png);
    testing::expectOneClearError(missing, "--scene-triangles without a value", "--scene-triangles: needs a value");
}

}  // namespace
}  // namespace punctual
