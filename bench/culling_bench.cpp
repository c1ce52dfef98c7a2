// Culling benchmark (issue targets, not a test): renders the default scene at 1280x720 with
// every light-list method in one process, interleaving the methods round by round (each round
// starting with the next method) so that machine noise hits them alike, and reports per-pass median GPU times, speed ratios and
// culling efficiency, with a PASS/FAIL line per target:
//   forward pass, tiled vs brute force:      >= 5x faster
//   clustered vs tiled (forward pass):       at least as fast (ratio <= 1.0)
//   culling efficiency (tested / affecting): tiled <= 2.0, clustered <= 1.5
// Usage: punctual_culling_bench [--rounds N] [--size WxH] [--heatmaps DIR] [--json FILE]
//                               [--clustered-tile N] [--slices N]
#include <algorithm>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/options.h"
#include "core/error.h"
#include "core/image.h"
#include "cli/output_paths.h"
#include "core/output_files.h"
#include "core/output_folder.h"
#include "metrics/culling_stats.h"
#include "metrics/heatmap.h"
#include "render/renderer.h"
#include "scene/default_scene.h"
#include "vk/context.h"

namespace {

using punctual::render::LightListMethod;

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : (v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]));
}

struct MethodRun {
    LightListMethod method;
    std::unique_ptr<punctual::render::Renderer> renderer;
    std::vector<double> culling, forward, total;
    punctual::CullingStats stats;
};

}  // namespace

int main(int argc, char** argv) {
    try {
        uint32_t rounds = 9;
        uint32_t width = 1280, height = 720;
        std::string heatmapDir, jsonPath;
        uint32_t clusteredTile = 16, slices = 16;
        for (int i = 1; i < argc; ++i) {
            const std::string arg = argv[i];
            auto value = [&]() -> std::string {
                if (i + 1 >= argc) throw punctual::Error(arg, "needs a value");
                return argv[++i];
            };
            if (arg == "--rounds") rounds = uint32_t(std::stoul(value()));
            else if (arg == "--size") punctual::cli::parseSize(value(), width, height);
            else if (arg == "--heatmaps") heatmapDir = value();
            else if (arg == "--json") jsonPath = value();
            else if (arg == "--clustered-tile") clusteredTile = uint32_t(std::stoul(value()));
            else if (arg == "--slices") slices = uint32_t(std::stoul(value()));
            else throw punctual::Error(arg, "unknown option");
        }
        // The output paths, before minutes of rendering (the heat map folder is created if missing).
        const punctual::OutputFolderLayout heatmapLayout = {"", {"heatmap-*.png"}, {}};
        if (!heatmapDir.empty()) punctual::checkOutputFolder(heatmapDir, heatmapLayout);
        if (!jsonPath.empty()) punctual::cli::checkOutputPaths({{"--json", jsonPath}});
        const punctual::Scene scene = punctual::makeDefaultScene();
        punctual::vk::Context context;
        std::vector<MethodRun> runs;
        for (LightListMethod method : {LightListMethod::Brute, LightListMethod::PerObject, LightListMethod::Tiled,
                                       LightListMethod::Clustered}) {
            punctual::render::RenderSettings settings;
            settings.width = width;
            settings.height = height;
            settings.method = method;
            settings.collectLightStats = true;
            settings.clusterSlices = slices;
            settings.shadows.enabled = false;  // light lists only: shadows cost the same for every method
            if (method == LightListMethod::Clustered) settings.tileSize = clusteredTile;
            MethodRun run{method, std::make_unique<punctual::render::Renderer>(context, scene, settings), {}, {}, {}, {}};
            run.renderer->render(1, 1);  // warm up
            runs.push_back(std::move(run));
        }
        for (uint32_t round = 0; round < rounds; ++round) {
            // Each round starts with a different method, so no method always follows the same one.
            for (size_t k = 0; k < runs.size(); ++k) {
                MethodRun& run = runs[(round + k) % runs.size()];
                const auto result = run.renderer->render(1, 0);
                run.culling.push_back(result.medianMs.of("culling"));
                run.forward.push_back(result.medianMs.of("forward"));
                run.total.push_back(result.medianMs.total);
            }
            std::fprintf(stderr, "\rround %u/%u", round + 1, rounds);
        }
        std::fprintf(stderr, "\n");

        punctual::OutputFiles outputs;
        std::map<LightListMethod, const MethodRun*> byMethod;
        nlohmann::json json;
        std::printf("default scene, %ux%u, %zu spot + %zu point lights, %s, %u interleaved rounds (median GPU ms)\n\n",
                    width, height, size_t(runs[0].renderer->lights().spotCount),
                    size_t(runs[0].renderer->lights().pointCount), context.deviceName().c_str(), rounds);
        std::printf("| method | culling | forward | culling + forward | frame total | tested/px | affecting/px | efficiency | max tested | missed energy |\n");
        std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
        for (MethodRun& run : runs) {
            const auto lightStats = run.renderer->readLightStats();
            run.stats = punctual::computeCullingStats(lightStats);
            byMethod[run.method] = &run;
            const double c = median(run.culling), f = median(run.forward), t = median(run.total);
            std::printf("| %s | %.1f | %.1f | %.1f | %.1f | %.2f | %.2f | %.2f | %u | %.4f |\n",
                        punctual::render::methodName(run.method), c, f, c + f, t, run.stats.testedPerPixel,
                        run.stats.affectingPerPixel, run.stats.efficiency, run.stats.maxTested, run.stats.missedEnergy);
            json[punctual::render::methodName(run.method)] = {
                {"culling_ms", c}, {"forward_ms", f}, {"total_ms", t},
                {"tested_per_pixel", run.stats.testedPerPixel}, {"affecting_per_pixel", run.stats.affectingPerPixel},
                {"efficiency", run.stats.efficiency}, {"max_tested", run.stats.maxTested},
                {"missed_energy", run.stats.missedEnergy}};
            if (!heatmapDir.empty()) {
                std::vector<uint8_t> background(lightStats.covered.size());
                for (size_t i = 0; i < background.size(); ++i) background[i] = lightStats.covered[i] ? 0 : 1;
                punctual::HeatmapOptions options;
                options.title = std::string("lights tested per pixel: ") + punctual::render::methodName(run.method);
                options.maxValue = 32;
                outputs.add(heatmapDir + "/heatmap-" + punctual::render::methodName(run.method) + ".png",
                            punctual::encodePng(punctual::renderHeatmap(lightStats.tested, background, width, height, options)));
            }
        }
        const double bruteForward = median(byMethod[LightListMethod::Brute]->forward);
        const double tiledForward = median(byMethod[LightListMethod::Tiled]->forward);
        const double clusteredForward = median(byMethod[LightListMethod::Clustered]->forward);
        const double tiledBoth = median(byMethod[LightListMethod::Tiled]->culling) + tiledForward;
        const double clusteredBoth = median(byMethod[LightListMethod::Clustered]->culling) + clusteredForward;
        const double tiledEfficiency = byMethod[LightListMethod::Tiled]->stats.efficiency;
        const double clusteredEfficiency = byMethod[LightListMethod::Clustered]->stats.efficiency;
        auto verdict = [](bool ok) { return ok ? "PASS" : "FAIL"; };
        std::printf("\n");
        std::printf("- forward pass, brute / tiled: %.2fx (target >= 5): %s\n", bruteForward / tiledForward,
                    verdict(bruteForward >= 5.0 * tiledForward));
        std::printf("- forward pass, clustered / tiled: %.2f (target <= 1.0): %s\n", clusteredForward / tiledForward,
                    verdict(clusteredForward <= tiledForward));
        std::printf("- culling + forward, clustered / tiled: %.2f (reported, not a target)\n", clusteredBoth / tiledBoth);
        std::printf("- efficiency tiled %.2f (target <= 2.0): %s\n", tiledEfficiency, verdict(tiledEfficiency <= 2.0));
        std::printf("- efficiency clustered %.2f (target <= 1.5): %s\n", clusteredEfficiency,
                    verdict(clusteredEfficiency <= 1.5));
        json["ratios"] = {{"forward_brute_over_tiled", bruteForward / tiledForward},
                          {"forward_clustered_over_tiled", clusteredForward / tiledForward},
                          {"culling_plus_forward_clustered_over_tiled", clusteredBoth / tiledBoth}};
        if (!jsonPath.empty()) outputs.add(jsonPath, json.dump(2) + "\n");
        if (!heatmapDir.empty()) outputs.addFolder(heatmapDir);
        outputs.commit();
        return 0;
    } catch (const std::exception& error) {
        std::fprintf(stderr, "punctual_culling_bench: error: %s\n", error.what());
        return 1;
    }
}
