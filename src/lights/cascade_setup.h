#pragma once
// The sun's cascaded shadow maps (seed: catlike-directional-cascaded-shadows.md): where the view is
// split, the sphere and orthographic view of each cascade, and its casters. The formulas are in
// shaders/shared/cascades.h, shared with the forward shader and the validation.
//
// Each cascade covers one slice of the camera's frustum, from the previous split (the camera's
// near plane for the first) to its own, bounded by the slice's smallest sphere. Its view looks
// along the sun's light and spans the sphere's diameter in both directions, so its size does not
// change as the camera turns; it is snapped to whole texels once its resolution is known
// (finishCascadeView), so it does not crawl as the camera moves. Its depth runs over the sphere
// along the light; casters between the sun and the sphere are pancaked onto the near plane (depth
// clamp), so the near plane need not reach them.
//
// Cascade views come after the points' in ShadowPlan::views and share the atlas and the budget
// with them, the most important views of the frame (the budget lowers them last).
#include <array>
#include <cstdint>

#include <glm/glm.hpp>

#include "gpu_types.h"
#include "lights/cascade_settings.h"
#include "lights/light_setup.h"
#include "scene/scene.h"
#include "scene/triangle_bvh.h"

namespace punctual {

struct ShadowPlan;
struct ShadowSettings;
struct ShadowView;

struct CascadePlan {
    uint32_t count = 0;            // cascades rendered; 0: the sun is not shadowed
    uint32_t firstView = 0;        // index of cascade 0's view in ShadowPlan::views
    uint32_t sceneLight = 0;       // the sun's index in Scene::lights
    float strength = 0.0f;         // the sun's shadow strength (its own x --shadow-strength)
    float shadowDistance = 0.0f;   // metres along the camera's axis
    bool distanceFitted = false;   // fitted to the frame's farthest visible receiver
    std::array<float, PUNCTUAL_MAX_CASCADES> splits{};      // each cascade's far end (metres)
    std::array<glm::vec4, PUNCTUAL_MAX_CASCADES> spheres{}; // culling spheres: centre, radius
    // What the forward shader selects cascades by (GpuFrame::cascadeSpheres), once sized: the
    // culling spheres shrunk by the filter's reach plus one texel (the seed's
    // "cullingSphere.w -= filterSize"), radius squared in w.
    std::array<glm::vec4, PUNCTUAL_MAX_CASCADES> selection{};
    // The sun's axes: x and y across its light, z towards the sun.
    glm::vec3 lightX{1.0f, 0.0f, 0.0f};
    glm::vec3 lightY{0.0f, 1.0f, 0.0f};
    glm::vec3 lightZ{0.0f, 0.0f, 1.0f};
};

// Where cascades 0 .. count - 1 end, in metres along the camera's axis: the settings' fractions of
// the shadow distance, or the practical scheme between the camera's near plane and it.
std::array<float, PUNCTUAL_MAX_CASCADES> cascadeSplits(const CascadeSettings& settings, float nearPlane,
                                                       float shadowDistance);

// The farthest view depth at which the frame (width x height, the scene's camera) shows a surface,
// sampled on a grid of at most 160 x 90 rays; 0 when it shows none.
// `geometry`: the scene's tree (lights/shadow_resolution.h); null builds one.
float farthestVisibleReceiver(const Scene& scene, uint32_t width, uint32_t height,
                              const LazyTriangleBvh* geometry = nullptr);

// The shadow distance the settings give: --shadow-distance, or the farthest visible receiver
// rounded up to a quarter octave (2^(k/4) metres, so that a small camera move does not change it)
// and kept within the camera's near plane and kMaxFittedShadowDistance.
float cascadeShadowDistance(const CascadeSettings& settings, const Scene& scene, uint32_t width, uint32_t height,
                            const LazyTriangleBvh* geometry = nullptr);

// Appends the sun's cascade views to `plan` (after the points') and fills plan.cascades, when
// shadows are on, the frame has a sun (lights.directionalCount) that casts shadows, and the
// settings ask for cascades. Views have casters but no resolution yet (sizeShadowViews).
void planCascades(ShadowPlan& plan, const Scene& scene, const FrameLights& lights, uint32_t width, uint32_t height,
                  const ShadowSettings& settings, const LazyTriangleBvh* geometry = nullptr);

// Once `view` (cascade view.face of plan.cascades) has its resolution: its orthographic
// view-projection, snapped to whole texels unless the settings turn snapping off, and its GPU
// parameters (span, rendered flag).
void finishCascadeView(ShadowView& view, const CascadePlan& cascades, const ShadowSettings& settings);

// The world size of a texel of cascade `index` at its resolution (0 without storage).
float cascadeTexelSize(const ShadowPlan& plan, uint32_t index);

// Fills plan.cascades.selection once every cascade has its resolution (sizeShadowViews).
void selectCascadesBy(ShadowPlan& plan, const ShadowSettings& settings);

// The cascade the forward shader reads at `position` (by CascadePlan::selection, as cascadeOf),
// cascades.count when none.
uint32_t cascadeAt(const CascadePlan& cascades, const glm::vec3& position);

// Whether `position` lies within one texel (of the inner cascade) of a split: the edge of a
// selection sphere other than the last, where the cascade read changes.
bool nearCascadeSplit(const ShadowPlan& plan, const glm::vec3& position);

}  // namespace punctual
