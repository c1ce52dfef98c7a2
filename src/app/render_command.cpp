#include "app/render_command.h"

#include <cstdio>
#include <filesystem>

#include "app/frame_stats.h"
#include "app/options.h"
#include "app/output_paths.h"
#include "app/scene_source.h"
#include "core/error.h"
#include "core/image.h"
#include "render/renderer.h"
#include "vk/context.h"

namespace punctual::app {

int runRenderCommand(const std::vector<std::string>& args) {
    for (const std::string& arg : args) {
        if (arg == "--help" || arg == "-h") {
            std::fputs(renderUsage().c_str(), stdout);
            return 0;
        }
    }
    const RenderOptions options = parseRenderOptions(args);
    checkOutputPath(options.outPath);
    checkOutputPath(options.statsPath);
    const Scene scene = loadSceneForOptions(options);

    vk::ContextOptions contextOptions;
    contextOptions.validation = options.validate;
    contextOptions.deviceIndex = options.deviceIndex;
    vk::Context context(contextOptions);

    render::RenderSettings settings;
    settings.width = options.width;
    settings.height = options.height;
    settings.exposure = options.exposure;
    render::Renderer renderer(context, scene, settings);
    const render::FrameResult result = renderer.render(options.frames);

    if (context.validationMessageCount() > 0) {
        throw Error("vulkan", std::to_string(context.validationMessageCount()) +
                                  " validation message(s) (printed above); no output written");
    }

    const FrameLights& lights = renderer.lights();
    std::printf("scene: %s (%zu triangles, %zu objects)\n", scene.source.c_str(), scene.triangleCount(),
                scene.objects.size());
    std::printf("device: %s, %ux%u, %u frame(s), median GPU times\n", context.deviceName().c_str(), settings.width,
                settings.height, options.frames);
    std::printf("lights: %u spot, %u point, %u directional (%u outside the view, %u over the caps)\n",
                lights.spotCount, lights.pointCount, lights.directionalCount, lights.culledByFrustum,
                lights.droppedByCap);
    std::fputs(timingTable(result.medianMs).c_str(), stdout);

    if (options.outPath) writePng(*options.outPath, result.image);
    if (options.statsPath) {
        try {
            writeFileAtomically(*options.statsPath,
                                frameStatsJson(result, renderer, scene, context.deviceName(), options.frames).dump(2) + "\n");
        } catch (...) {
            // No partial output: the image goes too when its stats cannot be written.
            std::error_code ec;
            if (options.outPath) std::filesystem::remove(*options.outPath, ec);
            throw;
        }
    }
    if (options.outPath) std::printf("wrote %s\n", options.outPath->c_str());
    if (options.statsPath) std::printf("wrote %s\n", options.statsPath->c_str());
    return 0;
}

}  // namespace punctual::app
