#include "bench/bench_rows.h"

#include <algorithm>
#include <sstream>

#include "report/frame_stats.h"
#include "report/validation_report.h"
#include "core/memory_usage.h"
#include "lights/cascade_setup.h"
#include "lights/shadow_sizing.h"
#include "metrics/culling_stats.h"
#include "reference/embree_scene.h"
#include "reference/shadow_validation.h"

namespace punctual::bench {
namespace {

std::string sunCascadeColumn(uint32_t cascade) { return "sun_cascade" + std::to_string(cascade) + "_misclassified_1px"; }

size_t lightsOfType(const Scene& scene, LightType type) {
    return size_t(std::count_if(scene.lights.begin(), scene.lights.end(), [&](const Light& l) { return l.type == type; }));
}

}  // namespace

std::string benchNumber(double value) {
    std::ostringstream s;
    s.precision(6);
    s << value;
    return s.str();
}

std::vector<std::string> benchColumns(const std::vector<std::string>& passes) {
    std::vector<std::string> columns = {"config",        "series",          "method",         "spot",
                                        "point",         "light_range",     "width",          "height",
                                        "pixels",        "scene",           "scene_triangles", "objects",
                                        "shadows",       "shadow_res",      "shadow_budget_mib", "shadow_format",
                                        "shadow_filter", "point_layout",    "cascades",       "shadowed_spots",
                                        "shadowed_points", "coarse_tiles",  "tile_kernel",    "tile_threads",
                                        "light_lists",
                                        "rounds",        "best_of"};
    std::vector<std::string> timed = passes;
    timed.emplace_back("total");
    for (const char* statistic : {"_ms", "_iqr_ms", "_cv"}) {
        for (const std::string& pass : timed) columns.push_back(pass + statistic);
    }
    for (const char* column :
         {"flagged", "flag_reason", "tested_per_pixel", "affecting_per_pixel", "shadow_lookups_per_pixel",
          "filter_taps_per_pixel", "shadow_views", "shadow_texels_rendered", "shadow_filter_taps", "objects_in_view",
          "camera_triangles", "depth_triangles", "forward_triangles", "transparent_triangles", "shadow_triangles",
          "depth_draws", "forward_draws", "transparent_draws", "shadow_draws", "shadow_draws_max",
          "shadow_memory_bytes", "shadow_floor_bytes", "shadow_pages", "shadow_pages_coarsened", "shadow_allocate_ms",
          "light_grid_bytes", "light_list_bytes", "light_grid_floor_bytes", "scene_bytes", "frame_bytes", "device_bytes", "peak_rss_bytes",
          "efficiency", "floor_efficiency", "missed_energy", "image_error", "pixels_off", "shadow_reduced_views", "shadow_misclassified",
          "shadow_misclassified_all", "shadow_misclassified_1px", "shadow_false_shadow", "shadow_false_lit",
          "sun_misclassified", "sun_misclassified_1px"}) {
        columns.emplace_back(column);
    }
    // The sun's error per cascade, outside a one-pixel edge band (empty beyond the row's count).
    for (uint32_t i = 0; i < PUNCTUAL_MAX_CASCADES; ++i) columns.push_back(sunCascadeColumn(i));
    return columns;
}

void addConfiguration(BenchRow& row, const BenchConfig& config, const Scene& scene, const render::Renderer& renderer,
                      uint32_t rounds, uint32_t bestOf) {
    const render::RenderSettings& settings = renderer.settings();
    const ShadowPlan& plan = renderer.shadowPlan();
    row["config"] = benchConfigName(config);
    row["series"] = config.series;
    row["method"] = render::methodName(config.method);
    // Fine tiles a side of the coarse pass's big tiles; 0: none (methods without a grid, or off).
    row["coarse_tiles"] = std::to_string(renderer.gridLayout().coarseTiles);
    // The grid methods' culling kernel (README: tile_culling.comp or light_culling.comp) and its
    // invocations a tile; empty for the methods without a grid.
    if (render::usesLightGrid(config.method)) {
        row["tile_kernel"] = renderer.gridLayout().subgroupKernel ? "subgroup" : "shared-memory";
        row["tile_threads"] = std::to_string(renderer.gridLayout().tileThreads);
        row["light_lists"] = render::lightListFormName(settings.lightLists);
    }
    row["spot"] = std::to_string(lightsOfType(scene, LightType::Spot));
    row["point"] = std::to_string(lightsOfType(scene, LightType::Point));
    if (!config.scene) row["light_range"] = benchNumber(config.lightRange);
    row["width"] = std::to_string(settings.width);
    row["height"] = std::to_string(settings.height);
    row["pixels"] = std::to_string(uint64_t(settings.width) * settings.height);
    row["scene"] = scene.source;
    row["scene_triangles"] = std::to_string(scene.triangleCount());
    row["objects"] = std::to_string(scene.objects.size());
    row["shadows"] = config.shadows.enabled ? "1" : "0";
    row["shadow_res"] = shadowResolutionName(config.shadows);
    if (config.shadows.enabled && config.shadows.autoResolution()) row["shadow_budget_mib"] = std::to_string(config.shadows.budgetBytes >> 20);
    row["shadow_format"] = shadowFormatName(config.shadows.format);
    row["shadow_filter"] = shadowFilterName(config.shadows.filter);
    row["point_layout"] = pointShadowLayoutName(config.shadows.pointLayout);
    row["cascades"] = std::to_string(plan.cascades.count);
    row["shadowed_spots"] = std::to_string(plan.shadowedSpots);
    row["shadowed_points"] = std::to_string(plan.shadowedPoints);
    row["rounds"] = std::to_string(rounds);
    row["best_of"] = std::to_string(bestOf);
}

render::PassTimings fastestPerPass(const std::vector<render::PassTimings>& frames) {
    if (frames.empty()) return {};
    render::PassTimings fastest = frames.front();
    for (const render::PassTimings& frame : frames) {
        for (auto& [pass, ms] : fastest.passes) ms = std::min(ms, frame.of(pass));
        fastest.total = std::min(fastest.total, frame.total);
    }
    return fastest;
}

RoundSummary addTimings(BenchRow& row, const std::vector<render::PassTimings>& rounds) {
    auto summarize = [&](const std::string& name, auto&& value) {
        std::vector<double> samples;
        for (const render::PassTimings& t : rounds) samples.push_back(value(t));
        const RoundSummary summary = summarizeRounds(samples);
        row[name + "_ms"] = benchNumber(summary.median);
        row[name + "_iqr_ms"] = benchNumber(summary.iqr);
        row[name + "_cv"] = benchNumber(summary.cv);
        return summary;
    };
    if (!rounds.empty()) {
        for (const auto& [pass, ms] : rounds.front().passes) {
            summarize(pass, [&](const render::PassTimings& t) { return t.of(pass); });
        }
    }
    const RoundSummary total = summarize("total", [](const render::PassTimings& t) { return t.total; });
    const bool flagged = exceedsSpreadLimit(total, kSpreadFlagLimit);
    row["flagged"] = flagged ? "1" : "0";
    if (flagged) {
        std::ostringstream why;
        why.precision(2);
        why << "frame IQR " << std::fixed << 100.0 * total.iqr / std::max(total.median, 1e-12) << "% of the median > "
            << 100.0 * kSpreadFlagLimit << "%";
        row["flag_reason"] = why.str();
    }
    return total;
}

void addCounters(BenchRow& row, render::Renderer& renderer, const LightStatsImage* pixelWork) {
    if (pixelWork) {
        const CullingStats culling = computeCullingStats(*pixelWork);
        row["tested_per_pixel"] = benchNumber(culling.testedPerPixel);
        row["affecting_per_pixel"] = benchNumber(culling.affectingPerPixel);
        row["shadow_lookups_per_pixel"] = benchNumber(culling.shadowLookupsPerPixel);
        row["filter_taps_per_pixel"] = benchNumber(culling.shadowTapsPerPixel);
        row["efficiency"] = benchNumber(culling.efficiency);
        row["floor_efficiency"] = benchNumber(culling.floorEfficiency);
        row["missed_energy"] = benchNumber(culling.missedEnergy);
    }
    const render::CameraDraws& camera = renderer.cameraDraws();
    const render::ShadowDraws shadowDraws = renderer.shadowDraws();
    row["objects_in_view"] = std::to_string(camera.objectsInView);
    row["camera_triangles"] = std::to_string(camera.triangles);
    row["depth_triangles"] = std::to_string(camera.depthTriangles);
    row["forward_triangles"] = std::to_string(camera.forwardTriangles);
    row["transparent_triangles"] = std::to_string(camera.transparentTriangles);
    row["depth_draws"] = std::to_string(camera.depthDraws);
    row["forward_draws"] = std::to_string(camera.forwardDraws);
    row["transparent_draws"] = std::to_string(camera.transparentDraws);
    row["shadow_draws"] = std::to_string(shadowDraws.total);
    row["shadow_draws_max"] = std::to_string(shadowDraws.maxPerView);
    row["shadow_triangles"] = std::to_string(shadowDraws.triangles);
    const ShadowPlan& plan = renderer.shadowPlan();
    row["shadow_views"] = std::to_string(plan.viewsRendered);
    row["shadow_texels_rendered"] = std::to_string(shadowTexelsRendered(plan));
    if (renderer.settings().shadows.enabled) {
        row["shadow_filter_taps"] = std::to_string(renderer.settings().shadows.filterTaps());
        row["shadow_reduced_views"] = std::to_string(plan.reductions.size());
    }
    if (renderer.settings().shadows.enabled && renderer.settings().shadows.virtualPages()) {
        row["shadow_pages"] = std::to_string(renderer.shadowPages().pages.size());
        row["shadow_pages_coarsened"] = std::to_string(renderer.shadowPageStats().coarsenedPages);
        row["shadow_allocate_ms"] = benchNumber(renderer.shadowPageStats().allocateMs);
    }
    const render::DeviceMemory memory = renderer.deviceMemory();
    row["shadow_memory_bytes"] = std::to_string(memory.shadows);
    row["light_grid_bytes"] = std::to_string(memory.lightGrid);
    row["light_list_bytes"] = std::to_string(renderer.lightListBytes());
    row["light_grid_floor_bytes"] = std::to_string(report::lightGridFloorBytes(renderer));
    row["scene_bytes"] = std::to_string(memory.scene);
    row["frame_bytes"] = std::to_string(memory.frame);
    row["device_bytes"] = std::to_string(memory.total());
    // Since this configuration's scene was built (resetPeakResident), or the whole run's peak.
    row["peak_rss_bytes"] = std::to_string(peakResidentSinceReset());
}

ShadowValidationRows addShadowValidation(BenchRow& row, render::Renderer& renderer,
                                         const reference::EmbreeScene& geometry, const Scene& scene) {
    ShadowValidationRows out;
    const ShadowFactorImage factors = renderer.readShadowFactors();
    const reference::ShadowValidation validation =
        reference::validateShadows(geometry, factors, renderer.lights(), renderer.shadowPlan());
    // The same comparison with an edge band one screen pixel wide: the fair one across
    // resolutions (a texel band widens with the texels).
    const reference::ShadowValidation onePixel =
        reference::validateShadows(geometry, factors, renderer.lights(), renderer.shadowPlan(),
                                   reference::EdgeBand::ofScreenPixels(1.0f, scene.camera, renderer.settings().height));
    row["shadow_misclassified"] = benchNumber(validation.overall.misclassifiedOutsideBand());
    row["shadow_misclassified_all"] = benchNumber(validation.overall.misclassified());
    row["shadow_misclassified_1px"] = benchNumber(onePixel.overall.misclassifiedOutsideBand());
    row["shadow_false_shadow"] = std::to_string(validation.overall.falseShadow);
    row["shadow_false_lit"] = std::to_string(validation.overall.falseLit);
    // The floor (DESIGN.md): one texel per compared pair, the (pixel, shadowed light) pairs shaded.
    row["shadow_floor_bytes"] =
        std::to_string(validation.overall.compared * renderer.settings().shadows.texelBytes());
    for (const reference::LightShadowValidation& light : onePixel.lights) {
        const reference::ShadowCounts& c = light.counts;
        out.perLight.push_back({{"light", light.sceneLight},
                                {"compared", c.compared},
                                {"misclassified", c.falseShadow + c.falseLit},
                                {"compared_outside_1px", c.comparedOutsideBand},
                                {"misclassified_outside_1px", c.falseShadowOutsideBand + c.falseLitOutsideBand}});
    }
    if (validation.sun && onePixel.sun) {
        const ShadowPlan& plan = renderer.shadowPlan();
        const CascadePlan& cascades = plan.cascades;
        row["sun_misclassified"] = benchNumber(validation.sun->counts.misclassifiedOutsideBand());
        row["sun_misclassified_1px"] = benchNumber(onePixel.sun->counts.misclassifiedOutsideBand());
        out.perCascade = nlohmann::json::array();
        for (uint32_t i = 0; i < cascades.count; ++i) {
            const reference::ShadowCounts& texelBand = validation.sun->cascades[i];
            const reference::ShadowCounts& pixelBand = onePixel.sun->cascades[i];
            row[sunCascadeColumn(i)] = benchNumber(pixelBand.misclassifiedOutsideBand());
            out.perCascade.push_back({{"cascade", i},
                                      {"far_m", cascades.splits[i]},
                                      {"resolution", plan.views[cascades.firstView + i].resolution},
                                      {"texel_m", cascadeTexelSize(plan, i)},
                                      {"compared", texelBand.compared},
                                      {"misclassified_outside_band", texelBand.misclassifiedOutsideBand()},
                                      {"misclassified_outside_1px", pixelBand.misclassifiedOutsideBand()}});
        }
    }
    if (!validation.lights.empty()) {
        out.mismatch = report::mismatchMap(validation.lights.front(), validation.width, validation.height);
    }
    return out;
}

}  // namespace punctual::bench
