#include "scene/study_scenes.h"

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/box_layout.h"
#include "scene/default_scene.h"

namespace punctual::study {
namespace {

// The scene's camera at `eye` looking at `target` (y up), as a file's camera (cameraFromFile).
void placeCamera(Scene& scene, const glm::vec3& eye, const glm::vec3& target, float yfov, float znear, float zfar) {
    scene.camera.view = glm::lookAtRH(eye, target, glm::vec3(0.0f, 1.0f, 0.0f));
    scene.camera.yfov = yfov;
    scene.camera.znear = znear;
    scene.camera.zfar = zfar;
    scene.cameraFromFile = true;
}

}  // namespace

Scene floorScene(const std::string& name) {
    Scene scene;
    scene.source = name;
    Material material;
    material.name = "grey";
    material.baseColorFactor = glm::vec4(0.6f, 0.6f, 0.6f, 1.0f);
    material.metallic = 0.0f;
    material.roughness = 0.6f;
    scene.materials.push_back(material);
    addBox(scene, glm::vec3(0.0f, -0.1f, 0.0f), glm::vec3(20.0f, 0.2f, 20.0f));
    placeCamera(scene, glm::vec3(0.0f, 3.0f, 10.0f), glm::vec3(0.0f), 1.0f, 0.1f, 40.0f);
    scene.computeBounds();
    return scene;
}

void addBox(Scene& scene, const glm::vec3& center, const glm::vec3& size, uint32_t material) {
    Object object;
    object.name = "box";
    object.mesh = appendBoxMesh(scene, "box", size, material);
    object.model = glm::translate(glm::mat4(1.0f), center);
    scene.objects.push_back(object);
}

void addQuad(Scene& scene, const std::string& name, glm::vec3 center, glm::vec3 u, glm::vec3 v, float halfU,
             float halfV, uint32_t material, float uvScale, const glm::mat4& model) {
    const glm::vec3 normal = glm::normalize(glm::cross(u, v));
    Mesh mesh;
    mesh.name = name;
    mesh.firstIndex = uint32_t(scene.indices.size());
    mesh.vertexOffset = uint32_t(scene.vertices.size());
    mesh.vertexCount = 4;
    mesh.indexCount = 6;
    mesh.material = material;
    const glm::vec2 corners[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (const glm::vec2 corner : corners) {
        const glm::vec3 position = center + (corner.x * 2.0f - 1.0f) * halfU * u + (corner.y * 2.0f - 1.0f) * halfV * v;
        scene.vertices.push_back(Vertex{position, normal, corner * uvScale, corner * uvScale * 0.5f});
        mesh.localBounds.extend(position);
    }
    scene.indices.insert(scene.indices.end(), {0, 1, 2, 0, 2, 3});
    scene.meshes.push_back(mesh);
    Object object;
    object.name = name;
    object.mesh = uint32_t(scene.meshes.size() - 1);
    object.model = model;
    scene.objects.push_back(object);
}

Light pointLight(const glm::vec3& position, float range, float intensity) {
    Light light;
    light.type = LightType::Point;
    light.position = position;
    light.range = range;
    light.intensity = intensity;
    return light;
}

Light spotLight(const glm::vec3& position, const glm::vec3& direction, float range, float intensity, float innerAngle,
                float outerAngle) {
    Light light = pointLight(position, range, intensity);
    light.type = LightType::Spot;
    light.direction = glm::normalize(direction);
    light.innerConeAngle = innerAngle;
    light.outerConeAngle = outerAngle;
    return light;
}

Scene grazingLightScene() {
    Scene scene = floorScene("grazing light");
    scene.lights.push_back(spotLight({-6.0f, 0.6f, 0.0f}, {1.0f, -0.08f, 0.0f}, 16.0f, 60.0f, 0.6f, 1.2f));
    scene.lights.push_back(pointLight({5.0f, 0.5f, -2.0f}, 12.0f, 20.0f));
    scene.computeBounds();
    return scene;
}

Scene contactCasterScene() {
    Scene scene = floorScene("contact casters");
    addBox(scene, {-2.0f, 0.75f, 0.0f}, {1.5f, 1.5f, 1.5f});  // stands on the floor
    addBox(scene, {1.5f, 0.03f, 0.5f}, {2.0f, 0.02f, 1.0f});  // thin slab 2 cm above the floor
    addBox(scene, {0.0f, 0.2f, 3.0f}, {3.0f, 0.05f, 0.3f});   // thin plank on edge-height
    scene.lights.push_back(spotLight({-1.0f, 5.0f, 4.0f}, {0.2f, -1.0f, -0.6f}, 14.0f, 60.0f, 0.5f, 0.8f));
    scene.lights.push_back(pointLight({3.0f, 3.0f, 3.0f}, 10.0f, 25.0f));
    scene.computeBounds();
    return scene;
}

Scene seamScene() {
    Scene scene = floorScene("cube seams");
    for (int i = 0; i < 12; ++i) {
        const float angle = 6.2831853f * (float(i) + 0.5f) / 12.0f;
        addBox(scene, {2.2f * std::cos(angle), 1.0f, 2.2f * std::sin(angle)}, {0.3f, 2.0f, 0.3f});
    }
    scene.lights.push_back(pointLight({0.0f, 1.5f, 0.0f}, 9.0f, 30.0f));
    scene.computeBounds();
    return scene;
}

Scene pancakingScene() {
    Scene scene = floorScene("pancaking");
    // A long wall slanting from under the spot down to the floor: with the near plane pushed out,
    // its upper end lies in front of it.
    Object wall;
    wall.name = "slanted wall";
    wall.mesh = appendBoxMesh(scene, "wall", {0.2f, 4.0f, 3.0f}, 0);
    wall.model = glm::rotate(glm::translate(glm::mat4(1.0f), {0.0f, 1.9f, 0.0f}), 0.5f, glm::vec3(0.0f, 0.0f, 1.0f));
    scene.objects.push_back(wall);
    scene.lights.push_back(spotLight({-1.5f, 4.5f, 0.0f}, {0.3f, -1.0f, 0.0f}, 10.0f, 60.0f, 0.5f, 0.75f));
    scene.computeBounds();
    return scene;
}

Scene wideSpotScene(float outerAngle) {
    Scene scene = floorScene("wide spot");
    addBox(scene, {1.5f, 0.5f, 0.0f}, {1.0f, 1.0f, 1.0f});
    addBox(scene, {-4.0f, 0.5f, 1.0f}, {1.0f, 1.0f, 1.0f});
    scene.lights.push_back(spotLight({0.0f, 2.0f, 0.0f}, {0.0f, -1.0f, 0.0f}, 12.0f, 40.0f, outerAngle * 0.8f, outerAngle));
    scene.computeBounds();
    return scene;
}

Scene postsScene() {
    Scene scene = floorScene("tile depth discontinuities");
    for (int i = 0; i < 7; ++i) {
        const float x = -3.6f + 1.2f * float(i);
        addBox(scene, {x, 1.5f, 6.0f}, {0.35f, 3.0f, 0.2f});
        scene.lights.push_back(pointLight({x, 1.0f + 0.4f * float(i % 3), 6.4f}, 0.7f, 1.0f));
    }
    for (int i = 0; i < 10; ++i) {
        scene.lights.push_back(pointLight({-9.0f + 2.0f * float(i), 0.8f, -5.0f + 0.6f * float(i % 4)}, 3.0f, 12.0f));
    }
    scene.computeBounds();
    return scene;
}

Scene largeFloorScene(int lightCount) {
    Scene scene = floorScene("large floor");
    for (int i = 0; i < lightCount; ++i) {
        const float angle = 6.2831853f * float(i) / float(lightCount);
        scene.lights.push_back(pointLight({4.0f * std::cos(angle), 1.5f, 4.0f * std::sin(angle)}, 9.0f, 4.0f));
    }
    scene.computeBounds();
    return scene;
}

Scene manyLightsScene(int spotCount, int pointCount) {
    Scene scene = floorScene("many lights");
    // Deterministic placement on two spirals over the visible floor.
    for (int i = 0; i < spotCount; ++i) {
        const float t = float(i) / float(std::max(spotCount, 1));
        const float angle = 37.0f * t;
        const glm::vec3 position(6.0f * t * std::cos(angle), 3.0f, 6.0f * t * std::sin(angle) - 1.0f);
        scene.lights.push_back(spotLight(position, {0.0f, -1.0f, 0.0f}, 5.0f, 3.0f + 2.0f * t, 0.3f, 0.6f));
    }
    for (int i = 0; i < pointCount; ++i) {
        const float t = float(i) / float(std::max(pointCount, 1));
        const float angle = 23.0f * t + 1.0f;
        scene.lights.push_back(pointLight({5.5f * t * std::cos(angle), 1.2f, 5.5f * t * std::sin(angle)}, 3.5f, 1.0f + t));
    }
    scene.computeBounds();
    return scene;
}

Scene longRangeScene(float range) {
    Scene scene = floorScene("long-range lights");
    addBox(scene, {-2.0f, 0.75f, 0.0f}, {1.5f, 1.5f, 1.5f});  // stands on the floor
    addBox(scene, {1.0f, 1.0f, -1.5f}, {0.3f, 2.0f, 0.3f});   // a post
    addBox(scene, {0.5f, 1.6f, 1.5f}, {1.4f, 0.1f, 1.0f});    // a slab hanging in the air
    scene.lights.push_back(spotLight({-2.0f, 4.5f, -3.0f}, {0.3f, -1.0f, 0.7f}, range, 60.0f, 0.8f, 1.0f));
    scene.lights.push_back(pointLight({2.0f, 2.5f, 1.0f}, range, 25.0f));
    scene.computeBounds();
    return scene;
}

Scene distantGeometryScene() {
    Scene scene = longRangeScene(1e4f);
    scene.source = "long-range lights with distant geometry";
    const Light& point = scene.lights[1];
    addBox(scene, point.position + glm::vec3(3000.0f, 0.0f, 0.0f), {1.0f, 400.0f, 400.0f});  // a wall 3 km away
    const Light& spot = scene.lights[0];
    addBox(scene, spot.position + spot.direction * 5000.0f, {50.0f, 50.0f, 50.0f});  // 5 km down the cone
    scene.computeBounds();
    return scene;
}

Light sunLight(const glm::vec3& direction, float lux) {
    Light light;
    light.name = "sun";
    light.type = LightType::Directional;
    light.direction = glm::normalize(direction);
    light.intensity = lux;
    light.castsShadow = true;
    return light;
}

Scene glassPanesScene(float wallDistance) {
    Scene scene;
    scene.source = "glass panes in front of a wall";
    Material wall;
    wall.name = "wall";
    wall.baseColorFactor = glm::vec4(0.7f, 0.7f, 0.7f, 1.0f);
    wall.metallic = 0.0f;
    wall.roughness = 0.8f;
    scene.materials.push_back(wall);
    Material glass = wall;
    glass.name = "blue glass";
    glass.baseColorFactor = glm::vec4(0.3f, 0.5f, 0.9f, 0.5f);
    glass.roughness = 0.3f;
    glass.alphaMode = AlphaMode::Blend;
    glass.doubleSided = true;
    scene.materials.push_back(glass);
    Material amber = glass;
    amber.name = "amber glass";
    amber.baseColorFactor = glm::vec4(0.9f, 0.6f, 0.2f, 0.35f);
    scene.materials.push_back(amber);
    const float wallZ = -3.0f - wallDistance;
    addQuad(scene, "wall", glm::vec3(0.0f, 0.0f, wallZ), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), 2.5f * -wallZ,
            1.6f * -wallZ, 0);
    addQuad(scene, "blue pane", glm::vec3(-0.6f, 0.0f, -3.0f), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), 1.0f, 1.2f, 1);
    addQuad(scene, "amber pane", glm::vec3(0.6f, 0.2f, -4.5f), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), 1.2f, 1.0f, 2);
    for (int i = 0; i < 6; ++i) {
        const float x = -1.5f + 0.6f * float(i);
        scene.lights.push_back(pointLight(glm::vec3(x, 0.5f - 0.3f * float(i % 3), -2.4f), 1.2f, 1.5f));
        scene.lights.push_back(pointLight(glm::vec3(x + 0.3f, -0.4f, -3.9f), 1.2f, 1.5f));
    }
    scene.lights.push_back(pointLight(glm::vec3(0.0f, 2.0f, wallZ + 3.0f), 8.0f, 20.0f));  // lights the wall
    placeCamera(scene, glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, -1.0f), 0.8f, 0.1f, 4.0f - 2.0f * wallZ);
    scene.computeBounds();
    return scene;
}

Scene cascadeFieldScene() {
    Scene scene;
    scene.source = "cascade field";
    scene.materials.push_back(plainMaterial("grey", {0.6f, 0.6f, 0.6f}, 0.0f, 0.7f));
    addBox(scene, {0.0f, -0.1f, -140.0f}, {400.0f, 0.2f, 320.0f});
    // Posts along the view, ever further apart (the cascades grow): 1 m to 160 m, alternately left
    // and right, tall and short.
    float z = -1.0f;
    for (int i = 0; z > -160.0f; ++i) {
        const float side = (i % 2 == 0) ? -1.0f : 1.0f;
        const float height = (i % 3 == 0) ? 3.0f : 1.2f;
        const float width = 0.15f + 0.01f * -z;
        addBox(scene, {side * (0.8f + 0.05f * -z), 0.5f * height, z}, {width, height, width});
        z -= 0.8f + 0.12f * -z;
    }
    addBox(scene, {6.0f, 1.5f, -30.0f}, {8.0f, 3.0f, 0.4f});      // a wall across the view
    addBox(scene, {-5.0f, 1.0f, -12.0f}, {2.0f, 2.0f, 2.0f});     // a box
    // Buildings whose shadows fall sideways across the far cascades' ground.
    addBox(scene, {-12.0f, 5.0f, -65.0f}, {6.0f, 10.0f, 6.0f});
    addBox(scene, {-25.0f, 7.0f, -120.0f}, {10.0f, 14.0f, 8.0f});
    addBox(scene, {-20.0f, 10.0f, -140.0f}, {12.0f, 20.0f, 12.0f});
    addBox(scene, {15.0f, 6.0f, -150.0f}, {10.0f, 12.0f, 10.0f});
    addBox(scene, {-40.0f, 9.0f, -175.0f}, {14.0f, 18.0f, 10.0f});
    addBox(scene, {10.0f, 10.0f, -186.0f}, {20.0f, 20.0f, 6.0f});  // its shadow lies in the last cascade
    addBox(scene, {2.0f, 0.25f, -4.0f}, {0.6f, 0.5f, 0.6f});      // a low crate close by
    scene.lights.push_back(sunLight({0.7f, -0.574f, 0.42f}, 3.0f));
    scene.camera.view = glm::lookAtRH(glm::vec3(0.0f, 8.0f, 0.0f), glm::vec3(0.0f, 0.0f, -40.0f), glm::vec3(0.0f, 1.0f, 0.0f));
    // A narrower field of view than the hall's: a cascade's sphere grows with the frustum's width,
    // and at 1 radian the third sphere already reached most of the way to the shadow distance.
    scene.camera.yfov = 0.6f;
    scene.camera.znear = 0.1f;
    scene.camera.zfar = 400.0f;
    scene.cameraFromFile = true;
    scene.computeBounds();
    return scene;
}

Scene cascadePancakingScene(float deckHeight) {
    Scene scene;
    scene.source = "cascade pancaking";
    scene.materials.push_back(plainMaterial("grey", {0.6f, 0.6f, 0.6f}, 0.0f, 0.7f));
    addBox(scene, {0.0f, -0.1f, -60.0f}, {300.0f, 0.2f, 200.0f});
    // The sun travels along +x only (no z), so the deck's shadow stays on the band z = -8 .. -5 m
    // whatever its height and only slides sideways, by 1.44 x the height; the deck reaches 70 m
    // to the sun's side so that the slid shadow still crosses the whole view.
    addBox(scene, {-27.5f, deckHeight + 0.25f, -6.5f}, {85.0f, 0.5f, 3.0f});
    scene.lights.push_back(sunLight({0.82f, -0.57f, 0.0f}, 3.0f));
    placeCamera(scene, glm::vec3(0.0f, 1.7f, 0.0f), glm::vec3(0.0f, 0.0f, -12.0f), 0.6f, 0.1f, 300.0f);
    scene.computeBounds();
    return scene;
}

Scene cascadeSeamScene() {
    Scene scene;
    scene.source = "cascade seams";
    scene.materials.push_back(plainMaterial("grey", {0.6f, 0.6f, 0.6f}, 0.0f, 0.7f));
    addBox(scene, {0.0f, -0.1f, -100.0f}, {400.0f, 0.2f, 240.0f});
    // Rows of posts ever further apart, five across the view's width at their depth and shifted
    // along it from row to row (so that near posts do not hide the rows behind), growing with depth
    // so that each spans a few pixels, each casting a shadow about 0.6 x its depth long away from the
    // camera: shadows cross every split of the view.
    int row = 0;
    for (float depth = 3.0f; depth < 180.0f; depth *= 1.25f, ++row) {
        const float halfWidth = 0.55f * depth;  // the view's half width at that depth (yfov 0.6, 16:9)
        const float width = 0.05f + 0.01f * depth;
        const float height = 0.5f + 0.2f * depth;
        const float shift = 0.38f * float(row % 5) - 0.76f;  // -0.76 .. 0.76 of the fifth of the width
        for (const float across : {-0.8f, -0.4f, 0.0f, 0.4f, 0.8f}) {
            addBox(scene, {(across + 0.2f * shift) * halfWidth, 0.5f * height, -depth}, {width, height, width});
        }
    }
    // Behind the camera and a little to its left, 17 degrees high: long shadows.
    scene.lights.push_back(sunLight({0.2f, -0.3f, -0.93f}, 3.0f));
    placeCamera(scene, glm::vec3(0.0f, 1.7f, 0.0f), glm::vec3(0.0f, 0.0f, -15.0f), 0.6f, 0.1f, 300.0f);
    scene.computeBounds();
    return scene;
}

}  // namespace punctual::study
