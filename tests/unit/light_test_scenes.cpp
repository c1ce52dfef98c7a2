#include "light_test_scenes.h"

namespace punctual::unit_testing {

Light pointLight(glm::vec3 position, float range, float intensity) {
    Light light;
    light.type = LightType::Point;
    light.position = position;
    light.range = range;
    light.intensity = intensity;
    return light;
}

Light spotLight(glm::vec3 position, glm::vec3 direction, float range, float outerDegrees, float innerDegrees,
                float intensity) {
    Light light;
    light.type = LightType::Spot;
    light.position = position;
    light.direction = direction;
    light.range = range;
    light.outerConeAngle = outerDegrees * kDegree;
    light.innerConeAngle = innerDegrees * kDegree;
    light.intensity = intensity;
    return light;
}

}  // namespace punctual::unit_testing
