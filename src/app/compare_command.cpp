#include "app/compare_command.h"

#include <cstdio>
#include <cstdlib>

#include "cli/options.h"
#include "cli/scene_source.h"
#include "core/error.h"
#include "metrics/image_diff.h"
#include "reference/embree_scene.h"
#include "reference/shadow_validation.h"
#include "report/frame_stats.h"
#include "render/renderer.h"
#include "vk/context.h"

namespace punctual::app {

using namespace cli;     // the command line (src/cli)
using namespace report;  // the lines the commands print about a frame (src/report)
namespace {

std::string usage() {
    return "usage: punctual compare [SCENE] [render options]\n\n"
           "Renders the frame with every light-list method (" +
           joinNames(render::methodNames(), " and ") +
           ", after one warm-up frame each,\n"
           "--frames N timed frames) and prints, side by side: the GPU time of every pass and of the\n"
           "whole frame; the image error against " +
           render::methodName(render::referenceMethod()) +
           " (mean absolute difference and the share of pixels\n"
           "more than 2/255 off); and, with shadows on, the share of (pixel, light) pairs whose shadow\n"
           "disagrees with Embree's ray-cast visibility outside the +-1 texel edge band. --culling is\n"
           "ignored: every method runs.\n";
}

}  // namespace

int runCompareCommand(const std::vector<std::string>& args) {
    for (const std::string& arg : args) {
        if (arg == "--help" || arg == "-h") {
            std::fputs(usage().c_str(), stdout);
            return 0;
        }
        if (arg == "--out" || arg == "--stats" || arg == "--heatmap") throw Error(arg, "not an option of compare");
    }
    const RenderOptions options = parseRenderOptions(args);
    const Scene scene = loadSceneForOptions(options);
    vk::Context context(contextOptionsFrom(options));
    std::optional<reference::EmbreeScene> embree;
    if (options.shadows.enabled) embree.emplace(scene);

    std::printf("%s, %ux%u, %s, shadows %s, median of %u frame(s)\n\n", scene.source.c_str(), options.width,
                options.height, context.deviceName().c_str(), options.shadows.enabled ? "on" : "off", options.frames);
    // One column per pass, named by the passes themselves (known once the first frame is built).
    bool headerPrinted = false;
    auto printHeader = [&](const std::vector<std::string>& passes) {
        std::string names = "method     ", units = "           ";
        for (const std::string& pass : passes) {
            char cell[32];
            std::snprintf(cell, sizeof(cell), " %9.9s", pass.c_str());
            names += cell;
            units += "        ms";
        }
        std::printf("%s %9s | %13s %11s | %13s %10s\n", names.c_str(), "frame", "error vs brute", "pixels off",
                    "shadows wrong", "sun wrong");
        std::printf("%s %9s | %13s %11s | %13s %10s\n", units.c_str(), "ms", "(mean /255)", "(>2/255)", "(vs Embree)",
                    "(cascades)");
        headerPrinted = true;
    };
    ImageRgba8 brute;
    for (render::LightListMethod method : variantValues(render::kLightListMethods)) {
        render::RenderSettings settings = renderSettingsFrom(options);
        settings.method = method;
        settings.collectShadowFactors = options.shadows.enabled;
        // Every method plans the same shadows: a budget that reduced views is said once, by the first.
        settings.warnReducedShadows = !headerPrinted;
        render::Renderer renderer(context, scene, settings);
        if (!headerPrinted) {
            // The same lights are shadowed for every method: said once, above the table.
            for (const std::string& said : {droppedLightsLine(renderer), unshadowedLightsLine(renderer)}) {
                if (!said.empty()) std::printf("%s\n\n", said.c_str());
            }
            printHeader(renderer.passNames());
        }
        const render::FrameResult result = renderer.render(options.frames, 1);
        if (method == render::referenceMethod()) brute = result.image;
        const ImageDifference error = compareImages(result.image, brute);
        // Every shadowed light, then the sun's cascades alone (outside the edge band).
        std::string shadowColumn = "-";
        std::string sunColumn = "-";
        if (embree) {
            const reference::ShadowValidation validation = reference::validateShadows(
                *embree, renderer.readShadowFactors(), renderer.lights(), renderer.shadowPlan());
            char text[32];
            std::snprintf(text, sizeof(text), "%.3f%%", 100.0 * validation.overall.misclassifiedOutsideBand());
            shadowColumn = text;
            if (validation.sun) {
                std::snprintf(text, sizeof(text), "%.3f%%", 100.0 * validation.sun->counts.misclassifiedOutsideBand());
                sunColumn = text;
            }
        }
        std::printf("%-11s", render::methodName(method));
        for (const auto& pass : result.medianMs.passes) std::printf(" %9.1f", pass.second);
        std::printf(" %9.1f | %13.3f %10.3f%% | %13s %10s\n", result.medianMs.total, 255.0 * error.meanAbsolute,
                    100.0 * error.pixelsOff, shadowColumn.c_str(), sunColumn.c_str());
        std::fflush(stdout);
    }
    if (context.validationMessageCount() > 0) {
        throw Error("vulkan", std::to_string(context.validationMessageCount()) + " validation message(s)");
    }
    return 0;
}

}  // namespace punctual::app
