// The variant tables as users meet them in --help: `render --help` lists every built-in scene,
// light-list method, shadow filter and point-shadow layout with its description and marks the
// defaults; `bench --help` names every method and filter it sweeps, and the quick subset. (No GPU
// work: --help exits before any device is made.)
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli/options.h"
#include "core/variant_table.h"
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
    EXPECT_EQ(run.out, cli::renderUsage());
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
    // Every name from its table, in table order; the quick subset from the tables' flags.
    std::vector<std::string> quickFilters;
    for (const ShadowFilterInfo& filter : kShadowFilters) {
        if (filter.quickBench) quickFilters.emplace_back(filter.name);
    }
    EXPECT_NE(run.out.find("the methods " + joinNames(render::methodNames(), ", ") + " (shadows off)"),
              std::string::npos)
        << run.out;
    EXPECT_NE(run.out.find("the filters " + joinNames(shadowFilterNames(), ", ") + " at auto resolution"),
              std::string::npos)
        << run.out;
    EXPECT_NE(run.out.find("filters " + joinNames(quickFilters, " and ") + " (under 3 minutes"), std::string::npos)
        << run.out;
}

// The README's synopsis of `punctual render` is the options part of its --help, word for word:
// one table (src/cli/render_option_table.cpp) says both.
TEST(VariantHelp, ReadmeSynopsisIsTheRenderHelp) {
    std::ifstream in(std::string(PUNCTUAL_DATA_DIR) + "/../README.md");
    std::stringstream text;
    text << in.rdbuf();
    const std::string readme = text.str();
    const std::string head = "punctual render [SCENE.gltf|SCENE.glb|--scene NAME] [options]\n";
    const size_t start = readme.find(head);
    ASSERT_NE(start, std::string::npos) << "README has no `punctual render` synopsis";
    const size_t end = readme.find("punctual reference ", start);
    ASSERT_NE(end, std::string::npos);
    const std::string synopsis = readme.substr(start + head.size(), end - start - head.size());
    const std::string usage = cli::renderUsage();
    const std::string options = usage.substr(usage.find("options:\n") + 9);
    EXPECT_EQ(synopsis, options) << "README's synopsis is not `punctual render --help`: run scripts/readme-synopsis.sh";
}

}  // namespace
}  // namespace punctual
