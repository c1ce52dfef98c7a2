// `--time T` on the command line (issue 34): an animated file rendered at T gives the same image,
// bit for bit, as the still file whose nodes hold the pose interpolated by hand at T (camera,
// spot and mesh, tests/unit/test_gltf_animation.cpp checks the pose itself); it differs from the
// rest pose; and the time is refused where it means nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "animated_gltf.h"
#include "core/image.h"
#include "gpu_test_support.h"
#include "image_test_support.h"

namespace punctual {
namespace {

using testing::AnimatedGltf;
using testing::cat;
using testing::quoted;

ImageRgba8 renderToPng(const testing::TempFolder& folder, const std::string& args, const std::string& name) {
    const std::string png = folder.file(name);
    const testing::RunResult run = testing::runPunctual(folder, cat("render ", args, " --size 96x64 --out ", quoted(png)));
    EXPECT_EQ(run.exitCode, 0) << run.err;
    EXPECT_EQ(run.err, "") << args;  // no warning either
    return readPng(png);
}

// The camera slides and turns (LINEAR translation, slerped rotation), the spot moves along a
// CUBICSPLINE, the square grows (STEP scale): at 0.5 s the still file's values, worked out here.
TEST(AnimationCli, TheFrameAtATimeIsTheStillFrameOfTheInterpolatedPose) {
    testing::TempFolder folder;
    AnimatedGltf animated;
    const float h = float(std::sqrt(0.5));  // a quarter turn about y: (0, sqrt(1/2), 0, sqrt(1/2))
    animated.addChannel(0, AnimatedGltf::kCamera, "translation", "LINEAR", {0.0f, 2.0f}, {0, 0, 3, 2, 0, 5});
    animated.addChannel(0, AnimatedGltf::kCamera, "rotation", "LINEAR", {0.0f, 2.0f}, {0, 0, 0, 1, 0, h, 0, h});
    animated.addChannel(0, AnimatedGltf::kSpot, "translation", "CUBICSPLINE", {0.0f, 1.0f},
                        {0, 0, 0, 0, 0, 2, 0, 0, 0, 0, 0, 0, 1, 0, 2, 0, 0, 0});
    animated.addChannel(0, AnimatedGltf::kSquare, "scale", "STEP", {0.0f, 0.5f}, {1, 1, 1, 1.5f, 1.5f, 1});
    const std::string file = animated.write(folder.file("animated.gltf"));

    AnimatedGltf still;
    // A quarter of the way: (0.5, 0, 3.5), and a quarter of the quarter turn, (0, sin(pi/16), 0,
    // cos(pi/16)) at constant angular speed.
    const double sixteenth = std::numbers::pi / 16;
    still.doc["nodes"][AnimatedGltf::kCamera]["translation"] = {0.5, 0.0, 3.5};
    still.doc["nodes"][AnimatedGltf::kCamera]["rotation"] = {0.0, double(float(std::sin(sixteenth))), 0.0,
                                                             double(float(std::cos(sixteenth)))};
    still.doc["nodes"][AnimatedGltf::kSpot]["translation"] = {0.5, 0.0, 2.0};  // Hermite at s = 1/2, zero tangents
    still.doc["nodes"][AnimatedGltf::kSquare]["scale"] = {1.5, 1.5, 1.0};
    const std::string stillFile = still.write(folder.file("still.gltf"));

    const ImageRgba8 posed = renderToPng(folder, cat(quoted(file), " --time 0.5"), "posed.png");
    const ImageRgba8 expected = renderToPng(folder, quoted(stillFile), "still.png");
    const ImageRgba8 rest = renderToPng(folder, quoted(file), "rest.png");
    ASSERT_EQ(posed.width, expected.width);
    EXPECT_EQ(posed.pixels, expected.pixels);
    EXPECT_NE(posed.pixels, rest.pixels);  // the time moved something
    // The reference poses the scene the same way.
    const std::string refPosed = folder.file("ref-posed.png");
    const std::string refStill = folder.file("ref-still.png");
    EXPECT_EQ(testing::runPunctual(folder, cat("reference ", quoted(file), " --time 0.5 --size 96x64 --out ", quoted(refPosed)))
                  .exitCode, 0);
    EXPECT_EQ(testing::runPunctual(folder, cat("reference ", quoted(stillFile), " --size 96x64 --out ", quoted(refStill)))
                  .exitCode, 0);
    EXPECT_EQ(readPng(refPosed).pixels, readPng(refStill).pixels);
    size_t lit = 0;  // and the frame shows the lit square
    for (size_t i = 0; i < posed.pixels.size(); i += 4) lit += posed.pixels[i] > 8 || posed.pixels[i + 1] > 8;
    EXPECT_GT(lit, size_t(posed.width) * posed.height / 10);
}

TEST(AnimationCli, ATimeIsRefusedWhereItMeansNothing) {
    testing::TempFolder folder;
    const std::string png = quoted(folder.file("x.png"));
    testing::expectOneClearError(testing::runPunctual(folder, "render --scene rooms --time 1 --out " + png), "render --time 1",
                                 "--time: poses a scene file's animations or a built-in scene's path; rooms has none (hall and outdoor have)");
    for (const char* bad : {"-1", "nan", "1e7", "soon"}) {
        const std::string args = cat("render --time ", bad, " --out ", png);
        testing::expectOneClearError(testing::runPunctual(folder, args), args, "--time");
    }
    testing::expectNothingLeftBehind(folder, "refused times");
}

TEST(AnimationCli, AMovingShareIsRefusedWhereNoPathMovesLights) {
    testing::TempFolder folder;
    const std::string png = quoted(folder.file("x.png"));
    for (const std::string option : {"--moving-lights", "--moving-casters"}) {
        testing::expectOneClearError(testing::runPunctual(folder, "render --scene rooms " + option + " 0.5 --out " + png),
                                     "render --scene rooms " + option + " 0.5",
                                     option + ": moves lights or props along a built-in scene's path (hall and outdoor); "
                                              "rooms has no path");
        for (const char* bad : {"-0.1", "1.5", "nan", "half"}) {
            const std::string args = cat("render --time 3 ", option, " ", bad, " --out ", png);
            testing::expectOneClearError(testing::runPunctual(folder, args), args, option + ": must be a share from 0 to 1");
        }
    }
    testing::expectNothingLeftBehind(folder, "refused moving shares");
}

}  // namespace
}  // namespace punctual
