#include "culling_test_scenes.h"

#include <cmath>

#include "gpu_types.h"
#include "scene/default_scene.h"
#include "scene/light_generator.h"
#include "scene/study_scenes.h"

namespace punctual::testing {

// Every scene stands on study::floorScene's 20 x 20 m floor at y = 0, seen from (0, 3, 10)
// looking at (0, 0, 0).
using study::addBox;
using study::floorScene;
using study::pointLight;
using study::spotLight;

std::vector<NamedScene> adversarialCullingScenes() {
    std::vector<NamedScene> scenes;
    {
        // Lights whose spheres cut the near plane: one centred between the eye and the near
        // plane, one just behind the eye, and a spot just in front of it shining forward.
        Scene scene = floorScene("light straddling the near plane");
        const glm::vec3 eye(0.0f, 3.0f, 10.0f);
        scene.lights.push_back(pointLight(eye + glm::vec3(0.3f, -0.2f, -0.05f), 6.0f, 40.0f));
        scene.lights.push_back(
            withColor(pointLight(eye + glm::vec3(-1.0f, -0.5f, 0.5f), 5.0f, 30.0f), glm::vec3(1.0f, 0.5f, 0.3f)));
        scene.lights.push_back(withColor(spotLight(eye + glm::vec3(0.0f, 0.0f, -0.08f), glm::vec3(0.0f, -0.3f, -1.0f),
                                                   14.0f, 80.0f, 0.2f, 0.5f),
                                         glm::vec3(0.4f, 0.6f, 1.0f)));
        scenes.push_back({scene.source, scene});
    }
    {
        // The camera inside a big point light's range and inside a spot's cone.
        Scene scene = floorScene("camera inside a light's range");
        scene.lights.push_back(pointLight(glm::vec3(1.0f, 2.0f, 8.0f), 25.0f, 30.0f));
        scene.lights.push_back(withColor(spotLight(glm::vec3(0.0f, 4.0f, 14.0f), glm::vec3(0.0f, -0.35f, -1.0f), 25.0f,
                                                   60.0f, 0.3f, 0.6f),
                                         glm::vec3(1.0f, 0.8f, 0.6f)));
        scenes.push_back({scene.source, scene});
    }
    {
        // Spots whose cones are seen edge-on: axes across the view direction, narrow cones
        // grazing the floor, so the lit region is a long thin wedge in screen space, and one
        // shining straight at the camera's side of the floor from above it.
        Scene scene = floorScene("spot cone seen edge-on");
        scene.lights.push_back(spotLight(glm::vec3(-9.0f, 1.5f, 1.0f), glm::vec3(1.0f, -0.2f, 0.0f), 18.0f, 150.0f,
                                         0.1f, 0.22f));
        scene.lights.push_back(withColor(spotLight(glm::vec3(9.0f, 1.2f, 4.0f), glm::vec3(-1.0f, -0.15f, 0.0f), 16.0f,
                                                   120.0f, 0.05f, 0.15f),
                                         glm::vec3(1.0f, 0.4f, 0.4f)));
        scene.lights.push_back(withColor(spotLight(glm::vec3(0.0f, 6.0f, 0.0f), glm::vec3(0.0f, -0.5f, 1.0f), 15.0f,
                                                   80.0f, 0.1f, 0.35f),
                                         glm::vec3(0.4f, 1.0f, 0.4f)));
        scenes.push_back({scene.source, scene});
    }
    {
        // A row of thin posts near the camera in front of a far floor: the tiles on each post's
        // edges span from 6 m to 20 m. Small lights hug the posts' faces and others light only the
        // far floor, so a tile's whole depth column touches lights that reach none of its pixels.
        // A third set floats in the gap, 8 m from the eye, behind each post's right edge on screen
        // (twice the post's distance, twice its x) and 1.3 m up with a 1 m range: they reach no
        // surface at all, yet sit inside the depth columns of the tiles on the posts' edges.
        Scene scene = floorScene("tile columns spanning a near wall and a far floor");
        for (int i = 0; i < 7; ++i) {
            const float x = -3.6f + 1.2f * float(i);
            addBox(scene, glm::vec3(x, 1.5f, 6.0f), glm::vec3(0.35f, 3.0f, 0.2f));
            scene.lights.push_back(withColor(pointLight(glm::vec3(x, 1.0f + 0.4f * float(i % 3), 6.4f), 0.7f, 1.0f),
                                             glm::vec3(1.0f, 0.6f, 0.3f)));
            scene.lights.push_back(pointLight(glm::vec3(2.0f * (x + 0.175f), 1.3f, 2.0f), 1.0f, 1.0f));
        }
        for (int i = 0; i < 10; ++i) {
            scene.lights.push_back(withColor(
                pointLight(glm::vec3(-9.0f + 2.0f * float(i), 0.8f, -5.0f + 0.6f * float(i % 4)), 3.0f, 12.0f),
                glm::vec3(0.3f, 0.6f, 1.0f)));
        }
        scenes.push_back({scene.source, scene});
    }
    {
        // All 96 lights (the caps: 64 spots and 32 points) overlap one spot on the floor.
        Scene scene = floorScene("all 96 lights overlapping one spot");
        for (int i = 0; i < PUNCTUAL_DEFAULT_MAX_SPOT_LIGHTS; ++i) {
            const float angle = 6.2831853f * float(i) / float(PUNCTUAL_DEFAULT_MAX_SPOT_LIGHTS);
            const glm::vec3 position(3.0f * std::cos(angle), 4.0f + 0.02f * float(i), 3.0f * std::sin(angle));
            scene.lights.push_back(
                withColor(spotLight(position, glm::vec3(0.0f) - position, 9.0f, 0.6f, 0.2f, 0.45f),
                          glm::vec3(0.5f + 0.5f * std::cos(angle), 0.7f, 0.5f + 0.5f * std::sin(angle))));
        }
        for (int i = 0; i < PUNCTUAL_DEFAULT_MAX_POINT_LIGHTS; ++i) {
            const float angle = 6.2831853f * float(i) / float(PUNCTUAL_DEFAULT_MAX_POINT_LIGHTS);
            scene.lights.push_back(pointLight(glm::vec3(1.5f * std::cos(angle), 1.0f, 1.5f * std::sin(angle)), 4.0f, 0.3f));
        }
        scenes.push_back({scene.source, scene});
    }
    for (NamedScene& named : scenes) named.scene.computeBounds();
    return scenes;
}

Scene largeFloorScene(int lightCount) {
    Scene scene = floorScene("large floor under overlapping lights");
    for (int i = 0; i < lightCount; ++i) {
        const float angle = 6.2831853f * float(i) / float(lightCount);
        scene.lights.push_back(
            withColor(pointLight(glm::vec3(4.0f * std::cos(angle), 1.5f, 4.0f * std::sin(angle)), 9.0f, 4.0f),
                      glm::vec3(0.6f + 0.4f * std::cos(angle), 0.8f, 0.6f + 0.4f * std::sin(angle))));
    }
    scene.computeBounds();
    return scene;
}

Scene manyLightsScene(uint32_t spots, uint32_t points) {
    Scene scene = makeDefaultScene();
    scene.computeBounds();
    replaceLights(scene, spots, points, 7, LightRange{LightRange::Kind::ConstantDensity, 0.0f});
    return scene;
}

}  // namespace punctual::testing
