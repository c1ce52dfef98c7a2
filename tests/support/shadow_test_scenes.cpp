#include "shadow_test_scenes.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/study_scenes.h"

namespace punctual::testing {

using study::addBox;
using study::pointLight;
using study::spotLight;

size_t countVerdicts(const reference::LightShadowValidation& light, reference::PixelVerdict verdict,
                     bool outsideBandOnly) {
    size_t count = 0;
    for (size_t i = 0; i < light.verdicts.size(); ++i) {
        if (light.verdicts[i] == verdict && !(outsideBandOnly && light.inBand[i])) ++count;
    }
    return count;
}

size_t countVerdicts(const reference::ShadowValidation& validation, bool points, reference::PixelVerdict verdict) {
    size_t count = 0;
    for (const reference::LightShadowValidation& light : validation.lights) {
        if (light.isPoint == points) count += countVerdicts(light, verdict);
    }
    return count;
}

float angleToLight(const glm::vec3& position, const glm::vec3& normal, const glm::vec3& lightPosition) {
    const float cosine = glm::dot(normal, glm::normalize(lightPosition - position));
    return std::acos(std::clamp(cosine, -1.0f, 1.0f));
}

namespace {

void setCamera(Scene& scene, const glm::vec3& eye, const glm::vec3& target, float yfov) {
    scene.camera.view = glm::lookAtRH(eye, target, glm::vec3(0.0f, 1.0f, 0.0f));
    scene.camera.yfov = yfov;
    scene.camera.znear = 0.1f;
    scene.camera.zfar = 80.0f;
    scene.cameraFromFile = true;
}

}  // namespace

Scene emptyFloorScene() {
    Scene scene;
    scene.source = "shadow test floor";
    Material material;
    material.name = "grey";
    material.baseColorFactor = glm::vec4(0.6f, 0.6f, 0.6f, 1.0f);
    material.metallic = 0.0f;
    material.roughness = 0.7f;
    scene.materials.push_back(material);
    addBox(scene, glm::vec3(0.0f, -0.1f, 0.0f), glm::vec3(40.0f, 0.2f, 40.0f));
    setCamera(scene, glm::vec3(0.0f, 9.0f, 8.0f), glm::vec3(0.0f), 1.2f);
    scene.computeBounds();
    return scene;
}

Scene floorSeenFromAbove() {
    Scene scene = emptyFloorScene();
    scene.camera.view = glm::lookAtRH(glm::vec3(0.0f, 10.0f, 0.0f), glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, -1.0f));
    scene.camera.yfov = glm::radians(90.0f);
    scene.camera.znear = 0.05f;
    scene.camera.zfar = 100.0f;
    return scene;
}

Scene grazingFloorScene(bool spot) {
    Scene scene = emptyFloorScene();
    scene.source = spot ? "grazing spot over an empty floor" : "grazing point over an empty floor";
    const glm::vec3 position(0.0f, kGrazingLightHeight, 0.0f);
    if (spot) {
        // Axis 50 degrees from straight down, cone 35 degrees: the floor is met at 15 to 85
        // degrees from its normal, along -Z, where the camera looks.
        const float tilt = glm::radians(50.0f);
        scene.lights.push_back(spotLight(position, glm::vec3(0.0f, -std::cos(tilt), -std::sin(tilt)), 14.0f, 20.0f,
                                         glm::radians(25.0f), glm::radians(35.0f)));
        setCamera(scene, glm::vec3(0.0f, 3.2f, 0.5f), glm::vec3(0.0f, 0.0f, -3.0f), 1.3f);
    } else {
        scene.lights.push_back(pointLight(position, 12.0f, 10.0f));
        setCamera(scene, glm::vec3(0.0f, 6.0f, 5.0f), glm::vec3(0.0f), 1.2f);
    }
    scene.computeBounds();
    return scene;
}

Scene pointAmongOccludersScene(bool lampCap) {
    Scene scene = emptyFloorScene();
    scene.source = "point light among occluders";
    const glm::vec3 light(0.0f, kOccludedPointHeight, 0.0f);
    // Posts at radius 1.1 m, 1.4 m tall: each shadow runs from r = 1.1 to 1.1 x 2 / 0.6 = 3.7 m,
    // across the floor square |x|, |z| <= 2 where the -Y face meets the side faces. Angles are
    // irregular, some near the diagonals where two side faces meet.
    const float postAngles[] = {0.0f, 25.0f, 44.0f, 80.0f, 118.0f, 136.0f, 170.0f, 205.0f, 226.0f, 260.0f, 300.0f, 316.0f};
    for (const float degrees : postAngles) {
        const float a = glm::radians(degrees);
        addBox(scene, glm::vec3(1.1f * std::cos(a), 0.7f, 1.1f * std::sin(a)), glm::vec3(0.16f, 1.4f, 0.16f));
    }
    // Boxes about the light's height throw shadows onto the two walls (the -X and -Z faces).
    addBox(scene, glm::vec3(-1.2f, 2.2f, 0.6f), glm::vec3(0.3f, 0.5f, 0.3f));
    addBox(scene, glm::vec3(0.5f, 1.9f, -1.3f), glm::vec3(0.5f, 0.3f, 0.3f));
    addBox(scene, glm::vec3(-0.9f, 2.0f, -0.9f), glm::vec3(0.25f, 0.25f, 0.25f));
    // Walls at x = -4 and z = -4.
    addBox(scene, glm::vec3(-4.1f, 2.0f, 0.0f), glm::vec3(0.2f, 4.0f, 12.0f));
    addBox(scene, glm::vec3(0.0f, 2.0f, -4.1f), glm::vec3(12.0f, 4.0f, 0.2f));
    if (lampCap) addBox(scene, light + glm::vec3(0.0f, 0.3f, 0.0f), glm::vec3(0.3f, 0.04f, 0.3f));
    scene.lights.push_back(pointLight(light, 14.0f, 12.0f));
    setCamera(scene, glm::vec3(4.5f, 6.5f, 5.5f), glm::vec3(-0.8f, 0.6f, -0.8f), 1.1f);
    scene.computeBounds();
    return scene;
}

Scene wideSpotScene(float outerConeAngle, bool bracket) {
    Scene scene = emptyFloorScene();
    scene.source = "wide spot";
    // Under the spot, well inside 80 degrees.
    addBox(scene, glm::vec3(0.9f, 0.2f, 0.4f), glm::vec3(0.6f, 0.4f, 0.6f));
    // Beside it: the face at x = 2.85 is seen at 80 degrees from the axis at y = 0.5, so its
    // lower half is in the shadow map's frustum and its upper half in the rim. Its shadow on the
    // floor starts at r = 3.2 and crosses 80 degrees (r = 5.7).
    addBox(scene, glm::vec3(3.0f, 0.75f, 0.0f), glm::vec3(0.3f, 1.5f, 0.6f));
    if (bracket) addBox(scene, kWideSpotPosition - glm::vec3(0.0f, 0.15f, 0.0f), glm::vec3(0.04f));
    scene.lights.push_back(spotLight(kWideSpotPosition, glm::vec3(0.0f, -1.0f, 0.0f), 30.0f, 10.0f,
                                     0.7f * outerConeAngle, outerConeAngle));
    setCamera(scene, glm::vec3(-3.0f, 7.0f, 6.0f), glm::vec3(4.0f, 0.0f, 0.0f), 1.2f);
    scene.computeBounds();
    return scene;
}

Scene offAxisPostScene() {
    Scene scene = emptyFloorScene();
    scene.source = "spot beside a post";
    addBox(scene, glm::vec3(1.0f, 1.3f, 0.0f), glm::vec3(0.1f, 2.6f, 0.1f));
    scene.lights.push_back(spotLight(glm::vec3(0.0f, 3.0f, 0.0f), glm::vec3(0.0f, -1.0f, 0.0f), 14.0f, 30.0f,
                                     glm::radians(55.0f), glm::radians(70.0f)));
    setCamera(scene, glm::vec3(-2.0f, 9.0f, 6.0f), glm::vec3(3.0f, 0.0f, 0.0f), 1.1f);
    scene.computeBounds();
    return scene;
}

Scene tiltedSpotOverPostsSeenFromAbove() {
    Scene scene = floorSeenFromAbove();
    scene.source = "tilted spot over posts, seen from above";
    for (float x = -2.5f; x <= 4.0f; x += 1.3f) {
        for (float z = -2.6f; z <= 2.7f; z += 1.3f) addBox(scene, glm::vec3(x, 0.4f, z), glm::vec3(0.08f, 0.8f, 0.08f));
    }
    scene.lights.push_back(spotLight(glm::vec3(-4.0f, 3.0f, 0.0f), glm::normalize(glm::vec3(1.0f, -1.0f, 0.0f)), 14.0f,
                                     40.0f, glm::radians(35.0f), glm::radians(45.0f)));
    scene.computeBounds();
    return scene;
}

}  // namespace punctual::testing
