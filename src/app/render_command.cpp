#include "app/render_command.h"

#include <cstdio>
#include <sstream>

#include "report/frame_stats.h"
#include "cli/options.h"
#include "cli/output_paths.h"
#include "cli/scene_source.h"
#include "core/error.h"
#include "core/image.h"
#include "core/log.h"
#include "core/output_files.h"
#include "lights/shadow_sizing.h"
#include "lights/virtual_pages.h"
#include "metrics/shadow_page_overlay.h"
#include "metrics/heatmap.h"
#include "metrics/shadow_density.h"
#include "render/renderer.h"
#include "vk/context.h"

namespace punctual::app {

using namespace cli;
using namespace report;  // the command line (src/cli) and the files the commands write (src/report)

namespace {

std::string heatmapTitle(const render::Renderer& renderer) {
    std::ostringstream title;  // (not string +: GCC 12 warns falsely about it, bug 105329)
    const render::LightListMethod method = renderer.settings().method;
    title << "lights tested per pixel: " << render::methodName(method);
    if (render::usesLightGrid(method)) {
        const render::LightGridLayout& grid = renderer.gridLayout();
        title << " " << grid.tileSize << "x" << grid.tileSize;
        if (grid.slices > 1) title << " x " << grid.slices << " slices";
    }
    return title.str();
}

// Nothing emits light but the lights, and the background is black, so a frame no light
// reaches (none in the scene, all out of view, all inside closed geometry) is black to the
// last pixel: say why, in one line, rather than leave a black image unexplained.
void warnIfNoLightReaches(const Scene& scene, const ImageRgba8& image, float exposure) {
    for (size_t i = 0; i < image.pixels.size(); i += 4)
        if (image.pixels[i] != 0 || image.pixels[i + 1] != 0 || image.pixels[i + 2] != 0) return;
    std::ostringstream message;
    message << scene.source << ": the image is black: ";
    if (scene.lights.empty()) {
        message << "the scene has no lights, not even a directional one (add some with --lights S,P)";
    } else {
        message << "none of the scene's " << scene.lights.size() << " light(s) reaches a surface the camera sees";
        if (exposure < 1.0f) message << " (or too little of their light at --exposure " << exposure << ")";
    }
    log::warn(message.str());
}

// What the frame was: scene, device, lights, shadows and the sun's cascades, a line each.
void printFrameSummary(const Scene& scene, const vk::Context& context, const render::Renderer& renderer,
                       uint32_t frames) {
    const render::RenderSettings& settings = renderer.settings();
    const FrameLights& lights = renderer.lights();
    std::printf("scene: %s (%zu triangles, %zu objects)\n", scene.source.c_str(), scene.triangleCount(),
                scene.objects.size());
    // The grid methods' list form, where it is not the default masks.
    const std::string lists = renderer.gridLayout().indexLists ? " (index lists)" : "";
    std::printf("device: %s, %ux%u, %s culling%s, %u frame(s), median GPU times\n", context.deviceName().c_str(),
                settings.width, settings.height, render::methodName(settings.method), lists.c_str(), frames);
    std::printf("%s\n", frameLightsLine(lights, settings.maxLights).c_str());
    const ShadowPlan& shadows = renderer.shadowPlan();
    if (settings.shadows.enabled) {
        std::printf("shadows: %u spot, %u point (%s), %u views rendered, %u skipped, %.1f MiB %s, %s filter\n",
                    shadows.shadowedSpots, shadows.shadowedPoints, pointShadowLayoutName(settings.shadows.pointLayout),
                    shadows.viewsRendered, shadows.viewsSkipped, double(renderer.shadowMemoryBytes()) / 1048576.0,
                    shadowFormatName(settings.shadows.format), shadowFilterName(settings.shadows.filter));
        const std::string unshadowed = unshadowedLightsLine(renderer);
        if (!unshadowed.empty()) std::printf("%s\n", unshadowed.c_str());
        std::printf("shadow resolution: %s; views at %s texels\n",
                    settings.shadows.autoResolution() ? "auto" : "fixed", describeShadowTiers(shadows).c_str());
        if (shadows.cascades.count > 0) {
            std::string cascades;
            for (uint32_t i = 0; i < shadows.cascades.count; ++i) {
                const ShadowView& view = shadows.views[shadows.cascades.firstView + i];
                char text[96];
                std::snprintf(text, sizeof(text), "%s%.1f m at %u (%.3f m texels)", i ? ", " : "",
                              double(shadows.cascades.splits[i]), view.resolution, double(cascadeTexelSize(shadows, i)));
                cascades += text;
            }
            std::printf("sun: %u cascades to %s, %s blend\n", shadows.cascades.count, cascades.c_str(),
                        cascadeBlendName(settings.shadows.cascades.blend));
        }
    }
}

// --shadow-density and --shadow-pages: how the frame's shadows are resolved, drawn on the CPU.
void addShadowImages(OutputFiles& outputs, const RenderOptions& options, const Scene& scene,
                     const render::Renderer& renderer, const ImageRgba8& frame) {
    const render::RenderSettings& settings = renderer.settings();
    if (options.shadowDensityPath) {
        const ShadowDensityImage density =
            computeShadowDensity(scene, renderer.lights(), renderer.shadowPlan(), settings.width, settings.height);
        const std::string title = "shadow texels per pixel (--shadow-res " + shadowResolutionName(settings.shadows) + ")";
        outputs.add(*options.shadowDensityPath, encodePng(renderShadowDensity(density, title)));
    }
    if (options.shadowPagesPath) {
        const std::vector<int8_t> levels = shadowPageLevels(scene, renderer.lights(), renderer.shadowPlan(), settings.width,
                                                            settings.height, settings.shadows);
        outputs.add(*options.shadowPagesPath, encodePng(shadowPageOverlay(frame, levels)));
    }
}

}  // namespace

int runRenderCommand(const std::vector<std::string>& args) {
    for (const std::string& arg : args) {
        if (arg == "--help" || arg == "-h") {
            std::fputs(renderUsage().c_str(), stdout);
            return 0;
        }
    }
    const RenderOptions options = parseRenderOptions(args);
    const std::vector<NamedOutput> outputPaths = {{"--out", options.outPath},
                                                  {"--stats", options.statsPath},
                                                  {"--heatmap", options.heatmapPath},
                                                  {"--shadow-density", options.shadowDensityPath},
                                                  {"--shadow-pages", options.shadowPagesPath}};
    if (options.shadowPagesPath && !(options.shadows.virtualPages() && options.shadows.enabled)) {
        throw Error("--shadow-pages", "shows virtual shadow pages: it needs --shadow-res virtual (and shadows on)");
    }
    checkOutputPaths(outputPaths);
    const Scene scene = loadSceneForOptions(options);
    checkOutputPaths(outputPaths);  // again, now that the files the scene reads are known

    vk::Context context(contextOptionsFrom(options));
    render::RenderSettings settings = renderSettingsFrom(options);
    settings.collectLightStats = options.statsPath.has_value() || options.heatmapPath.has_value();
    render::Renderer renderer(context, scene, settings);
    const render::FrameResult result = renderer.render(options.frames);
    std::optional<LightStatsImage> lightStats;
    if (settings.collectLightStats) lightStats = renderer.readLightStats();

    if (context.validationMessageCount() > 0) {
        throw Error("vulkan", std::to_string(context.validationMessageCount()) +
                                  " validation message(s) (printed above); no output written");
    }
    warnIfNoLightReaches(scene, result.image, settings.exposure);

    printFrameSummary(scene, context, renderer, options.frames);
    std::fputs(timingTable(result.medianMs).c_str(), stdout);

    OutputFiles outputs;
    if (options.outPath) outputs.add(*options.outPath, encodePng(result.image));
    if (lightStats) {
        const CullingStats culling = computeCullingStats(*lightStats);
        std::printf("culling: %.2f lights tested per pixel, %.2f reach it (efficiency %.2f), max %u, missed energy %.4f\n",
                    culling.testedPerPixel, culling.affectingPerPixel, culling.efficiency, culling.maxTested,
                    culling.missedEnergy);
        if (options.statsPath) {
            nlohmann::json stats = frameStatsJson(result, renderer, scene, context.deviceName(), options.frames);
            stats["culling"] = cullingStatsJson(culling, renderer);
            stats["shadows"] = shadowStatsJson(renderer);
            if (settings.shadows.enabled) {
                const std::vector<VirtualPageLayout> layouts = virtualPageLayoutsToCompare();
                const VirtualPageEstimate estimate = estimateVirtualPages(
                    scene, renderer.lights(), renderer.shadowPlan(), settings.width, settings.height, settings.shadows, layouts);
                stats["shadows"]["virtual_estimate"] = virtualPageEstimateJson(estimate, renderer);
                if (settings.shadows.virtualPages()) {
                    stats["shadows"]["virtual_pages"] = virtualPagesJson(renderer, estimate.shadedPairs);
                }
            }
            stats["memory"]["light_grid_floor_bytes"] = lightGridFloorBytes(renderer);
            outputs.add(*options.statsPath, stats.dump(2) + "\n");
        }
        if (options.heatmapPath) {
            std::vector<uint8_t> background(lightStats->covered.size());
            for (size_t i = 0; i < background.size(); ++i) background[i] = lightStats->covered[i] ? 0 : 1;
            HeatmapOptions heatmap;
            heatmap.title = heatmapTitle(renderer);
            outputs.add(*options.heatmapPath,
                        encodePng(renderHeatmap(lightStats->tested, background, settings.width, settings.height, heatmap)));
        }
    }
    addShadowImages(outputs, options, scene, renderer, result.image);
    const auto written = outputs.pending();
    outputs.commit();
    for (const auto& file : written) std::printf("wrote %s\n", file.first.c_str());
    return 0;
}

}  // namespace punctual::app
