// `punctual validate` as users run it: the report, the HTML page, the mismatch maps and the
// OpenEXR images are all written, and say what they should.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>
#include <tinyexr.h>

#include "core/image.h"
#include "gpu_test_support.h"

namespace punctual {
namespace {

using testing::readText;
using testing::RunResult;
using testing::runPunctual;

TEST(ValidateCli, WritesReportHtmlMapsAndExr) {
    testing::TempFolder folder;
    const std::string dir = folder.file("validation");
    const RunResult run =
        runPunctual(folder, "validate --validate --size 96x54 --shadow-res 256 --out-dir '" + dir + "' --export-exr");
    ASSERT_EQ(run.exitCode, 0) << run.err;
    EXPECT_EQ(run.err, "");  // validation layers printed nothing

    const nlohmann::json report = nlohmann::json::parse(readText(dir + "/report.json"));
    ASSERT_EQ(report["lights"].size(), 96u);  // every light is shadowed: 64 spots + 32 points
    for (const char* part : {"overall", "spot", "point"}) {
        const auto& counts = report[part];
        EXPECT_GT(counts["compared"].get<int>(), 0) << part;
        EXPECT_LE(counts["false_shadow"].get<int>() + counts["false_lit"].get<int>(), counts["compared"].get<int>());
        EXPECT_TRUE(counts["outside_edge_band"].contains("misclassified_fraction")) << part;
        // Over every compared pixel, no band excluded.
        EXPECT_DOUBLE_EQ(counts["misclassified_fraction"].get<double>(),
                         double(counts["false_shadow"].get<int>() + counts["false_lit"].get<int>()) /
                             counts["compared"].get<double>())
            << part;
    }
    const std::string html = readText(dir + "/report.html");
    EXPECT_NE(html.find("gpu.png"), std::string::npos);
    EXPECT_NE(html.find("reference.png"), std::string::npos);
    EXPECT_NE(html.find("mismatch-95.png"), std::string::npos);
    EXPECT_EQ(readPng(dir + "/mismatch-0.png").width, 96u);
    EXPECT_EQ(readPng(dir + "/reference.png").height, 54u);

    // Positions: NaN on background pixels, finite on geometry.
    float* rgba = nullptr;
    int width = 0, height = 0;
    const char* error = nullptr;
    ASSERT_EQ(LoadEXR(&rgba, &width, &height, (dir + "/positions.exr").c_str(), &error), TINYEXR_SUCCESS)
        << (error ? error : "");
    EXPECT_EQ(width, 96);
    EXPECT_EQ(height, 54);
    int background = 0, geometry = 0;
    for (int i = 0; i < width * height; ++i) (std::isnan(rgba[i * 4]) ? background : geometry)++;
    EXPECT_GT(background, 0);  // the default view shows a little sky in its top corners
    EXPECT_GT(geometry, width * height / 2);
    std::free(rgba);
    // One shadow-factor image per shadowed light, values in [0, 1] where the light reaches.
    ASSERT_EQ(LoadEXR(&rgba, &width, &height, (dir + "/shadow-factor-0.exr").c_str(), &error), TINYEXR_SUCCESS);
    int reached = 0;
    for (int i = 0; i < width * height; ++i) {
        const float f = rgba[i * 4];
        if (std::isnan(f)) continue;
        ++reached;
        EXPECT_GE(f, 0.0f);
        EXPECT_LE(f, 1.0f);
    }
    EXPECT_GT(reached, 0);
    std::free(rgba);
    EXPECT_TRUE(std::filesystem::exists(dir + "/shadow-factor-95.exr"));
}

// A coarse map (16 texels a side) has texels many pixels wide: its texel band hides most of its
// edges' error, and a band of one screen pixel does not. The verdicts do not depend on the band.
TEST(ValidateCli, AnEdgeBandOfScreenPixelsDoesNotWidenWithTheTexels) {
    testing::TempFolder folder;
    auto report = [&](const std::string& name, const std::string& band) {
        const std::string dir = folder.file(name);
        const RunResult run = runPunctual(folder, "validate --validate --size 320x180 --shadow-res 16 --shadowed 8,4 "
                                                      "--out-dir '" + dir + "'" + band);
        EXPECT_EQ(run.exitCode, 0) << run.err;
        return nlohmann::json::parse(readText(dir + "/report.json"));
    };
    const nlohmann::json texel = report("texel", "");
    const nlohmann::json pixel = report("pixel", " --edge-band-px 1");
    EXPECT_EQ(texel["edge_band_px"].get<double>(), 0.0);
    EXPECT_EQ(pixel["edge_band_px"].get<double>(), 1.0);
    EXPECT_NE(pixel["rule"].get<std::string>().find("1 screen pixel"), std::string::npos);
    const nlohmann::json& t = texel["overall"];
    const nlohmann::json& p = pixel["overall"];
    EXPECT_EQ(t["compared"], p["compared"]);
    EXPECT_EQ(t["false_shadow"], p["false_shadow"]);
    EXPECT_EQ(t["false_lit"], p["false_lit"]);
    EXPECT_EQ(t["misclassified_fraction"], p["misclassified_fraction"]);
    EXPECT_GT(p["edge_band"].get<int>(), 0);
    EXPECT_LT(2 * p["edge_band"].get<int>(), t["edge_band"].get<int>()) << "a 16-texel map's texels span many pixels";
    EXPECT_GE(p["outside_edge_band"]["false_lit"].get<int>() + p["outside_edge_band"]["false_shadow"].get<int>(),
              t["outside_edge_band"]["false_lit"].get<int>() + t["outside_edge_band"]["false_shadow"].get<int>());
}

// Lights left without a shadow (over --shadowed) are counted: validate's report and its summary,
// render's stats and summary, and compare's header all say how many the shadow figures leave out.
TEST(ValidateCli, LightsWithoutAShadowAreCountedWhereverShadowsAreReported) {
    testing::TempFolder folder;
    const std::string dir = folder.file("validation");
    const RunResult run = runPunctual(folder, "validate --validate --size 96x54 --shadowed 8,4 --out-dir '" + dir + "'");
    ASSERT_EQ(run.exitCode, 0) << run.err;
    const nlohmann::json report = nlohmann::json::parse(readText(dir + "/report.json"));
    EXPECT_EQ(report["lights"].size(), 12u);  // the shadowed ones are compared
    EXPECT_EQ(report["unshadowed_lights"]["count"], 84);
    EXPECT_EQ(report["unshadowed_lights"]["over_cap"], 84);
    EXPECT_EQ(report["unshadowed_lights"]["of"], 96);
    EXPECT_NE(readText(dir + "/report.html").find("Lights without a shadow (not compared): 84 of 96"), std::string::npos);
    const std::string line = "lights without a shadow: 84 of 96 (84 over --shadowed 8,4, 0 cast none)";
    EXPECT_NE(run.out.find(line), std::string::npos) << run.out;

    const std::string statsPath = folder.file("stats.json");
    const RunResult render = runPunctual(folder, "render --validate --size 96x54 --shadowed 8,4 --stats '" + statsPath + "'");
    ASSERT_EQ(render.exitCode, 0) << render.err;
    EXPECT_EQ(nlohmann::json::parse(readText(statsPath))["shadows"]["unshadowed_lights"], 84);
    EXPECT_NE(render.out.find(line), std::string::npos) << render.out;

    const RunResult compare = runPunctual(folder, "compare --validate --size 64x36 --shadowed 8,4 --lights 16,8");
    ASSERT_EQ(compare.exitCode, 0) << compare.err;
    EXPECT_NE(compare.out.find("lights without a shadow: 12 of 24 (12 over --shadowed 8,4, 0 cast none)"), std::string::npos)
        << compare.out;

    // With every light shadowed, none is reported and the line is not printed.
    const RunResult all = runPunctual(folder, "render --validate --size 96x54 --stats '" + statsPath + "'");
    ASSERT_EQ(all.exitCode, 0) << all.err;
    EXPECT_EQ(nlohmann::json::parse(readText(statsPath))["shadows"]["unshadowed_lights"], 0);
    EXPECT_EQ(all.out.find("lights without a shadow"), std::string::npos);
}

// Lights over the capacity are dropped, the most important kept, and compare and validate say how
// many in one line (render and reference say it in their lights line: test_scene_cli.cpp).
TEST(ValidateCli, LightsOverTheCapacityAreCountedInOneLine) {
    testing::TempFolder folder;
    const std::string line = "lights over the capacity: 4000 dropped, 96 kept, the most important (--max-lights 64,32)";
    const RunResult validate =
        runPunctual(folder, "validate --validate --scene warehouse --size 64x36 --out-dir '" + folder.file("v") + "'");
    ASSERT_EQ(validate.exitCode, 0) << validate.err;
    EXPECT_NE(validate.out.find(line), std::string::npos) << validate.out;
    const RunResult compare = runPunctual(folder, "compare --validate --scene warehouse --size 64x36");
    ASSERT_EQ(compare.exitCode, 0) << compare.err;
    EXPECT_NE(compare.out.find(line), std::string::npos) << compare.out;
    // Within the capacity, nothing is dropped and the line is not printed.
    const RunResult all = runPunctual(folder, "compare --validate --size 64x36 --lights 16,8");
    ASSERT_EQ(all.exitCode, 0) << all.err;
    EXPECT_EQ(all.out.find("lights over the capacity"), std::string::npos) << all.out;
}

TEST(ValidateCli, ABadEdgeBandFailsWithOneLine) {
    testing::TempFolder folder;
    for (const char* value : {"-1", "65", "x", "1px"}) {
        const std::string args = std::string("validate --edge-band-px ") + value + " --out-dir '" + folder.file("v") + "'";
        const RunResult run = runPunctual(folder, args);
        testing::expectOneClearError(run, args, "--edge-band-px: expected a number of screen pixels from 0 to 64");
        EXPECT_FALSE(std::filesystem::exists(folder.file("v"))) << args;
    }
}

}  // namespace
}  // namespace punctual

namespace punctual {
namespace {

// The sun: report.json's "directional" section, per cascade and in the split band, its maps, and
// the stats' cascade figures, on the built-in outdoor scene.
TEST(ValidateCli, ReportsTheSunPerCascade) {
    testing::TempFolder folder;
    const std::string dir = folder.file("validation");
    const RunResult run = testing::runPunctual(
        folder, "validate --validate --scene outdoor --size 160x90 --cascades 3 --cascade-blend dither --out-dir '" + dir + "'");
    ASSERT_EQ(run.exitCode, 0) << run.err;
    const nlohmann::json report = nlohmann::json::parse(testing::readText(dir + "/report.json"));
    ASSERT_TRUE(report.contains("directional"));
    const nlohmann::json& sun = report["directional"];
    EXPECT_GT(sun["compared"].get<int>(), 1000);
    EXPECT_EQ(sun["cascade_blend"], "dither");
    ASSERT_EQ(sun["cascades"].size(), 3u);
    int perCascade = 0;
    for (const auto& cascade : sun["cascades"]) {
        for (const char* key : {"compared", "false_shadow", "false_lit", "misclassified_fraction"}) {
            EXPECT_TRUE(cascade.contains(key)) << key;
        }
        EXPECT_GT(cascade["texel_m"].get<double>(), 0.0);
        perCascade += cascade["compared"].get<int>();
    }
    // Each compared pixel the sun shades inside the shadow distance belongs to one cascade.
    EXPECT_GT(perCascade, 0);
    EXPECT_LE(perCascade, sun["compared"].get<int>());
    EXPECT_TRUE(sun["split_band"].contains("compared"));
    EXPECT_EQ(readPng(dir + "/cascades.png").width, 160u);
    EXPECT_EQ(readPng(dir + "/mismatch-sun.png").height, 90u);
    EXPECT_NE(testing::readText(dir + "/report.html").find("cascades.png"), std::string::npos);
    EXPECT_NE(run.out.find("sun"), std::string::npos);

    const std::string statsPath = folder.file("stats.json");
    const RunResult render = testing::runPunctual(
        folder, "render --validate --scene outdoor --size 160x90 --cascades 2 --shadow-distance 80 --stats '" + statsPath + "'");
    ASSERT_EQ(render.exitCode, 0) << render.err;
    const nlohmann::json shadows = nlohmann::json::parse(testing::readText(statsPath))["shadows"];
    EXPECT_EQ(shadows["cascades"], 2);
    ASSERT_EQ(shadows["cascade_splits"].size(), 2u);
    EXPECT_FLOAT_EQ(shadows["cascade_splits"][0].get<float>(), 8.0f);  // the notes' 0.1 of 80 m
    EXPECT_FLOAT_EQ(shadows["cascade_splits"][1].get<float>(), 80.0f);
    EXPECT_EQ(shadows["shadow_distance_fitted"], false);
    for (const auto& cascade : shadows["cascade_list"]) EXPECT_GT(cascade["texel_m"].get<double>(), 0.0);
}

TEST(ValidateCli, BadCascadeOptionsFailWithOneLine) {
    testing::TempFolder folder;
    for (const char* options : {"--cascades 5", "--cascades 0", "--cascade-splits 0.5,0.25,0.7", "--cascade-splits 0.1,0.2",
                                "--cascade-lambda 2", "--shadow-distance -3", "--cascade-blend smooth"}) {
        const RunResult run = testing::runPunctual(folder, std::string("render --scene outdoor --size 32x18 ") + options);
        EXPECT_EQ(run.exitCode, 1) << options << ": " << run.err;
        EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << options << ": " << run.err;
    }
}

}  // namespace
}  // namespace punctual
