#pragma once
// The built-in scene used when no glTF file is given: a 40 m x 30 m hall built from boxes (floor,
// walls, pillars, crates), a fixed camera and 64 spot + 32 point lights. It needs no file and is
// identical bit for bit on every run and platform (fixed-seed, library-independent randomness).
#include <cstdint>
#include <string>

#include <glm/glm.hpp>

#include <optional>

#include "scene/scene.h"
#include "scene/scene_path.h"

namespace punctual {

namespace default_scene {
// The floor's top surface is the plane y = 0 over |x| <= kFloorHalfWidth, |z| <= kFloorHalfDepth.
constexpr float kFloorHalfWidth = 20.0f;
constexpr float kFloorHalfDepth = 15.0f;
// The aspect ratio the camera and the light placement are designed for (all lights in view).
constexpr float kDesignAspect = 16.0f / 9.0f;
constexpr const char* kSource = "built-in default scene";
// The walk's length (poseDefaultScene): 12 s, keyframes every 3.
constexpr float kWalkSeconds = 12.0f;
// The share of its lamps that sway along the walk (scene/scene_path.h, movingLights): every sixth.
constexpr double kMovingLightShare = 1.0 / 6.0;
}  // namespace default_scene

Scene makeDefaultScene();

// Poses the hall at `time` seconds of its walk (scene/scene_path.h): the camera walks down into
// the hall and along its left aisle, and 16 of the 96 lamps sway 1 m either way (`motion.lights`
// of them: movingLights, default kMovingLightShare; `motion.casters` of its crates lift). At 0,
// the still hall; past kWalkSeconds, the walk's end.
void poseDefaultScene(Scene& scene, double time, const PathMotion& motion = {});

// Appends an axis-aligned box of the given full `size`, centred on the origin of its own mesh
// space, as a new mesh (24 vertices, one flat normal and a 0..1 UV square per face, 12
// counter-clockwise triangles seen from outside) and returns its mesh index. Place it with an
// Object's model matrix.
uint32_t appendBoxMesh(Scene& scene, const std::string& name, const glm::vec3& size, uint32_t material);

}  // namespace punctual
