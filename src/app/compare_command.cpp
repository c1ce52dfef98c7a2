#include "app/compare_command.h"

#include <cstdio>
#include <cstdlib>

#include "app/options.h"
#include "app/scene_source.h"
#include "core/error.h"
#include "reference/embree_scene.h"
#include "reference/shadow_validation.h"
#include "render/renderer.h"
#include "vk/context.h"

namespace punctual::app {
namespace {

constexpr const char* kUsage = R"(usage: punctual compare [SCENE] [render options]

Renders the frame with brute, per-object, tiled and clustered light lists (after one warm-up
frame each, --frames N timed frames) and prints, side by side: the GPU time of the culling,
shadow and forward passes and of the whole frame; the image error against brute force (mean
absolute difference and the share of pixels more than 2/255 off); and, with shadows on, the
share of (pixel, light) pairs whose shadow disagrees with Embree's ray-cast visibility outside
the +-1 texel edge band. --culling is ignored: every method runs.
)";

struct ImageError {
    double mean = 0.0;      // 0..255 per channel
    double pixelsOff = 0.0;  // share with a channel more than 2/255 off
};

ImageError compareImages(const ImageRgba8& a, const ImageRgba8& b) {
    ImageError e;
    const size_t pixels = size_t(a.width) * a.height;
    size_t off = 0;
    double sum = 0.0;
    for (size_t i = 0; i < pixels; ++i) {
        int worst = 0;
        for (int c = 0; c < 3; ++c) {
            const int d = std::abs(int(a.pixels[i * 4 + c]) - int(b.pixels[i * 4 + c]));
            sum += d;
            worst = std::max(worst, d);
        }
        off += worst > 2;
    }
    e.mean = sum / (3.0 * double(pixels));
    e.pixelsOff = double(off) / double(pixels);
    return e;
}

}  // namespace

int runCompareCommand(const std::vector<std::string>& args) {
    for (const std::string& arg : args) {
        if (arg == "--help" || arg == "-h") {
            std::fputs(kUsage, stdout);
            return 0;
        }
        if (arg == "--out" || arg == "--stats" || arg == "--heatmap") throw Error(arg, "not an option of compare");
    }
    const RenderOptions options = parseRenderOptions(args);
    const Scene scene = loadSceneForOptions(options);
    vk::ContextOptions contextOptions;
    contextOptions.validation = options.validate;
    contextOptions.deviceIndex = options.deviceIndex;
    vk::Context context(contextOptions);
    std::optional<reference::EmbreeScene> embree;
    if (options.shadows.enabled) embree.emplace(scene);

    std::printf("%s, %ux%u, %s, shadows %s, median of %u frame(s)\n\n", scene.source.c_str(), options.width,
                options.height, context.deviceName().c_str(), options.shadows.enabled ? "on" : "off", options.frames);
    std::printf("%-11s %9s %9s %9s %9s | %13s %11s | %13s\n", "method", "culling", "shadows", "forward", "frame",
                "error vs brute", "pixels off", "shadows wrong");
    std::printf("%-11s %9s %9s %9s %9s | %13s %11s | %13s\n", "", "ms", "ms", "ms", "ms", "(mean /255)", "(>2/255)",
                "(vs Embree)");
    ImageRgba8 brute;
    for (render::LightListMethod method : {render::LightListMethod::Brute, render::LightListMethod::PerObject,
                                           render::LightListMethod::Tiled, render::LightListMethod::Clustered}) {
        render::RenderSettings settings;
        settings.width = options.width;
        settings.height = options.height;
        settings.exposure = options.exposure;
        settings.method = method;
        settings.tileSize = options.tileSize;
        settings.clusterSlices = options.slices;
        settings.shadows = options.shadows;
        settings.collectShadowFactors = options.shadows.enabled;
        render::Renderer renderer(context, scene, settings);
        const render::FrameResult result = renderer.render(options.frames, 1);
        if (method == render::LightListMethod::Brute) brute = result.image;
        const ImageError error = compareImages(result.image, brute);
        std::string shadowColumn = "-";
        if (embree) {
            const reference::ShadowValidation validation = reference::validateShadows(
                *embree, renderer.readShadowFactors(), renderer.lights(), renderer.shadowPlan(), settings.shadows);
            char text[32];
            std::snprintf(text, sizeof(text), "%.3f%%", 100.0 * validation.overall.misclassifiedOutsideBand());
            shadowColumn = text;
        }
        const render::PassTimings& ms = result.medianMs;
        std::printf("%-11s %9.1f %9.1f %9.1f %9.1f | %13.3f %10.3f%% | %13s\n", render::methodName(method), ms.culling,
                    ms.shadows, ms.forward, ms.total, error.mean, 100.0 * error.pixelsOff, shadowColumn.c_str());
        std::fflush(stdout);
    }
    if (context.validationMessageCount() > 0) {
        throw Error("vulkan", std::to_string(context.validationMessageCount()) + " validation message(s)");
    }
    return 0;
}

}  // namespace punctual::app
