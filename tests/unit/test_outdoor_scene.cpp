// The built-in outdoor scene: deterministic, one low slanted sun, casters from under a metre to
// beyond a hundred metres from the eye, a camera at eye height that sees all of them, and street
// lamps that light what the camera sees. Distances are measured on the scene's own objects, so
// the checks hold whatever the layout's numbers become.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>

#include "lights/light_setup.h"
#include "scene/light_reach.h"
#include "scene/outdoor_scene.h"
#include "scene_test_support.h"

namespace punctual {
namespace {

constexpr float kDegrees = 57.2957795f;

const Scene& outdoorScene() {
    static const Scene scene = makeOutdoorScene();
    return scene;
}

// Casters are every object standing on or above the ground: all but the ground itself, whose top
// is the plane y = 0.
bool isCaster(const Object& object) { return object.worldBounds.max.y > 1e-4f; }

// The view-space depth of a point (distance along the camera's axis).
float viewDepth(const Scene& scene, const glm::vec3& p) { return -(scene.camera.view * glm::vec4(p, 1.0f)).z; }

TEST(OutdoorScene, Deterministic) {
    EXPECT_EQ(testing::firstSceneDifference(makeOutdoorScene(), makeOutdoorScene()), "");
}

TEST(OutdoorScene, GroundIsAtLeast400MetresSquare) {
    const Scene& scene = outdoorScene();
    EXPECT_EQ(scene.source, outdoor_scene::kSource);
    ASSERT_FALSE(scene.objects.empty());
    const Bounds& ground = scene.objects[0].worldBounds;
    EXPECT_FALSE(isCaster(scene.objects[0]));
    EXPECT_FLOAT_EQ(ground.max.y, 0.0f);
    EXPECT_GE(ground.size().x, 400.0f);
    EXPECT_GE(ground.size().z, 400.0f);
    // Every other object stands on it or above it, inside its edges.
    for (size_t i = 1; i < scene.objects.size(); ++i) {
        const Bounds& b = scene.objects[i].worldBounds;
        EXPECT_GE(b.min.y, -1e-4f) << scene.objects[i].name;
        EXPECT_GT(b.min.x, ground.min.x) << scene.objects[i].name;
        EXPECT_LT(b.max.x, ground.max.x) << scene.objects[i].name;
        EXPECT_GT(b.min.z, ground.min.z) << scene.objects[i].name;
        EXPECT_LT(b.max.z, ground.max.z) << scene.objects[i].name;
    }
}

TEST(OutdoorScene, OneLowSlantedSunThatCastsShadows) {
    const Scene& scene = outdoorScene();
    int suns = 0;
    for (const Light& light : scene.lights) {
        if (light.type != LightType::Directional) continue;
        ++suns;
        EXPECT_TRUE(light.castsShadow);
        EXPECT_GT(light.intensity, 0.0f);
        EXPECT_NEAR(glm::length(light.direction), 1.0f, 1e-6f);
        const float elevation = std::asin(-light.direction.y) * kDegrees;
        EXPECT_GE(elevation, 35.0f);
        EXPECT_LE(elevation, 40.0f);
        // Not along any axis, nor in an axis plane: shadows run across the boxes' edges.
        for (int axis = 0; axis < 3; ++axis) EXPECT_GT(std::abs(light.direction[axis]), 0.2f) << axis;
    }
    EXPECT_EQ(suns, 1);
}

TEST(OutdoorScene, CastersFromUnderAMetreToBeyondAHundredMetres) {
    const Scene& scene = outdoorScene();
    const glm::vec3 eye = scene.camera.position();
    float nearest = 1e30f, farthest = 0.0f;
    int within1 = 0, from2To20 = 0, from20To100 = 0, beyond100 = 0;
    for (const Object& object : scene.objects) {
        if (!isCaster(object)) continue;
        const float distance = testing::distanceToObjectBox(scene, object, eye);
        nearest = std::min(nearest, distance);
        farthest = std::max(farthest, distance);
        within1 += distance < 1.0f ? 1 : 0;
        from2To20 += distance >= 2.0f && distance <= 20.0f ? 1 : 0;
        from20To100 += distance > 20.0f && distance <= 100.0f ? 1 : 0;
        beyond100 += distance > 100.0f ? 1 : 0;
        // The far plane is beyond every caster.
        const Bounds& b = object.worldBounds;
        for (int corner = 0; corner < 8; ++corner) {
            const glm::vec3 p((corner & 1) ? b.max.x : b.min.x, (corner & 2) ? b.max.y : b.min.y,
                              (corner & 4) ? b.max.z : b.min.z);
            EXPECT_LT(viewDepth(scene, p), scene.camera.zfar) << object.name;
        }
    }
    std::cout << "[ outdoor scene ] casters " << nearest << " m to " << farthest << " m from the eye: " << within1
              << " within 1 m, " << from2To20 << " at 2-20 m, " << from20To100 << " at 20-100 m, " << beyond100
              << " beyond 100 m\n";
    EXPECT_LT(nearest, 1.0f);
    EXPECT_GT(nearest, scene.camera.znear);  // not clipped by the near plane
    EXPECT_GT(farthest, 100.0f);
    EXPECT_GE(within1, 1);
    EXPECT_GE(from2To20, 5);
    EXPECT_GE(from20To100, 10);
    EXPECT_GE(beyond100, 3);
}

TEST(OutdoorScene, CameraAtEyeHeightLooksAlongTheGround) {
    const Scene& scene = outdoorScene();
    const Camera& camera = scene.camera;
    EXPECT_TRUE(scene.cameraFromFile);
    const glm::vec3 eye = camera.position();
    EXPECT_GE(eye.y, 1.5f);
    EXPECT_LE(eye.y, 2.0f);
    const glm::vec3 forward = -glm::vec3(glm::inverse(camera.view)[2]);
    const float pitchDegrees = std::asin(-forward.y) * kDegrees;
    EXPECT_GT(pitchDegrees, 0.0f);   // down...
    EXPECT_LT(pitchDegrees, 20.0f);  // ...but along the ground: the horizon is in the frame
    EXPECT_LT(pitchDegrees, camera.yfov * 0.5f * kDegrees);
}

// The casters beyond 100 m are in the frame (in front of the eye, inside the 16:9 frustum): a
// cascade that covers them has something to draw.
TEST(OutdoorScene, FarCastersAreInView) {
    const Scene& scene = outdoorScene();
    const glm::mat4 viewProjection = scene.camera.projection(16.0f / 9.0f) * scene.camera.view;
    const glm::vec3 eye = scene.camera.position();
    int farInView = 0;
    for (const Object& object : scene.objects) {
        if (!isCaster(object) || testing::distanceToObjectBox(scene, object, eye) <= 100.0f) continue;
        const glm::vec4 clip = viewProjection * glm::vec4(object.worldBounds.center(), 1.0f);
        farInView += clip.w > 0.0f && std::abs(clip.x) <= clip.w && std::abs(clip.y) <= clip.w ? 1 : 0;
    }
    EXPECT_GE(farInView, 3);
}

TEST(OutdoorScene, StreetLampsAndBollardsLightWhatTheCameraSees) {
    const Scene& scene = outdoorScene();
    EXPECT_NO_THROW(validateLights(scene.lights, scene.source));
    // A much finer grid than the light generator's (a sample every 0.3 degrees, about 4 pixels of
    // a 720-line frame): the pools of the lamps 50-60 m down the street are slivers a few pixels
    // high, which coarser grids step over.
    const LightReach reach(scene, 192);
    ASSERT_FALSE(reach.empty());
    int spots = 0, points = 0;
    for (const Light& light : scene.lights) {
        if (light.type == LightType::Directional) continue;
        spots += light.type == LightType::Spot ? 1 : 0;
        points += light.type == LightType::Point ? 1 : 0;
        EXPECT_TRUE(light.castsShadow) << light.name;
        EXPECT_TRUE(reach.reaches(light)) << light.name;
        if (light.type == LightType::Spot) {
            EXPECT_LT(light.direction.y, -0.9f) << light.name;  // down
        }
    }
    EXPECT_EQ(spots, 16);
    EXPECT_EQ(points, 16);
    // The frame keeps every light: none is outside the view or over the caps.
    const FrameLights frame = setupFrameLights(scene, scene.camera.view, scene.camera.projection(16.0f / 9.0f));
    EXPECT_EQ(frame.culledByFrustum, 0u);
    EXPECT_EQ(frame.droppedByCap, 0u);
    EXPECT_EQ(frame.directionalCount, 1u);
}

}  // namespace
}  // namespace punctual
