// Light setup for one frame: frustum culling, ranking under the caps, scene order, packing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include <glm/gtc/matrix_transform.hpp>

#include "light_test_scenes.h"
#include "lights/light_setup.h"
#include "scene/light_generator.h"
#include "shading.h"

namespace punctual {
namespace {

using unit_testing::kDegree;
using unit_testing::pointLight;
using unit_testing::spotLight;

// A camera at the origin looking down -Z, 60 degree vertical field of view, 16:9.
struct TestView {
    glm::mat4 view = glm::lookAtRH(glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, -1.0f), glm::vec3(0.0f, 1.0f, 0.0f));
    glm::mat4 projection;
    TestView() {
        Camera camera;
        camera.yfov = 60.0f * kDegree;
        camera.znear = 0.1f;
        camera.zfar = 100.0f;
        projection = camera.projection(16.0f / 9.0f);
    }
};

FrameLights setup(const std::vector<Light>& lights) {
    Scene scene;
    scene.lights = lights;
    const TestView view;
    return setupFrameLights(scene, view.view, view.projection);
}

// ---- culling -----------------------------------------------------------------------------------

TEST(LightSetup, LightBehindCameraIsCulled) {
    const FrameLights frame = setup({pointLight({0, 0, 10}, 2.0f), spotLight({0, 0, 10}, {0, 0, 1}, 2.0f, 30, 20)});
    EXPECT_EQ(frame.culledByFrustum, 2u);
    EXPECT_TRUE(frame.packed.empty());
    EXPECT_EQ(frame.spotCount + frame.pointCount, 0u);
}

TEST(LightSetup, LightInFrontIsKept) {
    const FrameLights frame = setup({pointLight({0, 0, -10}, 2.0f)});
    EXPECT_EQ(frame.culledByFrustum, 0u);
    ASSERT_EQ(frame.pointCount, 1u);
    EXPECT_EQ(frame.sceneLightIndex[0], 0u);
}

TEST(LightSetup, SphereStraddlingNearPlaneIsKept) {
    // Centre 0.3 m behind the eye, radius 0.5: it pokes through the near plane (z = -0.1).
    const FrameLights frame = setup({pointLight({0, 0, 0.3f}, 0.5f)});
    EXPECT_EQ(frame.culledByFrustum, 0u);
    EXPECT_EQ(frame.pointCount, 1u);
}

TEST(LightSetup, SphereBetweenEyeAndNearPlaneIsCulled) {
    // z in [-0.09, -0.01]: wholly in front of the eye but before the near plane at z = -0.1.
    const FrameLights frame = setup({pointLight({0, 0, -0.05f}, 0.04f)});
    EXPECT_EQ(frame.culledByFrustum, 1u);
}

TEST(LightSetup, SideAndFarPlanesCull) {
    // Far plane at z = -100; the horizontal half-angle at 16:9 is atan(tan(30 deg) 16/9) = 45.7 deg.
    const FrameLights frame = setup({pointLight({0, 0, -103}, 2.0f), pointLight({0, 0, -101}, 2.0f),
                                     pointLight({20, 0, -10}, 2.0f), pointLight({0, 20, -10}, 2.0f)});
    EXPECT_EQ(frame.culledByFrustum, 3u);
    ASSERT_EQ(frame.pointCount, 1u);
    EXPECT_EQ(frame.sceneLightIndex[0], 1u);
}

TEST(LightSetup, SpotPointingAwayIsCulledByItsCone) {
    // 1 m behind the eye, shining backwards (+Z), range 5, outer 30 deg: the cone's sphere has
    // centre z = 1 + 5/(2 cos 30) = 3.89 and radius 2.89, all behind the eye. A point light with the
    // same position and range reaches z = -4 and is kept.
    const FrameLights frame = setup({spotLight({0, 0, 1}, {0, 0, 1}, 5.0f, 30, 20), pointLight({0, 0, 1}, 5.0f)});
    EXPECT_EQ(frame.culledByFrustum, 1u);
    EXPECT_EQ(frame.spotCount, 0u);
    EXPECT_EQ(frame.pointCount, 1u);
}

TEST(LightSetup, SpotBehindCameraShiningIntoViewIsKept) {
    const FrameLights frame = setup({spotLight({0, 0, 2}, {0, 0, -1}, 5.0f, 30, 20)});
    EXPECT_EQ(frame.culledByFrustum, 0u);
    EXPECT_EQ(frame.spotCount, 1u);
}

TEST(LightSetup, FrustumAgreesWithClipSpace) {
    // A point (radius 0 sphere) is inside exactly when its clip coordinates are in Vulkan's volume.
    const TestView view;
    const glm::mat4 viewProjection = view.projection * view.view;
    const Frustum frustum = extractFrustum(viewProjection);
    PortableRandom random(5);
    int inside = 0;
    for (int i = 0; i < 4000; ++i) {
        const glm::vec3 p(random.uniform(-80, 80), random.uniform(-50, 50), random.uniform(-105, 5));
        const glm::vec4 clip = viewProjection * glm::vec4(p, 1.0f);
        const float slack = 1e-3f * std::abs(clip.w) + 1e-4f;  // skip points on a boundary
        const float margin = std::min({clip.w - std::abs(clip.x), clip.w - std::abs(clip.y), clip.z, clip.w - clip.z});
        if (std::abs(margin) < slack) continue;
        const bool expected = margin > 0.0f && clip.w > 0.0f;
        EXPECT_EQ(frustum.intersectsSphere(p, 0.0f), expected) << p.x << " " << p.y << " " << p.z;
        inside += expected ? 1 : 0;
    }
    EXPECT_GT(inside, 100);
}

// ---- spot bounding sphere ----------------------------------------------------------------------

void expectSphereHoldsCone(const Light& spot) {
    const BoundingSphere sphere = lightBoundingSphere(spot);
    const glm::vec3 axis = glm::normalize(spot.direction);
    const glm::vec3 side = glm::normalize(glm::cross(axis, glm::vec3(0.3f, 1.0f, 0.1f)));
    const float tolerance = 1e-4f * spot.range;
    EXPECT_LE(glm::distance(sphere.center, spot.position), sphere.radius + tolerance);  // apex
    // The rim and the cap: points at distance `range` and angle phi <= outer from the axis.
    for (int step = 0; step <= 16; ++step) {
        const float phi = spot.outerConeAngle * static_cast<float>(step) / 16.0f;
        const glm::vec3 p = spot.position + (axis * std::cos(phi) + side * std::sin(phi)) * spot.range;
        EXPECT_LE(glm::distance(sphere.center, p), sphere.radius + tolerance) << "phi " << phi;
    }
}

TEST(LightSetup, SpotSphereNarrowCone) {
    // theta = 30 deg, r = 2: centre r / (2 cos 30) = 1.1547 along the axis, radius the same.
    const Light spot = spotLight({1, 2, 3}, {0, -1, 0}, 2.0f, 30, 10);
    const BoundingSphere sphere = lightBoundingSphere(spot);
    EXPECT_NEAR(sphere.radius, 1.1547005f, 1e-5f);
    EXPECT_NEAR(glm::distance(sphere.center, glm::vec3(1.0f, 2.0f - 1.1547005f, 3.0f)), 0.0f, 1e-5f);
    expectSphereHoldsCone(spot);
}

TEST(LightSetup, SpotSphereWideCone) {
    // theta = 60 deg, r = 2: centre r cos 60 = 1 along the axis, radius r sin 60 = 1.7320508.
    const Light spot = spotLight({0, 0, 0}, {1, 0, 0}, 2.0f, 60, 30);
    const BoundingSphere sphere = lightBoundingSphere(spot);
    EXPECT_NEAR(sphere.radius, 1.7320508f, 1e-5f);
    EXPECT_NEAR(glm::distance(sphere.center, glm::vec3(1.0f, 0.0f, 0.0f)), 0.0f, 1e-5f);
    expectSphereHoldsCone(spot);
}

TEST(LightSetup, SpotSphereContinuousAt45Degrees) {
    const BoundingSphere below = lightBoundingSphere(spotLight({0, 0, 0}, {0, 0, -1}, 3.0f, 44.999f, 10));
    const BoundingSphere above = lightBoundingSphere(spotLight({0, 0, 0}, {0, 0, -1}, 3.0f, 45.001f, 10));
    EXPECT_NEAR(below.radius, above.radius, 1e-3f);
    EXPECT_NEAR(below.center.z, above.center.z, 1e-3f);
    for (float degrees : {5.0f, 25.0f, 44.0f, 46.0f, 70.0f, 90.0f})
        expectSphereHoldsCone(spotLight({0, 1, 0}, {0.3f, -1, 0.2f}, 3.0f, degrees, 1.0f));
}

// ---- ranking and caps --------------------------------------------------------------------------

// The documented ranking, recomputed independently.
float expectedImportance(const Light& light, const glm::vec3& camera) {
    const float peak = light.intensity * std::max({light.color.r, light.color.g, light.color.b});
    float fraction = 1.0f;
    glm::vec3 center = light.position;
    float radius = light.range;
    if (light.type == LightType::Spot) {
        const float theta = light.outerConeAngle;
        fraction = (1.0f - std::cos(theta)) / 2.0f;
        const glm::vec3 axis = glm::normalize(light.direction);
        if (std::cos(theta) < std::sqrt(0.5f)) {
            center += axis * (light.range * std::cos(theta));
            radius = light.range * std::sin(theta);
        } else {
            radius = light.range / (2.0f * std::cos(theta));
            center += axis * radius;
        }
    }
    const float ratio = radius / std::max(glm::distance(camera, center), radius);
    return peak * fraction * ratio * ratio;
}

// 100 spots and 40 points, all in view, interleaved in scene order (every 7th light a point,
// then the remaining points at the end).
std::vector<Light> manyLightsInView() {
    PortableRandom random(42);
    std::vector<Light> lights;
    int spots = 0, points = 0;
    for (int i = 0; spots < 100 || points < 40; ++i) {
        const glm::vec3 position(random.uniform(-3, 3), random.uniform(-2, 2), random.uniform(-30, -5));
        const bool makePoint = points < 40 && (i % 7 == 3 || spots == 100);
        Light light = makePoint ? pointLight(position, random.uniform(0.5f, 4.0f))
                                : spotLight(position, {random.uniform(-1, 1), -1, random.uniform(-1, 1)},
                                            random.uniform(0.5f, 4.0f), random.uniform(20, 70), 10);
        light.intensity = random.uniform(1.0f, 100.0f);
        light.color = glm::vec3(random.uniform(0.2f, 1.0f), random.uniform(0.2f, 1.0f), random.uniform(0.2f, 1.0f));
        (makePoint ? points : spots)++;
        lights.push_back(light);
    }
    return lights;
}

TEST(LightSetup, ImportanceMatchesDocumentedFormula) {
    for (const Light& light : manyLightsInView()) {
        const float expected = expectedImportance(light, glm::vec3(0.0f));
        EXPECT_NEAR(lightImportance(light, glm::vec3(0.0f)), expected, 1e-4f * expected);
    }
    // Camera inside the sphere: coverage saturates at 1.
    const Light near = pointLight({0, 0, -1}, 5.0f, 20.0f);
    EXPECT_FLOAT_EQ(lightImportance(near, glm::vec3(0.0f)), 20.0f);
}

TEST(LightSetup, CapsKeepTheMostImportantInSceneOrder) {
    Scene scene;
    scene.lights = manyLightsInView();
    const TestView view;
    const FrameLights frame = setupFrameLights(scene, view.view, view.projection);

    EXPECT_EQ(frame.culledByFrustum, 0u);
    ASSERT_EQ(frame.spotCount, 64u);
    ASSERT_EQ(frame.pointCount, 32u);
    ASSERT_EQ(frame.packed.size(), 96u);
    ASSERT_EQ(frame.sceneLightIndex.size(), 96u);
    EXPECT_EQ(frame.droppedByCap, (100u - 64u) + (40u - 32u));

    // Spots first, then points, each block strictly ascending in scene index.
    for (uint32_t i = 0; i < 96; ++i) {
        const LightType expectedType = i < 64 ? LightType::Spot : LightType::Point;
        EXPECT_EQ(scene.lights[frame.sceneLightIndex[i]].type, expectedType) << i;
        if (i != 0 && i != 64) {
            EXPECT_LT(frame.sceneLightIndex[i - 1], frame.sceneLightIndex[i]);
        }
    }

    // Every kept light is at least as important as every dropped one of its type.
    const std::set<uint32_t> kept(frame.sceneLightIndex.begin(), frame.sceneLightIndex.end());
    for (const LightType type : {LightType::Spot, LightType::Point}) {
        float minKept = 1e30f, maxDropped = -1.0f;
        for (uint32_t i = 0; i < scene.lights.size(); ++i) {
            if (scene.lights[i].type != type) continue;
            const float importance = lightImportance(scene.lights[i], glm::vec3(0.0f));
            if (kept.count(i)) minKept = std::min(minKept, importance);
            else maxDropped = std::max(maxDropped, importance);
        }
        EXPECT_GT(maxDropped, 0.0f);
        EXPECT_GE(minKept, maxDropped);
    }

    // Each packed light is its scene light packed.
    for (uint32_t i = 0; i < 96; ++i) {
        const gpu::GpuPunctualLight expected = packPunctualLight(scene.lights[frame.sceneLightIndex[i]]);
        EXPECT_EQ(frame.packed[i].positionInvRangeSq, expected.positionInvRangeSq);
        EXPECT_EQ(frame.packed[i].radiantColor, expected.radiantColor);
    }
}

TEST(LightSetup, TiesGoToTheLowerSceneIndex) {
    // 66 identical spots: the first 64 in scene order win.
    std::vector<Light> lights(66, spotLight({0, 0, -10}, {0, 0, -1}, 3.0f, 30, 20));
    const FrameLights frame = setup(lights);
    ASSERT_EQ(frame.spotCount, 64u);
    for (uint32_t i = 0; i < 64; ++i) EXPECT_EQ(frame.sceneLightIndex[i], i);
    EXPECT_EQ(frame.droppedByCap, 2u);
}

TEST(LightSetup, AddingACulledLightDoesNotReorder) {
    std::vector<Light> lights = {pointLight({0, 0, -5}, 2), spotLight({1, 0, -6}, {0, 0, -1}, 3, 30, 20),
                                 pointLight({-1, 0, -7}, 2)};
    const FrameLights before = setup(lights);
    lights.insert(lights.begin() + 1, pointLight({0, 0, 50}, 1));  // behind the camera
    const FrameLights after = setup(lights);
    ASSERT_EQ(before.packed.size(), after.packed.size());
    for (size_t i = 0; i < before.packed.size(); ++i)
        EXPECT_EQ(before.packed[i].positionInvRangeSq, after.packed[i].positionInvRangeSq);
}

// ---- packing -----------------------------------------------------------------------------------

TEST(LightSetup, SpotPackingMatchesFormulas) {
    Light spot = spotLight({1, 2, -5}, {0, 0, -2}, 4.0f, 45, 30, 8.0f);  // non-unit direction on purpose
    spot.color = glm::vec3(1.0f, 0.5f, 0.25f);
    const FrameLights frame = setup({spot});
    ASSERT_EQ(frame.spotCount, 1u);
    const gpu::GpuPunctualLight& packed = frame.packed[0];
    const float cosOuter = std::cos(45.0f * kDegree), cosInner = std::cos(30.0f * kDegree);
    const float k = 1.0f / (cosInner - cosOuter);  // 6.2925...
    EXPECT_EQ(packed.positionInvRangeSq, glm::vec4(1.0f, 2.0f, -5.0f, 1.0f / 16.0f));
    EXPECT_EQ(packed.radiantColor, glm::vec4(8.0f, 4.0f, 2.0f, 4.0f));
    EXPECT_EQ(glm::vec3(packed.directionAngleScale), glm::vec3(0.0f, 0.0f, -1.0f));
    EXPECT_NEAR(packed.directionAngleScale.w, k, 1e-4f);
    EXPECT_NEAR(packed.angleOffsetShadow.x, -cosOuter * k, 1e-4f);
    EXPECT_EQ(packed.angleOffsetShadow.y, -1.0f);  // no shadow slot yet
    EXPECT_FLOAT_EQ(packed.angleOffsetShadow.z, cosOuter);  // for the culling cone test
    EXPECT_EQ(packed.angleOffsetShadow.w, 0.0f);
    // The packed light reproduces the cone: 1 on the inner edge, 0 on the outer.
    const glm::vec3 apex(1.0f, 2.0f, -5.0f);
    auto attenuationAt = [&](float degrees) {
        const glm::vec3 toPoint(std::sin(degrees * kDegree), 0.0f, -std::cos(degrees * kDegree));
        return gpu::spotAttenuation(glm::vec3(packed.directionAngleScale), -toPoint, packed.directionAngleScale.w,
                                    packed.angleOffsetShadow.x);
    };
    EXPECT_NEAR(attenuationAt(29.9f), 1.0f, 1e-5f);
    EXPECT_EQ(attenuationAt(45.1f), 0.0f);
    EXPECT_GT(gpu::punctualAttenuation(packed, apex + glm::vec3(0.0f, 0.0f, -3.9f)), 0.0f);
    EXPECT_EQ(gpu::punctualAttenuation(packed, apex + glm::vec3(0.0f, 0.0f, -4.0f)), 0.0f);
}

TEST(LightSetup, PointPackingMatchesFormulas) {
    Light point = pointLight({3, -1, -8}, 0.001f, 5.0f);  // tiny range: 1/r^2 clamps to 1/1e-4
    point.color = glm::vec3(0.5f, 1.0f, 0.0f);
    const FrameLights frame = setup({point});
    ASSERT_EQ(frame.pointCount, 1u);
    const gpu::GpuPunctualLight& packed = frame.packed[0];
    EXPECT_EQ(packed.positionInvRangeSq, glm::vec4(3.0f, -1.0f, -8.0f, 1.0f / 1e-4f));
    EXPECT_EQ(packed.radiantColor, glm::vec4(2.5f, 5.0f, 0.0f, 0.001f));
    EXPECT_EQ(packed.directionAngleScale.w, 0.0f);
    EXPECT_EQ(packed.angleOffsetShadow, glm::vec4(1.0f, -1.0f, -1.0f, 0.0f));
}

TEST(LightSetup, NoDirectionalLight) {
    const FrameLights frame = setup({pointLight({0, 0, -5}, 2)});
    EXPECT_EQ(frame.directionalCount, 0u);
    EXPECT_EQ(frame.sun.directionToLight.w, 0.0f);
}

TEST(LightSetup, DirectionalPackingKeepsTheFirst) {
    Light sun;
    sun.type = LightType::Directional;
    sun.direction = glm::vec3(0.0f, -2.0f, 0.0f);
    sun.color = glm::vec3(1.0f, 0.9f, 0.8f);
    sun.intensity = 10.0f;
    Light second = sun;
    second.direction = glm::vec3(1.0f, 0.0f, 0.0f);
    const FrameLights frame = setup({sun, pointLight({0, 0, -5}, 2), second});
    EXPECT_EQ(frame.directionalCount, 1u);
    EXPECT_EQ(frame.droppedByCap, 1u);
    EXPECT_EQ(frame.sun.directionToLight, glm::vec4(0.0f, 1.0f, 0.0f, 1.0f));
    EXPECT_EQ(glm::vec3(frame.sun.illuminance), sun.color * sun.intensity);
    EXPECT_EQ(frame.sun.illuminance.r, 10.0f);
    EXPECT_EQ(frame.pointCount, 1u);
    EXPECT_EQ(frame.sceneLightIndex[0], 1u);
}

}  // namespace
}  // namespace punctual
