#pragma once
// What a frame needs, decided on the CPU before anything is allocated (the renderer's first step):
// the camera's matrices, the lights culled, ranked, capped and packed, the shadow views sized to
// their receivers within the budget (a request the device cannot hold fails here, in one line),
// the sun's cascades, the per-object lists or z-bins a method reads, the light grid's layout and
// the objects the camera sees. The Renderer (renderer.h) then allocates and records exactly this.
#include <cstdint>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "culling.h"
#include "lights/light_setup.h"
#include "lights/per_object_lights.h"
#include "lights/shadow_setup.h"
#include "lights/z_bins.h"
#include "render/light_culling_pass.h"
#include "render/render_settings.h"
#include "scene/scene.h"

namespace punctual::vk {
class Context;
}

namespace punctual::render {

struct FramePlan {
    glm::mat4 view{1.0f};
    glm::mat4 projection{1.0f};
    FrameLights lights;
    ShadowPlan shadows;
    PerObjectLightLists perObjectLists;  // empty unless the method reads per-object lists
    std::optional<ZBins> zBins;          // the z-bin methods' bins; nullopt for the others
    LightGridLayout gridLayout;
    std::vector<uint32_t> objectsInView;  // every object with RenderSettings::cullObjectsToView off
    // Whether the culling kernels read the transparent fragments' depth spans (the transparent
    // depth pass, GpuFrame::transparentSpans): a grid method, alphaMode BLEND objects in view, and
    // not RenderSettings::opaqueCullingDepth.
    bool transparentSpans = false;
};

// Plans the frame of `scene` under `settings` on `context`'s device (its subgroups and memory
// limits). Warns once when the shadow budget reduced views (settings.warnReducedShadows).
FramePlan planFrame(const vk::Context& context, const Scene& scene, const RenderSettings& settings);

// The cells the method's light lists are a function of (forward.frag, pixelListCell): one for brute
// force, the scene's objects (per-object), the grid's cells, or its cells times the z-bins.
uint32_t listCellCount(const Scene& scene, const RenderSettings& settings, const FramePlan& plan);

// The lights' culling shapes in view space (the same function the CPU re-cull of the tests uses).
std::vector<gpu::CullLight> viewCullLights(const FrameLights& frameLights, const glm::mat4& view);

}  // namespace punctual::render
