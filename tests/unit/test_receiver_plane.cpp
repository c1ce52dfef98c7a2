// Known answers for receiverPlaneDepthSlope (shaders/shared/shadows.h): the depth slope across a
// shadow view of the receiver's tangent plane, which the receiver-plane compares use to give each
// texel of a filter the receiver's own depth under it.
#include <gtest/gtest.h>

#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include "shadows.h"

namespace punctual {
namespace {

using gpu::receiverPlaneDepthSlope;

// A spot light at the origin looking down -Z, 90 degrees, near 1, far 10: Vulkan depth 0..1.
glm::mat4 spotViewProjection() {
    const glm::mat4 view = glm::lookAtRH(glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, -1.0f), glm::vec3(0.0f, 1.0f, 0.0f));
    return glm::perspectiveRH_ZO(glm::radians(90.0f), 1.0f, 1.0f, 10.0f) * view;
}

// (u, v, depth) of a world point in the view.
glm::vec3 project(const glm::mat4& viewProjection, glm::vec3 p) {
    const glm::vec4 clip = viewProjection * glm::vec4(p, 1.0f);
    const glm::vec3 ndc = glm::vec3(clip) / clip.w;
    return glm::vec3(ndc.x * 0.5f + 0.5f, ndc.y * 0.5f + 0.5f, ndc.z);
}

TEST(ReceiverPlane, PlaneFacingTheLightHasNoSlope) {
    // z = -5 faces the light square on: every point of it has view depth 5, so one NDC depth.
    const glm::vec2 slope = receiverPlaneDepthSlope(spotViewProjection(), glm::vec3(1.0f, -2.0f, -5.0f), glm::vec3(0.0f, 0.0f, 1.0f));
    EXPECT_NEAR(slope.x, 0.0f, 1e-6f);
    EXPECT_NEAR(slope.y, 0.0f, 1e-6f);
}

TEST(ReceiverPlane, TiltedPlaneByHand) {
    // The plane z = -5 - x (normal (1, 0, 1) / sqrt 2) through (0, 0, -5). Along it, view depth
    // d = 5 + x, and u = x / d / 2 + 1/2 (90 degrees: x_ndc = x / d). So x = d (2u - 1), and
    // d = 5 + d (2u - 1) gives d = 5 / (2 - 2u): d = 5 at u = 1/2, dd/du = 10 / (2 - 2u)^2 = 10.
    // NDC depth z = f (d - n) / (d (f - n)) = (10 / 9) (1 - 1 / d), dz/dd = (10 / 9) / d^2, so
    // dz/du = (10 / 9) / 25 x 10 = 4 / 9 there, and nothing along v (the plane is level in y).
    const glm::vec3 normal = glm::normalize(glm::vec3(1.0f, 0.0f, 1.0f));
    const glm::vec2 slope = receiverPlaneDepthSlope(spotViewProjection(), glm::vec3(0.0f, 0.0f, -5.0f), normal);
    EXPECT_NEAR(slope.x, 4.0f / 9.0f, 1e-5f);
    EXPECT_NEAR(slope.y, 0.0f, 1e-6f);
}

TEST(ReceiverPlane, DepthIsExactlyAffineAcrossTheView) {
    // Perspective keeps planes planes: the depth of any point of the plane, however far from the
    // receiver, is the receiver's depth plus the slope times the UV step. Random planes and points.
    const glm::mat4 viewProjection = spotViewProjection();
    std::mt19937 random(5);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    size_t checked = 0;
    for (int plane = 0; plane < 200; ++plane) {
        const glm::vec3 receiver(2.0f * unit(random), 2.0f * unit(random), -5.0f + 2.0f * unit(random));
        glm::vec3 normal = glm::normalize(glm::vec3(unit(random), unit(random), 1.0f + unit(random)));
        if (glm::dot(normal, -receiver) <= 0.1f * glm::length(receiver)) continue;  // faces the light
        const glm::vec2 slope = receiverPlaneDepthSlope(viewProjection, receiver, normal);
        const glm::vec3 at = project(viewProjection, receiver);
        const glm::vec3 s = glm::normalize(glm::cross(normal, glm::vec3(0.3f, 1.0f, 0.2f)));
        const glm::vec3 t = glm::cross(normal, s);
        for (int k = 0; k < 10; ++k) {
            const glm::vec3 other = receiver + 0.5f * unit(random) * s + 0.5f * unit(random) * t;
            const glm::vec3 there = project(viewProjection, other);
            const float predicted = at.z + glm::dot(slope, glm::vec2(there) - glm::vec2(at));
            ASSERT_NEAR(predicted, there.z, 2e-5f) << "plane " << plane << " point " << k;
            ++checked;
        }
    }
    EXPECT_GT(checked, 1000u);
}

TEST(ReceiverPlane, EdgeOnPlaneHasNoSlope) {
    // The plane x = 0 holds the light: every one of its points lies on the line u = 1/2, so depth
    // has no slope across the view to speak of; the formula returns 0 rather than infinity.
    const glm::vec2 slope = receiverPlaneDepthSlope(spotViewProjection(), glm::vec3(0.0f, 1.0f, -5.0f), glm::vec3(1.0f, 0.0f, 0.0f));
    EXPECT_EQ(slope.x, 0.0f);
    EXPECT_EQ(slope.y, 0.0f);
}

}  // namespace
}  // namespace punctual
