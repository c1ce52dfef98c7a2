// Known answers for the sun's cascades: the split schemes, the slices' bounding spheres, texel
// snapping, cascade selection and the seed's fades (shaders/shared/cascades.h,
// src/lights/cascade_setup.h).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include "cascades.h"
#include "lights/cascade_setup.h"
#include "lights/light_setup.h"
#include "lights/shadow_setup.h"
#include "scene/study_scenes.h"

namespace punctual {
namespace {

TEST(CascadeSplits, PracticalSchemeBlendsLinearAndLogarithmic) {
    // near 1, far 100, halfway: logarithmic 1 x 100^0.5 = 10, linear 1 + 99 / 2 = 50.5.
    EXPECT_NEAR(gpu::practicalSplit(1.0f, 100.0f, 0.5f, 1.0f), 10.0f, 1e-4f);
    EXPECT_NEAR(gpu::practicalSplit(1.0f, 100.0f, 0.5f, 0.0f), 50.5f, 1e-4f);
    EXPECT_NEAR(gpu::practicalSplit(1.0f, 100.0f, 0.5f, 0.5f), 30.25f, 1e-4f);
    // Both ends are fixed whatever lambda.
    for (float lambda : {0.0f, 0.3f, 1.0f}) {
        EXPECT_NEAR(gpu::practicalSplit(0.1f, 200.0f, 0.0f, lambda), 0.1f, 1e-5f);
        EXPECT_NEAR(gpu::practicalSplit(0.1f, 200.0f, 1.0f, lambda), 200.0f, 1e-3f);
    }
}

TEST(CascadeSplits, SeedRatiosOrLambda) {
    CascadeSettings settings;  // the seed's 0.1, 0.25, 0.5
    auto splits = cascadeSplits(settings, 0.1f, 100.0f);
    EXPECT_FLOAT_EQ(splits[0], 10.0f);
    EXPECT_FLOAT_EQ(splits[1], 25.0f);
    EXPECT_FLOAT_EQ(splits[2], 50.0f);
    EXPECT_FLOAT_EQ(splits[3], 100.0f);
    settings.count = 2;  // the first ratio, then the shadow distance
    splits = cascadeSplits(settings, 0.1f, 100.0f);
    EXPECT_FLOAT_EQ(splits[0], 10.0f);
    EXPECT_FLOAT_EQ(splits[1], 100.0f);
    settings.count = 4;
    settings.lambda = 1.0f;  // logarithmic from 1 m to 256 m: 4, 16, 64, 256
    splits = cascadeSplits(settings, 1.0f, 256.0f);
    EXPECT_NEAR(splits[0], 4.0f, 1e-3f);
    EXPECT_NEAR(splits[1], 16.0f, 1e-3f);
    EXPECT_NEAR(splits[2], 64.0f, 1e-2f);
    EXPECT_FLOAT_EQ(splits[3], 256.0f);
}

TEST(CascadeSpheres, ByHand) {
    // No spread (a zero field of view): the slice [1, 3] is a segment; centre 2, radius 1.
    glm::vec2 sphere = gpu::sliceBoundingSphere(1.0f, 3.0f, 0.0f);
    EXPECT_FLOAT_EQ(sphere.x, 2.0f);
    EXPECT_FLOAT_EQ(sphere.y, 1.0f);
    // spread 1 (corners 1 x distance off the axis), slice [1, 3]: c = (1 + 3)(1 + 1) / 2 = 4 lies
    // beyond 3, so the sphere sits on the far face: centre 3, radius 3 x 1.
    sphere = gpu::sliceBoundingSphere(1.0f, 3.0f, 1.0f);
    EXPECT_FLOAT_EQ(sphere.x, 3.0f);
    EXPECT_FLOAT_EQ(sphere.y, 3.0f);
    // spread 0.25, slice [10, 20]: c = 30 x 1.25 / 2 = 18.75; r^2 = 1.25^2 + 400 x 0.25 = 101.5625;
    // the near corners: 8.75^2 + 100 x 0.25 = 101.5625, the same.
    sphere = gpu::sliceBoundingSphere(10.0f, 20.0f, 0.25f);
    EXPECT_FLOAT_EQ(sphere.x, 18.75f);
    EXPECT_NEAR(sphere.y, std::sqrt(101.5625f), 1e-5f);
}

TEST(CascadeSpheres, HoldEverySliceCorner) {
    std::mt19937 random(3);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (int i = 0; i < 1000; ++i) {
        const float d0 = 0.01f + 50.0f * unit(random);
        const float d1 = d0 * (1.01f + 5.0f * unit(random));
        const float spread = 3.0f * unit(random);
        const glm::vec2 sphere = gpu::sliceBoundingSphere(d0, d1, spread);
        for (const float d : {d0, d1}) {
            const float offAxis = d * std::sqrt(spread);
            const float distance = std::hypot(d - sphere.x, offAxis);
            ASSERT_LE(distance, sphere.y * (1.0f + 1e-5f)) << d0 << " " << d1 << " " << spread;
        }
        // Tight: the far corners lie on the sphere.
        ASSERT_NEAR(std::hypot(d1 - sphere.x, d1 * std::sqrt(spread)), sphere.y, sphere.y * 1e-5f);
    }
}

TEST(CascadeSnapping, ByHand) {
    const glm::vec2 snapped = gpu::snapToTexels(glm::vec2(0.26f, -0.74f), 0.5f);
    EXPECT_FLOAT_EQ(snapped.x, 0.5f);
    EXPECT_FLOAT_EQ(snapped.y, -0.5f);
    EXPECT_EQ(gpu::snapToTexels(snapped, 0.5f), snapped);  // idempotent
}

// The cascade field's plan with every cascade at 512 texels, camera moved by `move`.
struct SnapRun {
    ShadowPlan plan;
    std::array<glm::mat4, PUNCTUAL_MAX_CASCADES> projections{};
};

SnapRun planWithCamera(const glm::vec3& move, bool snap) {
    Scene scene = study::cascadeFieldScene();
    scene.camera.view = scene.camera.view * glm::translate(glm::mat4(1.0f), -move);  // the eye moves by +move
    const FrameLights lights = setupFrameLights(scene, scene.camera.view, scene.camera.projection(16.0f / 9.0f));
    ShadowSettings settings;
    settings.cascades.shadowDistance = 100.0f;  // fixed: the fitted one may change with the camera
    settings.cascades.snapToTexels = snap;
    SnapRun run;
    planCascades(run.plan, scene, lights, 1280, 720, settings);
    for (uint32_t i = 0; i < run.plan.cascades.count; ++i) {
        ShadowView& view = run.plan.views[run.plan.cascades.firstView + i];
        view.resolution = 512;
        finishCascadeView(view, run.plan.cascades, settings);
        run.projections[i] = view.gpu.viewProjection;
    }
    return run;
}

TEST(CascadeSnapping, ASubTexelCameraMoveLeavesTheProjectionOrMovesItByWholeTexels) {
    const SnapRun start = planWithCamera(glm::vec3(0.0f), true);
    ASSERT_EQ(start.plan.cascades.count, 4u);
    const glm::vec3 acrossX = start.plan.cascades.lightX;
    std::mt19937 random(9);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    size_t unchanged = 0;
    for (int k = 0; k < 40; ++k) {
        // Up to 0.4 of cascade 0's texel in any direction.
        const float texel0 = 2.0f * start.plan.cascades.spheres[0].w / 512.0f;
        const glm::vec3 move = 0.4f * texel0 * glm::normalize(glm::vec3(unit(random), unit(random), unit(random)));
        const SnapRun moved = planWithCamera(move, true);
        for (uint32_t i = 0; i < 4; ++i) {
            const float radius = start.plan.cascades.spheres[i].w;
            const float texel = 2.0f * radius / 512.0f;
            // Clip x = (p.X - cx) / r: the translation moved by whole texels (2 / 512 in clip units).
            for (int row = 0; row < 2; ++row) {
                const float shift = (moved.projections[i][3][row] - start.projections[i][3][row]) * radius / texel;
                ASSERT_NEAR(shift, std::round(shift), 2e-3f) << "cascade " << i << " move " << k;
                ASSERT_LE(std::abs(shift), 1.0f + 2e-3f) << "cascade " << i << " moved by more than a texel";
            }
            unchanged += moved.projections[i] == start.projections[i];
        }
    }
    // Most small moves cross no texel boundary at all; the rest shift by exactly one texel.
    EXPECT_GT(unchanged, 80u);

    // Without snapping every move shows.
    const float texel0 = 2.0f * start.plan.cascades.spheres[0].w / 512.0f;
    const SnapRun unsnapped0 = planWithCamera(glm::vec3(0.0f), false);
    const SnapRun unsnapped1 = planWithCamera(0.3f * texel0 * acrossX, false);
    EXPECT_NE(unsnapped0.projections[0], unsnapped1.projections[0]);
}

TEST(CascadeSelection, FirstSphereThatHoldsThePoint) {
    const glm::vec4 a(0.0f, 0.0f, 0.0f, 4.0f);   // radius 2
    const glm::vec4 b(0.0f, 0.0f, -5.0f, 36.0f);  // radius 6
    const glm::vec4 none(0.0f);
    EXPECT_EQ(gpu::cascadeOf(glm::vec3(0.0f, 0.0f, -1.0f), a, b, none, none, 2u), 0u);
    EXPECT_EQ(gpu::cascadeOf(glm::vec3(0.0f, 0.0f, -3.0f), a, b, none, none, 2u), 1u);  // outside a, inside b
    EXPECT_EQ(gpu::cascadeOf(glm::vec3(0.0f, 0.0f, -20.0f), a, b, none, none, 2u), 2u);  // none: count
    EXPECT_EQ(gpu::cascadeOf(glm::vec3(0.0f, 0.0f, -3.0f), a, b, none, none, 1u), 1u);  // only a counts
}

TEST(CascadeFades, TheSeedsRamps) {
    // Shadow distance 100 m fading over its last 10%: full to 90 m, half at 95 m, none at 100 m.
    EXPECT_FLOAT_EQ(gpu::fadedShadowStrength(80.0f, 1.0f / 100.0f, 1.0f / 0.1f), 1.0f);
    EXPECT_NEAR(gpu::fadedShadowStrength(95.0f, 1.0f / 100.0f, 1.0f / 0.1f), 0.5f, 1e-5f);
    EXPECT_FLOAT_EQ(gpu::fadedShadowStrength(100.0f, 1.0f / 100.0f, 1.0f / 0.1f), 0.0f);
    // Cascade fade 0.1 over a radius of 10 (squared distances): full inside 9, none at 10.
    const float scale = gpu::cascadeFadeScale(0.1f);  // 1 / (1 - 0.81)
    EXPECT_NEAR(scale, 1.0f / 0.19f, 1e-4f);
    EXPECT_NEAR(gpu::fadedShadowStrength(81.0f, 1.0f / 100.0f, scale), 1.0f, 1e-5f);
    EXPECT_NEAR(gpu::fadedShadowStrength(100.0f, 1.0f / 100.0f, scale), 0.0f, 1e-5f);
}

TEST(CascadeFades, DitherNoiseIsAFixedThresholdInTheUnitInterval) {
    float sum = 0.0f;
    for (int y = 0; y < 64; ++y) {
        for (int x = 0; x < 64; ++x) {
            const float n = gpu::interleavedGradientNoise(glm::vec2(float(x) + 0.5f, float(y) + 0.5f));
            ASSERT_GE(n, 0.0f);
            ASSERT_LT(n, 1.0f);
            ASSERT_EQ(n, gpu::interleavedGradientNoise(glm::vec2(float(x) + 0.5f, float(y) + 0.5f)));
            sum += n;
        }
    }
    EXPECT_NEAR(sum / 4096.0f, 0.5f, 0.05f);  // about uniform
}

}  // namespace
}  // namespace punctual
