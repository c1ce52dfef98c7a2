#pragma once
// Shared by the light tests (test_light_setup.cpp, test_per_object_lights.cpp,
// test_light_generator.cpp): lights built in code.
#include <glm/glm.hpp>

#include "scene/scene.h"

namespace punctual::unit_testing {

constexpr float kDegree = 0.0174532925f;

// A white point light.
Light pointLight(glm::vec3 position, float range, float intensity = 10.0f);
// A white spot light with its cone angles in degrees; `direction` is stored as given (not normalized).
Light spotLight(glm::vec3 position, glm::vec3 direction, float range, float outerDegrees, float innerDegrees,
                float intensity = 10.0f);

}  // namespace punctual::unit_testing
