// The command line as users meet it: a good run writes the PNG and the stats JSON; every bad
// input gives one clear line on stderr naming the file or option, a non-zero exit, and no
// output file.
#include <gtest/gtest.h>

#include <map>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "gpu_test_support.h"
#include "lights/shadow_drawing_tiles.h"

namespace punctual {
namespace {

using testing::readText;
using testing::RunResult;
using testing::runPunctual;

// One failing run: one clear error naming `mention`, and no output.
void expectCleanFailure(const testing::TempFolder& folder, const std::string& args, const std::string& mention) {
    const std::string png = folder.file("out.png");
    const std::string json = folder.file("stats.json");
    const RunResult run = runPunctual(folder, args + " --validate --out '" + png + "' --stats '" + json + "'");
    testing::expectOneClearError(run, args, mention);
    EXPECT_FALSE(std::filesystem::exists(png)) << args;
    EXPECT_FALSE(std::filesystem::exists(json)) << args;
    EXPECT_FALSE(std::filesystem::exists(png + ".partial")) << args;
}

TEST(Cli, RenderWritesImageAndStats) {
    testing::TempFolder folder;
    const std::string png = folder.file("frame.png");
    const std::string json = folder.file("stats.json");
    const RunResult run =
        runPunctual(folder, "render --validate --size 160x90 --out '" + png + "' --stats '" + json + "'");
    ASSERT_EQ(run.exitCode, 0) << run.err;
    EXPECT_EQ(run.err, "");  // validation printed nothing
    EXPECT_NE(run.out.find("forward"), std::string::npos);
    const ImageRgba8 image = readPng(png);
    EXPECT_EQ(image.width, 160u);
    EXPECT_EQ(image.height, 90u);
    const nlohmann::json stats = nlohmann::json::parse(readText(json));
    for (const char* pass : {"depth", "culling", "shadows", "forward", "total"}) {
        ASSERT_TRUE(stats["gpu_ms"].contains(pass)) << pass;
        EXPECT_GE(stats["gpu_ms"][pass].get<double>(), 0.0);
    }
    EXPECT_GT(stats["gpu_ms"]["forward"].get<double>(), 0.0);
    EXPECT_GT(stats["gpu_ms"]["culling"].get<double>(), 0.0);  // tiled culling is the default
    EXPECT_GT(stats["gpu_ms"]["shadows"].get<double>(), 0.0);  // shadows are on by default
    // Every light is shadowed, each view at its own tier within the 64 MiB budget.
    const nlohmann::json& shadows = stats["shadows"];
    EXPECT_EQ(shadows["shadowed_spots"].get<int>(), 64);
    EXPECT_EQ(shadows["shadowed_points"].get<int>(), 32);
    EXPECT_EQ(shadows["views_rendered"].get<int>() + shadows["views_skipped"].get<int>(), 64 + 6 * 32);
    ASSERT_EQ(shadows["views"].size(), 64u + 6u * 32u);
    EXPECT_EQ(shadows["mode"].get<std::string>(), "auto");
    EXPECT_EQ(shadows["resolution"].get<std::string>(), "auto");
    EXPECT_EQ(shadows["format"].get<std::string>(), "d16");
    EXPECT_EQ(shadows["budget_bytes"].get<uint64_t>(), 64ull << 20);
    EXPECT_GT(shadows["memory_bytes"].get<double>(), 0.0);
    // The budget is the atlas's (--help: 16-bit texels); the shadow memory holds beside it the
    // drawing square (lights/shadow_drawing_tiles.h) and the placeholder cube array.
    const uint64_t atlasBytes = shadows["atlas"]["width"].get<uint64_t>() * shadows["atlas"]["height"].get<uint64_t>() * 2;
    EXPECT_GT(atlasBytes, 0u);
    EXPECT_LE(atlasBytes, shadows["budget_bytes"].get<uint64_t>());
    EXPECT_LE(shadows["memory_bytes"].get<uint64_t>(),
              shadows["budget_bytes"].get<uint64_t>() + uint64_t(kDrawingSquareSide) * kDrawingSquareSide * 2 + (64 << 10));
    EXPECT_EQ(shadows["filter_taps"].get<int>(), 9);  // tent5: Unity's 3 x 3 bilinear taps
    // texels_rendered is the sum of the rendered views' squares, and tiers counts them.
    uint64_t texels = 0;
    int rendered = 0;
    std::map<std::string, int> tiers;
    for (const auto& view : shadows["views"]) {
        if (!view["rendered"].get<bool>()) continue;
        const uint64_t side = view["resolution"].get<uint64_t>();
        texels += side * side;
        ++rendered;
        ++tiers[std::to_string(side)];
        EXPECT_LE(side, view["demanded_resolution"].get<uint64_t>());
    }
    EXPECT_EQ(shadows["texels_rendered"].get<uint64_t>(), texels);
    EXPECT_EQ(shadows["views_rendered"].get<int>(), rendered);
    const auto reportedTiers = shadows["tiers"].get<std::map<std::string, int>>();
    EXPECT_EQ(reportedTiers, tiers);
    EXPECT_NE(run.out.find("shadow resolution: auto; views at "), std::string::npos) << run.out;
    EXPECT_EQ(stats["shadows"]["faces_rendered"], stats["shadows"]["views_rendered"]);
    EXPECT_EQ(stats["shadows"]["faces_skipped"], stats["shadows"]["views_skipped"]);
    EXPECT_EQ(stats["culling"]["method"].get<std::string>(), "tiled");
    for (const char* key : {"tested_per_pixel", "affecting_per_pixel", "max_tested", "missed_energy"}) {
        EXPECT_TRUE(stats["culling"].contains(key)) << key;
    }
    EXPECT_EQ(stats["lights"]["spot"].get<int>(), 64);
    EXPECT_EQ(stats["lights"]["point"].get<int>(), 32);
    EXPECT_EQ(stats["lights"]["directional"].get<int>(), 0);
    // The virtual pages' estimate: its shaded pairs (CPU rays) are the shadow lookups the forward
    // pass counted (the default scene has no sun, whose cascades the estimate leaves out), and
    // each layout's bytes follow from its pages.
    const nlohmann::json& estimate = shadows["virtual_estimate"];
    const double pairs = estimate["shaded_pairs"].get<double>();
    const double lookups = stats["culling"]["shadow_lookups_per_pixel"].get<double>() *
                           stats["culling"]["covered_pixels"].get<double>();
    EXPECT_NEAR(pairs, lookups, 0.03 * lookups);
    EXPECT_EQ(estimate["floor_bytes"].get<uint64_t>(), 2 * estimate["shaded_pairs"].get<uint64_t>());
    ASSERT_EQ(estimate["layouts"].size(), 12u);
    for (const auto& layout : estimate["layouts"]) {
        const uint64_t page = layout["page_size"].get<uint64_t>();
        uint64_t marked = 0;
        for (const auto& count : layout["pages_per_level"]) marked += count.get<uint64_t>();
        EXPECT_EQ(layout["pages_marked"].get<uint64_t>(), marked);
        EXPECT_GT(marked, 0u);
        EXPECT_EQ(layout["physical_bytes"].get<uint64_t>(), marked * page * page * 2);
        EXPECT_EQ(layout["pages_per_level"].size(), layout["levels"].get<size_t>());
    }
}

TEST(Cli, HeatmapShowsTheFrameAndALegend) {
    testing::TempFolder folder;
    const std::string heatmap = folder.file("heat.png");
    const RunResult run =
        runPunctual(folder, "render --validate --size 320x180 --culling clustered --heatmap '" + heatmap + "'");
    ASSERT_EQ(run.exitCode, 0) << run.err;
    const ImageRgba8 image = readPng(heatmap);
    EXPECT_GE(image.width, 320u);
    EXPECT_GT(image.height, 180u);  // the legend strip below the frame
}

TEST(Cli, BruteForceRunsNoCullingPass) {
    testing::TempFolder folder;
    const std::string json = folder.file("stats.json");
    const RunResult run = runPunctual(folder, "render --validate --size 64x36 --culling brute --stats '" + json + "'");
    ASSERT_EQ(run.exitCode, 0) << run.err;
    const nlohmann::json stats = nlohmann::json::parse(readText(json));
    EXPECT_EQ(stats["gpu_ms"]["culling"].get<double>(), 0.0);
    EXPECT_EQ(stats["culling"]["tested_per_pixel"].get<double>(), 96.0);
}

TEST(Cli, ShadowsOffRunsNoShadowPassAndAllocatesPlaceholdersOnly) {
    testing::TempFolder folder;
    const std::string json = folder.file("stats.json");
    const RunResult run = runPunctual(folder, "render --validate --size 64x36 --shadows off --stats '" + json + "'");
    ASSERT_EQ(run.exitCode, 0) << run.err;
    const nlohmann::json stats = nlohmann::json::parse(readText(json));
    EXPECT_EQ(stats["gpu_ms"]["shadows"].get<double>(), 0.0);
    EXPECT_EQ(stats["shadows"]["views_rendered"].get<int>(), 0);
    EXPECT_LT(stats["shadows"]["memory_bytes"].get<double>(), 65536.0);  // three 1x1 placeholders
    EXPECT_FALSE(stats["shadows"].contains("virtual_estimate"));
}

TEST(Cli, GeneratedLightsReplaceTheScenes) {
    testing::TempFolder folder;
    const std::string json = folder.file("stats.json");
    const RunResult run = runPunctual(folder, "render --validate --size 64x36 --lights 5,3,9 --stats '" + json + "'");
    ASSERT_EQ(run.exitCode, 0) << run.err;
    const nlohmann::json stats = nlohmann::json::parse(readText(json));
    EXPECT_EQ(stats["lights"]["in_scene"].get<int>(), 8);
    EXPECT_LE(stats["lights"]["spot"].get<int>(), 5);
    EXPECT_LE(stats["lights"]["point"].get<int>(), 3);
}

TEST(Cli, CompareShowsEveryMethodSideBySide) {
    testing::TempFolder folder;
    const RunResult run = runPunctual(folder, "compare --validate --size 96x54 --shadow-res 256");
    ASSERT_EQ(run.exitCode, 0) << run.err;
    EXPECT_EQ(run.err, "");
    for (const std::string& method : render::methodNames()) {
        EXPECT_NE(run.out.find("\n" + method + " "), std::string::npos) << method << "\n" << run.out;
    }
    // The light-grid methods are bit-identical to brute force: zero error on their rows.
    for (render::LightListMethod method : render::gridMethods()) {
        const size_t row = run.out.find(std::string("\n") + render::methodName(method) + " ");
        ASSERT_NE(row, std::string::npos) << render::methodName(method);
        const std::string line = run.out.substr(row + 1, run.out.find('\n', row + 1) - row - 1);
        EXPECT_NE(line.find("0.000      0.000%"), std::string::npos) << line;
    }
}

// A budget that reduces views reduces them for every method alike: compare says so once, not once
// a method.
TEST(Cli, CompareWarnsOnceAboutTheShadowBudget) {
    testing::TempFolder folder;
    const RunResult run = runPunctual(folder, "compare --size 160x90 --shadow-budget 1");
    ASSERT_EQ(run.exitCode, 0) << run.err;
    EXPECT_EQ(testing::lineCount(run.err), 1u) << run.err;
    EXPECT_NE(run.err.find("to fit --shadow-budget 1"), std::string::npos) << run.err;
}

TEST(Cli, HelpExitsZero) {
    testing::TempFolder folder;
    const RunResult run = runPunctual(folder, "render --help");
    EXPECT_EQ(run.exitCode, 0);
    EXPECT_NE(run.out.find("--lights S,P[,SEED]"), std::string::npos);
}

TEST(Cli, BadOptionsFailCleanly) {
    testing::TempFolder folder;
    expectCleanFailure(folder, "render --size 0x5", "--size");
    expectCleanFailure(folder, "render --size big", "--size");
    expectCleanFailure(folder, "render --lights 65,0", "--lights");
    expectCleanFailure(folder, "render --lights 1,x", "--lights");
    expectCleanFailure(folder, "render --frames 0", "--frames");
    expectCleanFailure(folder, "render --exposure -1", "--exposure");
    expectCleanFailure(folder, "render --device 99", "--device");
    expectCleanFailure(folder, "render --culling fast", "--culling");
    expectCleanFailure(folder, "render --tile-size 2", "--tile-size");
    expectCleanFailure(folder, "render --slices 33", "--slices");
    expectCleanFailure(folder, "render --heatmap", "--heatmap");
    expectCleanFailure(folder, "render --shadows maybe", "--shadows");
    expectCleanFailure(folder, "render --shadow-res 1000", "--shadow-res");
    expectCleanFailure(folder, "render --shadow-filter box", "--shadow-filter");
    expectCleanFailure(folder, "render --shadow-samples 0", "--shadow-samples");
    expectCleanFailure(folder, "render --shadow-bias 1,2,3", "--shadow-bias");
    expectCleanFailure(folder, "render --shadow-bias 1,-2,3,0", "--shadow-bias");
    expectCleanFailure(folder, "render --shadow-penumbra x", "--shadow-penumbra");
    expectCleanFailure(folder, "render --shadow-strength 2", "--shadow-strength");
    expectCleanFailure(folder, "render --point-shadow-layout sphere", "--point-shadow-layout");
    expectCleanFailure(folder, "render --no-such-option", "--no-such-option");
    // Conflicting options, and outputs named for a format punctual does not write there.
    expectCleanFailure(folder, "render --cascade-lambda 0.5 --cascade-splits 0.1,0.2,0.4", "conflicts with --cascade-splits");
    expectCleanFailure(folder, "render --heatmap h.webp", "writes PNG there");
    expectCleanFailure(folder, "render --light-range auto", "give --lights S,P too");
    // The light capacity: S,P, each at most 16384, and generated lights within it.
    for (const char* capacity : {"64", "1,2,3", "a,b", "-1,2", "16385,0", "0,16385", ""}) {
        expectCleanFailure(folder, std::string("render --max-lights '") + capacity + "'", "--max-lights");
    }
    expectCleanFailure(folder, "render --lights 65,0", "65,0 is over the capacity, --max-lights 64,32: raise it too");
    expectCleanFailure(folder, "render --lights 100,100 --max-lights 100,99", "is over the capacity, --max-lights 100,99");
    for (const char* range : {"0", "-2", "nan", "inf", "1e7", "5m", ""}) {
        expectCleanFailure(folder, std::string("render --lights 4,4 --light-range '") + range + "'", "--light-range");
    }
    // (expectCleanFailure adds its own --out and --stats, which would win over these.)
    for (const auto& [args, mention] : {std::pair<std::string, std::string>{"render --out x.jpg", "'x.jpg' is named for JPEG (.jpg) but punctual writes PNG there"},
                                        {"render --stats s.txt", "is named for text (.txt) but punctual writes JSON there"}}) {
        testing::expectOneClearError(runPunctual(folder, args), args, mention);
        EXPECT_FALSE(std::filesystem::exists(folder.file("x.jpg")));
    }
}

TEST(Cli, BadFilesFailCleanly) {
    testing::TempFolder folder;
    expectCleanFailure(folder, "render '" + folder.file("missing.gltf") + "'", "missing.gltf");

    const std::string truncated = folder.file("truncated.gltf");
    std::ofstream(truncated) << R"({"asset": {"version": "2.0"}, "meshes": [{"primitives": [)";
    expectCleanFailure(folder, "render '" + truncated + "'", "truncated.gltf");

    // An output folder that does not exist fails before any work.
    const RunResult run = runPunctual(folder, "render --out '" + folder.file("no/such/folder/x.png") + "'");
    EXPECT_EQ(run.exitCode, 1);
    EXPECT_NE(run.err.find("does not exist"), std::string::npos) << run.err;
}

}  // namespace
}  // namespace punctual
