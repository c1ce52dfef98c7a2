// `punctual play` (issue 34): a sequence along the hall's walk writes a frame per 1/F s with its
// statistics, percentiles that are the frames' own, a chart and a page; each saved frame is the
// image `render --time T` gives, bit for bit; a glTF file plays its animations for their length;
// and bad input fails with one line and writes nothing.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "animated_gltf.h"
#include "core/image.h"
#include "core/run_program.h"
#include "gpu_test_support.h"
#include "report/sequence_report.h"

namespace punctual {
namespace {

using testing::cat;
using testing::quoted;

TEST(PlayCli, TheWalkWritesAFramePerStepWithItsOwnPercentiles) {
    testing::TempFolder folder;
    const std::string dir = folder.file("walk");
    const testing::RunResult run =
        testing::runPunctual(folder, cat("play --scene hall --fps 1 --seconds 2 --size 64x36 --save-frames --out-dir ", quoted(dir)));
    ASSERT_EQ(run.exitCode, 0) << run.err;
    EXPECT_EQ(run.err, "");
    const nlohmann::json document = nlohmann::json::parse(testing::readText(dir + "/frames.json"));
    EXPECT_EQ(document["frame_count"], 3);
    ASSERT_EQ(document["frames"].size(), 3u);
    std::vector<double> totals;
    for (size_t i = 0; i < 3; ++i) {
        EXPECT_DOUBLE_EQ(document["frames"][i]["time_s"].get<double>(), double(i));
        totals.push_back(document["frames"][i]["gpu_ms"]["total"].get<double>());
        EXPECT_GT(totals.back(), 0.0);
        EXPECT_EQ(document["frames"][i]["stats"]["lights"]["spot"].get<int>() +
                      document["frames"][i]["stats"]["lights"]["point"].get<int>() +
                      document["frames"][i]["stats"]["lights"]["culled_by_frustum"].get<int>(),
                  96);
    }
    EXPECT_DOUBLE_EQ(document["summary"]["total"]["p95"].get<double>(), report::percentile(totals, 95.0));
    EXPECT_EQ(testing::lineCount(testing::readText(dir + "/frames.csv")), 4u);  // a header and three frames
    EXPECT_NE(testing::readText(dir + "/frame_times.svg").find("p99"), std::string::npos);
    EXPECT_NE(testing::readText(dir + "/index.html").find("frame-0002.png"), std::string::npos);
    EXPECT_EQ(document["files"].size(), 7u);  // three frames, the CSV, the chart, the page and frames.json

    // The frame at 1 s is render --time 1.
    const std::string still = folder.file("still.png");
    ASSERT_EQ(testing::runPunctual(folder, cat("render --time 1 --size 64x36 --out ", quoted(still))).exitCode, 0);
    EXPECT_EQ(readPng(dir + "/frame-0001.png").pixels, readPng(still).pixels);
    EXPECT_NE(readPng(dir + "/frame-0000.png").pixels, readPng(still).pixels);  // and the walk moved
}

// --validate-every 2 over three frames validates the first and the third; the third's counts are
// validate --time 2's, to the pixel.
TEST(PlayCli, ValidatedFramesCountWhatValidateCountsAtTheirTime) {
    testing::TempFolder folder;
    const std::string dir = folder.file("walk");
    const testing::RunResult run = testing::runPunctual(
        folder, cat("play --scene hall --fps 1 --seconds 2 --size 64x36 --validate-every 2 --out-dir ", quoted(dir)));
    ASSERT_EQ(run.exitCode, 0) << run.err;
    const nlohmann::json document = nlohmann::json::parse(testing::readText(dir + "/frames.json"));
    ASSERT_EQ(document["frames"].size(), 3u);
    EXPECT_TRUE(document["frames"][0]["stats"].contains("validation"));
    EXPECT_FALSE(document["frames"][1]["stats"].contains("validation"));
    ASSERT_TRUE(document["frames"][2]["stats"].contains("validation"));
    EXPECT_EQ(document["summary"]["validation"]["frames"], 2);
    EXPECT_FALSE(document["frames"][0]["stats"]["validation"].contains("flips"));  // no frame before it
    EXPECT_GT(document["frames"][2]["stats"]["validation"]["flips"]["compared"].get<uint64_t>(), 100u);

    const std::string validateDir = folder.file("validate");
    ASSERT_EQ(testing::runPunctual(folder, cat("validate --time 2 --size 64x36 --out-dir ", quoted(validateDir))).exitCode, 0);
    const nlohmann::json overall = nlohmann::json::parse(testing::readText(validateDir + "/report.json"))["overall"];
    const nlohmann::json& played = document["frames"][2]["stats"]["validation"];
    EXPECT_GT(played["compared"].get<uint64_t>(), 1000u);
    for (const char* key : {"compared", "false_shadow", "false_lit", "edge_band"}) EXPECT_EQ(played[key], overall[key]) << key;
    const std::string csv = testing::readText(dir + "/frames.csv");
    EXPECT_NE(csv.find(",shadow_misclassified,shadow_flip_tests,shadow_flips\n"), std::string::npos);
    EXPECT_NE(csv.find(",,,,\n2,"), std::string::npos) << csv;  // frame 1's empty validation cells, then frame 2
}

// A budget too small for every frame: one warning for the sequence, not one a frame, and each
// frame's reduced views in its row.
TEST(PlayCli, AShortBudgetWarnsOnceForTheSequence) {
    testing::TempFolder folder;
    const std::string dir = folder.file("walk");
    const testing::RunResult run = testing::runPunctual(
        folder, cat("play --scene hall --fps 1 --seconds 1 --size 160x90 --shadow-budget 1 --out-dir ", quoted(dir)));
    ASSERT_EQ(run.exitCode, 0) << run.err;
    EXPECT_EQ(testing::lineCount(run.err), 1u) << run.err;
    EXPECT_NE(run.err.find("punctual: warning: shadows: in 2 of 2 frames, up to "), std::string::npos) << run.err;
    const std::string csv = testing::readText(dir + "/frames.csv");
    EXPECT_NE(csv.find("shadow_reduced_views"), std::string::npos);
}

// Along the walk the views' tiers follow the camera's distance; with a whole octave of hysteresis
// fewer of them switch from frame to frame (down late; up as before: 286 against 337 measured at
// 2 fps), and the first frame (no previous tiers) is the same.
TEST(PlayCli, HysteresisHoldsTheTiersBack) {
    testing::TempFolder folder;
    const auto switches = [&](const std::string& name, const std::string& extra) {
        const std::string dir = folder.file(name);
        const testing::RunResult run =
            testing::runPunctual(folder, cat("play --scene hall --fps 2 --seconds 6 --size 320x180 --save-frames ", extra,
                                             " --out-dir ", quoted(dir)));
        EXPECT_EQ(run.exitCode, 0) << run.err;
        uint64_t total = 0;
        const nlohmann::json document = nlohmann::json::parse(testing::readText(dir + "/frames.json"));
        for (const nlohmann::json& f : document["frames"]) {
            total += f["stats"]["shadows"]["tier_switches"].get<uint64_t>();
        }
        return std::make_pair(total, dir);
    };
    const auto [free, freeDir] = switches("free", "");
    const auto [held, heldDir] = switches("held", "--shadow-hysteresis 1");
    EXPECT_GT(free, 100u);  // the walk does switch tiers (337 measured)
    EXPECT_LT(held, free - free / 10) << free;
    EXPECT_EQ(readPng(freeDir + "/frame-0000.png").pixels, readPng(heldDir + "/frame-0000.png").pixels);
}

// Without --seconds a file plays its animations' length: keyframes to 1.5 s at 2 fps are frames
// at 0, 0.5, 1 and 1.5 s.
TEST(PlayCli, AFilePlaysForItsAnimationsLength) {
    testing::TempFolder folder;
    testing::AnimatedGltf animated;
    animated.addChannel(0, testing::AnimatedGltf::kCamera, "translation", "LINEAR", {0.0f, 1.5f}, {0, 0, 3, 0, 0, 5});
    const std::string file = animated.write(folder.file("a.gltf"));
    const std::string dir = folder.file("seq");
    const testing::RunResult run = testing::runPunctual(folder, cat("play ", quoted(file), " --fps 2 --size 48x32 --out-dir ", quoted(dir)));
    ASSERT_EQ(run.exitCode, 0) << run.err;
    const nlohmann::json document = nlohmann::json::parse(testing::readText(dir + "/frames.json"));
    EXPECT_DOUBLE_EQ(document["seconds"].get<double>(), 1.5);
    EXPECT_EQ(document["frames"].size(), 4u);

    // A still file plays for the --seconds given, one scene every frame, and says nothing.
    testing::AnimatedGltf stillFile;
    const std::string still = stillFile.write(folder.file("still.gltf"));
    const testing::RunResult stillRun =
        testing::runPunctual(folder, cat("play ", quoted(still), " --fps 1 --seconds 1 --size 48x32 --out-dir ", quoted(dir)));
    ASSERT_EQ(stillRun.exitCode, 0) << stillRun.err;
    EXPECT_EQ(stillRun.err, "");
    EXPECT_EQ(nlohmann::json::parse(testing::readText(dir + "/frames.json"))["frames"].size(), 2u);

    // Validated, a still sequence compares every lit receiver and flips none: the same frame twice.
    ASSERT_EQ(testing::runPunctual(folder, cat("play ", quoted(still), " --fps 1 --seconds 1 --size 48x32 --validate-every 1 "
                                                                      "--out-dir ", quoted(dir)))
                  .exitCode,
              0);
    const nlohmann::json validated = nlohmann::json::parse(testing::readText(dir + "/frames.json"));
    EXPECT_GT(validated["summary"]["validation"]["flip_tests"].get<double>(), 100.0);
    EXPECT_EQ(validated["summary"]["validation"]["flips"].get<double>(), 0.0);
}

TEST(PlayCli, BadInputFailsWithOneLineAndWritesNothing) {
    testing::TempFolder folder;
    testing::AnimatedGltf still;  // no animation
    const std::string file = still.write(folder.file("still.gltf"));
    const std::string dir = quoted(folder.file("out"));
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"play --scene hall --size 32x18", "--out-dir: play needs an output folder"},
        {"play --scene hall --fps 0 --out-dir " + dir, "--fps: expected frames a second from 0.1 to 240, got '0'"},
        {"play --scene hall --seconds -1 --out-dir " + dir, "--seconds: expected seconds"},
        {"play --scene hall --time 2 --out-dir " + dir, "--time: play sets each frame's time itself"},
        {"play --scene hall --out x.png --out-dir " + dir, "--out: not an option of play"},
        {"play --scene rooms --out-dir " + dir, "built-in rooms scene has no animation or path to take a length from"},
        {"play " + quoted(file) + " --out-dir " + dir, "has no animation or path to take a length from: give --seconds S"},
        {"play --scene hall --fps 240 --seconds 1000 --out-dir " + dir, "play renders at most 10000"},
        {"play --scene hall --validate-every 0 --out-dir " + dir, "--validate-every: expected a whole number of frames"},
        {"play --scene hall --validate-every 1.5 --out-dir " + dir, "--validate-every: expected a whole number of frames"},
        {"play --scene hall --shadows off --validate-every 1 --out-dir " + dir, "--validate-every: compares shadows"},
        {"play --scene hall --shadow-hysteresis 3 --out-dir " + dir, "--shadow-hysteresis: expected octaves from 0 to 2"},
    };
    for (const auto& [args, mention] : cases) testing::expectOneClearError(testing::runPunctual(folder, args), args, mention);
    testing::expectNothingLeftBehind(folder, "refused plays", {"still.gltf"});
}

// --video: where ffmpeg is on PATH, the frames as an MP4 (an ISO media file: "ftyp" at byte 4),
// listed in frames.json and shown on the page; where it is not, one line naming ffmpeg before
// anything is rendered, and nothing written.
TEST(PlayCli, AVideoIsEncodedWhereFfmpegIsAndRefusedWhereItIsNot) {
    testing::TempFolder folder;
    const std::string dir = folder.file("walk");
    const std::string args = cat("play --scene hall --fps 2 --seconds 1 --size 64x36 --video --out-dir ", quoted(dir));
    if (!findOnPath("ffmpeg").empty()) {
        const testing::RunResult run = testing::runPunctual(folder, args);
        ASSERT_EQ(run.exitCode, 0) << run.err;
        const std::string video = testing::readText(dir + "/frames.mp4");
        ASSERT_GT(video.size(), 8u);
        EXPECT_EQ(video.substr(4, 4), "ftyp");
        const nlohmann::json document = nlohmann::json::parse(testing::readText(dir + "/frames.json"));
        EXPECT_NE(document["files"].dump().find("frames.mp4"), std::string::npos);
        EXPECT_NE(testing::readText(dir + "/index.html").find("<video src=\"frames.mp4\""), std::string::npos);
        std::filesystem::remove_all(dir);
    } else {
        GTEST_LOG_(INFO) << "ffmpeg is not on PATH: only its absence is tested";
    }
    // Without ffmpeg on PATH (an empty folder as PATH: the shell that runs punctual is /bin/sh).
    const std::string path = std::getenv("PATH") ? std::getenv("PATH") : "";
    ::setenv("PATH", folder.path().c_str(), 1);
    const testing::RunResult refused = testing::runPunctual(folder, args);
    ::setenv("PATH", path.c_str(), 1);
    testing::expectOneClearError(refused, args, "--video: needs ffmpeg on PATH");
    testing::expectNothingLeftBehind(folder, "refused video");
}

}  // namespace
}  // namespace punctual
