#include "render/frame_plan.h"

#include <cmath>

#include <algorithm>
#include <string>

#include "core/log.h"
#include "lights/shadow_page_allocation.h"
#include "lights/cascade_setup.h"
#include "lights/shadow_sizing.h"
#include "lights/view_objects.h"
#include "render/light_list_method.h"
#include "render/shadow_maps.h"
#include "vk/context.h"

namespace punctual::render {
namespace {

// The shadow plan: spot and point views, the sun's cascades, every view's resolution.
ShadowPlan planFrameShadows(const vk::Context& context, const Scene& scene, FrameLights& lights,
                            const RenderSettings& settings) {
    ShadowPlan plan = planShadows(scene, lights, scene.camera.position(), settings.shadows);
    // Built on the first ray a planner casts, then shared (at 10^7 triangles a build takes
    // seconds), and freed before the frame's resources are allocated (peak memory).
    const LazyTriangleBvh geometry(scene);
    if (settings.cascadeCamera) {
        // The study's other camera: a copy of the scene seen from it (the cascades read its
        // camera, its objects as casters and, for a fitted distance, its visible receivers).
        Scene moved = scene;
        moved.camera = *settings.cascadeCamera;
        planCascades(plan, moved, lights, settings.width, settings.height, settings.shadows, &geometry);
    } else {
        planCascades(plan, scene, lights, settings.width, settings.height, settings.shadows, &geometry);
    }
    // Sized before anything is allocated: a request the device cannot hold fails here, in one line.
    sizeShadowViews(plan, scene, lights, scene.camera.position(), settings.width, settings.height, settings.shadows,
                    ShadowMaps::memoryLimits(context, settings.shadows), &geometry);
    // What the forward shader's virtualReadLevel reads of the camera (shadow_pages.glsl); unread
    // without virtual pages.
    const glm::mat4 cameraToWorld = glm::inverse(scene.camera.view);
    plan.virtualReads = {settings.shadows.virtualPages(), glm::vec3(cameraToWorld[3]),
                         -glm::normalize(glm::vec3(cameraToWorld[2])),
                         2.0f * std::tan(scene.camera.yfov * 0.5f) / float(settings.height),
                         settings.shadows.texelsPerPixel};
    usePreviousPageMarks(plan, lights, settings.shadows);
    if (!plan.reductions.empty() && settings.warnReducedShadows) {
        log::warn("shadows: " + std::to_string(plan.reductions.size()) + " view(s) got less resolution than " +
                  "their receivers need, to fit " + plan.reducedBy + " (the stats' shadows.reduced lists them)");
    }
    return plan;
}

}  // namespace

std::vector<gpu::CullLight> viewCullLights(const FrameLights& frameLights, const glm::mat4& view) {
    std::vector<gpu::CullLight> cullLights;
    for (const gpu::GpuPunctualLight& light : frameLights.packed) cullLights.push_back(gpu::makeCullLight(light, view));
    return cullLights;
}

uint32_t listCellCount(const Scene& scene, const RenderSettings& settings, const FramePlan& plan) {
    switch (methodInfo(settings.method).source.value) {
        case PUNCTUAL_LIGHT_SOURCE_OBJECT: return std::max<uint32_t>(uint32_t(scene.objects.size()), 1u);
        case PUNCTUAL_LIGHT_SOURCE_GRID: return plan.gridLayout.cellCount();
        case PUNCTUAL_LIGHT_SOURCE_GRID_ZBINS: return plan.gridLayout.cellCount() * PUNCTUAL_ZBIN_COUNT;
        default: return 1;  // brute force: one list for the screen
    }
}

FramePlan planFrame(const vk::Context& context, const Scene& scene, const RenderSettings& settings) {
    FramePlan plan;
    plan.view = scene.camera.view;
    plan.projection = scene.camera.projection(float(settings.width) / float(settings.height));
    plan.lights = setupFrameLights(scene, plan.view, plan.projection, settings.maxLights);
    plan.shadows = planFrameShadows(context, scene, plan.lights, settings);
    const LightListMethodInfo& method = methodInfo(settings.method);
    if (method.objectLists()) plan.perObjectLists = buildPerObjectLightLists(scene, plan.lights);
    plan.gridLayout = LightGridLayout::forMethod(method, settings.width, settings.height, settings.tileSize,
                                                 settings.clusterSlices, settings.coarseTiles,
                                                 settings.tileThreads ? settings.tileThreads : context.subgroupSize(),
                                                 settings.subgroupTiles && context.computeSubgroupArithmetic());
    // One bit per light the frame keeps (not per light it could keep): a frame under its capacity
    // holds and walks no empty words.
    plan.gridLayout.gridWords = gpu::gridWordsOf(plan.lights.spotCount + plan.lights.pointCount);
    plan.gridLayout.indexLists = method.usesLightGrid() && settings.lightLists == LightListForm::Indices;
    if (method.zBins()) {
        plan.zBins = buildZBins(viewCullLights(plan.lights, plan.view), glm::vec2(plan.projection[3][2], plan.projection[2][2]));
    }
    if (settings.cullObjectsToView) {
        plan.objectsInView = objectsInView(scene, plan.projection * plan.view);
    } else {
        plan.objectsInView.resize(scene.objects.size());
        for (uint32_t i = 0; i < plan.objectsInView.size(); ++i) plan.objectsInView[i] = i;
    }
    const bool blendedInView = std::any_of(plan.objectsInView.begin(), plan.objectsInView.end(), [&](uint32_t object) {
        return scene.materials.at(scene.meshes.at(scene.objects[object].mesh).material).alphaMode == AlphaMode::Blend;
    });
    plan.transparentSpans = method.usesLightGrid() && !settings.opaqueCullingDepth && blendedInView;
    return plan;
}

}  // namespace punctual::render
