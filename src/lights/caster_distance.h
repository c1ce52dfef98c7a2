#pragma once
// How close a shadow caster comes to a light, for the shadow views' near planes (shadow_setup.cpp).
#include <glm/glm.hpp>

#include "scene/scene.h"

namespace punctual {

// The distance from `point` to the nearest surface of object `object`: the distance to its world
// bounds when the point lies outside them (a lower bound, and exact for the boxes that bound
// it), else the exact distance to its nearest triangle. 0 when a triangle passes through the point.
float casterDistance(const Scene& scene, uint32_t object, const glm::vec3& point);

// The point of triangle (a, b, c) closest to p (Ericson, "Real-Time Collision Detection" 5.1.5:
// p's projection, or the nearest point of the edge or vertex whose Voronoi region holds it).
glm::vec3 closestPointOnTriangle(const glm::vec3& p, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c);

}  // namespace punctual
