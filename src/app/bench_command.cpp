#include "app/bench_command.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <optional>
#include <sstream>

#include <nlohmann/json.hpp>

#include "app/bench_failures.h"
#include "app/options.h"
#include "app/output_paths.h"
#include "app/scene_source.h"
#include "app/validation_report.h"
#include "core/error.h"
#include "core/memory_usage.h"
#include "core/output_files.h"
#include "core/output_folder.h"
#include "lights/cascade_setup.h"
#include "lights/shadow_sizing.h"
#include "metrics/heatmap.h"
#include "metrics/image_diff.h"
#include "reference/embree_scene.h"
#include "reference/shadow_validation.h"
#include "render/renderer.h"
#include "scene/builtin_scenes.h"
#include "scene/light_generator.h"
#include "vk/context.h"

namespace punctual::app {
namespace {

// Everything bench writes into --out-dir; results.json lists a run's files.
const OutputFolderLayout kFolderLayout = {
    "results.json",
    {"results.csv", "results.json", "failures.csv", "images/heatmap-*.png", "images/mismatch-*.png"},
    {"images"}};

// The method and filter lists come from their tables, as plan() sweeps them.
std::string usage() {
    std::vector<std::string> quickFilters;
    std::vector<std::string> texelFilters;  // the cascades series' (plan())
    for (const ShadowFilterInfo& filter : kShadowFilters) {
        if (filter.quickBench) quickFilters.emplace_back(filter.name);
        if (!filter.footprint.fromDiskSettings) texelFilters.emplace_back(filter.name);
    }
    return R"(usage: punctual bench [SCENE|--scene NAME] [--quick] --out-dir DIR [--size WxH] [--frames N]
                     [--series NAME[,NAME...]]

Sweeps, on SCENE or the built-in scene NAME (default: )" + std::string(kDefaultBuiltinScene.name) +
           R"() with generated lights:
  light counts 0 .. 64 spot + 32 point (2:1 mix, spot-only and point-only series)
  x the methods )" + joinNames(render::methodNames(), ", ") + R"( (shadows off);
  shadows off and on at the largest count, per method;
  shadow resolution auto and fixed 256..2048 (2048: the 32 spots and 5 points that matter
  most), each at 16 and 32 bits, and 1024 at 32 bits for 32 + 8 lights (the former default);
  the filters )" + joinNames(shadowFilterNames(), ", ") + R"( at auto resolution;
  the sun's cascades on the built-in outdoor scene (its own lights, the sun alone shadowed):
  1-4 cascades x resolution 512, 1024, 2048 x the filters )" + joinNames(texelFilters, ", ") + R"(;
  each shadow configuration validated against Embree (edge band one texel, and one pixel);
  cost against triangles: the built-in rooms scene at 10^4, 10^5, 10^6 and 10^7 triangles
  (quick: 10^4 and 10^5) x every method, its own lights, shadows on, with peak memory.
Every configuration renders one warm-up frame and N timed frames (default 5, quick 3) and keeps
the median and spread of each pass. Writes DIR/results.csv, DIR/results.json and DIR/images/.
Then the failure study (DIR/failures.csv): acne against bias, peter-panning against bias, cube
seams against resolution and layout, the pancaking leak, spots widening towards 90 degrees, tile
depth discontinuities (tiled against clustered), per-object lists on large objects, light counts
beyond the caps, and the sun's cascades: shimmering along a camera path (texel snapping on and
off), seams per blend, perspective aliasing against view depth (split schemes, 1-4 cascades) and
pancaking (depth clamp on and off).
--series: only the named series (mix, spot-only, point-only, shadows, shadow-quality,
shadow-filters, cascades, triangles; failures: the failure study).
--quick: 320x180, fewer counts, resolutions auto, 256 and 1024, 1 and 4 cascades at 512, fewer
values in the failure study, filters )" +
           joinNames(quickFilters, " and ") + R"( (under 3 minutes
on 2 CPU cores). Default size: 1280x720 (quick: 320x180).
Charts: /usr/bin/python3 bench/plot_results.py DIR && /usr/bin/python3 bench/plot_failures.py DIR
)";
}

std::string sunCascadeColumn(uint32_t cascade) { return "sun_cascade" + std::to_string(cascade) + "_misclassified_1px"; }

// The columns of results.csv (and the keys of each results.json row): the configuration, then
// <pass>_ms and <pass>_spread_ms for every pass of the frame in frame order (so a new pass gets
// its columns with no edit here), then the statistics.
std::vector<std::string> resultColumns(const std::vector<std::string>& passes) {
    std::vector<std::string> columns = {"config",        "series",        "method",        "spot",
                                        "point",         "shadows",       "shadow_res",    "shadow_format",
                                        "shadow_filter", "point_layout",  "shadowed_spots", "shadowed_points",
                                        "frames"};
    for (const std::string& pass : passes) columns.push_back(pass + "_ms");
    columns.push_back("total_ms");
    for (const std::string& pass : passes) columns.push_back(pass + "_spread_ms");
    columns.push_back("total_spread_ms");
    for (const char* column : {"tested_per_pixel", "affecting_per_pixel", "efficiency", "missed_energy", "image_error",
                               "pixels_off", "shadow_views", "shadow_memory_bytes", "shadow_texels_rendered",
                               "shadow_filter_taps", "shadow_reduced_views", "shadow_misclassified",
                               "shadow_misclassified_all", "shadow_misclassified_1px", "shadow_false_shadow",
                               "shadow_false_lit", "cascades", "sun_misclassified", "sun_misclassified_1px"}) {
        columns.emplace_back(column);
    }
    // The sun's error per cascade, outside a one-pixel edge band (empty beyond the row's count).
    for (uint32_t i = 0; i < PUNCTUAL_MAX_CASCADES; ++i) columns.push_back(sunCascadeColumn(i));
    // The triangle series' geometry and memory (empty in the other series).
    for (const char* column : {"scene_triangles", "objects", "objects_in_view", "camera_triangles", "camera_draws",
                               "shadow_draws", "shadow_draws_max", "shadow_triangles", "peak_rss_bytes",
                               "device_bytes"}) {
        columns.emplace_back(column);
    }
    return columns;
}

struct Config {
    std::string series;
    // A built-in scene of the series' own, lit by its own lights (spot and point are then 0);
    // nullptr: the bench's scene with `spot` + `point` generated lights.
    const BuiltinScene* scene = nullptr;
    render::LightListMethod method = render::LightListMethod::Tiled;
    uint32_t spot = 0;
    uint32_t point = 0;
    ShadowSettings shadows;
    bool validateShadows = false;
    uint64_t triangles = 0;  // a sized built-in scene's size (BuiltinScene::sized); 0: its default
};

using Row = std::map<std::string, std::string>;

std::string number(double value) {
    std::ostringstream s;
    s.precision(6);
    s << value;
    return s.str();
}

class ProgressBar {
public:
    explicit ProgressBar(size_t total) : total_(total), terminal_(isatty(2) != 0) {}
    void step(const std::string& what) {
        ++done_;
        if (!terminal_) return;
        const int width = 30;
        const int filled = int(double(done_) / double(total_) * width);
        std::fprintf(stderr, "\r[%s%s] %zu/%zu %-40.40s", std::string(size_t(filled), '#').c_str(),
                     std::string(size_t(width - filled), '.').c_str(), done_, total_, what.c_str());
        if (done_ == total_) std::fputc('\n', stderr);
    }

private:
    size_t total_;
    size_t done_ = 0;
    bool terminal_;
};

// The scene's lights of `type` (a generated row's counts; a built-in scene's own lamps).
size_t lightsOfType(const Scene& scene, LightType type) {
    return size_t(std::count_if(scene.lights.begin(), scene.lights.end(), [&](const Light& l) { return l.type == type; }));
}

std::string configName(const Config& c) {
    std::ostringstream s;
    s << c.series << "-" << render::methodName(c.method) << "-";
    if (c.scene) {
        s << c.scene->name;
        if (c.triangles) s << "-" << c.triangles << "t";
    } else {
        s << c.spot << "s" << c.point << "p";
    }
    if (c.shadows.enabled) {
        s << "-shadows-" << shadowResolutionName(c.shadows) << "-" << shadowFormatName(c.shadows.format) << "-"
          << shadowFilterName(c.shadows.filter) << "-" << pointShadowLayoutName(c.shadows.pointLayout);
        const ShadowSettings defaults;
        if (c.shadows.maxShadowedSpots != defaults.maxShadowedSpots ||
            c.shadows.maxShadowedPoints != defaults.maxShadowedPoints) {
            s << "-shadowed-" << c.shadows.maxShadowedSpots << "s" << c.shadows.maxShadowedPoints << "p";
        }
        if (c.scene) s << "-" << c.shadows.cascades.count << "c";
    }
    return s.str();
}

std::vector<Config> plan(bool quick) {
    const std::vector<uint32_t> counts = quick ? std::vector<uint32_t>{0, 16, 64} : std::vector<uint32_t>{0, 8, 16, 32, 48, 64};
    // Methods and filters in table order; --quick keeps the entries marked for it.
    std::vector<render::LightListMethod> methods;
    for (const render::LightListMethodInfo& method : render::kLightListMethods) {
        if (!quick || method.quickBench) methods.push_back(method.value);
    }
    std::vector<Config> configs;
    ShadowSettings off;
    off.enabled = false;
    for (uint32_t spots : counts) {
        for (const auto& [series, s, p] : {std::tuple<const char*, uint32_t, uint32_t>{"mix", spots, spots / 2},
                                           {"spot-only", spots, 0u}, {"point-only", 0u, spots / 2}}) {
            if (std::string(series) != "mix" && spots == 0) continue;  // the same empty frame as mix
            for (render::LightListMethod method : methods) configs.push_back({series, nullptr, method, s, p, off, false});
        }
    }
    for (render::LightListMethod method : methods) {
        configs.push_back({"shadows", nullptr, method, 64, 32, off, false});
        configs.push_back({"shadows", nullptr, method, 64, 32, ShadowSettings{}, false});
    }
    // Shadow quality against memory: auto (every light, each view at its tier) and fixed
    // resolutions, at 16 and 32 bits, validated against Embree; and today's former default, 1024 at
    // 32 bits for the 32 spots and 8 points that matter most (issue 11's "A").
    const std::vector<uint32_t> resolutions = quick ? std::vector<uint32_t>{ShadowSettings::kAutoResolution, 256, 1024}
                                                    : std::vector<uint32_t>{ShadowSettings::kAutoResolution, 256, 512,
                                                                            1024, 2048};
    for (uint32_t resolution : resolutions) {
        for (ShadowFormat format : {ShadowFormat::D16, ShadowFormat::D32}) {
            ShadowSettings shadows;
            shadows.resolution = resolution;
            shadows.format = format;
            // A 16384^2 atlas holds 64 views of 2048^2: not 256, nor the 80 of 32 spots and 8 points
            // (each point six slices); the fixed 2048 sweep shadows the 32 spots and 5 points that
            // matter most (62 views).
            if (resolution == 2048) {
                shadows.maxShadowedSpots = 32;
                shadows.maxShadowedPoints = 5;
            }
            configs.push_back({"shadow-quality", nullptr, render::LightListMethod::Tiled, 64, 32, shadows, true});
        }
    }
    ShadowSettings former;
    former.resolution = 1024;
    former.format = ShadowFormat::D32;
    former.maxShadowedSpots = 32;
    former.maxShadowedPoints = 8;
    configs.push_back({"shadow-quality", nullptr, render::LightListMethod::Tiled, 64, 32, former, true});
    // The filters at the default (auto) resolution.
    for (const ShadowFilterInfo& filter : kShadowFilters) {
        if (quick && !filter.quickBench) continue;
        ShadowSettings shadows;
        shadows.filter = filter.value;
        configs.push_back({"shadow-filters", nullptr, render::LightListMethod::Tiled, 64, 32, shadows, true});
    }
    // The sun's cascades on the outdoor scene: count x fixed resolution x filter. Its lamps keep
    // lighting the street but cast no shadow, so that the shadow stage and its memory are the
    // cascades' alone. The filters are those whose reach is counted in texels (the disk's radius is a
    // share of the map, the same for every cascade); --quick keeps the ones marked for it.
    const BuiltinScene& outdoor = parseBuiltinScene("outdoor");
    const std::vector<uint32_t> cascadeCounts = quick ? std::vector<uint32_t>{1, 4} : std::vector<uint32_t>{1, 2, 3, 4};
    const std::vector<uint32_t> cascadeResolutions = quick ? std::vector<uint32_t>{512} : std::vector<uint32_t>{512, 1024, 2048};
    std::vector<ShadowFilter> cascadeFilters;
    for (const ShadowFilterInfo& filter : kShadowFilters) {
        if (!filter.footprint.fromDiskSettings && (!quick || filter.quickBench)) cascadeFilters.push_back(filter.value);
    }
    for (uint32_t count : cascadeCounts) {
        for (uint32_t resolution : cascadeResolutions) {
            for (ShadowFilter filter : cascadeFilters) {
                ShadowSettings shadows;
                shadows.resolution = resolution;
                shadows.filter = filter;
                shadows.maxShadowedSpots = 0;
                shadows.maxShadowedPoints = 0;
                shadows.cascades.count = count;
                configs.push_back({"cascades", &outdoor, render::LightListMethod::Tiled, 0, 0, shadows, true});
            }
        }
    }
    // Cost against triangles: the rooms scene (its own 64 spots, 32 points and sun, every one
    // shadowed at auto resolution) at each size, every method. Sizes ascending, so each size's
    // peak memory is its own (the bench frees a size's scene before building the next).
    const BuiltinScene& rooms = parseBuiltinScene("rooms");
    const std::vector<uint64_t> sizes = quick ? std::vector<uint64_t>{10'000, 100'000}
                                              : std::vector<uint64_t>{10'000, 100'000, 1'000'000, 10'000'000};
    for (uint64_t triangles : sizes) {
        for (render::LightListMethod method : methods) {
            configs.push_back({"triangles", &rooms, method, 0, 0, ShadowSettings{}, false, triangles});
        }
    }
    return configs;
}

// The series --series names (and "failures" for the failure study); none given: all of them.
std::vector<std::string> parseSeries(const std::string& text) {
    const std::vector<std::string> known = {"mix",     "spot-only",      "point-only", "shadows",  "shadow-quality",
                                            "shadow-filters", "cascades", "triangles",  "failures"};
    std::vector<std::string> series;
    size_t start = 0;
    while (start <= text.size()) {
        const size_t comma = std::min(text.find(',', start), text.size());
        const std::string name = text.substr(start, comma - start);
        if (std::find(known.begin(), known.end(), name) == known.end()) {
            std::string list;
            for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
            throw Error("--series", "expected names from " + list + ", got '" + name + "'");
        }
        series.push_back(name);
        start = comma + 1;
    }
    return series;
}

}  // namespace

int runBenchCommand(const std::vector<std::string>& args) {
    std::vector<std::string> renderArgs;
    std::optional<std::string> outDir;
    bool quick = false;
    std::optional<std::vector<std::string>> onlySeries;
    for (size_t i = 0; i < args.size(); ++i) {
        if (args[i] == "--help" || args[i] == "-h") {
            std::fputs(usage().c_str(), stdout);
            return 0;
        } else if (args[i] == "--quick") {
            quick = true;
        } else if (args[i] == "--out-dir") {
            if (i + 1 >= args.size() || args[i + 1].rfind("--", 0) == 0) throw Error("--out-dir", "needs a value");
            outDir = args[++i];
        } else if (args[i] == "--series") {
            if (i + 1 >= args.size() || args[i + 1].rfind("--", 0) == 0) throw Error("--series", "needs a value");
            onlySeries = parseSeries(args[++i]);
        } else if (args[i] == "--scene" || args[i] == "--size" || args[i] == "--frames" || args[i] == "--device" ||
                   args[i] == "--validate" || args[i] == "--exposure" || args[i].rfind("--", 0) != 0) {
            renderArgs.push_back(args[i]);
            if (args[i] != "--validate" && args[i].rfind("--", 0) == 0 && i + 1 < args.size()) renderArgs.push_back(args[++i]);
        } else {
            throw Error(args[i], "not an option of bench (see punctual bench --help)");
        }
    }
    if (!outDir) throw Error("--out-dir", "bench needs an output folder (--out-dir DIR)");
    checkOutputFolder(*outDir, kFolderLayout);

    RenderOptions options = parseRenderOptions(renderArgs);
    const bool sizeGiven = std::find(renderArgs.begin(), renderArgs.end(), "--size") != renderArgs.end();
    if (quick && !sizeGiven) {
        options.width = 320;
        options.height = 180;
    }
    const uint32_t timedFrames = std::find(renderArgs.begin(), renderArgs.end(), "--frames") != renderArgs.end()
                                     ? options.frames
                                     : (quick ? 3u : 5u);
    const Scene baseScene = loadSceneForOptions(options);
    vk::Context context(contextOptionsFrom(options));
    const reference::EmbreeScene embree(baseScene);  // geometry only: shared by every configuration
    // The series with built-in scenes of their own (the cascades' outdoor scene, the rooms at each
    // size): each scene built once, on first use, its Embree scene only when a configuration
    // validates against it. A sized scene replaces the previous size's, so memory holds one size.
    struct OwnScene {
        Scene scene;
        std::unique_ptr<reference::EmbreeScene> embree;
    };
    std::map<std::pair<const BuiltinScene*, uint64_t>, OwnScene> ownScenes;

    auto wanted = [&](const std::string& series) {
        return !onlySeries || std::find(onlySeries->begin(), onlySeries->end(), series) != onlySeries->end();
    };
    std::vector<Config> configs;
    for (const Config& config : plan(quick)) {
        if (wanted(config.series)) configs.push_back(config);
    }
    const bool failureStudy = wanted("failures");
    ProgressBar progress(configs.size() + (failureStudy ? failureStudySize(context, quick) : 0));
    OutputFiles outputs;
    std::vector<Row> rows;
    std::vector<std::string> passes;  // the frame's pass names, from the first renderer
    std::map<std::string, ImageRgba8> bruteImages;  // by series + counts
    std::map<std::string, nlohmann::json> shadowLights;  // validated configurations: per-light counts
    std::map<std::string, nlohmann::json> sunCascades;   // validated configurations with a sun: per cascade
    for (const Config& config : configs) {
        Scene generatedLights;
        const Scene* sceneToRender = &generatedLights;
        const reference::EmbreeScene* geometry = &embree;
        if (config.scene) {
            const std::pair key{config.scene, config.triangles};
            auto own = ownScenes.find(key);
            if (own == ownScenes.end()) {
                if (config.triangles) {  // a new size: the previous one's memory goes first
                    std::erase_if(ownScenes, [&](const auto& entry) { return entry.first.first == config.scene; });
                    resetPeakResident();
                }
                own = ownScenes.emplace(key, OwnScene{makeBuiltinScene(*config.scene, config.triangles ? std::optional(config.triangles) : std::nullopt),
                                               nullptr}).first;
            }
            OwnScene& made = own->second;
            if (config.validateShadows && !made.embree) made.embree = std::make_unique<reference::EmbreeScene>(made.scene);
            sceneToRender = &made.scene;
            geometry = made.embree.get();
        } else {
            generatedLights = baseScene;
            replaceLights(generatedLights, config.spot, config.point, 1);
        }
        const Scene& scene = *sceneToRender;
        render::RenderSettings settings = renderSettingsFrom(options);
        settings.method = config.method;
        settings.shadows = config.shadows;
        // The statistics variant renders the frame once more: the triangle series, whose largest
        // frames take seconds, goes without.
        settings.collectLightStats = !config.validateShadows && config.series != "triangles";
        settings.collectShadowFactors = config.validateShadows;
        render::Renderer renderer(context, scene, settings);
        const render::FrameResult result = renderer.render(timedFrames, 1);
        // Median and spread (max - min over the timed frames) of every pass, by name.
        auto spread = [&](auto&& value) {
            double lo = 1e300, hi = 0.0;
            for (const render::PassTimings& t : result.framesMs) {
                lo = std::min(lo, value(t));
                hi = std::max(hi, value(t));
            }
            return hi - lo;
        };
        const std::string name = configName(config);
        Row row = {{"config", name},
                   {"series", config.series},
                   {"method", render::methodName(config.method)},
                   {"spot", std::to_string(lightsOfType(scene, LightType::Spot))},
                   {"point", std::to_string(lightsOfType(scene, LightType::Point))},
                   {"shadows", config.shadows.enabled ? "1" : "0"},
                   {"shadow_res", shadowResolutionName(config.shadows)},
                   {"shadow_format", shadowFormatName(config.shadows.format)},
                   {"shadow_filter", shadowFilterName(config.shadows.filter)},
                   {"shadowed_spots", std::to_string(renderer.shadowPlan().shadowedSpots)},
                   {"shadowed_points", std::to_string(renderer.shadowPlan().shadowedPoints)},
                   {"point_layout", pointShadowLayoutName(config.shadows.pointLayout)},
                   {"frames", std::to_string(timedFrames)},
                   {"total_ms", number(result.medianMs.total)},
                   {"total_spread_ms", number(spread([](const render::PassTimings& t) { return t.total; }))}};
        for (const auto& [pass, ms] : result.medianMs.passes) {
            row[pass + "_ms"] = number(ms);
            row[pass + "_spread_ms"] = number(spread([&](const render::PassTimings& t) { return t.of(pass); }));
        }
        if (passes.empty()) passes = renderer.passNames();
        if (config.triangles) {
            const render::CameraDraws& camera = renderer.cameraDraws();
            const render::ShadowDraws shadowDraws = renderer.shadowDraws();
            row["scene_triangles"] = std::to_string(scene.triangleCount());
            row["objects"] = std::to_string(scene.objects.size());
            row["objects_in_view"] = std::to_string(camera.objectsInView);
            row["camera_triangles"] = std::to_string(camera.triangles);
            row["camera_draws"] = std::to_string(camera.depthDraws + camera.forwardDraws + camera.transparentDraws);
            row["shadow_draws"] = std::to_string(shadowDraws.total);
            row["shadow_draws_max"] = std::to_string(shadowDraws.maxPerView);
            row["shadow_triangles"] = std::to_string(shadowDraws.triangles);
            // Since this size's scene was built (resetPeakResident), or the whole run's peak.
            row["peak_rss_bytes"] = std::to_string(peakResidentSinceReset());
            row["device_bytes"] = std::to_string(renderer.deviceMemoryBytes());
        }
        if (settings.collectLightStats) {
            const LightStatsImage stats = renderer.readLightStats();
            const CullingStats culling = computeCullingStats(stats);
            row["tested_per_pixel"] = number(culling.testedPerPixel);
            row["affecting_per_pixel"] = number(culling.affectingPerPixel);
            row["efficiency"] = number(culling.efficiency);
            row["missed_energy"] = number(culling.missedEnergy);
            // Sample heat maps: every method at the largest mixed count.
            if (config.series == "mix" && config.spot == 64) {
                std::vector<uint8_t> background(stats.covered.size());
                for (size_t i = 0; i < background.size(); ++i) background[i] = stats.covered[i] ? 0 : 1;
                HeatmapOptions heatmap;
                heatmap.title = std::string("lights tested per pixel: ") + render::methodName(config.method);
                heatmap.maxValue = 32;
                outputs.add(*outDir + "/images/heatmap-" + render::methodName(config.method) + ".png",
                            encodePng(renderHeatmap(stats.tested, background, settings.width, settings.height, heatmap)));
            }
        }
        const std::string bruteKey = config.series + std::to_string(config.spot) + "," + std::to_string(config.point) +
                                     (config.shadows.enabled ? "s" : "") + std::to_string(config.triangles);
        if (config.method == render::referenceMethod() && !config.validateShadows) {
            bruteImages[bruteKey] = result.image;
        } else if (bruteImages.count(bruteKey)) {
            const ImageDifference difference = compareImages(result.image, bruteImages[bruteKey]);
            row["image_error"] = number(difference.meanAbsolute);
            row["pixels_off"] = number(difference.pixelsOff);
        }
        if (config.shadows.enabled) {
            const ShadowPlan& shadowPlan = renderer.shadowPlan();
            row["shadow_views"] = std::to_string(shadowPlan.viewsRendered);
            row["shadow_memory_bytes"] = std::to_string(renderer.shadowMemoryBytes());
            row["shadow_texels_rendered"] = std::to_string(shadowTexelsRendered(shadowPlan));
            row["shadow_filter_taps"] = std::to_string(config.shadows.filterTaps());
            row["shadow_reduced_views"] = std::to_string(shadowPlan.reductions.size());
        }
        if (config.validateShadows) {
            const ShadowFactorImage factors = renderer.readShadowFactors();
            const reference::ShadowValidation validation =
                reference::validateShadows(*geometry, factors, renderer.lights(), renderer.shadowPlan());
            // The same comparison with an edge band one screen pixel wide: the fair one across
            // resolutions (a texel band widens with the texels).
            const reference::ShadowValidation onePixel = reference::validateShadows(
                *geometry, factors, renderer.lights(), renderer.shadowPlan(),
                reference::EdgeBand::ofScreenPixels(1.0f, scene.camera, settings.height));
            row["shadow_misclassified"] = number(validation.overall.misclassifiedOutsideBand());
            row["shadow_misclassified_all"] = number(validation.overall.misclassified());
            row["shadow_misclassified_1px"] = number(onePixel.overall.misclassifiedOutsideBand());
            nlohmann::json perLight = nlohmann::json::array();
            for (const reference::LightShadowValidation& light : onePixel.lights) {
                const reference::ShadowCounts& c = light.counts;
                perLight.push_back({{"light", light.sceneLight},
                                    {"compared", c.compared},
                                    {"misclassified", c.falseShadow + c.falseLit},
                                    {"compared_outside_1px", c.comparedOutsideBand},
                                    {"misclassified_outside_1px", c.falseShadowOutsideBand + c.falseLitOutsideBand}});
            }
            shadowLights[name] = perLight;
            if (validation.sun && onePixel.sun) {
                const CascadePlan& cascades = renderer.shadowPlan().cascades;
                row["cascades"] = std::to_string(cascades.count);
                row["sun_misclassified"] = number(validation.sun->counts.misclassifiedOutsideBand());
                row["sun_misclassified_1px"] = number(onePixel.sun->counts.misclassifiedOutsideBand());
                nlohmann::json perCascade = nlohmann::json::array();
                for (uint32_t i = 0; i < cascades.count; ++i) {
                    const reference::ShadowCounts& texelBand = validation.sun->cascades[i];
                    const reference::ShadowCounts& pixelBand = onePixel.sun->cascades[i];
                    row[sunCascadeColumn(i)] = number(pixelBand.misclassifiedOutsideBand());
                    perCascade.push_back({{"cascade", i},
                                          {"far_m", cascades.splits[i]},
                                          {"resolution", renderer.shadowPlan().views[cascades.firstView + i].resolution},
                                          {"texel_m", cascadeTexelSize(renderer.shadowPlan(), i)},
                                          {"compared", texelBand.compared},
                                          {"misclassified_outside_band", texelBand.misclassifiedOutsideBand()},
                                          {"misclassified_outside_1px", pixelBand.misclassifiedOutsideBand()}});
                }
                sunCascades[name] = perCascade;
            }
            row["shadow_false_shadow"] = std::to_string(validation.overall.falseShadow);
            row["shadow_false_lit"] = std::to_string(validation.overall.falseLit);
            if (!validation.lights.empty()) {
                outputs.add(*outDir + "/images/mismatch-" + name + "-light0.png",
                            encodePng(mismatchMap(validation.lights.front(), validation.width, validation.height)));
            }
        }
        rows.push_back(row);
        progress.step(name);
    }
    // Where methods fail: one scene per known failure, error against the provoking parameter.
    const std::vector<FailureRow> failures =
        failureStudy ? runFailureStudy(context, quick, options.width, options.height,
                                       [&](const std::string& what) { progress.step(what); })
                     : std::vector<FailureRow>{};
    if (context.validationMessageCount() > 0) {
        throw Error("vulkan", std::to_string(context.validationMessageCount()) + " validation message(s); no output written");
    }

    const std::vector<std::string> columns = resultColumns(passes);
    std::ostringstream csv;
    for (size_t i = 0; i < columns.size(); ++i) csv << (i ? "," : "") << columns[i];
    csv << "\n";
    nlohmann::json json = nlohmann::json::array();
    for (const Row& row : rows) {
        nlohmann::json entry;
        for (size_t i = 0; i < columns.size(); ++i) {
            const auto it = row.find(columns[i]);
            const std::string value = it == row.end() ? "" : it->second;
            csv << (i ? "," : "") << value;
            entry[columns[i]] = value;
        }
        const auto lightsIt = shadowLights.find(row.at("config"));
        if (lightsIt != shadowLights.end()) entry["shadow_lights"] = lightsIt->second;
        const auto cascadesIt = sunCascades.find(row.at("config"));
        if (cascadesIt != sunCascades.end()) entry["sun_cascades"] = cascadesIt->second;
        csv << "\n";
        json.push_back(entry);
    }
    // The variant and pass names, so the chart scripts list what this run has without a list of
    // their own.
    nlohmann::json document = {{"scene", baseScene.source},
                               {"device", context.deviceName()},
                               {"size", {{"width", options.width}, {"height", options.height}}},
                               {"quick", quick},
                               {"methods", render::methodNames()},
                               {"shadow_filters", shadowFilterNames()},
                               {"point_layouts", pointShadowLayoutNames()},
                               {"passes", passes},
                               {"configurations", json}};
    outputs.add(*outDir + "/results.csv", csv.str());
    outputs.add(*outDir + "/failures.csv", failuresCsv(failures));
    // results.json lists every file of this run, so the next run into DIR removes the images
    // it does not write again (a full run's extra resolutions after a --quick one, say).
    const std::vector<std::string> files = outputFolderFiles(outputs, *outDir, kFolderLayout);
    document["files"] = files;
    outputs.add(*outDir + "/results.json", document.dump(2) + "\n");
    prepareOutputFolder(outputs, *outDir, kFolderLayout, files);
    outputs.commit();
    std::printf("bench: %zu configurations on %s at %ux%u, %u timed frames each; wrote %s/results.csv\n", rows.size(),
                baseScene.source.c_str(), options.width, options.height, timedFrames, outDir->c_str());
    return 0;
}

}  // namespace punctual::app
