#pragma once
// The built-in outdoor scene (`--scene outdoor`): a street under a low sun, the case that needs
// cascaded sun shadows. Casters range from a fence rail under a metre from the eye to buildings
// 150-300 m away, all on one 500 m x 500 m ground, so no single shadow map of the sun can give
// both ends texels of a useful size. Street lamps (16 spots) and bollards (16 points) light parts
// of the street too. Like the hall (scene/default_scene.h) it needs no file and is identical bit
// for bit on every run and platform: fixed positions, fixed-seed colours, no trigonometry.
#include <optional>

#include "scene/scene.h"
#include "scene/scene_path.h"

namespace punctual {

namespace outdoor_scene {
constexpr const char* kSource = "built-in outdoor scene";
// The ground's top surface is the plane y = 0 over |x| <= kGroundHalfWidth and
// kGroundNearZ >= z >= kGroundFarZ (the camera stands at z = 0 and looks towards -z).
constexpr float kGroundHalfWidth = 250.0f;
constexpr float kGroundNearZ = 100.0f;
constexpr float kGroundFarZ = -400.0f;
// The drive's length (poseOutdoorScene): 60 m at 6 m/s.
constexpr float kDriveSeconds = 10.0f;
}  // namespace outdoor_scene

Scene makeOutdoorScene();

// Poses the street at `time` seconds of its drive (scene/scene_path.h): the camera moves 60 m
// down the street at eye height, looking ahead; the lights stand still (or `motion.lights` of them
// sway, scene/scene_path.h's addSwayingLights; `motion.casters` of the props lift). At 0, the
// still street.
void poseOutdoorScene(Scene& scene, double time, const PathMotion& motion = {});

}  // namespace punctual
