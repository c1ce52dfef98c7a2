#pragma once
// Scene checks the built-in scenes' tests share. CPU only, like everything in tests/support.
#include <string>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace punctual::testing {

// The first difference between two scenes, compared bit for bit: vertices, indices, meshes,
// objects (model matrices), materials, the camera and every light parameter; "" when there is
// none. A built-in scene built twice must give "": its placement may depend on nothing but
// constants and fixed seeds.
std::string firstSceneDifference(const Scene& a, const Scene& b);

// The distance from `point` to the nearest point of an object's box: its mesh's local bounds,
// placed by its model matrix. Exact for the built-in scenes' boxes, whose model matrices are a
// turn and a move (distances measured in the box's own space are world distances).
float distanceToObjectBox(const Scene& scene, const Object& object, const glm::vec3& point);

}  // namespace punctual::testing
