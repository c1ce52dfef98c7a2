#pragma once
// Temporal stability of shadows (issue 34): between two consecutive frames of a sequence, the
// shadow tests whose state flipped where nothing that decides them changed. On a static receiver
// lit by a light that did not move the ray-traced truth cannot change from frame to frame, so a
// change of the GPU's state there is an artifact: a texel grid that slid (a cascade following the
// camera), a resolution tier or a page level that switched, a filter that rounds the other way.
//
// Each pixel of the current frame is reprojected into the previous frame's camera; where that
// pixel saw the same surface point (within two pixels' world size: the receiver is static there
// and not occluded in either frame), each light that did not move and reaches the point in both
// frames is compared: counted where the ray-traced truth agrees at the two points (both lit or
// both shadowed) and the previous frame's pixel lies inside a region (its 3 x 3 neighbours share
// its GPU state and its truth), so that an edge the sub-pixel offset between the two samples
// crosses does not count, and a flip where the GPU's states differ. A shadow edge that crawls by
// less than a pixel is therefore not counted; one that jumps (a tier or a level that switched, a
// texel grid that slid by a texel of several pixels) is. The sun counts as a light (its cascades follow the camera).
// Generalises the cascades study's shimmer count (bench "failures") to every light and mode.
#include <cstdint>
#include <map>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "metrics/shadow_factor_image.h"
#include "lights/shadow_setup.h"
#include "reference/shadow_validation.h"
#include "scene/scene.h"

namespace punctual::reference {

// What one validated frame leaves for the next.
struct StabilityFrame {
    glm::mat4 viewProjection{1.0f};  // the camera's, at the frame's aspect
    float pixelSpanAtUnitDepth = 0.0f;
    glm::mat4 view{1.0f};
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<glm::vec3> positions;  // per pixel, world space
    std::vector<uint8_t> covered;
    std::map<uint32_t, std::vector<PixelVerdict>> verdicts;  // by scene light index (the sun's included)
    std::vector<Light> lights;                               // the scene's, to tell which moved
    // By scene light index: its views' resolutions (a spot's one, a point's six faces, the sun's
    // cascades), to tell the flips that come with a resized map (recordMapResolutions; empty: not
    // told).
    std::map<uint32_t, std::vector<uint32_t>> mapResolutions;
};

StabilityFrame stabilityFrame(const Scene& scene, const ShadowFactorImage& factors, const ShadowValidation& validation);

// Fills frame.mapResolutions from the frame's shadow plan (`sceneLightIndex`: FrameLights's, from
// packed light to scene light; the sun's cascades under `sunLight`, the scene's directional light).
void recordMapResolutions(StabilityFrame& frame, const ShadowPlan& plan, const std::vector<uint32_t>& sceneLightIndex,
                          std::optional<uint32_t> sunLight);

struct ShadowFlips {
    uint64_t compared = 0;  // (pixel, light) tests on the same static point with an unchanged truth
    uint64_t flips = 0;     // of them, where the GPU's state changed
    // Of the flips, those of a light whose maps changed resolution between the frames (a tier or,
    // for the sun, a cascade refitted): the rest flipped under maps of the same size, where the
    // texels slid (a cascade following the camera) or the samples moved across a texel's error.
    uint64_t flipsWhereMapsResized = 0;

    double rate() const { return compared ? double(flips) / double(compared) : 0.0; }
};

// The flips from `previous` to `current` (same frame size).
ShadowFlips countShadowFlips(const StabilityFrame& previous, const StabilityFrame& current);

}  // namespace punctual::reference
