#pragma once
// The built-in engine (`--scene engine`): a model with thin parts, the case where a whole shadow
// view's one resolution fails (issue 33). An air-cooled four-cylinder engine on a stand: each
// cylinder a stack of square cooling fins 6 mm thick with 14 mm gaps, a radiator grille of 8 mm
// bars 30 mm apart, exhaust pipes and rods, over a 3 m x 3 m floor, lit by 64 spots and 32 points
// generated around it (--lights 64,32 with a fixed seed, as a user would light a model). The
// camera stands about 2 m away, where a fin is 2-3 pixels thick at 1280x720: a fin's shadow needs
// texels of a few millimetres on the receivers near it and far coarser ones elsewhere in the same
// view. Identical bit for bit on every run and platform: fixed positions and seed, no
// trigonometry.
#include <cstdint>

#include "scene/scene.h"

namespace punctual {

namespace engine_scene {
constexpr const char* kSource = "built-in engine scene";
constexpr uint32_t kCylinders = 4;
constexpr uint32_t kFinsPerCylinder = 13;
constexpr float kFinThickness = 0.006f;  // metres
constexpr float kFinPitch = 0.02f;       // fin to fin: a 14 mm gap
constexpr uint32_t kGrilleBars = 21;
constexpr float kGrilleBarWidth = 0.008f;
constexpr uint32_t kSpots = 64;  // the design notes' 64 + 32, generated
constexpr uint32_t kPoints = 32;
constexpr uint64_t kLightSeed = 0x656e67696e65ull;  // "engine": any fixed value works
}  // namespace engine_scene

Scene makeEngineScene();

}  // namespace punctual
