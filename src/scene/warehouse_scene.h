#pragma once
// The built-in warehouse (`--scene warehouse`): the regime of thousands of lights. An 8 x 8 grid
// of 10 m rooms under an open roof, partition walls 3.5 m high with a doorway in every inner
// wall, two racks in every room, and 64 lamps a room: 4,096 lights, 2,048 spots and 2,048
// points, each reaching about its own room. The camera looks down across the grid from above a
// corner, so that every room's floor, the tops of the walls and the racks stand in front of one
// another: depth discontinuities in almost every screen tile, where tile, cluster and 2.5D
// culling part ways. Like the other built-in scenes it is identical bit for bit on every run and
// platform: fixed positions, fixed-seed colours, no trigonometry. Until the light capacity grows
// beyond the design notes' 64 + 32 (issue 32), a frame keeps the most important of its lights
// and says how many it dropped.
#include <cstdint>

#include "scene/scene.h"

namespace punctual {

namespace warehouse_scene {
constexpr const char* kSource = "built-in warehouse scene";
constexpr uint32_t kRoomsPerSide = 8;
constexpr float kRoomSize = 10.0f;      // metres between wall centres
constexpr float kWallHeight = 3.5f;
constexpr uint32_t kSpotsPerRoom = 32;  // a 4 x 8 grid under the roof line
constexpr uint32_t kPointsPerRoom = 32;
}  // namespace warehouse_scene

Scene makeWarehouseScene();

}  // namespace punctual
