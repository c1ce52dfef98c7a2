#pragma once
// Sizing a shadow plan: each view's resolution and its place in the storage, then the GPU records.
// Fixed mode gives every view with a caster --shadow-res N; auto mode asks the estimator
// (lights/shadow_resolution.h) for each view's tier and fits the tiers to the budget
// (lights/shadow_budget.h) and the atlas (lights/shadow_atlas.h). Apart from shadow_setup.h so that
// planning (which lights, which casters, near and far) does not depend on the estimator that
// reads the plan.
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "lights/light_setup.h"
#include "lights/shadow_setup.h"
#include "scene/scene.h"
#include "scene/triangle_bvh.h"

namespace punctual {

// What the device can hold of the shadow maps: all of them together (`total`, named by
// `totalName`, e.g. "the device's largest heap"), the atlas's side (maxImageDimension2D) and
// bytes (maxResourceSize), and the cube array's bytes.
struct ShadowMemoryLimits {
    uint64_t total = std::numeric_limits<uint64_t>::max();
    std::string totalName = "the device's largest heap";
    uint32_t atlasSide = 16384;
    uint64_t atlasBytes = std::numeric_limits<uint64_t>::max();
    uint64_t cubeArrayBytes = std::numeric_limits<uint64_t>::max();
};

// Gives every view of `plan` its resolution and storage, and fills the GPU views:
//  - fixed mode: every view with a caster at settings.resolution; throws Error("--shadow-res N",
//    ...) saying what is needed, what the device has and the largest resolution that fits when
//    the maps do not fit `limits` (before anything is allocated);
//  - auto mode: each view its demanded tier from the receivers the frame shows (frameWidth x
//    frameHeight, see shadow_resolution.h), fitted to min(budget, what the device has).
void sizeShadowViews(ShadowPlan& plan, const Scene& scene, const FrameLights& lights, const glm::vec3& cameraPosition,
                     uint32_t frameWidth, uint32_t frameHeight, const ShadowSettings& settings,
                     const ShadowMemoryLimits& limits, const LazyTriangleBvh* geometry = nullptr);

// Each view's light's rank by importance (lightImportance; 0: the sun's cascades, then 1 for the
// most important light), which orders the budget's reductions.
std::vector<uint32_t> shadowViewRanks(const ShadowPlan& plan, const Scene& scene, const FrameLights& lights,
                                      const glm::vec3& cameraPosition);

// Bytes of the fixed-mode maps of `plan` at `resolution` texels a side: the atlas (spots and
// slices) with its drawing square, and the cube array. A lower bound of what the device allocates (it may pad).
uint64_t shadowMapBytes(const ShadowPlan& plan, const ShadowSettings& settings, uint32_t resolution);

// The resolutions the rendered views of `plan` use, largest first, each with how many views use
// it; and the same as text, e.g. "4 x 1024, 18 x 512, 40 x 256" ("none" for no view).
std::vector<std::pair<uint32_t, uint32_t>> shadowTierCounts(const ShadowPlan& plan);
std::string describeShadowTiers(const ShadowPlan& plan);

// Texels drawn into by the rendered views of `plan` (the sum of their squares).
uint64_t shadowTexelsRendered(const ShadowPlan& plan);

}  // namespace punctual
