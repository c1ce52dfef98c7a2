// The CPU ray caster behind generated-light placement (TriangleBvh) and the reach test on top of
// it (LightReach): exact answers on boxes, and the tree agrees with a linear scan everywhere.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <optional>

#include <glm/gtc/matrix_transform.hpp>

#include "light_test_scenes.h"
#include "scene/light_generator.h"
#include "scene/light_reach.h"
#include "scene/study_scenes.h"
#include "scene/triangle_bvh.h"

namespace punctual {
namespace {

using unit_testing::pointLight;
using unit_testing::spotLight;

Scene boxes(const std::vector<std::pair<glm::vec3, glm::vec3>>& centersAndSizes) {
    Scene scene;
    for (const auto& [center, size] : centersAndSizes) study::addBox(scene, center, size);
    scene.materials.push_back(Material{});
    scene.computeBounds();
    scene.camera = fitCameraToBounds(scene.bounds);
    return scene;
}

TEST(TriangleBvh, HitsAndMissesABox) {
    const TriangleBvh bvh(boxes({{glm::vec3(0.0f), glm::vec3(1.0f)}}));
    EXPECT_EQ(bvh.triangleCount(), 12u);
    const auto hit = bvh.intersect({0.1f, 0.2f, 5.0f}, {0.0f, 0.0f, -1.0f}, 100.0f);
    ASSERT_TRUE(hit);
    EXPECT_FLOAT_EQ(hit->distance, 4.5f);
    EXPECT_NEAR(hit->normal.z, 1.0f, 1e-6f);  // faces the ray's origin
    EXPECT_FALSE(bvh.intersect({0.1f, 0.2f, 5.0f}, {0.0f, 0.0f, -1.0f}, 4.4f));  // too short
    EXPECT_FALSE(bvh.intersect({0.1f, 0.6f, 5.0f}, {0.0f, 0.0f, -1.0f}, 100.0f));  // passes above
    EXPECT_TRUE(bvh.occluded({0.0f, 0.0f, 5.0f}, {0.0f, 0.0f, -5.0f}));
    EXPECT_FALSE(bvh.occluded({0.0f, 0.0f, 5.0f}, {0.0f, 0.0f, 1.0f}));
    EXPECT_FALSE(bvh.occluded({0.0f, 0.0f, 5.0f}, {0.0f, 0.0f, 0.5f}));  // ends on the face
    EXPECT_TRUE(bvh.occluded({0.0f, 0.0f, 0.0f}, {0.0f, 3.0f, 0.0f}));   // from inside, out
}

// Möller-Trumbore over every triangle, the reference the tree must match.
std::optional<float> linearScan(const Scene& scene, const glm::vec3& origin, const glm::vec3& direction) {
    std::optional<float> nearest;
    for (const Object& object : scene.objects) {
        const Mesh& mesh = scene.meshes[object.mesh];
        for (uint32_t i = 0; i < mesh.indexCount; i += 3) {
            glm::vec3 v[3];
            for (uint32_t k = 0; k < 3; ++k)
                v[k] = glm::vec3(object.model *
                                 glm::vec4(scene.vertices[mesh.vertexOffset + scene.indices[mesh.firstIndex + i + k]].position, 1.0f));
            const glm::vec3 e1 = v[1] - v[0], e2 = v[2] - v[0];
            const glm::vec3 p = glm::cross(direction, e2);
            const float det = glm::dot(e1, p);
            if (det == 0.0f) continue;
            const glm::vec3 s = origin - v[0];
            const float u = glm::dot(s, p) / det;
            const glm::vec3 q = glm::cross(s, e1);
            const float w = glm::dot(direction, q) / det;
            const float t = glm::dot(e2, q) / det;
            if (u >= 0.0f && u <= 1.0f && w >= 0.0f && u + w <= 1.0f && t > 0.0f && (!nearest || t < *nearest))
                nearest = t;
        }
    }
    return nearest;
}

TEST(TriangleBvh, AgreesWithALinearScan) {
    std::vector<std::pair<glm::vec3, glm::vec3>> layout;
    PortableRandom random(4);
    for (int i = 0; i < 60; ++i)
        layout.push_back({glm::vec3(random.uniform(-10, 10), random.uniform(0, 4), random.uniform(-10, 10)),
                          glm::vec3(random.uniform(0.2f, 2), random.uniform(0.2f, 2), random.uniform(0.2f, 2))});
    const Scene scene = boxes(layout);
    const TriangleBvh bvh(scene);
    int hits = 0;
    for (int i = 0; i < 2000; ++i) {
        const glm::vec3 origin(random.uniform(-12, 12), random.uniform(-1, 6), random.uniform(-12, 12));
        const glm::vec3 direction = glm::normalize(
            glm::vec3(random.uniform(-1, 1), random.uniform(-1, 1), random.uniform(-1, 1)) + glm::vec3(1e-3f));
        const std::optional<float> expected = linearScan(scene, origin, direction);
        const auto hit = bvh.intersect(origin, direction, std::numeric_limits<float>::max());
        ASSERT_EQ(hit.has_value(), expected.has_value()) << i;
        if (!hit) continue;
        ++hits;
        EXPECT_NEAR(hit->distance, *expected, 1e-4f * *expected) << i;
        EXPECT_EQ(bvh.occluded(origin, origin + direction * (*expected * 1.01f)), true) << i;
        EXPECT_EQ(bvh.occluded(origin, origin + direction * (*expected * 0.99f)), false) << i;
    }
    EXPECT_GT(hits, 200);  // the rays test something
}

// The frame's planners share one tree: get() builds it once, and what it answers is the tree's.
TEST(LazyTriangleBvh, BuildsOnceOnFirstUse) {
    const Scene scene = boxes({{glm::vec3(0.0f), glm::vec3(1.0f)}});
    const LazyTriangleBvh lazy(scene);
    const TriangleBvh& first = lazy.get();
    EXPECT_EQ(&first, &lazy.get());  // the same tree, not a rebuild
    EXPECT_EQ(first.triangleCount(), 12u);
    const auto hit = first.intersect({0.1f, 0.2f, 5.0f}, {0.0f, 0.0f, -1.0f}, 100.0f);
    ASSERT_TRUE(hit);
    EXPECT_FLOAT_EQ(hit->distance, 4.5f);
}

TEST(LightReach, ClosedCube) {
    const Scene scene = boxes({{glm::vec3(0.0f, 0.5f, 0.0f), glm::vec3(1.0f)}});
    const LightReach reach(scene);
    ASSERT_FALSE(reach.empty());
    EXPECT_FALSE(reach.reaches(pointLight({0.0f, 0.5f, 0.0f}, 10.0f)));  // inside: lights only the inside
    EXPECT_TRUE(reach.reaches(pointLight({0.0f, 2.0f, 0.0f}, 10.0f)));   // above: the top, which the camera sees
    EXPECT_FALSE(reach.reaches(pointLight({0.0f, 2.0f, 0.0f}, 0.9f)));   // out of range of the top (1 m away)
    EXPECT_FALSE(reach.reaches(pointLight({0.0f, -2.0f, 0.0f}, 10.0f)));  // below: the bottom, which it does not
    EXPECT_TRUE(reach.reaches(spotLight({0.0f, 2.0f, 0.0f}, {0.0f, -1.0f, 0.0f}, 10.0f, 30.0f, 20.0f)));
    EXPECT_FALSE(reach.reaches(spotLight({0.0f, 2.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, 10.0f, 30.0f, 20.0f)));  // aims away
}

TEST(LightReach, NothingToTestWithoutGeometryInView) {
    Scene scene = boxes({{glm::vec3(0.0f), glm::vec3(1.0f)}});
    scene.camera.view = glm::lookAt(glm::vec3(0.0f, 0.0f, 5.0f), glm::vec3(0.0f, 0.0f, 10.0f), glm::vec3(0.0f, 1.0f, 0.0f));
    EXPECT_TRUE(LightReach(scene).empty());  // looking away
    scene.objects.clear();
    EXPECT_TRUE(LightReach(scene).empty());
}

}  // namespace
}  // namespace punctual
