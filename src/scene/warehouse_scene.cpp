#include "scene/warehouse_scene.h"

#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/box_layout.h"
#include "scene/light_generator.h"

namespace punctual {
namespace {

using namespace warehouse_scene;

constexpr float kWallThickness = 0.2f;
constexpr float kDoorway = 2.0f;  // the gap in the middle of every inner wall
constexpr float kSide = kRoomsPerSide * kRoomSize;
enum Materials : uint32_t { kFloor, kWall, kRack };

void addMaterials(Scene& scene) {
    scene.materials.push_back(plainMaterial("concrete floor", glm::vec3(0.55f, 0.55f, 0.52f), 0.0f, 0.85f));
    scene.materials.push_back(plainMaterial("partition", glm::vec3(0.7f, 0.68f, 0.62f), 0.0f, 0.7f));
    scene.materials.push_back(plainMaterial("steel rack", glm::vec3(0.35f, 0.4f, 0.5f), 0.6f, 0.45f));
}

// A wall along one grid line from `from` to `to` (along x when `alongX`, else along z), at
// `line` on the other axis, with the doorway cut out of its middle when `door`.
void addWall(std::vector<BoxSpec>& boxes, bool alongX, float line, float from, float to, bool door) {
    const float half = 0.5f * kWallThickness;
    auto box = [&](float a, float b) {
        const glm::vec3 min = alongX ? glm::vec3(a, 0.0f, line - half) : glm::vec3(line - half, 0.0f, a);
        const glm::vec3 max = alongX ? glm::vec3(b, kWallHeight, line + half) : glm::vec3(line + half, kWallHeight, b);
        boxes.push_back({"partition", min, max, kWall});
    };
    if (!door) {
        box(from, to);
        return;
    }
    const float middle = 0.5f * (from + to);
    box(from, middle - 0.5f * kDoorway);
    box(middle + 0.5f * kDoorway, to);
}

std::vector<BoxSpec> warehouseLayout() {
    std::vector<BoxSpec> boxes;
    boxes.push_back({"floor", glm::vec3(-1.0f, -0.2f, -1.0f), glm::vec3(kSide + 1.0f, 0.0f, kSide + 1.0f), kFloor});
    for (uint32_t line = 0; line <= kRoomsPerSide; ++line) {
        const bool outer = line == 0 || line == kRoomsPerSide;
        for (uint32_t room = 0; room < kRoomsPerSide; ++room) {
            const float from = float(room) * kRoomSize;
            addWall(boxes, true, float(line) * kRoomSize, from, from + kRoomSize, !outer);
            addWall(boxes, false, float(line) * kRoomSize, from, from + kRoomSize, !outer);
        }
    }
    // Two racks a room, 6 m x 1 m x 2.4 m, turned a quarter in every other room.
    for (uint32_t i = 0; i < kRoomsPerSide; ++i) {
        for (uint32_t j = 0; j < kRoomsPerSide; ++j) {
            const glm::vec2 corner(float(i) * kRoomSize, float(j) * kRoomSize);
            const bool turned = (i + j) % 2 == 1;
            const glm::vec2 facing = turned ? glm::vec2(0.0f, 1.0f) : glm::vec2(1.0f, 0.0f);
            for (const float offset : {3.0f, 7.0f}) {
                const glm::vec2 centre = corner + (turned ? glm::vec2(offset, 5.0f) : glm::vec2(5.0f, offset));
                boxes.push_back(standing("rack", centre.x, centre.y, glm::vec3(6.0f, 2.4f, 1.0f), kRack, facing));
            }
        }
    }
    return boxes;
}

// Above the corner at the origin, 50 m up, looking at the grid's middle: every room is in view,
// near rooms seen steeply, far ones at a grazing angle over the walls.
void addCamera(Scene& scene) {
    Camera& camera = scene.camera;
    camera.name = "warehouse";
    camera.view = glm::lookAtRH(glm::vec3(-12.0f, 50.0f, -12.0f), glm::vec3(0.4f * kSide, 0.0f, 0.4f * kSide),
                                glm::vec3(0.0f, 1.0f, 0.0f));
    camera.yfov = 1.04719755f;  // 60 degrees
    camera.znear = 0.5f;
    camera.zfar = farthestViewDepth(scene.bounds, camera.view) + 1.0f;
    scene.cameraFromFile = true;
}

// Per room, a 4 x 8 grid of spots 3.2 m up shining straight down (outer cone 40-55 degrees, range
// 5 m, 0.08-0.16 lux on the floor below each), and under them a 4 x 8 grid of points 2.6 m up
// (range 3.5 m, 0.05-0.1 lux below each). A floor point lies in about 11 spots' cones (each
// covers some 36 m^2 of the 100 m^2 room) and 5 points' reach (17 m^2 each): about 1.5 lux in
// all, mid-grey at exposure 1 once every lamp is kept. Each lights about its own room: a wall
// between rooms stops the rest.
void addLamps(Scene& scene) {
    constexpr float kDegree = 0.0174532925f;
    PortableRandom random(0x7761726568ull);  // "wareh": any fixed value works
    // A lamp of room (i, j) hanging at `position`, shining down, its colour drawn first.
    const auto lamp = [&](LightType type, const char* kind, uint32_t i, uint32_t j, uint32_t k, glm::vec3 position) {
        Light light;
        light.name = "room " + std::to_string(i) + "," + std::to_string(j) + " " + kind + " " + std::to_string(k);
        light.type = type;
        light.position = position;
        light.direction = glm::vec3(0.0f, -1.0f, 0.0f);
        light.color = randomLightColor(random);
        light.castsShadow = true;
        return light;
    };
    std::vector<Light> spots;
    std::vector<Light> points;
    for (uint32_t i = 0; i < kRoomsPerSide; ++i) {
        for (uint32_t j = 0; j < kRoomsPerSide; ++j) {
            const glm::vec2 corner(float(i) * kRoomSize, float(j) * kRoomSize);
            for (uint32_t k = 0; k < kSpotsPerRoom; ++k) {
                Light light = lamp(LightType::Spot, "spot", i, j, k,
                                   glm::vec3(corner.x + 1.25f + 2.5f * float(k % 4), 3.2f, corner.y + 0.625f + 1.25f * float(k / 4)));
                light.outerConeAngle = random.uniform(40.0f, 55.0f) * kDegree;
                light.innerConeAngle = light.outerConeAngle * 0.6f;
                light.range = 5.0f;
                light.intensity = intensityForIlluminance(random.uniform(0.08f, 0.16f), 3.2f, light.range);
                spots.push_back(light);
            }
            for (uint32_t k = 0; k < kPointsPerRoom; ++k) {
                Light light = lamp(LightType::Point, "point", i, j, k,
                                   glm::vec3(corner.x + 1.25f + 2.5f * float(k % 4), 2.6f, corner.y + 1.15f + 1.1f * float(k / 4)));
                light.range = 3.5f;
                light.intensity = intensityForIlluminance(random.uniform(0.05f, 0.1f), 2.6f, light.range);
                points.push_back(light);
            }
        }
    }
    scene.lights = std::move(spots);
    scene.lights.insert(scene.lights.end(), points.begin(), points.end());
}

}  // namespace

Scene makeWarehouseScene() {
    Scene scene;
    scene.source = kSource;
    addMaterials(scene);
    addBoxes(scene, warehouseLayout());
    scene.computeBounds();
    addCamera(scene);
    addLamps(scene);
    return scene;
}

}  // namespace punctual
