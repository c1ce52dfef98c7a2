// Known answers for how close a caster comes to a light (lights/caster_distance.h), which the
// shadow views' near planes are built from.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "lights/caster_distance.h"
#include "scene/study_scenes.h"

namespace punctual {
namespace {

TEST(ClosestPointOnTriangle, EachVoronoiRegionHasItsHandComputedAnswer) {
    const glm::vec3 a(0.0f, 0.0f, 0.0f), b(4.0f, 0.0f, 0.0f), c(0.0f, 4.0f, 0.0f);
    // Above the face: straight down onto it.
    EXPECT_EQ(closestPointOnTriangle({1.0f, 1.0f, 3.0f}, a, b, c), glm::vec3(1.0f, 1.0f, 0.0f));
    // Beyond each vertex: the vertex.
    EXPECT_EQ(closestPointOnTriangle({-1.0f, -1.0f, 2.0f}, a, b, c), a);
    EXPECT_EQ(closestPointOnTriangle({6.0f, -1.0f, 0.0f}, a, b, c), b);
    EXPECT_EQ(closestPointOnTriangle({-1.0f, 6.0f, 0.0f}, a, b, c), c);
    // Beside edge AB (y < 0): onto it. Beside AC (x < 0). Beyond BC (x + y > 4): onto BC at (2.5, 1.5).
    EXPECT_EQ(closestPointOnTriangle({2.0f, -3.0f, 1.0f}, a, b, c), glm::vec3(2.0f, 0.0f, 0.0f));
    EXPECT_EQ(closestPointOnTriangle({-2.0f, 1.5f, 0.0f}, a, b, c), glm::vec3(0.0f, 1.5f, 0.0f));
    const glm::vec3 onBc = closestPointOnTriangle({4.0f, 3.0f, 0.0f}, a, b, c);
    EXPECT_NEAR(onBc.x, 2.5f, 1e-6f);
    EXPECT_NEAR(onBc.y, 1.5f, 1e-6f);
    // A degenerate triangle (three points on a line) still gives a point of it.
    EXPECT_EQ(closestPointOnTriangle({0.0f, 5.0f, 0.0f}, a, a, a), a);
}

TEST(CasterDistance, OutsideABoxItIsTheDistanceToTheBoxInsideToItsNearestFace) {
    Scene scene = study::floorScene("distances");  // object 0: the floor, 20 x 0.2 x 20 centred at y = -0.1
    study::addBox(scene, {0.0f, 5.0f, 0.0f}, {4.0f, 2.0f, 6.0f});  // object 1: x -2..2, y 4..6, z -3..3
    scene.computeBounds();
    // 2.5 m above the floor's top face, then 3 and 4 m off the box's corner edge: 5 m.
    EXPECT_FLOAT_EQ(casterDistance(scene, 0, {1.0f, 2.5f, 1.0f}), 2.5f);
    EXPECT_FLOAT_EQ(casterDistance(scene, 1, {5.0f, 5.0f, 7.0f}), 5.0f);
    // Inside the box (a room modelled around its light): its nearest face, 0.5 m above.
    EXPECT_NEAR(casterDistance(scene, 1, {0.0f, 5.5f, 0.0f}), 0.5f, 1e-6f);
    EXPECT_NEAR(casterDistance(scene, 1, {1.5f, 5.0f, 0.0f}), 0.5f, 1e-6f);
    // On a face: 0.
    EXPECT_NEAR(casterDistance(scene, 1, {0.0f, 6.0f, 0.0f}), 0.0f, 1e-6f);
}

}  // namespace
}  // namespace punctual
