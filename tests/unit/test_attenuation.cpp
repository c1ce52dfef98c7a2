// Known answers for the shared shading math (shaders/shared/shading.h), computed by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <iterator>

#include "shading.h"

namespace punctual {
namespace {

using gpu::distanceAttenuation;
using gpu::punctualAttenuation;
using gpu::spotAngleScale;
using gpu::spotAttenuation;

constexpr float kPi = 3.14159265358979f;

// ---- distance attenuation: window (1 - (d^2/r^2)^2)^2 / d^2 --------------------------------

TEST(Attenuation, DistanceAtHalfRange) {
    // r = 4, d = 2: d^2/r^2 = 1/4, squared 1/16, window (1 - 1/16)^2 = (15/16)^2 = 225/256
    // = 0.87890625; divided by d^2 = 4 gives 0.2197265625. Every step is exact in binary.
    EXPECT_EQ(distanceAttenuation(4.0f, 1.0f / 16.0f), 0.87890625f / 4.0f);
}

TEST(Attenuation, DistanceExactlyAtRangeIsZero) {
    // d = r = 4: ratio 1, window 1 - 1 = 0.
    EXPECT_EQ(distanceAttenuation(16.0f, 1.0f / 16.0f), 0.0f);
}

TEST(Attenuation, DistanceBeyondRangeIsZero) {
    // d = 5 > r = 4: 1 - (25/16)^2 < 0, clamped to 0, so exactly 0 (not a tiny negative).
    EXPECT_EQ(distanceAttenuation(25.0f, 1.0f / 16.0f), 0.0f);
    EXPECT_EQ(distanceAttenuation(1e6f, 1.0f / 16.0f), 0.0f);
}

TEST(Attenuation, DistanceNearLightIsInverseSquare) {
    // r = 10, d = 0.1 = 0.01 r: d^2/r^2 = 1e-4, window (1 - 1e-8)^2 ~ 1, so att ~ 1/d^2 = 100.
    EXPECT_NEAR(distanceAttenuation(0.01f, 0.01f), 100.0f, 1e-3f);
    // d^2 below 1e-4 is clamped: att = 1 / 1e-4 at most.
    EXPECT_FLOAT_EQ(distanceAttenuation(0.0f, 1.0f), 1e4f);
}

// ---- spot angle attenuation: saturate(cos(theta) k - cosOuter k)^2 ---------------------------
// cosInner = 0.75, cosOuter = 0.25: k = 1 / 0.5 = 2, offset = -0.5. The light shines down -Y;
// a surface point seen at angle theta from the axis has -toLight = (sin theta, -cos theta, 0).

float spotAt(float cosTheta) {
    const float k = spotAngleScale(0.75f, 0.25f);
    const glm::vec3 shine(0.0f, -1.0f, 0.0f);
    const float sinTheta = std::sqrt(1.0f - cosTheta * cosTheta);
    const glm::vec3 toLight(-sinTheta, cosTheta, 0.0f);
    return spotAttenuation(shine, toLight, k, -0.25f * k);
}

TEST(Attenuation, SpotScaleIsInverseConeDifference) {
    EXPECT_EQ(spotAngleScale(0.75f, 0.25f), 2.0f);
    EXPECT_EQ(spotAngleScale(0.5f, 0.5f), 1e4f);  // degenerate cones clamp to 1 / 1e-4
}

TEST(Attenuation, SpotAtInnerEdgeIsOne) { EXPECT_EQ(spotAt(0.75f), 1.0f); }          // 0.75*2 - 0.5 = 1
TEST(Attenuation, SpotAtOuterEdgeIsZero) { EXPECT_EQ(spotAt(0.25f), 0.0f); }         // 0.25*2 - 0.5 = 0
TEST(Attenuation, SpotHalfwayInCosineIsQuarter) { EXPECT_EQ(spotAt(0.5f), 0.25f); }  // (0.5*2 - 0.5)^2
TEST(Attenuation, SpotOnAxisIsOne) { EXPECT_EQ(spotAt(1.0f), 1.0f); }                // saturate(1.5) = 1
TEST(Attenuation, SpotOutsideOuterConeIsZero) { EXPECT_EQ(spotAt(0.1f), 0.0f); }     // saturate(-0.3) = 0
TEST(Attenuation, SpotBehindLightIsZero) { EXPECT_EQ(spotAt(-1.0f), 0.0f); }         // saturate(-2.5) = 0

TEST(Attenuation, PointLightAngleFactorIsExactlyOne) {
    // Points pass scale 0 and offset 1: saturate(x * 0 + 1)^2 = 1 in every direction.
    for (const glm::vec3& toLight : {glm::vec3(0, 1, 0), glm::vec3(0, -1, 0), glm::vec3(0.6f, 0, 0.8f)})
        EXPECT_EQ(spotAttenuation(glm::vec3(0.0f, 0.0f, -1.0f), toLight, 0.0f, 1.0f), 1.0f);
}

// ---- both combined -----------------------------------------------------------------------------

gpu::GpuPunctualLight downwardSpot(glm::vec3 position, float range, float cosInner, float cosOuter) {
    const float k = spotAngleScale(cosInner, cosOuter);
    gpu::GpuPunctualLight light{};
    light.positionInvRangeSq = glm::vec4(position, 1.0f / (range * range));
    light.radiantColor = glm::vec4(1.0f, 1.0f, 1.0f, range);
    light.directionAngleScale = glm::vec4(0.0f, -1.0f, 0.0f, k);
    light.angleOffsetShadow = glm::vec4(-cosOuter * k, -1.0f, 0.0f, 0.0f);
    return light;
}

TEST(Attenuation, PunctualOnAxisIsDistanceOnly) {
    // Light 4 m above the point, range 16: d^2/r^2 = 16/256 = 1/16, window (1 - 1/256)^2 =
    // (255/256)^2 = 65025/65536; / 16 = 65025/1048576. On the axis the angle factor is 1.
    const auto light = downwardSpot({0, 4, 0}, 16.0f, 0.75f, 0.25f);
    EXPECT_FLOAT_EQ(punctualAttenuation(light, glm::vec3(0.0f)), 65025.0f / 1048576.0f);
}

TEST(Attenuation, PunctualOffAxisMultipliesBoth) {
    // Light 2 m up; the point 2 sqrt(3) m to the side: d = 4 m, cos(theta) = 2/4 = 0.5, so the angle
    // factor is 0.25 (halfway in cosine), the distance factor with r = 8 is
    // (1 - (16/64)^2)^2 / 16 = (15/16)^2 / 16 = 0.87890625 / 16.
    const auto light = downwardSpot({0, 2, 0}, 8.0f, 0.75f, 0.25f);
    const glm::vec3 point(2.0f * std::sqrt(3.0f), 0.0f, 0.0f);
    EXPECT_NEAR(punctualAttenuation(light, point), 0.25f * 0.87890625f / 16.0f, 1e-6f);
}

TEST(Attenuation, PunctualPointLightAndBeyondRange) {
    auto light = downwardSpot({0, 2, 0}, 8.0f, 0.75f, 0.25f);
    light.directionAngleScale.w = 0.0f;  // a point light: scale 0, offset 1
    light.angleOffsetShadow.x = 1.0f;
    // 2 m straight up and 2 m sideways at the same height (a spot would give 0 there): d = 2 m.
    const float expected = (1.0f - (4.0f / 64.0f) * (4.0f / 64.0f)) * (1.0f - (4.0f / 64.0f) * (4.0f / 64.0f)) / 4.0f;
    EXPECT_FLOAT_EQ(punctualAttenuation(light, glm::vec3(0.0f)), expected);
    EXPECT_FLOAT_EQ(punctualAttenuation(light, glm::vec3(2.0f, 2.0f, 0.0f)), expected);
    EXPECT_EQ(punctualAttenuation(light, glm::vec3(0.0f, 2.0f, 8.0f)), 0.0f);   // exactly at the range
    EXPECT_EQ(punctualAttenuation(light, glm::vec3(0.0f, -10.0f, 0.0f)), 0.0f);  // beyond it
}

// ---- BRDF sanity ---------------------------------------------------------------------------------

TEST(Shading, WhiteLambertianHeadOnReflectsOneOverPi) {
    // White dielectric, roughness 1 (alpha 1), lit and viewed along the normal with E = 1.
    // Diffuse: 1/pi. Specular: D = alpha^2 / (pi ((a2 - 1) + 1)^2) = 1/pi; V = 0.5 / (1 + 1) = 0.25;
    // F = f0 = 0.04 at normal incidence. Total (1 + 0.25 * 0.04) / pi = 1.01 / pi.
    const glm::vec3 n(0.0f, 1.0f, 0.0f);
    const gpu::Surface surface = gpu::makeSurface(glm::vec3(0.0f), n, n, glm::vec3(1.0f), 0.0f, 1.0f);
    const glm::vec3 radiance = gpu::shadeBrdf(surface, n, glm::vec3(1.0f));
    for (int c = 0; c < 3; ++c) {
        EXPECT_GE(radiance[c], 1.0f / kPi);
        EXPECT_LE(radiance[c], 1.0f / kPi + 0.01f);  // specular of a rough dielectric stays small
        EXPECT_NEAR(radiance[c], 1.01f / kPi, 1e-5f);
    }
}

TEST(Shading, LightBelowHorizonGivesNothing) {
    const glm::vec3 n(0.0f, 1.0f, 0.0f);
    const gpu::Surface surface = gpu::makeSurface(glm::vec3(0.0f), n, n, glm::vec3(1.0f), 0.0f, 0.5f);
    EXPECT_EQ(gpu::shadeBrdf(surface, glm::vec3(0.0f, -1.0f, 0.0f), glm::vec3(1.0f)), glm::vec3(0.0f));
}

TEST(Shading, FacesLightExactlyWhereTheBrdfCanBeNonZero) {
    // The forward shader skips a shadow lookup where facesLight is false, which must be exactly
    // where shadeBrdf gives 0 whatever the radiance: N.L <= 0, the horizon (N.L = 0) included.
    const glm::vec3 n(0.0f, 1.0f, 0.0f);
    const gpu::Surface surface = gpu::makeSurface(glm::vec3(0.0f), n, n, glm::vec3(1.0f), 0.0f, 0.5f);
    const glm::vec3 directions[] = {{0.0f, 1.0f, 0.0f},  {0.6f, 0.8f, 0.0f},   {1.0f, 1e-6f, 0.0f},
                                    {1.0f, 0.0f, 0.0f},  {0.0f, 0.0f, -1.0f},  {1.0f, -1e-6f, 0.0f},
                                    {0.6f, -0.8f, 0.0f}, {0.0f, -1.0f, 0.0f}};
    const bool expected[] = {true, true, true, false, false, false, false, false};
    for (size_t i = 0; i < std::size(directions); ++i) {
        EXPECT_EQ(gpu::facesLight(surface, directions[i]), expected[i]) << i;
        const glm::vec3 radiance = gpu::shadeBrdf(surface, directions[i], glm::vec3(1e6f));
        EXPECT_EQ(radiance != glm::vec3(0.0f), expected[i]) << i;
    }
}

TEST(Shading, LambertCosineLaw) {
    // The diffuse response scales with cos(incidence): 60 degrees gives half of head-on. The rough
    // dielectric's specular (f0 = 0.04, about 1% here) shifts the ratio by ~0.002 only.
    const glm::vec3 n(0.0f, 1.0f, 0.0f);
    const gpu::Surface surface = gpu::makeSurface(glm::vec3(0.0f), n, n, glm::vec3(1.0f), 0.0f, 1.0f);
    const glm::vec3 at60(std::sqrt(3.0f) * 0.5f, 0.5f, 0.0f);
    const float ratio = gpu::shadeBrdf(surface, at60, glm::vec3(1.0f)).r / gpu::shadeBrdf(surface, n, glm::vec3(1.0f)).r;
    EXPECT_NEAR(ratio, 0.5f, 0.01f);
}

}  // namespace
}  // namespace punctual
