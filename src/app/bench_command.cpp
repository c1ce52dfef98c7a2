#include "app/bench_command.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>

#include <nlohmann/json.hpp>

#include "cli/option_values.h"
#include "cli/options.h"
#include "cli/output_paths.h"
#include "cli/scene_source.h"
#include "bench/bench_failures.h"
#include "bench/bench_plan.h"
#include "bench/bench_provenance.h"
#include "bench/bench_report.h"
#include "bench/bench_rows.h"
#include "bench/bench_run.h"
#include "core/error.h"
#include "core/run_program.h"
#include "core/output_files.h"
#include "core/output_folder.h"
#include "lights/shadow_filters.h"
#include "metrics/round_statistics.h"
#include "render/renderer.h"
#include "scene/input_file.h"
#include "vk/context.h"

namespace punctual::app {

using namespace cli;  // the command line (src/cli)
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
    for (const bench::BenchSeries& s : bench::benchSeries()) series += "  " + std::string(s.name) + ": " + s.description + "\n";
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
    auto value = [&](size_t& i) -> const std::string& { return optionValue(args, i); };
    for (size_t i = 0; i < args.size(); ++i) {
        const std::string& arg = args[i];
        if (arg == "--help" || arg == "-h") {
            parsed.help = true;
        } else if (arg == "--quick") {
            parsed.quick = true;
        } else if (arg == "--out-dir") {
            parsed.outDir = value(i);
        } else if (arg == "--series") {
            parsed.series = bench::parseBenchSeries(value(i));
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
    const std::string script = bench::benchScriptDir() + "/compare_runs.py";
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



// Writes results.csv, failures.csv and results.json (which lists every file of the run, so the
// next run into DIR removes the images it does not write again) and commits them all.
void commitResults(OutputFiles& outputs, const std::string& outDir, const bench::BenchRecord& record,
                   const std::vector<bench::FailureRow>& failures, nlohmann::json document) {
    const std::vector<std::string> columns = bench::benchColumns(record.passes);
    document["configurations"] = bench::resultsConfigurations(record, columns);
    outputs.add(outDir + "/results.csv", bench::resultsCsv(record, columns));
    outputs.add(outDir + "/failures.csv", bench::failuresCsv(failures));
    const std::vector<std::string> files = outputFolderFiles(outputs, outDir, kFolderLayout);
    document["files"] = files;
    outputs.add(outDir + "/results.json", document.dump(2) + "\n");
    prepareOutputFolder(outputs, outDir, kFolderLayout, files);
    outputs.commit();
}

// The variant and pass names, so the chart scripts list what this run has without a list of their
// own; where the numbers come from; how noisy the run was.
nlohmann::json resultsDocument(const vk::Context& context, const Scene& scene, const RenderOptions& options,
                               const BenchArgs& bench, const bench::BenchRunSettings& run,
                               const bench::BenchRecord& record, const std::vector<std::string>& args) {
    return {{"scene", scene.source},
            {"device", context.deviceName()},
            {"size", {{"width", options.width}, {"height", options.height}}},
            {"quick", bench.quick},
            {"methods", render::methodNames()},
            {"light_lists", render::lightListFormNames()},
            {"shadow_filters", shadowFilterNames()},
            {"point_layouts", pointShadowLayoutNames()},
            {"passes", record.passes},
            {"provenance", bench::benchProvenance(context, args, {scene.source, scene.triangleCount()}, options.width,
                                                  options.height)},
            {"noise",
             {{"rounds", run.rounds},
              {"best_of", run.bestOf},
              {"seed", bench.seed},
              {"median_cv", medianOf(record.frameCvs)},
              {"frame_median_cv", medianOf(record.singleFrameCvs)},
              {"flag_limit", bench::kSpreadFlagLimit},
              {"flagged", record.flagged}}}};
}

// The charts and index.html, when python3-matplotlib is there; 1 when a chart script failed and
// named the problem itself.
int drawCharts(const std::string& outDir, bool failureStudy) {
    std::string why;
    if (!bench::chartsAvailable(why)) {
        std::printf("bench: no charts: %s\n", why.c_str());
        return 0;
    }
    if (!bench::drawBenchReport(outDir, failureStudy, why)) {
        if (why.empty()) return 1;  // the chart script's one line named the file and the problem
        throw Error("charts", why + " (results.csv and results.json are written)");
    }
    std::printf("bench: wrote %s/index.html\n", outDir.c_str());
    return 0;
}

}  // namespace

int runBenchCommand(const std::vector<std::string>& args) {
    const BenchArgs bench = parseBenchArgs(args);
    if (bench.help) {
        std::fputs(usage().c_str(), stdout);
        return 0;
    }
    if (!bench.outDir) throw Error("--out-dir", "bench needs an output folder (--out-dir DIR)");
    if (bench.compare) return runCompare(bench);
    const std::string& outDir = *bench.outDir;
    checkOutputFolder(outDir, kFolderLayout);

    bench::BenchRunSettings run;
    run.options = parseRenderOptions(bench.renderArgs);
    RenderOptions& options = run.options;
    const bool sizeGiven = std::find(bench.renderArgs.begin(), bench.renderArgs.end(), "--size") != bench.renderArgs.end();
    if (bench.quick && !sizeGiven) {
        options.width = 320;
        options.height = 180;
    }
    run.rounds = bench.rounds ? bench.rounds : (bench.quick ? 3u : 5u);
    run.bestOf = bench.bestOf ? bench.bestOf : (bench.quick ? bench::kQuickBestOf : bench::kDefaultBestOf);
    run.seed = bench.seed;
    run.outDir = outDir;
    const Scene baseScene = loadSceneForOptions(options);
    checkOutputFolder(outDir, kFolderLayout);  // again, now that the files the scene reads are known
    vk::Context context(contextOptionsFrom(options));

    auto wanted = [&](const std::string& series) {
        return !bench.series || std::find(bench.series->begin(), bench.series->end(), series) != bench.series->end();
    };
    std::vector<bench::BenchConfig> configs;
    for (const bench::BenchConfig& config : bench::benchPlan(bench.quick)) {
        if (wanted(config.series)) configs.push_back(config);
    }
    const bool failureStudy = wanted("failures");
    bench::ProgressBar progress(configs.size() + (failureStudy ? bench::failureStudySize(context, bench.quick) : 0));
    OutputFiles outputs;
    bench::BenchRun measured(context, baseScene, run, outputs);
    measured.measure(configs, progress);
    // Where methods fail: one scene per known failure, error against the provoking parameter.
    const std::vector<bench::FailureRow> failures =
        failureStudy ? bench::runFailureStudy(context, bench.quick, options.width, options.height,
                                              [&](const std::string& what) { progress.step(what); })
                     : std::vector<bench::FailureRow>{};
    if (context.validationMessageCount() > 0) {
        throw Error("vulkan", std::to_string(context.validationMessageCount()) + " validation message(s); no output written");
    }
    const bench::BenchRecord& record = measured.record();
    commitResults(outputs, outDir, record, failures,
                  resultsDocument(context, baseScene, options, bench, run, record, args));
    std::printf("bench: %zu configurations on %s, %u rounds of the fastest of %u frames (noise: median CV %.1f%%, "
                "%.1f%% frame to frame; %u flagged); wrote %s/results.csv\n",
                record.rows.size(), baseScene.source.c_str(), run.rounds, run.bestOf, 100.0 * medianOf(record.frameCvs),
                100.0 * medianOf(record.singleFrameCvs), record.flagged, outDir.c_str());
    return drawCharts(outDir, failureStudy);
}

}  // namespace punctual::app
