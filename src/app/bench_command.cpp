#include "app/bench_command.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>

#include <nlohmann/json.hpp>

#include "app/bench_failures.h"
#include "app/bench_plan.h"
#include "app/bench_provenance.h"
#include "app/bench_report.h"
#include "app/bench_rows.h"
#include "app/options.h"
#include "app/output_paths.h"
#include "app/scene_source.h"
#include "core/error.h"
#include "core/memory_usage.h"
#include "core/output_files.h"
#include "core/output_folder.h"
#include "lights/shadow_filters.h"
#include "metrics/heatmap.h"
#include "metrics/image_diff.h"
#include "reference/embree_scene.h"
#include "render/renderer.h"
#include "scene/input_file.h"
#include "scene/light_generator.h"
#include "vk/context.h"

namespace punctual::app {
namespace {

// Everything bench writes into --out-dir itself; results.json lists a run's files. The chart
// scripts then add charts/, index.html and failures.html (bench/plot_*.py).
const OutputFolderLayout kFolderLayout = {
    "results.json",
    {"results.csv", "results.json", "failures.csv", "images/heatmap-*.png", "images/mismatch-*.png"},
    {"images"}};

std::string usage() {
    std::vector<std::string> quickFilters;
    for (const ShadowFilterInfo& filter : kShadowFilters) {
        if (filter.quickBench) quickFilters.emplace_back(filter.name);
    }
    std::string series;
    for (const BenchSeries& s : benchSeries()) series += "  " + std::string(s.name) + ": " + s.description + "\n";
    return R"(usage: punctual bench [SCENE|--scene NAME] [--quick] --out-dir DIR [--size WxH] [--rounds R]
                     [--best-of K] [--seed N] [--series NAME[,NAME...]]
       punctual bench --compare DIR_A DIR_B --out-dir DIR

Measures, on SCENE or the built-in scene NAME (default: )" + std::string(kDefaultBuiltinScene.name) +
           R"() with generated lights, the series:
)" + series + R"(
Every configuration renders one warm-up frame, then R rounds (default 5): in each round every
configuration of a group (a series on one scene) renders K frames back to back (--best-of,
default 3) and keeps each pass's fastest, in a random order drawn per round from --seed
(default 1). Each pass gets its median, interquartile range and coefficient of variation over the
rounds; a configuration whose frame IQR exceeds 15% of its median is flagged. Beside the times: lights tested and reaching per pixel, shadow lookups and filter taps
per pixel, triangles and draws per pass, shadow texels, memory by kind. Shadow configurations are
validated against Embree (edge band one texel, and one pixel).
Writes DIR/results.csv, DIR/results.json (with provenance and the run's noise), DIR/images/,
DIR/failures.csv (the failure study), then draws DIR/charts/, DIR/index.html and
DIR/failures.html (bench/plot_results.py and plot_failures.py; they need python3-matplotlib:
without it the bench says so and keeps the CSV and JSON). docs/BENCH_RESULTS.md says what every
column means.
--series: only the named series (failures: the failure study).
--quick: 320x180, 3 rounds of one frame, fewer values per series: the light counts as the mix alone, brute
force and tiled alone where frames cost seconds (shadows, triangles), auto and 256 shadow maps,
filters )" + joinNames(quickFilters, " and ") + R"( (under 3 minutes on 2 CPU cores).
--compare: a side-by-side page of two runs, DIR/compare.html and DIR/compare.csv: per
configuration each pass's time in both and the ratio, and the counters, which should match.
Default size: 1280x720 (quick: 320x180).
)";
}

class ProgressBar {
public:
    explicit ProgressBar(size_t total) : total_(total), terminal_(isatty(2) != 0) {}
    void step(const std::string& what) {
        ++done_;
        if (!terminal_) return;
        const int width = 30;
        const int filled = int(double(done_) / double(std::max<size_t>(total_, 1)) * width);
        std::fprintf(stderr, "\r[%s%s] %zu/%zu %-40.40s", std::string(size_t(filled), '#').c_str(),
                     std::string(size_t(width - std::min(filled, width)), '.').c_str(), done_, total_, what.c_str());
        if (done_ == total_) std::fputc('\n', stderr);
    }

private:
    size_t total_;
    size_t done_ = 0;
    bool terminal_;
};

struct BenchArgs {
    std::vector<std::string> renderArgs;
    std::optional<std::string> outDir;
    bool quick = false;
    uint32_t rounds = 0;  // 0: the default (5, quick 3)
    uint32_t bestOf = 0;  // 0: the default (kDefaultBestOf, quick 1)
    uint64_t seed = 1;
    std::optional<std::vector<std::string>> series;
    std::optional<std::pair<std::string, std::string>> compare;
    bool help = false;
};

uint64_t parseCount(const std::string& option, const std::string& text, uint64_t lo, uint64_t hi) {
    size_t used = 0;
    unsigned long long value = 0;
    try {
        value = std::stoull(text, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used != text.size() || text.empty() || text[0] == '-' || value < lo || value > hi) {
        throw Error(option, "expected a whole number from " + std::to_string(lo) + " to " + std::to_string(hi) +
                                ", got '" + text + "'");
    }
    return value;
}

BenchArgs parseBenchArgs(const std::vector<std::string>& args) {
    BenchArgs parsed;
    auto value = [&](size_t& i) -> const std::string& {
        if (i + 1 >= args.size() || args[i + 1].rfind("--", 0) == 0) throw Error(args[i], "needs a value");
        return args[++i];
    };
    for (size_t i = 0; i < args.size(); ++i) {
        const std::string& arg = args[i];
        if (arg == "--help" || arg == "-h") {
            parsed.help = true;
        } else if (arg == "--quick") {
            parsed.quick = true;
        } else if (arg == "--out-dir") {
            parsed.outDir = value(i);
        } else if (arg == "--series") {
            parsed.series = parseBenchSeries(value(i));
        } else if (arg == "--rounds") {
            parsed.rounds = uint32_t(parseCount(arg, value(i), 1, 1000));
        } else if (arg == "--best-of") {
            parsed.bestOf = uint32_t(parseCount(arg, value(i), 1, 100));
        } else if (arg == "--seed") {
            parsed.seed = parseCount(arg, value(i), 0, UINT64_MAX);
        } else if (arg == "--compare") {
            const std::string a = value(i);
            const std::string b = value(i);
            parsed.compare = std::pair(a, b);
        } else if (arg == "--scene" || arg == "--size" || arg == "--device" || arg == "--validate" ||
                   arg == "--exposure" || arg.rfind("--", 0) != 0) {
            parsed.renderArgs.push_back(arg);
            if (arg != "--validate" && arg.rfind("--", 0) == 0 && i + 1 < args.size()) parsed.renderArgs.push_back(args[++i]);
        } else if (arg == "--frames") {
            throw Error(arg, "bench times rounds, not frames: use --rounds R");
        } else {
            throw Error(arg, "not an option of bench (see punctual bench --help)");
        }
    }
    return parsed;
}

// What a bench file may weigh: bench/input_file.py's MAX_BYTES (the script reads with the same cap).
constexpr uint64_t kMaxBenchFileBytes = 256ull << 20;

// `punctual bench --compare DIR_A DIR_B --out-dir DIR`: bench/compare_runs.py writes the page.
int runCompare(const BenchArgs& args) {
    // The files compare_runs.py reads, by the one reader's rules (scene/input_file.h, and
    // bench/input_file.py on the script's side): a FIFO or a folder is refused here, never opened.
    for (const std::string& dir : {args.compare->first, args.compare->second}) {
        for (const char* name : {"results.json", "results.csv"}) {
            const std::string path = dir + "/" + name;
            const std::string problem = regularFileProblem(path, kMaxBenchFileBytes);
            if (problem == "no such file") throw Error(dir, std::string("not a bench folder (no ") + name + ")");
            if (!problem.empty()) throw Error(path, "cannot be read (" + problem + ")");
        }
    }
    if (access("/usr/bin/python3", X_OK) != 0) throw Error("--compare", "needs /usr/bin/python3 (apt-get install python3)");
    const std::string script = benchScriptDir() + "/compare_runs.py";
    const int status = runProgram("/usr/bin/python3", {script, args.compare->first, args.compare->second, *args.outDir});
    // Status 1: bad input, which the script has named in its one line (file and problem).
    if (status == 1) return 1;
    if (status != 0) {
        endAsTheChildEnded(status);
        throw Error("--compare", script + " exited with status " + std::to_string(status));
    }
    std::printf("bench: compared %s with %s; wrote %s/compare.html\n", args.compare->first.c_str(),
                args.compare->second.c_str(), args.outDir->c_str());
    return 0;
}

// One configuration while its group is measured: its scene, renderer and rounds.
struct Measurement {
    BenchConfig config;
    std::unique_ptr<Scene> ownScene;  // generated lights: a copy of the bench's scene
    const Scene* scene = nullptr;
    const reference::EmbreeScene* geometry = nullptr;
    std::unique_ptr<render::Renderer> renderer;
    std::vector<render::PassTimings> rounds;  // one sample a round: the fastest of its frames
    std::vector<double> frameTotals;          // every timed frame, for the run's frame noise
    ImageRgba8 image;
};

}  // namespace

int runBenchCommand(const std::vector<std::string>& args) {
    const BenchArgs bench = parseBenchArgs(args);
    if (bench.help) {
        std::fputs(usage().c_str(), stdout);
        return 0;
    }
    if (!bench.outDir) throw Error("--out-dir", "bench needs an output folder (--out-dir DIR)");
    if (bench.compare) return runCompare(bench);
    checkOutputFolder(*bench.outDir, kFolderLayout);

    RenderOptions options = parseRenderOptions(bench.renderArgs);
    const bool sizeGiven = std::find(bench.renderArgs.begin(), bench.renderArgs.end(), "--size") != bench.renderArgs.end();
    if (bench.quick && !sizeGiven) {
        options.width = 320;
        options.height = 180;
    }
    const uint32_t rounds = bench.rounds ? bench.rounds : (bench.quick ? 3u : 5u);
    const uint32_t bestOf = bench.bestOf ? bench.bestOf : (bench.quick ? kQuickBestOf : kDefaultBestOf);
    Scene baseScene = loadSceneForOptions(options);
    checkOutputFolder(*bench.outDir, kFolderLayout);  // again, now that the files the scene reads are known
    vk::Context context(contextOptionsFrom(options));
    const reference::EmbreeScene embree(baseScene);  // geometry only: shared by every configuration
    // The generated lights: the largest set once; each configuration takes its first lights at its
    // range (nested sets, docs/BENCH_RESULTS.md).
    Scene fullSet = baseScene;
    replaceLights(fullSet, kBenchSpots, kBenchPoints, 1);
    // The series with built-in scenes of their own (the cascades' outdoor scene, the rooms at each
    // size): each built once, on first use, its Embree scene only when a configuration validates
    // against it. A sized scene replaces the previous size's, so memory holds one size.
    struct OwnScene {
        Scene scene;
        std::unique_ptr<reference::EmbreeScene> embree;
    };
    std::map<std::pair<const BuiltinScene*, uint64_t>, OwnScene> ownScenes;

    auto wanted = [&](const std::string& series) {
        return !bench.series || std::find(bench.series->begin(), bench.series->end(), series) != bench.series->end();
    };
    std::vector<BenchConfig> configs;
    for (const BenchConfig& config : benchPlan(bench.quick)) {
        if (wanted(config.series)) configs.push_back(config);
    }
    const bool failureStudy = wanted("failures");
    ProgressBar progress(configs.size() + (failureStudy ? failureStudySize(context, bench.quick) : 0));
    OutputFiles outputs;
    std::vector<BenchRow> rows;
    std::vector<double> frameCvs;        // each configuration's CV over its rounds
    std::vector<double> singleFrameCvs;  // each configuration's CV over every timed frame
    uint32_t flagged = 0;
    std::vector<std::string> passes;  // the frame's pass names, from the first renderer
    std::map<std::string, ImageRgba8> bruteImages;  // by what brute force's image is compared on
    std::map<std::string, nlohmann::json> shadowLights;  // validated configurations: per-light counts
    std::map<std::string, nlohmann::json> sunCascades;   // validated configurations with a sun: per cascade
    std::map<std::string, nlohmann::json> frameSamples;  // every configuration: its timed frames' totals

    uint32_t groupIndex = 0;
    for (size_t first = 0; first < configs.size(); ++groupIndex) {
        size_t end = first;
        while (end < configs.size() && benchGroupKey(configs[end]) == benchGroupKey(configs[first])) ++end;
        // The group's renderers, all alive while its rounds run.
        std::vector<Measurement> group;
        for (size_t c = first; c < end; ++c) {
            Measurement m;
            m.config = configs[c];
            const BenchConfig& config = m.config;
            if (config.scene) {
                const std::pair key{config.scene, config.triangles};
                auto own = ownScenes.find(key);
                if (own == ownScenes.end()) {
                    if (config.triangles) {  // a new size: the previous one's memory goes first
                        std::erase_if(ownScenes, [&](const auto& entry) { return entry.first.first == config.scene; });
                        resetPeakResident();
                    }
                    own = ownScenes
                              .emplace(key, OwnScene{makeBuiltinScene(*config.scene, config.triangles
                                                                                        ? std::optional(config.triangles)
                                                                                        : std::nullopt),
                                                     nullptr})
                              .first;
                }
                OwnScene& made = own->second;
                if (config.validateShadows && !made.embree) made.embree = std::make_unique<reference::EmbreeScene>(made.scene);
                m.scene = &made.scene;
                m.geometry = made.embree.get();
            } else {
                m.ownScene = std::make_unique<Scene>(fullSet);
                setLightRanges(*m.ownScene, config.lightRange);
                keepFirstLights(*m.ownScene, config.spot, config.point);
                m.scene = m.ownScene.get();
                m.geometry = &embree;
            }
            render::RenderSettings settings = renderSettingsFrom(options);
            if (config.width) {
                settings.width = config.width;
                settings.height = config.height;
            }
            settings.method = config.method;
            settings.coarseTiles = config.coarseTiles;
            settings.shadows = config.shadows;
            settings.collectLightStats = true;  // rendered apart, untimed (addCounters)
            settings.collectShadowFactors = config.validateShadows;
            settings.warnReducedShadows = false;  // recorded in shadow_reduced_views
            m.renderer = std::make_unique<render::Renderer>(context, *m.scene, settings);
            m.renderer->render(1, 0);  // warm-up: pipelines compiled, memory touched
            group.push_back(std::move(m));
        }
        for (uint32_t round = 0; round < rounds; ++round) {
            for (uint32_t i : roundOrder(uint32_t(group.size()), bench.seed, groupIndex, round)) {
                // The round's visit: bestOf frames back to back, the fastest per pass kept.
                std::vector<render::PassTimings> frames;
                for (uint32_t frame = 0; frame < bestOf; ++frame) {
                    render::FrameResult result = group[i].renderer->render(1, 0);
                    frames.push_back(result.framesMs.front());
                    group[i].frameTotals.push_back(result.framesMs.front().total);
                    group[i].image = std::move(result.image);
                }
                group[i].rounds.push_back(fastestPerPass(frames));
            }
        }
        for (Measurement& m : group) {
            const BenchConfig& config = m.config;
            render::Renderer& renderer = *m.renderer;
            if (passes.empty()) passes = renderer.passNames();
            BenchRow row;
            addConfiguration(row, config, *m.scene, renderer, rounds, bestOf);
            const RoundSummary frame = addTimings(row, m.rounds);
            frameCvs.push_back(frame.cv);
            singleFrameCvs.push_back(summarizeRounds(m.frameTotals).cv);
            flagged += row["flagged"] == "1" ? 1u : 0u;
            const LightStatsImage pixelWork = renderer.readLightStats();
            addCounters(row, renderer, &pixelWork);
            const std::string name = row["config"];
            // The raw samples, in the order they were taken (round by round, bestOf frames each),
            // so that a reader can look at the spread behind a flag.
            frameSamples[name] = m.frameTotals;
            // Sample heat maps: every method at the largest mixed count.
            if (config.series == "mix" && config.spot == kBenchSpots) {
                std::vector<uint8_t> background(pixelWork.covered.size());
                for (size_t i = 0; i < background.size(); ++i) background[i] = pixelWork.covered[i] ? 0 : 1;
                HeatmapOptions heatmap;
                heatmap.title = std::string("lights tested per pixel: ") + render::methodName(config.method);
                heatmap.maxValue = 32;
                outputs.add(*bench.outDir + "/images/heatmap-" + render::methodName(config.method) + ".png",
                            encodePng(renderHeatmap(pixelWork.tested, background, renderer.settings().width,
                                                    renderer.settings().height, heatmap)));
            }
            // Brute force's image, for the other methods of the same frame.
            const std::string bruteKey = config.series + "/" + std::to_string(config.spot) + "," +
                                         std::to_string(config.point) + "/" + benchNumber(config.lightRange) + "/" +
                                         row["width"] + "x" + row["height"] + (config.shadows.enabled ? "/s" : "") +
                                         "/" + std::to_string(config.triangles);
            if (!config.validateShadows && config.method == render::referenceMethod()) {
                bruteImages[bruteKey] = m.image;
            } else if (!config.validateShadows && bruteImages.count(bruteKey)) {
                const ImageDifference difference = compareImages(m.image, bruteImages[bruteKey]);
                row["image_error"] = benchNumber(difference.meanAbsolute);
                row["pixels_off"] = benchNumber(difference.pixelsOff);
            }
            if (config.validateShadows && m.geometry) {
                ShadowValidationRows validation = addShadowValidation(row, renderer, *m.geometry, *m.scene);
                shadowLights[name] = validation.perLight;
                if (!validation.perCascade.is_null()) sunCascades[name] = validation.perCascade;
                if (validation.mismatch) {
                    outputs.add(*bench.outDir + "/images/mismatch-" + name + "-light0.png", encodePng(*validation.mismatch));
                }
            }
            m.renderer.reset();  // the group's memory goes as its rows are written
            rows.push_back(std::move(row));
            progress.step(name);
        }
        first = end;
    }
    // Where methods fail: one scene per known failure, error against the provoking parameter.
    const std::vector<FailureRow> failures =
        failureStudy ? runFailureStudy(context, bench.quick, options.width, options.height,
                                       [&](const std::string& what) { progress.step(what); })
                     : std::vector<FailureRow>{};
    if (context.validationMessageCount() > 0) {
        throw Error("vulkan", std::to_string(context.validationMessageCount()) + " validation message(s); no output written");
    }

    const std::vector<std::string> columns = benchColumns(passes);
    std::string csv;
    for (size_t i = 0; i < columns.size(); ++i) csv += (i ? "," : "") + columns[i];
    csv += "\n";
    nlohmann::json json = nlohmann::json::array();
    for (const BenchRow& row : rows) {
        nlohmann::json entry;
        for (size_t i = 0; i < columns.size(); ++i) {
            const auto it = row.find(columns[i]);
            const std::string value = it == row.end() ? "" : it->second;
            // Only flag_reason holds free text; it never has a comma or a quote.
            csv += (i ? "," : "") + value;
            entry[columns[i]] = value;
        }
        const auto lightsIt = shadowLights.find(row.at("config"));
        if (lightsIt != shadowLights.end()) entry["shadow_lights"] = lightsIt->second;
        const auto cascadesIt = sunCascades.find(row.at("config"));
        if (cascadesIt != sunCascades.end()) entry["sun_cascades"] = cascadesIt->second;
        entry["frame_total_ms"] = frameSamples.at(row.at("config"));
        csv += "\n";
        json.push_back(entry);
    }
    // The variant and pass names, so the chart scripts list what this run has without a list of
    // their own; where the numbers come from; how noisy the run was.
    nlohmann::json document = {
        {"scene", baseScene.source},
        {"device", context.deviceName()},
        {"size", {{"width", options.width}, {"height", options.height}}},
        {"quick", bench.quick},
        {"methods", render::methodNames()},
        {"shadow_filters", shadowFilterNames()},
        {"point_layouts", pointShadowLayoutNames()},
        {"passes", passes},
        {"provenance", benchProvenance(context, args, {baseScene.source, baseScene.triangleCount()}, options.width,
                                       options.height)},
        {"noise",
         {{"rounds", rounds},
          {"best_of", bestOf},
          {"seed", bench.seed},
          {"median_cv", medianOf(frameCvs)},
          {"frame_median_cv", medianOf(singleFrameCvs)},
          {"flag_limit", kSpreadFlagLimit},
          {"flagged", flagged}}},
        {"configurations", json}};
    outputs.add(*bench.outDir + "/results.csv", csv);
    outputs.add(*bench.outDir + "/failures.csv", failuresCsv(failures));
    // results.json lists every file of this run, so the next run into DIR removes the images
    // it does not write again (a full run's extra resolutions after a --quick one, say).
    const std::vector<std::string> files = outputFolderFiles(outputs, *bench.outDir, kFolderLayout);
    document["files"] = files;
    outputs.add(*bench.outDir + "/results.json", document.dump(2) + "\n");
    prepareOutputFolder(outputs, *bench.outDir, kFolderLayout, files);
    outputs.commit();
    std::printf("bench: %zu configurations on %s, %u rounds of the fastest of %u frames (noise: median CV %.1f%%, "
                "%.1f%% frame to frame; %u flagged); wrote %s/results.csv\n",
                rows.size(), baseScene.source.c_str(), rounds, bestOf, 100.0 * medianOf(frameCvs),
                100.0 * medianOf(singleFrameCvs), flagged, bench.outDir->c_str());
    std::string why;
    if (!chartsAvailable(why)) {
        std::printf("bench: no charts: %s\n", why.c_str());
        return 0;
    }
    if (!drawBenchReport(*bench.outDir, failureStudy, why)) {
        if (why.empty()) return 1;  // the chart script's one line named the file and the problem
        throw Error("charts", why + " (results.csv and results.json are written)");
    }
    std::printf("bench: wrote %s/index.html\n", bench.outDir->c_str());
    return 0;
}

}  // namespace punctual::app
