#include "app/reference_command.h"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdio>

#include <tbb/task_arena.h>

#include "cli/option_values.h"
#include "cli/options.h"
#include "cli/output_paths.h"
#include "cli/scene_source.h"
#include "core/error.h"
#include "core/image.h"
#include "core/output_files.h"
#include "reference/reference_renderer.h"
#include "report/frame_stats.h"

namespace punctual::app {

using namespace cli;  // the command line (src/cli)
namespace {

// Options of `render` that mean nothing for the ray-traced image: rejected rather than silently
// ignored, so nobody believes they changed the reference (or waits for a stats file that never
// comes). The shadow-map options tune an approximation the reference has no need of: its shadows
// are exact visibility.
constexpr std::array<const char*, 15> kRenderOnlyOptions = {
    "--stats", "--heatmap", "--culling", "--tile-size", "--slices", "--frames", "--device", "--validate",
    "--shadow-res", "--shadow-filter", "--shadow-samples", "--shadow-bias", "--shadow-penumbra",
    "--shadow-strength", "--point-shadow-layout"};

}  // namespace

std::string referenceUsage() {
    return R"(usage: punctual reference [SCENE.gltf|SCENE.glb|--scene NAME] [options] --out FILE.png

Ray traces SCENE (or a built-in scene) on the CPU with Embree: one ray per pixel
centre from the GPU's camera, the GPU's lights and shading code, and one shadow ray per light
reaching each point. The ground truth the GPU image is compared with.

options:
  --out FILE.png       the tone-mapped reference image (required)
  --shadows on|off     shadow rays to every light reaching a point (default on)
  --no-shadows         the same as --shadows off: every light unoccluded
  --scene NAME         the built-in scene NAME instead of a file (see punctual render --help)
  --scene-triangles N  the size of --scene rooms, 10k to 10M triangles (default 100k)
  --time T             pose the scene file at T seconds of its glTF animations, as render's
  --max-lights S,P     the light capacity, as render's (default 64,32)
  --lights S,P[,SEED]  replace the scene's lights with S spot and P point lights (at most
                       --max-lights) generated inside its bounds (same seed, same lights; seed 1)
  --size WxH           output size in pixels (default 1280x720)
  --exposure X         linear exposure before tone mapping (default 1)
)";
}

reference::ReferenceSettings referenceSettingsFrom(const RenderOptions& options, bool shadows) {
    reference::ReferenceSettings settings;
    settings.width = options.width;
    settings.height = options.height;
    settings.exposure = options.exposure;
    settings.shadows = shadows;
    settings.transparentShadows = options.shadows.transparent;
    settings.maxLights = options.maxLights;
    return settings;
}

int runReferenceCommand(const std::vector<std::string>& args) {
    std::vector<std::string> renderArgs;
    bool shadows = true;
    for (const std::string& arg : args) {
        if (arg == "--help" || arg == "-h") {
            std::fputs(referenceUsage().c_str(), stdout);
            return 0;
        }
    }
    // The shadow switches are the reference's own (shadow rays, not maps); the rest is parsed
    // as for `render`.
    for (size_t i = 0; i < args.size(); ++i) {
        if (args[i] == "--no-shadows") {
            shadows = false;
        } else if (args[i] == "--shadows") {
            const std::string& value = optionValue(args, i);
            if (value != "on" && value != "off") throw Error("--shadows", "expected on or off, got '" + value + "'");
            shadows = value == "on";
        } else {
            renderArgs.push_back(args[i]);
        }
    }
    RenderOptions options;
    try {
        options = parseRenderOptions(renderArgs);
    } catch (const Error& error) {
        if (error.problem().rfind("unknown option", 0) != 0) throw;
        throw Error(error.subject(), "unknown option (see punctual reference --help)");
    }
    for (const std::string& arg : renderArgs) {
        if (std::find(kRenderOnlyOptions.begin(), kRenderOnlyOptions.end(), arg) != kRenderOnlyOptions.end()) {
            throw Error(arg, "applies to `punctual render` only, not to the CPU reference (see punctual reference --help)");
        }
    }
    if (!options.outPath) throw Error("--out", "required: the file to write the reference image to");
    checkOutputPaths({{"--out", options.outPath}});
    const Scene scene = loadSceneForOptions(options);
    checkOutputPaths({{"--out", options.outPath}});  // again, now that the files the scene reads are known

    reference::ReferenceSettings settings = referenceSettingsFrom(options, shadows);
    settings.showProgress = isatty(STDERR_FILENO) != 0;
    const reference::ReferenceRenderer renderer(scene, settings);
    reference::ReferenceStats stats;
    const ImageRgba8 image = renderer.render(&stats);

    OutputFiles outputs;
    outputs.add(*options.outPath, encodePng(image));

    const FrameLights& lights = renderer.lights();
    std::printf("scene: %s (%zu triangles, %zu objects)\n", scene.source.c_str(), scene.triangleCount(),
                scene.objects.size());
    std::printf("%s\n", report::frameLightsLine(lights, settings.maxLights).c_str());
    std::printf("reference: %ux%u, shadows %s, %d threads, BVH build %.3f s\n", settings.width, settings.height,
                shadows ? "on" : "off", tbb::this_task_arena::max_concurrency(), stats.buildSeconds);
    std::printf("rays: %llu (%llu primary + %llu shadow) in %.3f s: %.2f M rays/s\n",
                static_cast<unsigned long long>(stats.rays()), static_cast<unsigned long long>(stats.primaryRays),
                static_cast<unsigned long long>(stats.shadowRays), stats.seconds, stats.raysPerSecond() * 1e-6);
    const auto written = outputs.pending();
    outputs.commit();
    for (const auto& file : written) std::printf("wrote %s\n", file.first.c_str());
    return 0;
}

}  // namespace punctual::app
