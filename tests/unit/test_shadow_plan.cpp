// The shadow plan, on the CPU: which lights the caps keep, views with no caster skipped, and the
// cube faces' matrices against Vulkan's cube-map conventions. No GPU: planShadows is CPU code.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <glm/gtc/matrix_transform.hpp>

#include "lights/light_setup.h"
#include "lights/shadow_setup.h"
#include "lights/shadow_sizing.h"
#include "scene/study_scenes.h"
#include "shadow_test_scenes.h"
#include "shadows.h"

namespace punctual {
namespace {

// A floor seen from above with lights placed over it, all inside the view.
Scene planScene() {
    Scene scene = testing::emptyFloorScene();
    scene.camera.view = glm::lookAtRH(glm::vec3(0.0f, 30.0f, 0.1f), glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f));
    return scene;
}

FrameLights frameLights(const Scene& scene) {
    return setupFrameLights(scene, scene.camera.view, scene.camera.projection(16.0f / 9.0f));
}

TEST(ShadowPlan, CapsChooseTheMostImportantLights) {
    Scene scene = planScene();
    // 40 shadow-casting spots and 12 points with intensities in a scrambled order (importance is
    // not scene order), plus bright lights that cast no shadow: they must neither be shadowed nor
    // take a shadowed place.
    for (int i = 0; i < 40; ++i) {
        const glm::vec3 position(-8.0f + 0.4f * float(i), 3.0f, -3.0f + 0.15f * float(i % 7));
        scene.lights.push_back(study::spotLight(position, glm::vec3(0.0f, -1.0f, 0.0f), 6.0f,
                                                1.0f + float((i * 17) % 40), 0.3f, 0.5f));
    }
    for (int i = 0; i < 12; ++i) {
        scene.lights.push_back(study::pointLight(glm::vec3(-6.0f + float(i), 2.0f, 4.0f), 5.0f, 1.0f + float((i * 5) % 12)));
    }
    for (int i = 0; i < 3; ++i) {
        Light spot = study::spotLight(glm::vec3(float(i), 3.0f, 6.0f), glm::vec3(0.0f, -1.0f, 0.0f), 6.0f, 1000.0f, 0.3f, 0.5f);
        spot.castsShadow = false;
        scene.lights.push_back(spot);
        Light point = study::pointLight(glm::vec3(float(i), 2.0f, -6.0f), 5.0f, 1000.0f);
        point.castsShadow = false;
        scene.lights.push_back(point);
    }
    FrameLights lights = frameLights(scene);
    ASSERT_EQ(lights.spotCount, 43u) << "every spot should be in view and under the light caps";
    ASSERT_EQ(lights.pointCount, 15u);
    const glm::vec3 camera = scene.camera.position();
    ShadowSettings settings;  // --shadowed 32,8
    settings.maxShadowedSpots = 32;
    settings.maxShadowedPoints = 8;
    settings.resolution = 256;
    ShadowPlan plan = planShadows(scene, lights, camera, settings);
    sizeShadowViews(plan, scene, lights, camera, 160, 90, settings, ShadowMemoryLimits{});

    EXPECT_EQ(plan.shadowedSpots, 32u);
    EXPECT_EQ(plan.shadowedPoints, 8u);
    EXPECT_EQ(plan.droppedByCap, 8u + 4u);
    EXPECT_EQ(plan.views.size(), 32u + 6u * 8u);
    EXPECT_EQ(plan.viewsRendered + plan.viewsSkipped, uint32_t(plan.views.size()));

    for (const bool points : {false, true}) {
        const uint32_t first = points ? lights.spotCount : 0;
        const uint32_t count = points ? lights.pointCount : lights.spotCount;
        float leastShadowed = 1e30f;
        float mostDropped = -1.0f;
        uint32_t shadowed = 0;
        for (uint32_t i = first; i < first + count; ++i) {
            const Light& source = scene.lights[lights.sceneLightIndex[i]];
            const bool hasShadow = lights.packed[i].angleOffsetShadow.y >= 0.0f;
            if (!source.castsShadow) {
                EXPECT_FALSE(hasShadow) << "light " << lights.sceneLightIndex[i] << " casts no shadow";
                continue;
            }
            const float importance = lightImportance(source, camera);
            if (hasShadow) {
                ++shadowed;
                leastShadowed = std::min(leastShadowed, importance);
                EXPECT_EQ(lights.packed[i].angleOffsetShadow.w, 1.0f);
                const ShadowView& view = plan.views.at(size_t(lights.packed[i].angleOffsetShadow.y));
                EXPECT_EQ(view.packedLight, i);
                EXPECT_EQ(view.isPoint, points);
            } else {
                mostDropped = std::max(mostDropped, importance);
            }
        }
        EXPECT_EQ(shadowed, points ? 8u : 32u);
        EXPECT_GT(leastShadowed, mostDropped) << (points ? "points" : "spots")
                                              << ": a dropped light is more important than a shadowed one";
    }
}

TEST(ShadowPlan, EveryLightIsShadowedByDefault) {
    Scene scene = planScene();
    for (int i = 0; i < 40; ++i) {
        scene.lights.push_back(study::spotLight(glm::vec3(-8.0f + 0.4f * float(i), 3.0f, 0.0f),
                                                glm::vec3(0.0f, -1.0f, 0.0f), 6.0f, 1.0f, 0.3f, 0.5f));
    }
    for (int i = 0; i < 12; ++i) {
        scene.lights.push_back(study::pointLight(glm::vec3(-6.0f + float(i), 2.0f, 4.0f), 5.0f, 1.0f));
    }
    FrameLights lights = frameLights(scene);
    const ShadowPlan plan = planShadows(scene, lights, scene.camera.position(), ShadowSettings{});
    EXPECT_EQ(plan.shadowedSpots, 40u);
    EXPECT_EQ(plan.shadowedPoints, 12u);
    EXPECT_EQ(plan.droppedByCap, 0u);
    EXPECT_EQ(plan.views.size(), 40u + 6u * 12u);
    // Each light's slot, from its first view (gpu::shadowSlot, as the shader and the validation
    // compute it): spots 0..39 by view, then the points 40..51, whichever of its faces is given.
    EXPECT_EQ(gpu::shadowSlot(0u, 40u), 0u);
    EXPECT_EQ(gpu::shadowSlot(39u, 40u), 39u);
    EXPECT_EQ(gpu::shadowSlot(40u, 40u), 40u);       // the first point's +X face
    EXPECT_EQ(gpu::shadowSlot(45u, 40u), 40u);       // its -Z face
    EXPECT_EQ(gpu::shadowSlot(46u, 40u), 41u);       // the second point
    EXPECT_EQ(gpu::shadowSlot(40u + 6u * 11u, 40u), 51u);
    for (uint32_t i = 0; i < plan.views.size(); ++i) {
        const ShadowView& view = plan.views[i];
        const gpu::GpuPunctualLight& light = lights.packed[view.packedLight];
        EXPECT_EQ(gpu::shadowSlot(uint32_t(light.angleOffsetShadow.y), plan.shadowedSpots),
                  view.isPoint ? 40u + (i - 40u) / 6u : i)
            << "view " << i;
    }
}

TEST(ShadowPlan, SpotWithoutCasterIsSkipped) {
    Scene scene = planScene();
    // Pointing up from above the floor: nothing in its frustum. The other looks down at the floor.
    scene.lights.push_back(study::spotLight(glm::vec3(-2.0f, 1.0f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f), 4.0f, 10.0f, 0.3f, 0.5f));
    scene.lights.push_back(study::spotLight(glm::vec3(2.0f, 3.0f, 0.0f), glm::vec3(0.0f, -1.0f, 0.0f), 6.0f, 10.0f, 0.3f, 0.5f));
    FrameLights lights = frameLights(scene);
    ASSERT_EQ(lights.spotCount, 2u);
    ShadowSettings settings;
    settings.resolution = 1024;
    ShadowPlan plan = planShadows(scene, lights, scene.camera.position(), settings);
    sizeShadowViews(plan, scene, lights, scene.camera.position(), 160, 90, settings, ShadowMemoryLimits{});
    ASSERT_EQ(plan.views.size(), 2u);
    EXPECT_EQ(plan.views[0].resolution, 0u) << "no caster: no storage";
    EXPECT_EQ(plan.views[1].resolution, 1024u);
    EXPECT_EQ(plan.views[0].gpu.params.x, -1.0f);
    EXPECT_TRUE(plan.views[0].casters.empty());
    EXPECT_GE(plan.views[1].gpu.params.x, 0.0f);
    EXPECT_EQ(plan.views[1].casters.size(), 1u);
    EXPECT_EQ(plan.viewsSkipped, 1u);
    EXPECT_EQ(plan.viewsRendered, 1u);
    // The light keeps its shadow slot: the shader reads the view and finds it skipped (always lit).
    EXPECT_EQ(lights.packed[0].angleOffsetShadow.y, 0.0f);
}

// Vulkan's cube map face selection table (spec, "Cube Map Face Selection and Transformations"),
// written out here independently of shadows.h: (sc, tc, ma) for a direction on each face.
glm::vec3 vulkanCubeCoordinates(uint32_t face, const glm::vec3& r) {
    switch (face) {
        case 0: return {-r.z, -r.y, r.x};
        case 1: return {r.z, -r.y, r.x};
        case 2: return {r.x, r.z, r.y};
        case 3: return {r.x, -r.z, r.y};
        case 4: return {r.x, -r.y, r.z};
        default: return {-r.x, -r.y, r.z};
    }
}

TEST(ShadowPlan, CubeFaceMatricesFollowVulkanCubeConventions) {
    const glm::vec3 light(1.0f, 2.0f, -3.0f);
    const float nearPlane = 0.1f;
    const float farPlane = 10.0f;
    for (uint32_t face = 0; face < 6; ++face) {
        const glm::vec3 axis = gpu::cubeFaceAxis(face);
        EXPECT_EQ(gpu::cubeFaceOfDirection(axis), face);
        const glm::mat4 m = cubeFaceViewProjection(light, face, nearPlane, farPlane);
        auto ndc = [&](const glm::vec3& p) {
            const glm::vec4 clip = m * glm::vec4(p, 1.0f);
            EXPECT_GT(clip.w, 0.0f) << "face " << face;
            return glm::vec3(clip) / clip.w;
        };
        // On the axis: the centre of the face, depth in [0, 1] as perspectiveDepth gives it.
        for (const float distance : {nearPlane, 0.5f, 4.0f, farPlane}) {
            const glm::vec3 onAxis = ndc(light + axis * distance);
            EXPECT_NEAR(onAxis.x, 0.0f, 1e-5f) << "face " << face;
            EXPECT_NEAR(onAxis.y, 0.0f, 1e-5f) << "face " << face;
            EXPECT_GE(onAxis.z, -1e-5f);
            EXPECT_LE(onAxis.z, 1.0f + 1e-5f);
            EXPECT_NEAR(onAxis.z, gpu::perspectiveDepth(distance, nearPlane, farPlane), 1e-5f) << "face " << face;
        }
        // Along U: positive NDC x; along V: positive NDC y.
        EXPECT_NEAR(ndc(light + axis * 2.0f + gpu::cubeFaceU(face) * 0.5f).x, 0.25f, 1e-5f) << "face " << face;
        EXPECT_NEAR(ndc(light + axis * 2.0f + gpu::cubeFaceV(face) * 0.5f).y, 0.25f, 1e-5f) << "face " << face;
        // Everywhere on the face, NDC is Vulkan's (sc / |ma|, tc / |ma|): what the render writes at
        // texel (s, t) is what the sampler reads for that direction. With a widened slice, NDC
        // shrinks by the scale.
        for (int i = 0; i < 25; ++i) {
            const float a = -0.9f + 0.075f * float(i);
            const float b = 0.85f - 0.07f * float(i);
            const glm::vec3 direction = axis + gpu::cubeFaceU(face) * a + gpu::cubeFaceV(face) * b;
            ASSERT_EQ(gpu::cubeFaceOfDirection(direction), face);
            const glm::vec3 vk = vulkanCubeCoordinates(face, direction);
            const glm::vec3 p = ndc(light + direction * 3.0f);
            EXPECT_NEAR(p.x, vk.x / std::abs(vk.z), 1e-5f) << "face " << face << " direction " << i;
            EXPECT_NEAR(p.y, vk.y / std::abs(vk.z), 1e-5f) << "face " << face << " direction " << i;
            const glm::vec4 wide = cubeFaceViewProjection(light, face, nearPlane, farPlane, 1.25f) *
                                   glm::vec4(light + direction * 3.0f, 1.0f);
            EXPECT_NEAR(wide.x / wide.w, vk.x / std::abs(vk.z) / 1.25f, 1e-5f) << "face " << face;
        }
    }
}

}  // namespace
}  // namespace punctual
