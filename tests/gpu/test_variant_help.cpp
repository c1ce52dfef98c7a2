// The variant tables as users meet them in --help: `render --help` lists every built-in scene,
// light-list method, shadow filter and point-shadow layout with its description and marks the
// defaults; `bench --help` names every method and filter it sweeps, and the quick subset. (No GPU
// work: --help exits before any device is made.)
#include <gtest/gtest.h>

#include <string>

#include "app/options.h"
#include "gpu_test_support.h"
#include "lights/shadow_filters.h"
#include "render/light_list_method.h"
#include "scene/builtin_scenes.h"

namespace punctual {
namespace {

using testing::RunResult;
using testing::runPunctual;

// `name` followed by spaces and `description` on one line of `help`.
bool listsEntry(const std::string& help, const std::string& name, const std::string& description) {
    for (size_t at = help.find(" " + name + " "); at != std::string::npos; at = help.find(" " + name + " ", at + 1)) {
        const size_t end = help.find('\n', at);
        if (help.substr(at, end - at).find(description) != std::string::npos) return true;
    }
    return false;
}

TEST(VariantHelp, RenderHelpListsEveryVariant) {
    testing::TempFolder folder;
    const RunResult run = runPunctual(folder, "render --help");
    ASSERT_EQ(run.exitCode, 0) << run.err;
    EXPECT_EQ(run.out, app::renderUsage());
    for (const render::LightListMethodInfo& method : render::kLightListMethods) {
        EXPECT_TRUE(listsEntry(run.out, method.name, method.description)) << method.name << "\n" << run.out;
    }
    for (const ShadowFilterInfo& filter : kShadowFilters) {
        EXPECT_TRUE(listsEntry(run.out, filter.name, filter.description)) << filter.name << "\n" << run.out;
    }
    for (const PointShadowLayoutInfo& layout : kPointShadowLayouts) {
        EXPECT_TRUE(listsEntry(run.out, layout.name, layout.description)) << layout.name << "\n" << run.out;
    }
    for (const BuiltinScene& scene : kBuiltinScenes) {
        EXPECT_TRUE(listsEntry(run.out, scene.name, scene.description)) << scene.name << "\n" << run.out;
    }
    // The defaults of RenderOptions: the hall, tiled culling, tent5 filter, slices layout.
    EXPECT_TRUE(listsEntry(run.out, "hall", std::string(kBuiltinScenes[0].description) + " (default)"));
    EXPECT_TRUE(listsEntry(run.out, "tiled", std::string(render::kLightListMethods[2].description) + " (default)"));
    EXPECT_TRUE(listsEntry(run.out, "tent5", std::string(kShadowFilters[2].description) + " (default)"));
    EXPECT_TRUE(listsEntry(run.out, "slices", std::string(kPointShadowLayouts[1].description) + " (default)"));
}

TEST(VariantHelp, BenchHelpNamesTheSweptVariants) {
    testing::TempFolder folder;
    const RunResult run = runPunctual(folder, "bench --help");
    ASSERT_EQ(run.exitCode, 0) << run.err;
    EXPECT_NE(run.out.find("the methods brute, per-object, tiled, clustered, tiled-2.5d, zbin, zbin-2d (shadows off)"), std::string::npos)
        << run.out;
    EXPECT_NE(run.out.find("the filters hw, tent3, tent5, tent7, disk at auto resolution"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("filters hw and tent5 (under 3 minutes"), std::string::npos) << run.out;
}

}  // namespace
}  // namespace punctual
