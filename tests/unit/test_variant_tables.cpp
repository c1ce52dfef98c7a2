// The variant tables (light-list methods, shadow filters, point-shadow layouts): names round-trip,
// unknown names fail with one line listing every name, --help lists every entry, the footprints,
// and every entry has its explicit case in the shaders.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include "cli/options.h"
#include "core/error.h"
#include "lights/shadow_filters.h"
#include "lights/shadow_setup.h"
#include "render/light_list_form.h"
#include "render/light_list_method.h"
#include "render/shadow_cache.h"

namespace punctual {
namespace {

using render::LightListMethod;

std::string problemOf(void (*parse)(const std::string&), const std::string& name) {
    try {
        parse(name);
    } catch (const Error& error) {
        return error.what();
    }
    return "(no error)";
}

// ---- names ------------------------------------------------------------------------------------

// The names of a table, in table order: what every list shown to users must be.
template <typename Table>
std::vector<std::string> tableNames(const Table& table) {
    std::vector<std::string> names;
    for (const auto& entry : table) names.emplace_back(entry.name);
    return names;
}

// Names are unique, plain (lower case, digits, '-' and '.'), and not empty.
template <typename Table>
void expectPlainUniqueNames(const Table& table) {
    std::set<std::string> seen;
    for (const auto& entry : table) {
        EXPECT_TRUE(std::regex_match(entry.name, std::regex("[a-z0-9][a-z0-9.-]*"))) << entry.name;
        EXPECT_TRUE(seen.insert(entry.name).second) << entry.name << " twice";
    }
}

TEST(VariantTables, MethodNamesRoundTrip) {
    EXPECT_EQ(render::methodNames(), tableNames(render::kLightListMethods));
    expectPlainUniqueNames(render::kLightListMethods);
    for (const render::LightListMethodInfo& method : render::kLightListMethods) {
        EXPECT_EQ(render::parseMethod(method.name), method.value);
        EXPECT_STREQ(render::methodName(method.value), method.name);
    }
    EXPECT_STREQ(render::methodName(LightListMethod(render::kLightListMethods.size())), "unknown");
}

TEST(VariantTables, ShadowFilterNamesRoundTrip) {
    EXPECT_EQ(shadowFilterNames(), tableNames(kShadowFilters));
    expectPlainUniqueNames(kShadowFilters);
    for (const ShadowFilterInfo& filter : kShadowFilters) {
        EXPECT_EQ(parseShadowFilter(filter.name), filter.value);
        EXPECT_STREQ(shadowFilterName(filter.value), filter.name);
    }
    EXPECT_STREQ(shadowFilterName(ShadowFilter(kShadowFilters.size())), "unknown");
}

TEST(VariantTables, PointShadowLayoutNamesRoundTrip) {
    EXPECT_EQ(pointShadowLayoutNames(), tableNames(kPointShadowLayouts));
    expectPlainUniqueNames(kPointShadowLayouts);
    for (const PointShadowLayoutInfo& layout : kPointShadowLayouts) {
        EXPECT_EQ(parsePointShadowLayout(layout.name), layout.value);
        EXPECT_STREQ(pointShadowLayoutName(layout.value), layout.name);
    }
    EXPECT_STREQ(pointShadowLayoutName(PointShadowLayout(PUNCTUAL_POINT_SHADOW_LAYOUT_COUNT)), "unknown");
}

TEST(VariantTables, LightListFormNamesRoundTrip) {
    EXPECT_EQ(render::lightListFormNames(), tableNames(render::kLightListForms));
    expectPlainUniqueNames(render::kLightListForms);
    for (const render::LightListFormInfo& form : render::kLightListForms) {
        EXPECT_EQ(render::parseLightListForm(form.name), form.value);
        EXPECT_STREQ(render::lightListFormName(form.value), form.name);
    }
    EXPECT_STREQ(render::lightListFormName(render::LightListForm(render::kLightListForms.size())), "unknown");
    EXPECT_EQ(problemOf([](const std::string& n) { render::parseLightListForm(n); }, "bits"),
              "--light-lists: expected " + joinNames(tableNames(render::kLightListForms)) + ", got 'bits'");
}

TEST(VariantTables, UnknownNamesFailWithOneLineListingEveryName) {
    // "a, b or c": every name of the table, in its order.
    EXPECT_EQ(joinNames({"a", "b", "c"}), "a, b or c");
    EXPECT_EQ(problemOf([](const std::string& n) { render::parseMethod(n); }, "fast"),
              "--culling: expected " + joinNames(tableNames(render::kLightListMethods)) + ", got 'fast'");
    EXPECT_EQ(problemOf([](const std::string& n) { parseShadowFilter(n); }, "box"),
              "--shadow-filter: expected " + joinNames(tableNames(kShadowFilters)) + ", got 'box'");
    EXPECT_EQ(problemOf([](const std::string& n) { parsePointShadowLayout(n); }, "sphere"),
              "--point-shadow-layout: expected " + joinNames(tableNames(kPointShadowLayouts)) + ", got 'sphere'");
    // Names are matched exactly: no case folding, no prefixes.
    EXPECT_NE(problemOf([](const std::string& n) { render::parseMethod(n); }, "Tiled"), "(no error)");
    EXPECT_NE(problemOf([](const std::string& n) { parseShadowFilter(n); }, "tent"), "(no error)");
    EXPECT_NE(problemOf([](const std::string& n) { parsePointShadowLayout(n); }, ""), "(no error)");
}

TEST(VariantTables, JoinNames) {
    EXPECT_EQ(joinNames({}), "");
    EXPECT_EQ(joinNames({"a"}), "a");
    EXPECT_EQ(joinNames({"a", "b"}), "a or b");
    EXPECT_EQ(joinNames({"a", "b", "c"}, " and "), "a, b and c");
}

// ---- --help -----------------------------------------------------------------------------------

// Every entry on its own line, indented, with its description; only the default marked.
template <typename Entry, size_t N>
void expectHelpListsEveryEntry(const std::array<Entry, N>& table, decltype(Entry::value) defaultValue) {
    const std::string help = variantHelp(table, defaultValue, 4);
    std::istringstream lines(help);
    std::string line;
    size_t count = 0;
    while (std::getline(lines, line)) {
        ASSERT_LT(count, N) << help;
        const Entry& entry = table[count++];
        EXPECT_EQ(line.rfind(std::string("    ") + entry.name + " ", 0), 0u) << line;
        EXPECT_NE(line.find(entry.description), std::string::npos) << line;
        EXPECT_EQ(line.find("(default)") != std::string::npos, entry.value == defaultValue) << line;
    }
    EXPECT_EQ(count, N) << help;
}

TEST(VariantTables, HelpListsEveryEntryAndTheDefault) {
    expectHelpListsEveryEntry(render::kLightListMethods, LightListMethod::Tiled);
    const ShadowSettings defaults;
    expectHelpListsEveryEntry(kShadowFilters, defaults.filter);
    expectHelpListsEveryEntry(kPointShadowLayouts, defaults.pointLayout);
    expectHelpListsEveryEntry(kCascadeBlends, defaults.cascades.blend);
    expectHelpListsEveryEntry(kShadowResolutionModes, defaults.resolution);
    expectHelpListsEveryEntry(render::kLightListForms, cli::RenderOptions{}.lightLists);
    expectHelpListsEveryEntry(render::kShadowCacheModes, render::ShadowCacheMode::Off);  // each on one line
    // The descriptions line up in one column after the longest name.
    EXPECT_EQ(variantHelp(kPointShadowLayouts, PointShadowLayout::Cube, 2).substr(0, 10), "  cube    ");
}

// ---- footprints and bench sweeps --------------------------------------------------------------

TEST(VariantTables, ShadowSettingsTakeEachFiltersReachAndTapsFromItsKernel) {
    ShadowSettings settings;
    settings.diskSamples = 9;
    for (const ShadowFilterInfo& filter : kShadowFilters) {
        settings.filter = filter.value;
        for (uint32_t resolution : {1024u, 2048u}) {
            const float diskTexels = settings.diskRadius * float(resolution);
            EXPECT_EQ(settings.penumbraTexels(resolution),
                      gpu::shadowKernelReachTexels(filter.kernel.value, filter.size, diskTexels))
                << filter.name;
        }
        EXPECT_EQ(settings.filterTaps(), gpu::shadowKernelTaps(filter.kernel.value, filter.size, 9)) << filter.name;
        EXPECT_GT(settings.filterTaps(), 0u) << filter.name;
    }
}

TEST(VariantTables, QuickBenchSweepsTheReferenceTheDefaultsAndASubset) {
    // --quick stays under 3 minutes: it sweeps a subset, which holds what every comparison needs
    // (the reference method, the default method and filter) and leaves some out.
    size_t quickMethods = 0;
    for (const render::LightListMethodInfo& method : render::kLightListMethods) {
        quickMethods += method.quickBench;
        if (method.isReference || method.value == cli::RenderOptions{}.culling) {
            EXPECT_TRUE(method.quickBench) << method.name;
        }
    }
    EXPECT_LT(quickMethods, render::kLightListMethods.size());
    size_t quickFilters = 0;
    for (const ShadowFilterInfo& filter : kShadowFilters) {
        quickFilters += filter.quickBench;
        if (filter.value == ShadowSettings{}.filter) {
            EXPECT_TRUE(filter.quickBench) << filter.name;
        }
    }
    EXPECT_GE(quickFilters, 2u);  // the default and one to compare it with
    EXPECT_LT(quickFilters, kShadowFilters.size());
}

TEST(VariantTables, LightGridMethods) {
    EXPECT_FALSE(render::usesLightGrid(LightListMethod::Brute));
    EXPECT_FALSE(render::usesLightGrid(LightListMethod::PerObject));
    EXPECT_TRUE(render::usesLightGrid(LightListMethod::Tiled));
    EXPECT_TRUE(render::usesLightGrid(LightListMethod::Clustered));
    // The grid methods are those whose forward pass reads a light grid, in table order.
    std::vector<LightListMethod> grid;
    for (const render::LightListMethodInfo& info : render::kLightListMethods) {
        const bool readsGrid = info.source.value == PUNCTUAL_LIGHT_SOURCE_GRID || info.source.value == PUNCTUAL_LIGHT_SOURCE_GRID_ZBINS;
        EXPECT_EQ(render::usesLightGrid(info.value), readsGrid) << info.name;
        if (readsGrid) grid.push_back(info.value);
    }
    EXPECT_EQ(render::gridMethods(), grid);
    EXPECT_GE(grid.size(), 2u);
}

// What the renderer builds for each method comes from the table: depth slices only for clusters,
// per-object lists only for per-object, and brute force is the reference the others are compared
// against (rendered first).
TEST(VariantTables, MethodPropertiesDecideWhatTheFrameBuilds) {
    for (const render::LightListMethodInfo& info : render::kLightListMethods) {
        EXPECT_EQ(info.depthSlices, info.value == LightListMethod::Clustered) << info.name;
        EXPECT_EQ(info.objectLists(), info.value == LightListMethod::PerObject) << info.name;
        EXPECT_EQ(info.isReference, info.value == LightListMethod::Brute) << info.name;
        EXPECT_TRUE(!info.depthSlices || info.usesLightGrid()) << info.name << ": slices split a light grid";
        EXPECT_TRUE(info.cullFlags == 0 || info.usesLightGrid()) << info.name << ": culling flags shape a light grid";
    }
    EXPECT_EQ(render::referenceMethod(), LightListMethod::Brute);
    EXPECT_THROW(render::methodInfo(static_cast<LightListMethod>(render::kLightListMethods.size())), InternalError);
}

// ---- the shaders have a case for every entry ----------------------------------------------------

std::string readShader(const std::string& path) {
    std::ifstream file(std::string(PUNCTUAL_SHADER_DIR) + "/" + path);
    EXPECT_TRUE(file) << path;
    std::stringstream text;
    text << file.rdbuf();
    return text.str();
}

// The bodies of every `switch (selector) { ... }` in `source`, by brace matching.
std::vector<std::string> switchBodies(const std::string& source, const std::string& selector) {
    std::vector<std::string> bodies;
    const std::string head = "switch (" + selector + ")";
    for (size_t at = source.find(head); at != std::string::npos; at = source.find(head, at + 1)) {
        const size_t open = source.find('{', at);
        int depth = 0;
        for (size_t i = open; i < source.size(); ++i) {
            depth += source[i] == '{' ? 1 : source[i] == '}' ? -1 : 0;
            if (depth == 0) {
                bodies.push_back(source.substr(open, i - open + 1));
                break;
            }
        }
    }
    return bodies;
}

// The GPU constants a table's entries use (`member` of each entry: its own value, or a parameter
// such as a filter's kernel), once each.
template <typename Entry, size_t N>
std::vector<GpuConstant> constantsOf(const std::array<Entry, N>& table, GpuConstant Entry::*member) {
    std::vector<GpuConstant> constants;
    for (const Entry& entry : table) {
        const GpuConstant constant = entry.*member;
        const bool seen = std::any_of(constants.begin(), constants.end(),
                                      [&](const GpuConstant& c) { return std::string(c.name) == constant.name; });
        if (!seen) constants.push_back(constant);
    }
    return constants;
}

// Every switch on `selector` in the shader file names every constant in a `case`, and there are at
// least `minimumSwitches` of them, each with a default that flags an unknown value.
void expectEveryConstantHasItsCase(const std::vector<GpuConstant>& constants, const std::string& path,
                                   const std::string& selector, size_t minimumSwitches) {
    const std::vector<std::string> bodies = switchBodies(readShader(path), selector);
    EXPECT_GE(bodies.size(), minimumSwitches) << path << ": switch (" << selector << ")";
    for (const std::string& body : bodies) {
        for (const GpuConstant& constant : constants) {
            EXPECT_NE(body.find(std::string("case ") + constant.name + ":"), std::string::npos)
                << path << ": no case for " << constant.name << " in\n" << body;
        }
        EXPECT_TRUE(std::regex_search(body, std::regex("default:\\s*unknownVariant = true;")))
            << path << ": an unknown value must set unknownVariant\n" << body;
    }
}

// shadow_kernels.h's part for both languages (before its GLSL-only block) and its GLSL part.
std::pair<std::string, std::string> shadowKernelsParts() {
    const std::string source = readShader("shared/shadow_kernels.h");
    const size_t glsl = source.find("#ifndef __cplusplus");
    EXPECT_NE(glsl, std::string::npos);
    return {source.substr(0, glsl), source.substr(glsl)};
}

TEST(VariantTables, EveryShadowKernelHasItsShaderCases) {
    const std::vector<GpuConstant> kernels = constantsOf(kShadowFilters, &ShadowFilterInfo::kernel);
    const auto [shared, glsl] = shadowKernelsParts();
    // Footprint, taps and reach for both languages; samples and texel weights in GLSL.
    size_t sharedSwitches = 0;
    for (const std::string& body : switchBodies(shared, "kernel")) {
        ++sharedSwitches;
        for (const GpuConstant& kernel : kernels) {
            EXPECT_NE(body.find(std::string("case ") + kernel.name + ":"), std::string::npos) << kernel.name << body;
        }
    }
    EXPECT_EQ(sharedSwitches, 3u);
    const std::vector<std::string> glslSwitches = switchBodies(glsl, "kernel");
    EXPECT_EQ(glslSwitches.size(), 2u);
    for (const std::string& body : glslSwitches) {
        for (const GpuConstant& kernel : kernels) {
            EXPECT_NE(body.find(std::string("case ") + kernel.name + ":"), std::string::npos) << kernel.name << body;
        }
        EXPECT_TRUE(std::regex_search(body, std::regex("default:\\s*unknownVariant = true;"))) << body;
    }
}

TEST(VariantTables, EveryLightListFormHasItsForwardShaderCase) {
    expectEveryConstantHasItsCase(constantsOf(render::kLightListForms, &render::LightListFormInfo::gpu),
                                  "raster/forward.frag", "LIGHT_LIST_FORM", 1);
}

TEST(VariantTables, EveryPointShadowLayoutHasItsShaderCase) {
    expectEveryConstantHasItsCase(constantsOf(kPointShadowLayouts, &PointShadowLayoutInfo::gpu),
                                  "shared/shadow_sampling.glsl", "POINT_SHADOW_LAYOUT", 1);
}

TEST(VariantTables, EveryCascadeBlendHasItsShaderCase) {
    expectEveryConstantHasItsCase(constantsOf(kCascadeBlends, &CascadeBlendInfo::gpu), "shared/shadow_sampling.glsl",
                                  "CASCADE_BLEND", 1);
}

TEST(VariantTables, EveryShadowResolutionModeHasItsShaderCase) {
    expectEveryConstantHasItsCase(constantsOf(kShadowResolutionModes, &ShadowResolutionModeInfo::pages),
                                  "shared/shadow_sampling.glsl", "SHADOW_PAGES", 1);
}

TEST(VariantTables, EveryLightSourceHasItsShaderCase) {
    expectEveryConstantHasItsCase(constantsOf(render::kLightListMethods, &render::LightListMethodInfo::source),
                                  "raster/forward.frag", "LIGHT_SOURCE", 1);
}

// Every value define of a kind in `path` (`#define PREFIX<NAME> <n>u`, the count aside) is a
// constant some entry uses: a value added to the shaders that no table row reaches fails here.
void expectEveryDefineIsUsed(const std::vector<GpuConstant>& constants, const std::string& path,
                             const std::string& prefix) {
    const std::string source = readShader(path);
    const std::regex define("#define (" + prefix + "\\w+) \\d+u");
    std::set<std::string> defines;
    for (auto it = std::sregex_iterator(source.begin(), source.end(), define); it != std::sregex_iterator(); ++it) {
        const std::string name = (*it)[1].str();
        if (!name.ends_with("_COUNT")) defines.insert(name);
    }
    std::set<std::string> used;
    for (const GpuConstant& constant : constants) used.insert(constant.name);
    EXPECT_EQ(defines, used) << prefix;
}

TEST(VariantTables, EveryGpuValueHasAnEntry) {
    expectEveryDefineIsUsed(constantsOf(render::kLightListMethods, &render::LightListMethodInfo::source),
                            "shared/gpu_types.h", "PUNCTUAL_LIGHT_SOURCE_");
    expectEveryDefineIsUsed(constantsOf(kShadowFilters, &ShadowFilterInfo::kernel), "shared/shadow_kernels.h",
                            "PUNCTUAL_SHADOW_KERNEL_");
    expectEveryDefineIsUsed(constantsOf(kPointShadowLayouts, &PointShadowLayoutInfo::gpu), "shared/gpu_types.h",
                            "PUNCTUAL_POINT_SHADOW_");
    expectEveryDefineIsUsed(constantsOf(kCascadeBlends, &CascadeBlendInfo::gpu), "shared/gpu_types.h",
                            "PUNCTUAL_CASCADE_BLEND_");
}

// The culling flags the methods use are the ones culling.h defines, and every method's flags are
// ones the general kernel implements: light_culling.comp names each flag it reads.
TEST(VariantTables, EveryCullingFlagIsDefinedAndImplemented) {
    const std::string culling = readShader("shared/culling.h");
    const std::string kernel = readShader("compute/light_culling.comp");
    const std::regex define("#define (PUNCTUAL_CULL_\\w+) (\\d+)u");
    uint32_t defined = 0;
    for (auto it = std::sregex_iterator(culling.begin(), culling.end(), define); it != std::sregex_iterator(); ++it) {
        const uint32_t bit = uint32_t(std::stoul((*it)[2].str()));
        EXPECT_EQ(bit & (bit - 1), 0u) << (*it)[1].str() << ": one bit a flag";
        EXPECT_EQ(defined & bit, 0u) << (*it)[1].str() << ": a bit of its own";
        defined |= bit;
        EXPECT_NE(kernel.find((*it)[1].str()), std::string::npos) << "light_culling.comp lacks " << (*it)[1].str();
    }
    for (const render::LightListMethodInfo& method : render::kLightListMethods) {
        EXPECT_EQ(method.cullFlags & ~defined, 0u) << method.name;
    }
    EXPECT_EQ(PUNCTUAL_TILE_KERNEL_CULL_FLAGS & ~defined, 0u);
    EXPECT_EQ(PUNCTUAL_CLUSTER_KERNEL_CULL_FLAGS & ~defined, 0u);
}

}  // namespace
}  // namespace punctual
