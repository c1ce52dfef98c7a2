#include "scene/engine_scene.h"

#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/box_layout.h"
#include "scene/light_generator.h"

namespace punctual {
namespace {

using namespace engine_scene;

enum Materials : uint32_t { kFloor, kCasting, kSteel };

void addMaterials(Scene& scene) {
    scene.materials.push_back(plainMaterial("workshop floor", glm::vec3(0.5f, 0.5f, 0.48f), 0.0f, 0.8f));
    scene.materials.push_back(plainMaterial("cast aluminium", glm::vec3(0.75f, 0.74f, 0.7f), 0.3f, 0.55f));
    scene.materials.push_back(plainMaterial("steel", glm::vec3(0.45f, 0.47f, 0.5f), 0.6f, 0.4f));
}

constexpr float kCrankcaseTop = 0.7f;
constexpr float kCylinderPitch = 0.22f;  // cylinder centres along x
constexpr float kFinSide = 0.2f;         // a fin's square, 2 cm apart from the next cylinder's

// Four legs and the rails between them, under the crankcase.
void addStand(std::vector<BoxSpec>& boxes) {
    for (const float x : {-0.45f, 0.45f}) {
        for (const float z : {-0.25f, 0.25f}) boxes.push_back(standing("stand leg", x, z, glm::vec3(0.03f, 0.35f, 0.03f), kSteel));
        boxes.push_back({"stand rail", glm::vec3(x - 0.015f, 0.12f, -0.25f), glm::vec3(x + 0.015f, 0.15f, 0.25f), kSteel});
    }
}

// Each cylinder: a core and its fins, then an exhaust pipe out towards +z and down to the floor.
void addCylinders(std::vector<BoxSpec>& boxes) {
    for (uint32_t c = 0; c < kCylinders; ++c) {
        const float x = (float(c) - 0.5f * float(kCylinders - 1)) * kCylinderPitch;
        boxes.push_back(standing("cylinder core", x, 0.0f, glm::vec3(0.1f, 0.27f, 0.1f), kCasting, {1.0f, 0.0f}, kCrankcaseTop));
        for (uint32_t f = 0; f < kFinsPerCylinder; ++f) {
            const float y = kCrankcaseTop + 0.01f + float(f) * kFinPitch;
            boxes.push_back(standing("cooling fin", x, 0.0f, glm::vec3(kFinSide, kFinThickness, kFinSide), kCasting, {1.0f, 0.0f}, y));
        }
        boxes.push_back({"exhaust pipe", glm::vec3(x - 0.0125f, 0.85f, 0.05f), glm::vec3(x + 0.0125f, 0.875f, 0.42f), kSteel});
        boxes.push_back({"exhaust pipe", glm::vec3(x - 0.0125f, 0.45f, 0.42f), glm::vec3(x + 0.0125f, 0.875f, 0.445f), kSteel});
    }
    // Two pushrod tubes along the heads.
    for (const float z : {-0.03f, 0.03f}) {
        boxes.push_back({"pushrod tube", glm::vec3(-0.45f, 0.98f, z - 0.006f), glm::vec3(0.45f, 0.992f, z + 0.006f), kSteel});
    }
}

// A radiator grille beside the engine (-x): vertical bars in a frame.
void addGrille(std::vector<BoxSpec>& boxes) {
    const float x = -0.75f;
    const float half = 0.5f * kGrilleBarWidth;
    for (uint32_t b = 0; b < kGrilleBars; ++b) {
        const float z = -0.3f + float(b) * 0.03f;
        boxes.push_back({"grille bar", glm::vec3(x - half, 0.2f, z - half), glm::vec3(x + half, 0.8f, z + half), kSteel});
    }
    for (const float y : {0.18f, 0.8f}) {
        boxes.push_back({"grille frame", glm::vec3(x - 0.01f, y, -0.32f), glm::vec3(x + 0.01f, y + 0.02f, 0.32f), kSteel});
    }
    for (const float z : {-0.32f, 0.32f}) boxes.push_back(standing("grille post", x, z, glm::vec3(0.02f, 0.82f, 0.02f), kSteel));
}

std::vector<BoxSpec> engineLayout() {
    std::vector<BoxSpec> boxes;
    boxes.push_back({"floor", glm::vec3(-1.5f, -0.05f, -1.5f), glm::vec3(1.5f, 0.0f, 1.5f), kFloor});
    addStand(boxes);
    boxes.push_back({"crankcase", glm::vec3(-0.5f, 0.35f, -0.28f), glm::vec3(0.5f, kCrankcaseTop, 0.28f), kCasting});
    addCylinders(boxes);
    addGrille(boxes);
    return boxes;
}

// A three-quarter view from the exhaust side, about 2 m away, down onto the fins and the grille.
void addCamera(Scene& scene) {
    Camera& camera = scene.camera;
    camera.name = "engine";
    camera.view = glm::lookAtRH(glm::vec3(0.8f, 1.3f, 1.05f), glm::vec3(-0.2f, 0.6f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f));
    camera.yfov = 1.04719755f;  // 60 degrees
    camera.znear = 0.05f;
    camera.zfar = farthestViewDepth(scene.bounds, camera.view) + 0.5f;
    scene.cameraFromFile = true;
}

}  // namespace

Scene makeEngineScene() {
    Scene scene;
    scene.source = kSource;
    addMaterials(scene);
    addBoxes(scene, engineLayout());
    scene.computeBounds();
    addCamera(scene);
    replaceLights(scene, kSpots, kPoints, kLightSeed);
    return scene;
}

}  // namespace punctual
