// Valid but extreme values through the command line: any finite exposure > 0 tone-maps to a
// correct (saturated) image, and a shadow resolution whose maps cannot fit the device fails with
// one line saying what was asked for and what fits, before anything is allocated. The CPU sides
// are in tests/unit/test_extreme_values.cpp.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "core/error.h"
#include "gpu_test_support.h"
#include "lights/shadow_setup.h"
#include "lights/shadow_sizing.h"
#include "render/shadow_maps.h"
#include "scene/default_scene.h"

namespace punctual {
namespace {

using testing::cat;
using testing::quoted;
using testing::RunResult;
using testing::runPunctual;

// `expectBlackWarning`: an exposure so small that every pixel rounds to black must say so, in the
// one line render prints whenever no light shows in the image (src/app/render_command.cpp).
ImageRgba8 renderWithExposure(const testing::TempFolder& folder, const std::string& exposure,
                              bool expectBlackWarning = false) {
    const std::string png = folder.file("exposure-" + exposure + ".png");
    const RunResult run =
        runPunctual(folder, cat("render --validate --size 96x54 --shadows off --exposure ", exposure, " --out ", quoted(png)));
    EXPECT_EQ(run.exitCode, 0) << exposure << ": " << run.err;
    if (expectBlackWarning) {
        EXPECT_NE(run.err.find("warning: built-in default scene: the image is black"), std::string::npos) << run.err;
        EXPECT_NE(run.err.find("--exposure " + exposure), std::string::npos) << run.err;
        EXPECT_EQ(run.err.find('\n'), run.err.size() - 1) << "one line: " << run.err;
    } else {
        EXPECT_EQ(run.err, "") << exposure;
    }
    return readPng(png);
}

TEST(ExtremeExposure, HugeIsWhiteWhereLitAndTinyIsBlack) {
    testing::TempFolder folder;
    const ImageRgba8 normal = renderWithExposure(folder, "1");
    const ImageRgba8 huge = renderWithExposure(folder, "1e30");
    const ImageRgba8 tiny = renderWithExposure(folder, "1e-30", /*expectBlackWarning=*/true);
    ASSERT_EQ(huge.pixels.size(), normal.pixels.size());
    ASSERT_EQ(tiny.pixels.size(), normal.pixels.size());
    size_t lit = 0;
    size_t litNotWhite = 0;
    size_t tinyNotBlack = 0;
    for (size_t p = 0; p < normal.pixels.size() / 4; ++p) {
        const uint8_t* n = &normal.pixels[4 * p];
        const uint8_t* h = &huge.pixels[4 * p];
        const uint8_t* t = &tiny.pixels[4 * p];
        // Lit at exposure 1 (some channel above black): every channel must saturate at 1e30.
        if (n[0] > 0 || n[1] > 0 || n[2] > 0) {
            ++lit;
            litNotWhite += h[0] != 255 || h[1] != 255 || h[2] != 255;
        }
        tinyNotBlack += t[0] != 0 || t[1] != 0 || t[2] != 0;
    }
    EXPECT_GT(lit, normal.pixels.size() / 4 / 2) << "the default scene should be mostly lit";
    EXPECT_EQ(litNotWhite, 0u) << "of " << lit << " lit pixels, not white at --exposure 1e30";
    EXPECT_EQ(tinyNotBlack, 0u) << "pixels not black at --exposure 1e-30";
}

// The default scene shadows every light, 64 spots and 32 points: 256 views of 8192^2 x 2 bytes,
// 32 GiB, more than any single 2D image of lavapipe (16384^2 texels, 4 GiB) or its 2 GiB heap, so
// the request fails there; a device with room for it would render it, and the test is skipped
// (tests/unit/test_extreme_values.cpp covers the check with made-up limits).
TEST(ExtremeShadowResolution, MapsLargerThanTheDeviceFailWithOneLine) {
    ShadowMemoryLimits limits;
    std::string expected;
    {
        auto context = testing::makeValidatedContext();
        ShadowSettings settings;
        settings.resolution = 8192;
        limits = render::ShadowMaps::memoryLimits(*context, settings);
        // The plan the command line makes (render --size 64x36 on the default scene).
        const Scene scene = makeDefaultScene();
        const float aspect = 64.0f / 36.0f;
        FrameLights lights = setupFrameLights(scene, scene.camera.view, scene.camera.projection(aspect));
        ShadowPlan plan = planShadows(scene, lights, scene.camera.position(), settings);
        try {
            sizeShadowViews(plan, scene, lights, scene.camera.position(), 64, 36, settings, limits);
        } catch (const Error& e) {
            expected = e.what();
        }
        EXPECT_GT(limits.total, 0u);
        testing::expectNoValidationMessages(*context);
    }
    if (expected.empty()) GTEST_SKIP() << "this device holds the 8192-texel maps of the default scene";
    testing::TempFolder folder;
    const std::string args = cat("render --validate --size 64x36 --shadow-res 8192 --out ", quoted(folder.file("out.png")),
                                 " --stats ", quoted(folder.file("stats.json")));
    const RunResult run = runPunctual(folder, args);
    testing::expectOneClearError(run, args, "--shadow-res 8192: ");
    EXPECT_EQ(run.err, "punctual: error: " + expected + "\n");
    EXPECT_NE(run.err.find("fits)"), std::string::npos) << "the line should say what fits: " << run.err;
    testing::expectNothingLeftBehind(folder, args);
}

}  // namespace
}  // namespace punctual
