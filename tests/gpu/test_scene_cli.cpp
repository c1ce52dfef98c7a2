// Built-in scenes on the command line (--scene NAME): the outdoor scene renders lit and
// validation-clean, with its own lights or generated ones; every command that takes a scene takes
// --scene; an unknown name, or a name and a file together, fail with one line and no output.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "gpu_test_support.h"
#include "scene/outdoor_scene.h"
#include "scene/warehouse_scene.h"

namespace punctual {
namespace {

using testing::quoted;
using testing::readText;
using testing::RunResult;
using testing::runPunctual;

// A failing run of `args`: status 1 (a user error, README "Exit status"), one line naming
// `mention`, and nothing written.
void expectUserErrorAndNoOutput(const testing::TempFolder& folder, const std::string& args,
                                const std::string& mention) {
    const RunResult run = runPunctual(folder, args);
    testing::expectOneClearError(run, args, mention);
    EXPECT_EQ(run.exitCode, 1) << args;
    testing::expectNothingLeftBehind(folder, args);
}

TEST(SceneCli, OutdoorRendersLitAndValidationClean) {
    testing::TempFolder folder;
    const std::string png = folder.file("outdoor.png");
    const std::string json = folder.file("stats.json");
    const RunResult run = runPunctual(
        folder, "render --scene outdoor --validate --size 160x90 --out " + quoted(png) + " --stats " + quoted(json));
    ASSERT_EQ(run.exitCode, 0) << run.err;
    EXPECT_EQ(run.err, "");  // no validation message, no warning
    const ImageRgba8 image = readPng(png);
    ASSERT_EQ(image.width, 160u);
    ASSERT_EQ(image.height, 90u);
    testing::saveTestImage("scene_cli_outdoor", image);
    // Neither black nor blown out: the sunlit street fills most of the frame (the sky, above the
    // buildings, is the black background), at mid-range brightness.
    const double luma = testing::meanLuma(image);
    EXPECT_GT(luma, 0.2);
    EXPECT_LT(luma, 0.75);
    EXPECT_GT(testing::fractionBrighterThan(image, 20), 0.6);
    EXPECT_LT(testing::fractionBrighterThan(image, 250), 0.05);
    const nlohmann::json stats = nlohmann::json::parse(readText(json));
    EXPECT_EQ(stats["scene"].get<std::string>(), outdoor_scene::kSource);
    EXPECT_EQ(stats["lights"]["directional"].get<int>(), 1);
    EXPECT_EQ(stats["lights"]["spot"].get<int>(), 16);
    EXPECT_EQ(stats["lights"]["point"].get<int>(), 16);
}

// The warehouse holds 4,096 lamps; a frame keeps the most important within the capacity and says
// how many it dropped. With shadows on, every kept light is shadowed, and rendering is clean.
TEST(SceneCli, WarehouseKeepsTheMostImportantLampsAndSaysHowManyItDropped) {
    testing::TempFolder folder;
    const std::string png = folder.file("warehouse.png");
    const std::string json = folder.file("stats.json");
    const RunResult run = runPunctual(
        folder, "render --scene warehouse --validate --size 160x90 --out " + quoted(png) + " --stats " + quoted(json));
    ASSERT_EQ(run.exitCode, 0) << run.err;
    const nlohmann::json stats = nlohmann::json::parse(readText(json));
    EXPECT_EQ(stats["scene"].get<std::string>(), warehouse_scene::kSource);
    const nlohmann::json& lights = stats["lights"];
    EXPECT_EQ(lights["in_scene"].get<int>(), 4096);
    EXPECT_EQ(lights["spot"].get<int>(), PUNCTUAL_DEFAULT_MAX_SPOT_LIGHTS);  // the capacity, full
    EXPECT_EQ(lights["point"].get<int>(), PUNCTUAL_DEFAULT_MAX_POINT_LIGHTS);
    const int dropped = lights["dropped_by_cap"].get<int>();
    EXPECT_EQ(dropped + lights["culled_by_frustum"].get<int>() + PUNCTUAL_DEFAULT_MAX_SPOT_LIGHTS + PUNCTUAL_DEFAULT_MAX_POINT_LIGHTS, 4096);
    EXPECT_NE(run.out.find(std::to_string(dropped) + " over the capacity, --max-lights 64,32"), std::string::npos) << run.out;
    const ImageRgba8 image = readPng(png);
    testing::saveTestImage("scene_cli_warehouse", image);
    EXPECT_GT(testing::fractionBrighterThan(image, 20), 0.02);  // the kept lamps light some rooms
}

// --light-range auto holds the lights reaching a pixel about where 96 put them, where drawn ranges
// let them grow with the count (measured on the hall at 320x180: 17.8 a pixel at 96, 27.5 at
// 1,932 kept; drawn ranges 87 at 2,000).
TEST(SceneCli, AutoLightRangeHoldsTheLightsReachingAPixelAsTheyMultiply) {
    testing::TempFolder folder;
    const auto affectingPerPixel = [&](const std::string& lights) {
        const std::string json = folder.file("stats.json");
        const RunResult run = runPunctual(folder, "render --lights " + lights + " --max-lights 1000,1000 --shadows off " +
                                                      "--size 160x90 --stats " + quoted(json));
        EXPECT_EQ(run.exitCode, 0) << run.err;
        return nlohmann::json::parse(readText(json))["culling"]["affecting_per_pixel"].get<double>();
    };
    const double reference = affectingPerPixel("64,32 --light-range auto");
    const double automatic = affectingPerPixel("1000,1000 --light-range auto");
    const double drawn = affectingPerPixel("1000,1000");
    EXPECT_GT(reference, 5.0);  // not vacuous: lights reach the pixels
    EXPECT_LT(automatic, 2.0 * reference);
    EXPECT_GT(automatic, 0.5 * reference);
    EXPECT_GT(drawn, 3.0 * reference);
}

TEST(SceneCli, OutdoorTakesGeneratedLights) {
    testing::TempFolder folder;
    const std::string png = folder.file("outdoor.png");
    const std::string json = folder.file("stats.json");
    const RunResult run = runPunctual(folder, "render --scene outdoor --lights 8,8 --validate --size 160x90 --out " +
                                                  quoted(png) + " --stats " + quoted(json));
    ASSERT_EQ(run.exitCode, 0) << run.err;
    EXPECT_EQ(run.err, "");  // in particular no "the image is black" warning
    const nlohmann::json stats = nlohmann::json::parse(readText(json));
    // The generated lights replace all of the scene's, the sun included, and every one reaches
    // something in view, so the frame keeps them all.
    EXPECT_EQ(stats["lights"]["in_scene"].get<int>(), 16);
    EXPECT_EQ(stats["lights"]["directional"].get<int>(), 0);
    EXPECT_EQ(stats["lights"]["spot"].get<int>(), 8);
    EXPECT_EQ(stats["lights"]["point"].get<int>(), 8);
    const ImageRgba8 image = readPng(png);
    testing::saveTestImage("scene_cli_outdoor_generated", image);
    EXPECT_GT(testing::meanLuma(image), 0.05);
}

TEST(SceneCli, EveryCommandTakesAScene) {
    testing::TempFolder folder;
    const std::string png = folder.file("reference.png");
    const RunResult reference = runPunctual(folder, "reference --scene outdoor --size 64x36 --out " + quoted(png));
    ASSERT_EQ(reference.exitCode, 0) << reference.err;
    EXPECT_NE(reference.out.find(std::string("scene: ") + outdoor_scene::kSource), std::string::npos) << reference.out;
    EXPECT_GT(testing::meanLuma(readPng(png)), 0.1);

    const RunResult compare = runPunctual(folder, "compare --scene outdoor --validate --size 64x36 --shadow-res 256");
    ASSERT_EQ(compare.exitCode, 0) << compare.err;
    EXPECT_EQ(compare.err, "");
    EXPECT_EQ(compare.out.rfind(outdoor_scene::kSource, 0), 0u) << compare.out;

    const std::string dir = folder.file("validate");
    const RunResult validate =
        runPunctual(folder, "validate --scene outdoor --validate --size 64x36 --out-dir " + quoted(dir));
    ASSERT_EQ(validate.exitCode, 0) << validate.err;
    const nlohmann::json report = nlohmann::json::parse(readText(dir + "/report.json"));
    EXPECT_NE(report.dump().find(outdoor_scene::kSource), std::string::npos);
}

TEST(SceneCli, AnUnknownSceneFailsWithOneLineListingTheNames) {
    testing::TempFolder folder;
    const std::string png = quoted(folder.file("x.png"));
    const std::string dir = quoted(folder.file("dir"));
    const std::string names = "expected hall, outdoor, rooms, warehouse or engine, got 'nosuch'";
    expectUserErrorAndNoOutput(folder, "render --scene nosuch --out " + png, names);
    expectUserErrorAndNoOutput(folder, "reference --scene nosuch --out " + png, names);
    expectUserErrorAndNoOutput(folder, "compare --scene nosuch", names);
    expectUserErrorAndNoOutput(folder, "validate --scene nosuch --out-dir " + dir, names);
    expectUserErrorAndNoOutput(folder, "bench --scene nosuch --quick --out-dir " + dir, names);
    expectUserErrorAndNoOutput(folder, "render --scene --out " + png, "--scene: needs a value");
}

TEST(SceneCli, ASceneNameAndASceneFileTogetherFail) {
    testing::TempFolder folder;
    const std::string png = quoted(folder.file("x.png"));
    // The file need not exist: the command line is refused before anything is read.
    const std::string both = "a built-in scene and a scene file ('some.gltf') cannot both be given";
    expectUserErrorAndNoOutput(folder, "render --scene outdoor some.gltf --out " + png, both);
    expectUserErrorAndNoOutput(folder, "render some.gltf --scene outdoor --out " + png, both);
    expectUserErrorAndNoOutput(folder, "reference --scene hall some.gltf --out " + png, both);
}

}  // namespace
}  // namespace punctual
