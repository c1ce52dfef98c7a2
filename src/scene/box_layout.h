#pragma once
// The parts the built-in scenes are made of: plain materials and boxes standing on a floor,
// optionally turned about their vertical axis. Every built-in scene (scene/builtin_scenes.h) is a
// list of these plus its camera and lights, so a new scene writes only its layout.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace punctual {

// One box of a layout: world-space extents before an optional turn about its vertical centre
// axis. The turn is given as the world (x, z) direction of the box's own +X axis, not as an angle,
// so it needs no sin/cos (whose last bit may differ between maths libraries).
struct BoxSpec {
    const char* name;
    glm::vec3 min;
    glm::vec3 max;
    uint32_t material;
    glm::vec2 facing{1.0f, 0.0f};
};

// A box standing on the plane y = baseY, centred at (x, z), of the given full size.
BoxSpec standing(const char* name, float x, float z, glm::vec3 size, uint32_t material,
                 glm::vec2 facing = {1.0f, 0.0f}, float baseY = 0.0f);

// A metallic-roughness material with a base colour and no texture.
Material plainMaterial(const char* name, glm::vec3 color, float metallic, float roughness);

// Appends each box as a mesh of its own (appendBoxMesh) and an object placing it: turned to
// `facing`, then moved to the centre of its extents. Call Scene::computeBounds() afterwards.
void addBoxes(Scene& scene, const std::vector<BoxSpec>& boxes);

// The intensity (cd) that gives `lux` at `distance` from a light of `range`, by the renderer's
// own distance attenuation (shaders/shared/shading.h): how the built-in scenes set their lamps.
float intensityForIlluminance(float lux, float distance, float range);

// The largest view depth (distance along the view axis) of the corners of `bounds`: a far
// plane just beyond it keeps all of the scene in view.
float farthestViewDepth(const Bounds& bounds, const glm::mat4& view);

}  // namespace punctual
