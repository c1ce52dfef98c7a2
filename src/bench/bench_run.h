#pragma once
// The bench's measuring loop: every configuration of a plan (bench_plan.h) rendered in groups
// (a series on one scene), each group's renderers alive together while their rounds run in an
// order drawn per round, then one row per configuration (bench_rows.h) with its times, counters,
// image error against brute force and, where asked, shadow validation against Embree. The
// command (app/bench_command.cpp) loads the scene, writes the files and draws the charts.
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/options.h"
#include "bench/bench_plan.h"
#include "bench/bench_rows.h"
#include "bench/progress_bar.h"
#include "core/image.h"
#include "core/output_files.h"
#include "reference/embree_scene.h"
#include "scene/builtin_scenes.h"
#include "scene/scene.h"
#include "vk/context.h"

namespace punctual::bench {

// Adds the names of `names` that `known` lacks, each after the last name of `names` before it that
// `known` has (the frame order of both kept).
void mergePassNames(std::vector<std::string>& known, const std::vector<std::string>& names);

struct BenchRunSettings {
    cli::RenderOptions options;  // the frame's settings; each configuration overrides its own
    uint32_t rounds = 5;
    uint32_t bestOf = 3;
    uint64_t seed = 1;
    std::string outDir;  // where the sample heat maps and mismatch maps go (added to the outputs)
};

// What a run measured, for results.csv and results.json.
struct BenchRecord {
    std::vector<BenchRow> rows;
    std::vector<double> frameCvs;        // each configuration's CV over its rounds
    std::vector<double> singleFrameCvs;  // each configuration's CV over every timed frame
    uint32_t flagged = 0;
    std::vector<std::string> passes;                     // the frame's pass names, from the first renderer
    std::map<std::string, nlohmann::json> shadowLights;  // validated configurations: per-light counts
    std::map<std::string, nlohmann::json> sunCascades;   // validated configurations with a sun: per cascade
    std::map<std::string, nlohmann::json> frameSamples;  // every configuration: its timed frames' totals
};

class BenchRun {
public:
    // `baseScene` with generated lights serves the configurations without a scene of their own.
    BenchRun(vk::Context& context, const Scene& baseScene, const BenchRunSettings& settings, OutputFiles& outputs);
    ~BenchRun();
    BenchRun(const BenchRun&) = delete;
    BenchRun& operator=(const BenchRun&) = delete;

    // Measures `configs` (in plan order) group by group, a progress step per configuration.
    void measure(const std::vector<BenchConfig>& configs, ProgressBar& progress);
    const BenchRecord& record() const { return record_; }

private:
    struct Measurement;
    struct OwnScene;
    Measurement prepare(const BenchConfig& config);
    void runRounds(std::vector<Measurement>& group, uint32_t groupIndex);
    void recordMeasurement(Measurement& m);
    void addImageRows(BenchRow& row, const Measurement& m, const LightStatsImage& pixelWork);

    vk::Context& context_;
    BenchRunSettings settings_;
    OutputFiles& outputs_;
    const reference::EmbreeScene embree_;  // the base scene's geometry: shared by every configuration
    Scene fullSet_;                        // the base scene with the largest set of generated lights
    std::map<std::pair<const BuiltinScene*, uint64_t>, std::unique_ptr<OwnScene>> ownScenes_;
    std::map<std::string, ImageRgba8> bruteImages_;  // by what brute force's image is compared on
    BenchRecord record_;
};

// results.csv: a header of `columns`, then one line per row.
std::string resultsCsv(const BenchRecord& record, const std::vector<std::string>& columns);

// results.json's "configurations": each row's columns, with its per-light and per-cascade shadow
// counts and its timed frames' totals.
nlohmann::json resultsConfigurations(const BenchRecord& record, const std::vector<std::string>& columns);

}  // namespace punctual::bench
