// Shadows of lights with very long ranges (glTF allows any positive range): the shadow views'
// near and far planes are fitted to the geometry the light reaches, not to the range, so a range
// of 1e4 or 1e6 m over a 20 m scene gives the same shadows as a range of 20 m, validated against
// Embree. (With the near plane at range / 1000, a 1e4 m light clipped every caster nearer than
// 10 m and a 1e6 m one found no caster at all.)
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "gpu_test_support.h"
#include "lights/shadow_setup.h"
#include "scene/study_scenes.h"
#include "shadow_test_runs.h"

namespace punctual {
namespace {

using reference::PixelVerdict;
using testing::countVerdicts;
using testing::ShadowRun;

TEST(ShadowRange, LongRangesShadowLikeShortOnes) {
    auto context = testing::makeValidatedContext();
    ShadowSettings shadows;
    shadows.resolution = 512;
    const render::RenderSettings settings = testing::shadowRenderSettings(320, 180, shadows);

    const ShadowRun shortRun = testing::renderAndValidateShadows(*context, study::longRangeScene(20.0f), settings);
    testing::saveShadowRun("shadow-range-20", shortRun);
    ASSERT_EQ(shortRun.validation.lights.size(), 2u) << "the spot and the point are both shadowed";
    // The short range is itself right: few misclassified pixels, and real shadows of both lights.
    for (const reference::LightShadowValidation& light : shortRun.validation.lights) {
        const char* type = light.isPoint ? "point" : "spot";
        EXPECT_LE(light.counts.misclassifiedOutsideBand(), 0.02) << type;
        EXPECT_GE(countVerdicts(light, PixelVerdict::AgreeShadow, true), 500u) << type << ": too little shadow";
        EXPECT_GE(countVerdicts(light, PixelVerdict::AgreeLit, true), 5000u) << type << ": too little light";
    }

    for (const float range : {1e4f, 1e6f}) {
        const std::string what = "range " + std::to_string(range) + " m";
        const ShadowRun run = testing::renderAndValidateShadows(*context, study::longRangeScene(range), settings);
        testing::saveShadowRun("shadow-range-" + std::to_string(int(range)), run);
        ASSERT_EQ(run.validation.lights.size(), shortRun.validation.lights.size()) << what;
        // The same geometry in reach, so the same planes: the depth mapping does not follow the range.
        ASSERT_EQ(run.plan.views.size(), shortRun.plan.views.size()) << what;
        for (size_t v = 0; v < run.plan.views.size(); ++v) {
            EXPECT_EQ(run.plan.views[v].gpu.params, shortRun.plan.views[v].gpu.params) << what << ", view " << v;
            EXPECT_EQ(run.plan.views[v].casters, shortRun.plan.views[v].casters) << what << ", view " << v;
        }
        for (size_t l = 0; l < run.validation.lights.size(); ++l) {
            const reference::LightShadowValidation& light = run.validation.lights[l];
            const reference::LightShadowValidation& reference = shortRun.validation.lights[l];
            const char* type = light.isPoint ? "point" : "spot";
            ASSERT_EQ(light.verdicts.size(), reference.verdicts.size());
            size_t compared = 0;
            size_t differing = 0;
            for (size_t p = 0; p < light.verdicts.size(); ++p) {
                if (light.verdicts[p] == PixelVerdict::NotCompared || reference.verdicts[p] == PixelVerdict::NotCompared) {
                    continue;
                }
                ++compared;
                differing += light.verdicts[p] != reference.verdicts[p];
            }
            EXPECT_GE(compared, 20000u) << what << ", " << type;
            EXPECT_EQ(differing, 0u) << what << ", " << type << ": pixels classified differently from range 20 m, of "
                                     << compared;
            EXPECT_LE(light.counts.misclassifiedOutsideBand(), 0.02) << what << ", " << type;
            EXPECT_EQ(countVerdicts(light, PixelVerdict::AgreeShadow, true),
                      countVerdicts(reference, PixelVerdict::AgreeShadow, true))
                << what << ", " << type;
            std::printf("[ shadows  ] %s, %s: %zu pixels compared with range 20 m, %zu differ; %.2f%% misclassified\n",
                        what.c_str(), type, compared, differing, 100.0 * light.counts.misclassifiedOutsideBand());
        }
    }
    testing::expectNoValidationMessages(*context);
}

// Geometry kilometres away but inside a light's reach must not cost the near shadows their casters
// (issue 30: a wall 3 km away left a point light's nearby shadows 10% false-lit, a box 5 km down a
// spot's cone 14% misclassified). The same frame is validated with and without that geometry, at
// both depth formats; the distant geometry is outside the camera's view, so the same pixels are
// compared.
TEST(ShadowRange, DistantGeometryInReachKeepsTheNearCasters) {
    auto context = testing::makeValidatedContext();
    for (const ShadowFormat format : {ShadowFormat::D16, ShadowFormat::D32}) {
        ShadowSettings shadows;
        shadows.resolution = 512;
        shadows.format = format;
        const render::RenderSettings settings = testing::shadowRenderSettings(320, 180, shadows);
        const ShadowRun nearOnly = testing::renderAndValidateShadows(*context, study::longRangeScene(1e4f), settings);
        const ShadowRun distant = testing::renderAndValidateShadows(*context, study::distantGeometryScene(), settings);
        testing::saveShadowRun(std::string("shadow-distant-") + shadowFormatName(format), distant);
        ASSERT_EQ(distant.validation.lights.size(), 2u);
        ASSERT_EQ(nearOnly.validation.lights.size(), 2u);
        const double overall = distant.validation.overall.misclassified();
        std::printf("[ shadows  ] %s, distant geometry: %.4f%% of %llu pairs misclassified (%.4f%% without it)\n",
                    shadowFormatName(format), 100.0 * overall,
                    static_cast<unsigned long long>(distant.validation.overall.compared),
                    100.0 * nearOnly.validation.overall.misclassified());
        EXPECT_LE(overall, 0.01) << shadowFormatName(format);
        for (size_t l = 0; l < distant.validation.lights.size(); ++l) {
            const reference::LightShadowValidation& light = distant.validation.lights[l];
            const char* type = light.isPoint ? "point" : "spot";
            // The same pixels reach the light with and without the far geometry (it is out of view).
            EXPECT_EQ(light.counts.compared, nearOnly.validation.lights[l].counts.compared) << type;
            EXPECT_GE(light.counts.compared, 20000u) << type;
            EXPECT_GE(countVerdicts(light, PixelVerdict::AgreeShadow, true), 500u) << type << ": too little shadow";
            std::printf("[ shadows  ] %s, %s light: %.4f%% misclassified (false lit %llu, false shadow %llu)\n",
                        shadowFormatName(format), type, 100.0 * light.counts.misclassified(),
                        static_cast<unsigned long long>(light.counts.falseLit),
                        static_cast<unsigned long long>(light.counts.falseShadow));
            EXPECT_LE(light.counts.misclassified(), 0.02) << shadowFormatName(format) << ", " << type;
        }
    }
    testing::expectNoValidationMessages(*context);
}

}  // namespace
}  // namespace punctual
