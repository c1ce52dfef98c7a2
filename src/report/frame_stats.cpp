#include "report/frame_stats.h"

#include <bit>
#include <cstdio>

#include "core/memory_usage.h"
#include "lights/shadow_sizing.h"
#include "lights/view_objects.h"

namespace punctual::report {

nlohmann::json geometryStatsJson(const render::Renderer& renderer, const Scene& scene) {
    std::vector<uint32_t> everyObject(scene.objects.size());
    for (uint32_t i = 0; i < everyObject.size(); ++i) everyObject[i] = i;
    const render::CameraDraws& camera = renderer.cameraDraws();
    const render::ShadowDraws shadows = renderer.shadowDraws();
    return {{"triangles", scene.triangleCount()},
            {"triangles_instanced", trianglesOf(scene, everyObject)},
            {"objects", scene.objects.size()},
            {"objects_in_view", camera.objectsInView},
            {"camera_triangles", camera.triangles},
            {"camera_draws", {{"depth", camera.depthDraws},
                              {"forward", camera.forwardDraws},
                              {"transparent", camera.transparentDraws}}},
            {"camera_pass_triangles", {{"depth", camera.depthTriangles},
                                       {"forward", camera.forwardTriangles},
                                       {"transparent", camera.transparentTriangles}}},
            {"shadow_draws", {{"total", shadows.total}, {"max_per_view", shadows.maxPerView}}},
            {"shadow_triangles", shadows.triangles}};
}

nlohmann::json frameStatsJson(const render::FrameResult& result, const render::Renderer& renderer,
                              const Scene& scene, const std::string& deviceName, uint32_t frames) {
    const render::PassTimings& ms = result.medianMs;
    const FrameLights& lights = renderer.lights();
    nlohmann::json stats;
    stats["scene"] = scene.source;
    stats["device"] = deviceName;
    stats["size"] = {{"width", renderer.settings().width}, {"height", renderer.settings().height}};
    stats["frames"] = frames;
    // Every pass under its own name, then the whole frame.
    nlohmann::json gpuMs = nlohmann::json::object();
    for (const auto& [pass, passMs] : ms.passes) gpuMs[pass] = passMs;
    gpuMs["total"] = ms.total;
    stats["gpu_ms"] = gpuMs;
    stats["lights"] = {{"spot", lights.spotCount},
                       {"point", lights.pointCount},
                       {"directional", lights.directionalCount},
                       {"culled_by_frustum", lights.culledByFrustum},
                       {"dropped_by_cap", lights.droppedByCap},
                       {"in_scene", scene.lights.size()}};
    stats["triangles"] = scene.triangleCount();
    stats["objects"] = scene.objects.size();
    stats["geometry"] = geometryStatsJson(renderer, scene);
    const render::DeviceMemory memory = renderer.deviceMemory();
    stats["memory"] = {{"peak_rss_bytes", peakResidentBytes()},
                       {"device_bytes", memory.total()},
                       {"scene_bytes", memory.scene},
                       {"shadow_bytes", memory.shadows},
                       {"light_grid_bytes", memory.lightGrid},
                       // The lists alone (masks, or headers and indices), beside the floor.
                       {"light_list_bytes", renderer.lightListBytes()},
                       {"frame_bytes", memory.frame}};
    return stats;
}

uint64_t lightGridFloorBytes(render::Renderer& renderer) {
    uint64_t entries = 0;
    for (const uint32_t word : renderer.readLightGrid()) entries += uint64_t(std::popcount(word));
    return entries * kLightIndexBytes;
}

nlohmann::json cullingStatsJson(const CullingStats& stats, const render::Renderer& renderer) {
    const render::RenderSettings& settings = renderer.settings();
    nlohmann::json json = {
        {"method", render::methodName(settings.method)},
        {"light_lists", render::usesLightGrid(settings.method) ? render::lightListFormName(settings.lightLists) : ""},
        {"tested_per_pixel", stats.testedPerPixel},
        {"affecting_per_pixel", stats.affectingPerPixel},
        // The shadow work of the method's lights: filtered reads and the taps they issued.
        {"shadow_lookups_per_pixel", stats.shadowLookupsPerPixel},
        {"shadow_taps_per_pixel", stats.shadowTapsPerPixel},
        {"efficiency", stats.efficiency},
        // Exact lists at the method's granularity (its tiles, clusters, tile and z-bin pairs or
        // objects): the efficiency no conservative method of that granularity beats.
        {"floor_efficiency", stats.floorEfficiency},
        {"max_tested", stats.maxTested},
        {"max_affecting", stats.maxAffecting},
        {"missed_energy", stats.missedEnergy},
        {"pixels_missing_light", stats.pixelsMissingLight},
        {"covered_pixels", stats.coveredPixels},
        // The alphaMode BLEND fragments, counted apart from the opaque pixels under them.
        {"transparent_fragments", stats.transparentFragments},
        {"transparent_tested_per_fragment", stats.transparentTestedPerFragment},
        {"transparent_affecting_per_fragment", stats.transparentAffectingPerFragment},
        {"transparent_fragments_missing_light", stats.transparentFragmentsMissingLight},
    };
    if (render::usesLightGrid(settings.method)) {
        const render::LightGridLayout& grid = renderer.gridLayout();
        json["tile_size"] = grid.tileSize;
        json["slices"] = grid.slices;
        json["cells"] = grid.cellCount();
        json["coarse_tiles"] = grid.coarseTiles;  // fine tiles a side of a coarse tile; 0: no coarse pass
        json["tile_threads"] = grid.tileThreads;  // the culling kernel's invocations per tile
        json["tile_kernel"] = grid.subgroupKernel ? "subgroup" : "shared-memory";  // tile_/cluster_culling.comp or light_culling.comp
    }
    if (render::methodInfo(settings.method).objectLists()) {
        json["per_object"] = {{"objects_over_cap", renderer.perObjectLists().objectsOverCap},
                              {"max_candidates", renderer.perObjectLists().maxCandidates}};
    }
    return json;
}

namespace {

// The scene light a view shadows: the packed light's, or the sun's for a cascade.
uint32_t viewSceneLight(const ShadowView& view, const ShadowPlan& plan, const FrameLights& lights) {
    return view.isCascade ? plan.cascades.sceneLight : lights.sceneLightIndex[view.packedLight];
}

// The sun's cascades: how many, where they split (metres along the camera's axis), and each one's
// sphere, resolution and texel size (metres).
nlohmann::json cascadeStatsJson(const ShadowPlan& plan, const ShadowSettings& settings) {
    const CascadePlan& cascades = plan.cascades;
    nlohmann::json splits = nlohmann::json::array();
    nlohmann::json list = nlohmann::json::array();
    for (uint32_t i = 0; i < cascades.count; ++i) {
        const ShadowView& view = plan.views[cascades.firstView + i];
        splits.push_back(cascades.splits[i]);
        list.push_back({{"far_m", cascades.splits[i]},
                        {"radius_m", cascades.spheres[i].w},
                        {"resolution", view.resolution},
                        {"texel_m", cascadeTexelSize(plan, i)},
                        {"casters", view.casters.size()},
                        {"rendered", view.rendered()}});
    }
    return {{"cascades", cascades.count},
            {"cascade_splits", splits},
            {"shadow_distance_m", cascades.shadowDistance},
            {"shadow_distance_fitted", cascades.distanceFitted},
            {"cascade_blend", cascadeBlendName(settings.cascades.blend)},
            {"cascade_list", list}};
}

}  // namespace

nlohmann::json shadowStatsJson(const render::Renderer& renderer) {
    const ShadowSettings& settings = renderer.settings().shadows;
    const ShadowPlan& plan = renderer.shadowPlan();
    const FrameLights& lights = renderer.lights();
    nlohmann::json views = nlohmann::json::array();
    for (const ShadowView& view : plan.views) {
        nlohmann::json entry = {{"light", viewSceneLight(view, plan, lights)},
                                {"type", view.isCascade ? "cascade" : view.isPoint ? "point face" : "spot"},
                                {"face", view.face},
                                {"resolution", view.resolution},
                                {"rendered", view.rendered()},
                                {"casters", view.casters.size()}};
        if (settings.autoResolution()) {
            entry["demand"] = view.demand;
            entry["demanded_resolution"] = view.demandedTier;
        }
        views.push_back(std::move(entry));
    }
    nlohmann::json reduced = nlohmann::json::array();
    for (const ShadowReduction& reduction : plan.reductions) {
        const ShadowView& view = plan.views[reduction.view];
        reduced.push_back({{"light", viewSceneLight(view, plan, lights)},
                           {"face", view.face},
                           {"demanded", reduction.demanded},
                           {"granted", reduction.granted}});
    }
    nlohmann::json tiers = nlohmann::json::object();  // "1024": views at 1024 x 1024, ...
    for (const auto& [resolution, count] : shadowTierCounts(plan)) tiers[std::to_string(resolution)] = count;
    nlohmann::json json = {
        {"enabled", settings.enabled},
        {"mode", settings.autoResolution() ? shadowResolutionName(settings) : "fixed"},
        {"resolution", settings.autoResolution() ? nlohmann::json(shadowResolutionName(settings)) : nlohmann::json(settings.resolution)},
        {"tiers", tiers},
        {"format", shadowFormatName(settings.format)},
        {"budget_bytes", settings.autoResolution() ? plan.budgetBytes : 0},
        {"memory_bytes", renderer.shadowMemoryBytes()},
        {"atlas", {{"width", plan.atlas.width}, {"height", plan.atlas.height}}},
        {"texels_rendered", shadowTexelsRendered(plan)},
        {"filter", shadowFilterName(settings.filter)},
        {"filter_taps", settings.filterTaps()},
        {"samples", settings.diskSamples},
        {"penumbra", settings.diskRadius},
        {"bias", {settings.bias.x, settings.bias.y, settings.bias.z, settings.bias.w}},
        {"receiver_plane", settings.receiverPlane},
        {"strength", settings.strength},
        {"point_layout", pointShadowLayoutName(settings.pointLayout)},
        {"shadowed_spots", plan.shadowedSpots},
        {"shadowed_points", plan.shadowedPoints},
        {"dropped_by_cap", plan.droppedByCap},
        {"unshadowed_lights", plan.unshadowedLights(renderer.lights().spotCount + renderer.lights().pointCount)},
        {"views_rendered", plan.viewsRendered},
        {"views_skipped", plan.viewsSkipped},
        // The same counts under the names of the shadow design: a spot's view is its one face.
        {"faces_rendered", plan.viewsRendered},
        {"faces_skipped", plan.viewsSkipped},
        {"reduced", reduced},
        {"reduced_by", plan.reducedBy},
        {"views", views},
    };
    json.update(cascadeStatsJson(plan, settings));
    if (settings.autoResolution()) {
        json["receiver_samples"] = plan.receiverSamples;
        json["receiver_sample_step_px"] = plan.sampleStep;
    }
    return json;
}

nlohmann::json virtualPagesJson(const render::Renderer& renderer, uint64_t shadedPairs) {
    const uint32_t texelBytes = renderer.settings().shadows.texelBytes();
    const ShadowPageAllocation& allocation = renderer.shadowPages();
    const render::ShadowPageStats& stats = renderer.shadowPageStats();
    const render::Renderer::ShadowPageDrawCounts draws = renderer.shadowPageDraws();
    const uint64_t floorBytes = shadedPairs * texelBytes;
    const uint64_t physical = allocation.physicalBytes(texelBytes);
    return {{"virtual_size", PUNCTUAL_VIRTUAL_SHADOW_SIZE},
            {"page_texels", PUNCTUAL_VIRTUAL_SHADOW_PAGE},
            {"slot_texels", PUNCTUAL_VIRTUAL_SHADOW_SLOT},
            {"levels", PUNCTUAL_VIRTUAL_SHADOW_LEVELS},
            {"pages_marked", stats.marked.total()},
            {"pages_marked_per_level", stats.marked.perLevel},
            {"pages_allocated", allocation.pages.size()},
            {"pages_allocated_per_level", allocation.pagesPerLevel},
            {"pages_coarsened", stats.coarsenedPages},
            {"views_coarsened", stats.coarsenedViews},
            {"marking_frames", stats.markingFrames},
            {"pages_drawn", draws.pagesDrawn},
            {"draws", draws.draws},
            {"instances", draws.instances},
            {"physical_bytes", physical},
            {"page_table_bytes", allocation.tableBytes()},
            {"marks_bytes", stats.marksBytes},
            {"shaded_pairs", shadedPairs},
            {"floor_bytes", floorBytes},
            {"over_floor", floorBytes ? double(physical + allocation.tableBytes()) / double(floorBytes) : 0.0},
            {"allocate_ms", stats.allocateMs}};
}

nlohmann::json virtualPageEstimateJson(const VirtualPageEstimate& estimate, const render::Renderer& renderer) {
    const uint32_t texelBytes = renderer.settings().shadows.texelBytes();
    const uint64_t floorBytes = estimate.floorBytes(texelBytes);
    // The whole views' atlas of this frame (spot views and point slices; cascades apart).
    const ShadowPlan& plan = renderer.shadowPlan();
    const uint64_t atlasBytes = uint64_t(plan.atlas.width) * plan.atlas.height * texelBytes;
    nlohmann::json layouts = nlohmann::json::array();
    for (const VirtualPageDemand& demand : estimate.layouts) {
        const uint64_t bytes = demand.physicalBytes(texelBytes) + demand.usedLevelsPageTableBytes();
        layouts.push_back({{"virtual_size", demand.layout.virtualSize},
                           {"page_size", demand.layout.pageSize},
                           {"levels", demand.layout.levels()},
                           {"pages_marked", demand.markedPages()},
                           {"pages_under_receivers", demand.centrePages},
                           {"pages_per_level", demand.markedPerLevel},
                           {"views_with_pages", demand.viewsWithPages},
                           {"physical_bytes", demand.physicalBytes(texelBytes)},
                           {"page_table_bytes", demand.pageTableBytes()},
                           {"used_levels_page_table_bytes", demand.usedLevelsPageTableBytes()},
                           {"over_floor", floorBytes ? double(bytes) / double(floorBytes) : 0.0},
                           {"over_atlas", atlasBytes ? double(bytes) / double(atlasBytes) : 0.0},
                           {"pairs_coarser_than_asked", demand.pairsCoarserThanAsked}});
    }
    return {{"shaded_pairs", estimate.shadedPairs},
            {"floor_bytes", floorBytes},
            {"atlas_bytes", atlasBytes},
            {"layouts", layouts}};
}

std::string timingTable(const render::PassTimings& ms) {
    std::string table = "pass        GPU ms\n";
    auto row = [&](const char* name, double value) {
        char line[64];
        std::snprintf(line, sizeof(line), "%-10s %8.3f\n", name, value);
        table += line;
    };
    for (const auto& [pass, passMs] : ms.passes) row(pass.c_str(), passMs);
    row("total", ms.total);
    return table;
}

std::string frameLightsLine(const FrameLights& lights, const LightCapacity& capacity) {
    return "lights: " + std::to_string(lights.spotCount) + " spot, " + std::to_string(lights.pointCount) + " point, " +
           std::to_string(lights.directionalCount) + " directional (" + std::to_string(lights.culledByFrustum) +
           " outside the view, " + std::to_string(lights.droppedByCap) + " over the capacity, --max-lights " +
           std::to_string(capacity.spots) + "," + std::to_string(capacity.points) + ")";
}

std::string droppedLightsLine(const render::Renderer& renderer) {
    const FrameLights& lights = renderer.lights();
    const LightCapacity& capacity = renderer.settings().maxLights;
    if (lights.droppedByCap == 0) return "";
    return "lights over the capacity: " + std::to_string(lights.droppedByCap) + " dropped, " +
           std::to_string(lights.spotCount + lights.pointCount) + " kept, the most important (--max-lights " +
           std::to_string(capacity.spots) + "," + std::to_string(capacity.points) + ")";
}

std::string unshadowedLightsLine(const render::Renderer& renderer) {
    const ShadowSettings& settings = renderer.settings().shadows;
    const ShadowPlan& plan = renderer.shadowPlan();
    const uint32_t lights = renderer.lights().spotCount + renderer.lights().pointCount;
    const uint32_t unshadowed = plan.unshadowedLights(lights);
    if (!settings.enabled || unshadowed == 0) return "";
    return "lights without a shadow: " + std::to_string(unshadowed) + " of " + std::to_string(lights) + " (" +
           std::to_string(plan.droppedByCap) + " over --shadowed " + std::to_string(settings.maxShadowedSpots) + "," +
           std::to_string(settings.maxShadowedPoints) + ", " + std::to_string(unshadowed - plan.droppedByCap) +
           " cast none); the shadow figures count the shadowed only";
}

}  // namespace punctual::report
