// Every scene file written by others in ../shared/data (real assets, never copied into the
// repository) loads and renders: something of it is drawn, tiled culling stays bit-identical to
// brute force, and validation stays silent. Skipped cleanly where the folder is absent.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "gpu_test_support.h"
#include "render/renderer.h"
#include "scene/gltf_loader.h"
#include "scene/light_generator.h"

namespace punctual {
namespace {

namespace fs = std::filesystem;

// The .gltf and .glb files under the folder, sorted (a stable order for the log).
std::vector<fs::path> sceneFiles(const fs::path& folder) {
    std::vector<fs::path> files;
    for (const fs::directory_entry& entry : fs::recursive_directory_iterator(folder)) {
        const std::string extension = entry.path().extension().string();
        if (entry.is_regular_file() && (extension == ".gltf" || extension == ".glb")) files.push_back(entry.path());
    }
    std::sort(files.begin(), files.end());
    return files;
}

size_t drawnPixels(const std::vector<float>& depth) {
    return size_t(std::count_if(depth.begin(), depth.end(), [](float d) { return d > 0.0f; }));  // 0: the far plane
}

TEST(SharedData, EverySceneFileRendersAndCulledMethodsStayLossless) {
    const fs::path folder = fs::path(PUNCTUAL_SHARED_DATA_DIR);
    if (!fs::is_directory(folder)) GTEST_SKIP() << "no " << folder.string() << " (../shared/data is absent)";
    const std::vector<fs::path> files = sceneFiles(folder);
    if (files.empty()) GTEST_SKIP() << "no .gltf or .glb file under " << folder.string();
    auto context = testing::makeValidatedContext();
    for (const fs::path& file : files) {
        SCOPED_TRACE(file.string());
        Scene scene = loadGltf(file.string());
        // Lit by generated lights as well as its own: a scene without lights would be black, and
        // the comparison needs light lists to differ between methods.
        if (scene.lights.size() < 4) replaceLights(scene, 8, 4, 7);
        render::RenderSettings settings = testing::renderSettings(200, 150);
        settings.method = render::LightListMethod::Brute;
        render::Renderer brute(*context, scene, settings);
        const ImageRgba8 image = brute.render(1, 0).image;
        EXPECT_GT(drawnPixels(brute.readDepth()), size_t(200 * 150 / 20)) << "the file's view shows its geometry";
        for (render::LightListMethod method : render::gridMethods()) {
            settings.method = method;
            render::Renderer culled(*context, scene, settings);
            EXPECT_TRUE(culled.render(1, 0).image.pixels == image.pixels) << render::methodName(method);
        }
        testing::saveTestImage("shared-data-" + file.stem().string(), image);
    }
    testing::expectNoValidationMessages(*context);
}

}  // namespace
}  // namespace punctual
