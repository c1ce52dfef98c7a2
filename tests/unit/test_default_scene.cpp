// The built-in default scene: content, determinism, camera, and that its 96 lights are all in
// view and overlap like a real many-light scene.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>

#include "lights/light_setup.h"
#include "scene/default_scene.h"
#include "scene_test_support.h"
#include "shading.h"

namespace punctual {
namespace {

using default_scene::kDesignAspect;
using default_scene::kFloorHalfDepth;
using default_scene::kFloorHalfWidth;

const Scene& defaultScene() {
    static const Scene scene = makeDefaultScene();
    return scene;
}

glm::mat4 viewProjection(const Scene& scene) { return scene.camera.projection(kDesignAspect) * scene.camera.view; }

bool insideFrustum(const glm::mat4& viewProjectionMatrix, const glm::vec3& p) {
    const glm::vec4 clip = viewProjectionMatrix * glm::vec4(p, 1.0f);
    return clip.w > 0.0f && std::abs(clip.x) <= clip.w && std::abs(clip.y) <= clip.w && clip.z >= 0.0f &&
           clip.z <= clip.w;
}

// ---- content -----------------------------------------------------------------------------------

TEST(DefaultScene, Content) {
    const Scene& scene = defaultScene();
    EXPECT_EQ(scene.source, "built-in default scene");
    EXPECT_FALSE(scene.materials.empty());
    EXPECT_GE(scene.objects.size(), 20u);
    EXPECT_TRUE(scene.textures.empty());
    for (const Mesh& mesh : scene.meshes) EXPECT_LT(mesh.material, scene.materials.size());
    // Varied materials: some metals, some dielectrics, a spread of roughness.
    float minRoughness = 1.0f, maxRoughness = 0.0f;
    int metals = 0;
    for (const Material& material : scene.materials) {
        minRoughness = std::min(minRoughness, material.roughness);
        maxRoughness = std::max(maxRoughness, material.roughness);
        metals += material.metallic > 0.5f ? 1 : 0;
        EXPECT_EQ(material.baseColorTexture.image, -1);
    }
    EXPECT_GE(metals, 1);
    EXPECT_LT(metals, static_cast<int>(scene.materials.size()));
    EXPECT_LT(minRoughness, 0.4f);
    EXPECT_GT(maxRoughness, 0.8f);
    // The floor: 40 m x 30 m with its top at y = 0.
    EXPECT_FLOAT_EQ(scene.bounds.min.y, -0.2f);
    EXPECT_GE(scene.bounds.size().x, 40.0f);
    EXPECT_GE(scene.bounds.size().z, 30.0f);
}

TEST(DefaultScene, TrianglesFaceOutwardWithFlatNormals) {
    const Scene& scene = defaultScene();
    ASSERT_EQ(scene.indices.size() % 3, 0u);
    for (const Mesh& mesh : scene.meshes) {
        ASSERT_EQ(mesh.indexCount, 36u);
        ASSERT_EQ(mesh.vertexCount, 24u);
        const glm::vec3 center = mesh.localBounds.center();
        for (uint32_t t = 0; t < mesh.indexCount; t += 3) {
            const Vertex* v[3];
            for (uint32_t k = 0; k < 3; ++k) {
                const uint32_t index = scene.indices[mesh.firstIndex + t + k];
                ASSERT_LT(index, mesh.vertexCount);
                v[k] = &scene.vertices[mesh.vertexOffset + index];
            }
            const glm::vec3 geometric = glm::cross(v[1]->position - v[0]->position, v[2]->position - v[0]->position);
            // Counter-clockwise seen from outside: the winding normal agrees with the stored one...
            EXPECT_GT(glm::dot(geometric, v[0]->normal), 0.0f);
            // ...which points away from the box centre and is the same at all three corners.
            EXPECT_GT(glm::dot(v[0]->position - center, v[0]->normal), 0.0f);
            EXPECT_EQ(v[0]->normal, v[1]->normal);
            EXPECT_EQ(v[0]->normal, v[2]->normal);
            for (const Vertex* vertex : v) {
                EXPECT_GE(vertex->uv.x, 0.0f);
                EXPECT_LE(vertex->uv.y, 1.0f);
            }
        }
    }
}

TEST(DefaultScene, Deterministic) {
    EXPECT_EQ(testing::firstSceneDifference(makeDefaultScene(), makeDefaultScene()), "");
}

// ---- camera ------------------------------------------------------------------------------------

TEST(DefaultScene, CameraLooksDownOntoTheFloor) {
    const Scene& scene = defaultScene();
    const Camera& camera = scene.camera;
    EXPECT_TRUE(scene.cameraFromFile);
    EXPECT_NEAR(camera.yfov, 1.0471976f, 1e-6f);  // 60 degrees
    EXPECT_NEAR(camera.znear, 0.1f, 1e-6f);
    const glm::vec3 forward = -glm::vec3(glm::inverse(camera.view)[2]);
    const float pitchDegrees = std::asin(-forward.y) * 57.2957795f;
    EXPECT_GE(pitchDegrees, 30.0f);
    EXPECT_LE(pitchDegrees, 40.0f);
    // zfar is beyond every corner of the scene, but not by much.
    float farthest = 0.0f;
    for (int corner = 0; corner < 8; ++corner) {
        const glm::vec3 p((corner & 1) ? scene.bounds.max.x : scene.bounds.min.x,
                          (corner & 2) ? scene.bounds.max.y : scene.bounds.min.y,
                          (corner & 4) ? scene.bounds.max.z : scene.bounds.min.z);
        farthest = std::max(farthest, -(camera.view * glm::vec4(p, 1.0f)).z);
    }
    EXPECT_GT(camera.zfar, farthest);
    EXPECT_LT(camera.zfar, farthest * 1.1f);
}

// First hit along a ray against every triangle (Moller-Trumbore); returns the object index or -1.
int firstHit(const Scene& scene, const glm::vec3& origin, const glm::vec3& direction) {
    float nearest = 1e30f;
    int hitObject = -1;
    for (size_t o = 0; o < scene.objects.size(); ++o) {
        const Object& object = scene.objects[o];
        const Mesh& mesh = scene.meshes[object.mesh];
        for (uint32_t t = 0; t < mesh.indexCount; t += 3) {
            glm::vec3 p[3];
            for (uint32_t k = 0; k < 3; ++k)
                p[k] = glm::vec3(object.model *
                                 glm::vec4(scene.vertices[mesh.vertexOffset + scene.indices[mesh.firstIndex + t + k]].position, 1.0f));
            const glm::vec3 e1 = p[1] - p[0], e2 = p[2] - p[0];
            const glm::vec3 pv = glm::cross(direction, e2);
            const float det = glm::dot(e1, pv);
            if (std::abs(det) < 1e-12f) continue;
            const glm::vec3 tv = origin - p[0];
            const float u = glm::dot(tv, pv) / det;
            if (u < 0.0f || u > 1.0f) continue;
            const glm::vec3 qv = glm::cross(tv, e1);
            const float v = glm::dot(direction, qv) / det;
            if (v < 0.0f || u + v > 1.0f) continue;
            const float distance = glm::dot(e2, qv) / det;
            if (distance > 1e-4f && distance < nearest) {
                nearest = distance;
                hitObject = static_cast<int>(o);
            }
        }
    }
    return hitObject;
}

TEST(DefaultScene, FloorFillsMostOfTheFrame) {
    // Ray cast a 64 x 36 grid of pixel centres at 16:9: most see the floor, almost none the void.
    const Scene& scene = defaultScene();
    const glm::mat4 inverse = glm::inverse(viewProjection(scene));
    const glm::vec3 eye = scene.camera.position();
    int floorPixels = 0, emptyPixels = 0, total = 0;
    for (int y = 0; y < 36; ++y) {
        for (int x = 0; x < 64; ++x) {
            const glm::vec2 ndc((static_cast<float>(x) + 0.5f) / 32.0f - 1.0f, (static_cast<float>(y) + 0.5f) / 18.0f - 1.0f);
            const glm::vec4 far = inverse * glm::vec4(ndc, 1.0f, 1.0f);
            const int hit = firstHit(scene, eye, glm::normalize(glm::vec3(far) / far.w - eye));
            floorPixels += hit == 0 ? 1 : 0;  // object 0 is the floor
            emptyPixels += hit < 0 ? 1 : 0;
            ++total;
        }
    }
    const float floorFraction = static_cast<float>(floorPixels) / static_cast<float>(total);
    const float emptyFraction = static_cast<float>(emptyPixels) / static_cast<float>(total);
    std::cout << "[ default scene ] floor covers " << 100.0f * floorFraction << "% of the frame, background "
              << 100.0f * emptyFraction << "%\n";
    EXPECT_GT(floorFraction, 0.55f);
    EXPECT_LT(emptyFraction, 0.1f);
}

// ---- lights ------------------------------------------------------------------------------------

TEST(DefaultScene, Has64SpotsAnd32PointsThatValidate) {
    const Scene& scene = defaultScene();
    ASSERT_EQ(scene.lights.size(), 96u);
    int spots = 0, points = 0;
    for (const Light& light : scene.lights) {
        spots += light.type == LightType::Spot ? 1 : 0;
        points += light.type == LightType::Point ? 1 : 0;
        EXPECT_TRUE(light.castsShadow);
        EXPECT_GT(light.intensity, 0.0f);
        if (light.type == LightType::Spot) {
            EXPECT_LT(light.direction.y, -0.85f) << light.name;  // mostly down
            EXPECT_GE(light.outerConeAngle, 0.4363f);            // 25 degrees
            EXPECT_LE(light.outerConeAngle, 0.8727f);            // 50 degrees
            EXPECT_GE(light.innerConeAngle, 0.5f * light.outerConeAngle * 0.9999f);
            EXPECT_LE(light.innerConeAngle, 0.9f * light.outerConeAngle * 1.0001f);
        }
    }
    EXPECT_EQ(spots, 64);
    EXPECT_EQ(points, 32);
    EXPECT_NO_THROW(validateLights(scene.lights, scene.source));
}

TEST(DefaultScene, AllLightsInsideTheView) {
    const Scene& scene = defaultScene();
    const glm::mat4 vp = viewProjection(scene);
    for (const Light& light : scene.lights) EXPECT_TRUE(insideFrustum(vp, light.position)) << light.name;
}

TEST(DefaultScene, SetupKeepsEveryLight) {
    const Scene& scene = defaultScene();
    const FrameLights frame = setupFrameLights(scene, scene.camera.view, scene.camera.projection(kDesignAspect));
    EXPECT_EQ(frame.culledByFrustum, 0u);
    EXPECT_EQ(frame.droppedByCap, 0u);
    EXPECT_EQ(frame.spotCount, 64u);
    EXPECT_EQ(frame.pointCount, 32u);
    EXPECT_EQ(frame.directionalCount, 0u);
}

// Floor points (y = 0) on a 0.25 m grid that the camera's frustum contains and that no object
// standing on the floor covers. Occlusion by walls is ignored, as in the light-count estimate.
std::vector<glm::vec3> visibleFloorGrid(const Scene& scene) {
    const glm::mat4 vp = viewProjection(scene);
    std::vector<glm::vec3> points;
    for (float z = -kFloorHalfDepth; z <= kFloorHalfDepth; z += 0.25f) {
        for (float x = -kFloorHalfWidth; x <= kFloorHalfWidth; x += 0.25f) {
            const glm::vec3 p(x, 0.0f, z);
            if (!insideFrustum(vp, p)) continue;
            bool covered = false;
            for (size_t o = 1; o < scene.objects.size() && !covered; ++o) {
                const Bounds& b = scene.objects[o].worldBounds;
                covered = b.min.y > -0.01f && b.min.y < 0.01f && x > b.min.x && x < b.max.x && z > b.min.z && z < b.max.z;
            }
            if (!covered) points.push_back(p);
        }
    }
    return points;
}

TEST(DefaultScene, EveryLightReachesVisibleFloor) {
    const Scene& scene = defaultScene();
    const FrameLights frame = setupFrameLights(scene, scene.camera.view, scene.camera.projection(kDesignAspect));
    const std::vector<glm::vec3> floor = visibleFloorGrid(scene);
    for (size_t i = 0; i < frame.packed.size(); ++i) {
        const bool reaches = std::any_of(floor.begin(), floor.end(), [&](const glm::vec3& p) {
            return gpu::punctualAttenuation(frame.packed[i], p) > 0.0f;
        });
        EXPECT_TRUE(reaches) << scene.lights[frame.sceneLightIndex[i]].name;
    }
}

TEST(DefaultScene, LightsOverlapAndLightTheFloorModerately) {
    const Scene& scene = defaultScene();
    const FrameLights frame = setupFrameLights(scene, scene.camera.view, scene.camera.projection(kDesignAspect));
    const std::vector<glm::vec3> floor = visibleFloorGrid(scene);
    ASSERT_GT(floor.size(), 5000u);
    size_t totalCount = 0, minCount = 1000, maxCount = 0, unlit = 0;
    double totalLux = 0.0;
    float maxLux = 0.0f;
    for (const glm::vec3& p : floor) {
        size_t count = 0;
        float lux = 0.0f;
        for (const gpu::GpuPunctualLight& light : frame.packed) {
            const float att = gpu::punctualAttenuation(light, p);
            if (att <= 0.0f) continue;
            ++count;
            // E = I att cos(incidence) with the floor normal +Y; I = the peak colour channel x intensity.
            const glm::vec3 toLight = glm::normalize(glm::vec3(light.positionInvRangeSq) - p);
            const float peak = std::max({light.radiantColor.r, light.radiantColor.g, light.radiantColor.b});
            lux += peak * att * std::max(toLight.y, 0.0f);
        }
        totalCount += count;
        minCount = std::min(minCount, count);
        maxCount = std::max(maxCount, count);
        unlit += count == 0 ? 1 : 0;
        totalLux += static_cast<double>(lux);
        maxLux = std::max(maxLux, lux);
    }
    const double points = static_cast<double>(floor.size());
    const double averageCount = static_cast<double>(totalCount) / points;
    const double averageLux = totalLux / points;
    std::cout << "[ default scene ] " << floor.size() << " visible floor points: lights per point average "
              << averageCount << ", min " << minCount << ", max " << maxCount << ", unlit " << unlit
              << "; illuminance average " << averageLux << " lux, max " << maxLux << " lux\n";
    EXPECT_GE(averageCount, 4.0);
    EXPECT_GE(averageLux, 1.0);
    EXPECT_LE(averageLux, 4.0);
    EXPECT_LT(static_cast<double>(unlit) / points, 0.05);
}

}  // namespace
}  // namespace punctual
