#pragma once
// Small scenes built in code for the culling tests, each provoking one way culling can go wrong.
#include <string>
#include <vector>

#include "scene/scene.h"

namespace punctual::testing {

struct NamedScene {
    std::string name;
    Scene scene;
};

// A box of `size` centred at `center` added to `scene` (mesh + object).
void addBox(Scene& scene, const glm::vec3& center, const glm::vec3& size, uint32_t material = 0);
Light pointLight(const glm::vec3& position, float range, float intensity, const glm::vec3& color = glm::vec3(1.0f));
Light spotLight(const glm::vec3& position, const glm::vec3& direction, float range, float intensity,
                float innerAngle, float outerAngle, const glm::vec3& color = glm::vec3(1.0f));

// The adversarial scenes of issue 3: a light straddling the near plane, the camera inside a
// light's range, a spot cone seen edge-on, tile columns spanning a near wall and a far floor,
// and all 96 lights overlapping one spot.
std::vector<NamedScene> adversarialCullingScenes();

// A large floor (one object) lit by `lightCount` overlapping point lights: more than 8 makes
// per-object lists drop some.
Scene largeFloorScene(int lightCount);

}  // namespace punctual::testing
