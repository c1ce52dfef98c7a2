// Valid but extreme values, on the CPU: tone mapping at huge and tiny exposures (shading.h), and
// the shadow maps' memory check against a device's heap (shadow_setup.h), with made-up heap sizes
// so that no test allocates gigabytes. The GPU side (the same through the command line) is
// tests/gpu/test_extreme_values_cli.cpp.
#include <gtest/gtest.h>

#include <limits>
#include <string>

#include "core/error.h"
#include "lights/shadow_setup.h"
#include "lights/shadow_sizing.h"
#include "shading.h"

namespace punctual {
namespace {

using gpu::toneMapAces;

constexpr uint64_t kGiB = 1ull << 30;

// ---- tone mapping -------------------------------------------------------------------------------

TEST(ToneMapping, HugeExposureSaturatesToWhite) {
    // radiance 1 x exposure 1e30: x^2 = 1e60 overflows float; the curve must still give 1.
    EXPECT_EQ(toneMapAces(glm::vec3(1.0f), 1e30f), glm::vec3(1.0f));
    // radiance x exposure itself overflows to inf (1e10 x 1e30 > 3.4e38).
    EXPECT_EQ(toneMapAces(glm::vec3(1e10f, 0.5f, 3.0f), 1e30f), glm::vec3(1.0f));
    EXPECT_EQ(toneMapAces(glm::vec3(std::numeric_limits<float>::max()), std::numeric_limits<float>::max()),
              glm::vec3(1.0f));
    // No light stays black at any exposure.
    EXPECT_EQ(toneMapAces(glm::vec3(0.0f), 1e30f), glm::vec3(0.0f));
}

TEST(ToneMapping, TinyExposureGivesBlack) {
    // x = 1e-30: (0.03 x) / 0.14 = 2e-31, far below half an 8-bit step.
    const glm::vec3 mapped = toneMapAces(glm::vec3(1.0f, 100.0f, 1e4f), 1e-30f);
    for (int c = 0; c < 3; ++c) {
        EXPECT_GE(mapped[c], 0.0f);
        EXPECT_LT(mapped[c], 1e-20f);
    }
}

TEST(ToneMapping, TheInputCapChangesNoOutput) {
    // The curve crosses 1 at x = 7.24 (0.08 x^2 - 0.56 x - 0.14 = 0) and stays above it: at
    // x = 7.3 the ratio is (2.51 * 53.29 + 0.219) / (2.43 * 53.29 + 4.307 + 0.14) = 133.97 / 133.94
    // > 1, so 1 after the clamp, as every x up to the cap (1e4) and beyond it.
    EXPECT_EQ(toneMapAces(glm::vec3(7.3f), 1.0f), glm::vec3(1.0f));
    EXPECT_EQ(toneMapAces(glm::vec3(PUNCTUAL_ACES_MAX_INPUT), 1.0f), glm::vec3(1.0f));
    // Below 7.24 the curve is below 1 and untouched: x = 1 gives 2.54 / 3.16 = 0.8038.
    EXPECT_NEAR(toneMapAces(glm::vec3(1.0f), 1.0f).x, 2.54f / 3.16f, 1e-6f);
}

// ---- shadow-map memory --------------------------------------------------------------------------

// `spots` spot views and six faces for each of `points` point lights, each with a caster (so each
// needs storage in fixed mode).
ShadowPlan planWith(uint32_t spots, uint32_t points) {
    ShadowPlan plan;
    plan.shadowedSpots = spots;
    plan.shadowedPoints = points;
    ShadowView view;
    view.casters = {0};
    for (uint32_t s = 0; s < spots; ++s) plan.views.push_back(view);
    view.isPoint = true;
    for (uint32_t p = 0; p < 6 * points; ++p) plan.views.push_back(view);
    return plan;
}

ShadowSettings d32(PointShadowLayout layout = PointShadowLayout::Slices) {
    ShadowSettings settings;
    settings.format = ShadowFormat::D32;
    settings.pointLayout = layout;
    return settings;
}

TEST(ShadowMemory, BytesCountASquarePerSpotAndSixPerPoint) {
    // 8192^2 texels x 4 bytes = 256 MiB a view; 32 spots + 6 x 8 points = 80 views = 20 GiB, in the
    // atlas (slices) or split between the atlas and the cube array: the same bytes. Beside the
    // atlas, the drawing square: 1024^2 x 4 bytes = 4 MiB (8192 views draw in 64 tiles of it).
    EXPECT_EQ(shadowMapBytes(planWith(32, 8), d32(), 8192), 20 * kGiB + (4ull << 20));
    EXPECT_EQ(shadowMapBytes(planWith(32, 8), d32(PointShadowLayout::Cube), 8192), 20 * kGiB + (4ull << 20));
    // 16 bits a texel: half.
    EXPECT_EQ(shadowMapBytes(planWith(32, 8), ShadowSettings{}, 8192), 10 * kGiB + (2ull << 20));
    // 1024^2 x 4 = 4 MiB a view; 1 spot + 6 = 7 views, and a drawing square of one view: 8 x 4 MiB.
    EXPECT_EQ(shadowMapBytes(planWith(1, 1), d32(), 1024), 32ull << 20);
    // 512^2 x 4 = 1 MiB a view: 7 views and a square of 512.
    EXPECT_EQ(shadowMapBytes(planWith(1, 1), d32(), 512), 8ull << 20);
    EXPECT_EQ(shadowMapBytes(planWith(0, 0), d32(), 8192), 0u);
}

TEST(ShadowMemory, ViewsWithoutCastersTakeNoAtlasStorage) {
    ShadowPlan plan = planWith(4, 0);
    plan.views[1].casters.clear();
    plan.views[3].casters.clear();
    EXPECT_EQ(shadowMapBytes(plan, d32(), 1024), 12ull << 20);  // two views of 4 MiB and the drawing square
}

ShadowMemoryLimits heapOf(uint64_t bytes, const std::string& name = "the device's largest heap") {
    ShadowMemoryLimits limits;
    limits.total = bytes;
    limits.totalName = name;
    limits.atlasSide = 1u << 20;  // no side limit unless a test sets one
    return limits;
}

// The error's whole line, or "no error".
std::string errorOf(ShadowPlan plan, uint32_t resolution, const ShadowMemoryLimits& limits,
                    ShadowSettings settings = d32()) {
    settings.resolution = resolution;
    FrameLights lights;
    lights.packed.resize(1);
    lights.sceneLightIndex.resize(1);
    try {
        sizeShadowViews(plan, Scene{}, lights, glm::vec3(0.0f), 64, 36, settings, limits);
    } catch (const Error& e) {
        return e.what();
    }
    return "no error";
}

TEST(ShadowMemory, ARequestOverTheHeapFailsWithOneClearLine) {
    // 2048: 80 views x 16 MiB = 1.25 GiB (and the 4 MiB drawing square) fits; 4096 (5 GiB) does
    // not. 8192: 20 GiB and 4 MiB, 20.004 GiB.
    EXPECT_EQ(errorOf(planWith(32, 8), 8192, heapOf(2 * kGiB)),
              "--shadow-res 8192: the shadow maps of 32 spot and 8 point lights need 20.0 GiB, the device's "
              "largest heap has 2.0 GiB (at most --shadow-res 2048 fits)");
}

TEST(ShadowMemory, RequestsThatFitPass) {
    EXPECT_EQ(errorOf(planWith(32, 8), 8192, heapOf(20 * kGiB + (4ull << 20))), "no error");  // exactly
    EXPECT_EQ(errorOf(planWith(0, 0), 8192, heapOf(0)), "no error");
    EXPECT_EQ(errorOf(planWith(32, 8), 1024, heapOf(2 * kGiB)), "no error");
}

TEST(ShadowMemory, AnImageOverTheLargestImageFails) {
    // Lavapipe's maxResourceSize is 4 GiB - 1: 32 spot views at 8192 (8 GiB) exceed it even with
    // a heap large enough for everything; 4096 (2 GiB) fits.
    ShadowMemoryLimits limits = heapOf(64 * kGiB);
    limits.atlasBytes = 4 * kGiB - 1;
    limits.cubeArrayBytes = 4 * kGiB - 1;
    EXPECT_EQ(errorOf(planWith(32, 0), 8192, limits),
              "--shadow-res 8192: the shadow atlas needs 8.0 GiB, the device's largest such image holds 4.0 GiB "
              "(at most --shadow-res 4096 fits)");
    // Cube layout, 8 points: 48 faces in the cube array, 12 GiB at 8192, 3 GiB at 4096.
    EXPECT_EQ(errorOf(planWith(1, 8), 8192, limits, d32(PointShadowLayout::Cube)),
              "--shadow-res 8192: the point shadow cube array (48 layers) needs 12.0 GiB, the device's largest such "
              "image holds 4.0 GiB (at most --shadow-res 4096 fits)");
    EXPECT_EQ(errorOf(planWith(32, 8), 4096, limits, d32(PointShadowLayout::Cube)), "no error");
}

TEST(ShadowMemory, AnAtlasWiderThanTheDeviceAllowsFails) {
    // 16384-texel sides: 80 views of 2048^2 need 80 pages of 2048, 8 to a row, 10 rows = 20480
    // texels: too tall. 1024: 80 pages of 1024, 16 to a row, 5 rows: fits.
    ShadowMemoryLimits limits = heapOf(64 * kGiB);
    limits.atlasSide = 16384;
    EXPECT_EQ(errorOf(planWith(32, 8), 2048, limits),
              "--shadow-res 2048: the shadow atlas would be wider or taller than the device's largest 2D image "
              "(16384 texels) (at most --shadow-res 1024 fits)");
    EXPECT_EQ(errorOf(planWith(32, 8), 1024, limits), "no error");
}

TEST(ShadowMemory, WhenNothingFitsTheMessageSuggestsNoResolution) {
    // 64^2 x 4 x 80 = 1.25 MiB and a 16 KiB drawing square (1.27 MiB); even 16 texels (81 KiB)
    // exceed 1 KiB.
    EXPECT_EQ(errorOf(planWith(32, 8), 64, heapOf(1024, "the device's memory budget")),
              "--shadow-res 64: the shadow maps of 32 spot and 8 point lights need 1.3 MiB, the device's memory "
              "budget has 1.0 KiB");
}

}  // namespace
}  // namespace punctual
