#pragma once
// Small scenes built in code for the culling tests, each provoking one way culling can go wrong.
// They stand on the floor, boxes and lights of scene/study_scenes.h.
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace punctual::testing {

struct NamedScene {
    std::string name;
    Scene scene;
};

// `light` with its colour set to `color` (study::pointLight and study::spotLight make white ones).
inline Light withColor(Light light, const glm::vec3& color) {
    light.color = color;
    return light;
}

// The adversarial scenes of issue 3: a light straddling the near plane, the camera inside a
// light's range, a spot cone seen edge-on, tile columns spanning a near wall and a far floor,
// and all 96 lights overlapping one spot.
std::vector<NamedScene> adversarialCullingScenes();

// A large floor (one object) lit by `lightCount` overlapping point lights: more than 8 makes
// per-object lists drop some.
Scene largeFloorScene(int lightCount);

// The default scene's hall lit by `spots` + `points` generated lights (seed 7) at constant density
// (--light-range auto): past the design notes' 96, so that a light-grid cell has many words (one
// bit a light; 1,000 lights: 32 words, eleven triples of the subgroup kernels, four chunks of the
// shared-memory kernel).
Scene manyLightsScene(uint32_t spots, uint32_t points);

}  // namespace punctual::testing
