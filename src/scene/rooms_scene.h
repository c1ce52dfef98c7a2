#pragma once
// The built-in procedural scene (`--scene rooms`, sized by `--scene-triangles N`): a grid of
// furnished rooms without ceilings, seen from above one corner, for measuring how costs grow with
// the geometry. From 10^4 to 10^7 triangles the rooms, the objects and the tessellation grow
// together: about N^0.875 / 10^3.5 rooms (1 at 10^4, 422 at 10^7), each with a floor, two walls
// with door openings, a column, crates (2 at 10^4, 8 at 10^7), a table with a vase on it, a barrel
// and a planter of alpha-masked foliage cards; the round things are lathes whose segment and ring
// counts take up the rest of the target, so the triangle count lands within 2% of it. Lit by
// 64 spots and 32 points in the rooms the camera sees, and a dim sun. Every object has a mesh of
// its own (memory grows linearly with the triangles, about 50 bytes each). Like the other
// built-in scenes it is the same bit for bit on every run and platform for the same target:
// fixed seeds, sqrt only, angles from unitCircle (scene/procedural_meshes.h).
#include <cstdint>

#include "scene/scene.h"

namespace punctual {

namespace rooms_scene {
constexpr const char* kSource = "built-in rooms scene";
constexpr uint64_t kMinTriangles = 10'000;
constexpr uint64_t kMaxTriangles = 10'000'000;
constexpr uint64_t kDefaultTriangles = 100'000;
constexpr float kRoomSide = 8.0f;  // each room is kRoomSide x kRoomSide metres, walls included
constexpr float kWallHeight = 3.0f;

// What a target asks for; roomsLayoutFor(T) is what makeRoomsScene(T) builds.
struct Layout {
    uint32_t rooms = 1;
    uint32_t columns = 1;        // rooms along +x; the last row along +z may be short
    uint32_t rows = 1;
    uint32_t cratesPerRoom = 2;
    uint32_t segments = 12;      // around every lathe
    uint32_t rings = 2;          // profile points of the vase and the barrel
    uint64_t triangles = 0;      // what the layout comes to
};
// Throws Error("--scene-triangles", ...) for a target outside kMinTriangles .. kMaxTriangles.
Layout layoutFor(uint64_t targetTriangles);
}  // namespace rooms_scene

Scene makeRoomsScene(uint64_t targetTriangles = rooms_scene::kDefaultTriangles);

}  // namespace punctual
