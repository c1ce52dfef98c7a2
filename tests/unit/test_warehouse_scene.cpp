// The built-in warehouse: deterministic, 4,096 lamps, 64 in each of its 8 x 8 rooms below the
// tops of the walls, a doorway in every inner wall, every room in the camera's view, and lamps
// that light what the camera sees. Measured on the scene's own objects and lights.
#include <gtest/gtest.h>

#include <cmath>

#include "scene/light_reach.h"
#include "scene/warehouse_scene.h"
#include "scene_test_support.h"

namespace punctual {
namespace {

using namespace warehouse_scene;

const Scene& warehouse() {
    static const Scene scene = makeWarehouseScene();
    return scene;
}

bool insideAnyObject(const Scene& scene, const glm::vec3& p) {
    for (const Object& object : scene.objects) {
        const Bounds& b = object.worldBounds;
        if (glm::all(glm::greaterThanEqual(p, b.min)) && glm::all(glm::lessThanEqual(p, b.max))) return true;
    }
    return false;
}

TEST(WarehouseScene, Deterministic) {
    EXPECT_EQ(testing::firstSceneDifference(makeWarehouseScene(), makeWarehouseScene()), "");
}

TEST(WarehouseScene, SixtyFourLampsInEveryRoomBelowTheWallTops) {
    const Scene& scene = warehouse();
    EXPECT_EQ(scene.source, kSource);
    const uint32_t rooms = kRoomsPerSide * kRoomsPerSide;
    ASSERT_EQ(scene.lights.size(), size_t(rooms) * (kSpotsPerRoom + kPointsPerRoom));
    EXPECT_GE(scene.lights.size(), 4096u);
    std::vector<uint32_t> perRoom(rooms, 0);
    size_t spots = 0;
    for (size_t i = 0; i < scene.lights.size(); ++i) {
        const Light& light = scene.lights[i];
        const bool spot = light.type == LightType::Spot;
        spots += spot;
        // Spots first, then points (the packed order the frame keeps).
        EXPECT_EQ(spot, i < size_t(rooms) * kSpotsPerRoom) << i;
        const int x = int(std::floor(light.position.x / kRoomSize));
        const int z = int(std::floor(light.position.z / kRoomSize));
        ASSERT_TRUE(x >= 0 && x < int(kRoomsPerSide) && z >= 0 && z < int(kRoomsPerSide)) << light.name;
        ++perRoom[size_t(z) * kRoomsPerSide + size_t(x)];
        EXPECT_LT(light.position.y, kWallHeight) << light.name;  // the walls part the rooms' lights
        EXPECT_GT(light.range, 0.0f);
        EXPECT_LE(light.range, kRoomSize) << light.name;  // it reaches about its own room
    }
    EXPECT_EQ(spots, size_t(rooms) * kSpotsPerRoom);
    for (uint32_t count : perRoom) EXPECT_EQ(count, kSpotsPerRoom + kPointsPerRoom);
}

TEST(WarehouseScene, EveryInnerWallHasADoorway) {
    const Scene& scene = warehouse();
    size_t checked = 0;
    for (uint32_t line = 1; line < kRoomsPerSide; ++line) {
        for (uint32_t room = 0; room < kRoomsPerSide; ++room) {
            const float across = float(line) * kRoomSize;
            const float middle = (float(room) + 0.5f) * kRoomSize;
            for (const bool alongX : {true, false}) {
                const auto at = [&](float along) {
                    return alongX ? glm::vec3(along, 1.0f, across) : glm::vec3(across, 1.0f, along);
                };
                EXPECT_FALSE(insideAnyObject(scene, at(middle))) << "no doorway at line " << line << ", room " << room;
                EXPECT_TRUE(insideAnyObject(scene, at(middle + 3.0f))) << "no wall at line " << line << ", room " << room;
                ++checked;
            }
        }
    }
    EXPECT_EQ(checked, size_t(2 * (kRoomsPerSide - 1) * kRoomsPerSide));
}

TEST(WarehouseScene, TheCameraSeesEveryRoom) {
    const Scene& scene = warehouse();
    const glm::mat4 viewProjection = scene.camera.projection(16.0f / 9.0f) * scene.camera.view;
    for (uint32_t i = 0; i < kRoomsPerSide; ++i) {
        for (uint32_t j = 0; j < kRoomsPerSide; ++j) {
            const glm::vec4 clip =
                viewProjection * glm::vec4((float(i) + 0.5f) * kRoomSize, 0.0f, (float(j) + 0.5f) * kRoomSize, 1.0f);
            ASSERT_GT(clip.w, 0.0f);
            const glm::vec3 ndc = glm::vec3(clip) / clip.w;
            EXPECT_LE(std::abs(ndc.x), 1.0f) << i << "," << j;
            EXPECT_LE(std::abs(ndc.y), 1.0f) << i << "," << j;
        }
    }
}

// Lamps light what the camera sees. LightReach samples the view in a square of the vertical field
// of view (scene/light_reach.h), so the lamps checked are those of rooms whose centre lies in that
// square; a fine grid of samples, since each room holds a small share of the view and a lamp
// reaches only its own room's floor and walls. Rooms seen at a grazing angle (the far ones, and
// the corners at the view's sides) have part of their floor hidden by the wall nearer the camera,
// and a spot that lights only that part lights nothing in view: measured, 14 of the 216 lamps
// sampled, in rooms (0,7), (6,1) and past the grid's diagonal. At least 90% must reach.
TEST(WarehouseScene, LampsLightWhatTheCameraSees) {
    const Scene& scene = warehouse();
    const LightReach reach(scene, 96);
    ASSERT_FALSE(reach.empty());
    const glm::mat4 square = scene.camera.projection(1.0f) * scene.camera.view;
    const auto inSquare = [&](const Light& light) {
        const glm::vec2 room = (glm::floor(glm::vec2(light.position.x, light.position.z) / kRoomSize) + 0.5f) * kRoomSize;
        const glm::vec4 clip = square * glm::vec4(room.x, 0.0f, room.y, 1.0f);
        return clip.w > 0.0f && std::abs(clip.x) <= clip.w && std::abs(clip.y) <= clip.w;
    };
    size_t reaching = 0;
    size_t sampled = 0;
    for (size_t i = 0; i < scene.lights.size(); i += 19) {  // a spread sample of spots and points
        const Light& light = scene.lights[i];
        if (!inSquare(light)) continue;
        reaching += reach.reaches(light);
        ++sampled;
    }
    EXPECT_GT(sampled, 100u);
    EXPECT_GE(double(reaching), 0.9 * double(sampled)) << reaching << " of " << sampled;
}

}  // namespace
}  // namespace punctual
