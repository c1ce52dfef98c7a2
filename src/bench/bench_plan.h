#pragma once
// What `punctual bench` measures: its series and their configurations, in the order they run
// (docs/BENCH_RESULTS.md "Series"). Each configuration belongs to a group, the configurations
// measured together in interleaved rounds (bench_command.cpp).
#include <cstdint>
#include <string>
#include <vector>

#include "lights/shadow_setup.h"
#include "render/light_list_form.h"
#include "render/light_list_method.h"
#include "scene/builtin_scenes.h"

namespace punctual::bench {

// The range every generated light gets in the series that hold the overlap fixed, as a share of
// the scene's bounds diagonal: the middle of the generator's 0.25-0.45.
inline constexpr float kBenchLightRange = 0.35f;
// The largest generated set of the series up to the design notes' caps; smaller counts take its
// first lights. (The scale series generates its own, up to kBenchScaleLights.)
inline constexpr uint32_t kBenchSpots = 64;
inline constexpr uint32_t kBenchPoints = 32;
// The scale series' largest count: half spots, half points.
inline constexpr uint32_t kBenchScaleLights = 8192;
// Frames per round visit; the round keeps each pass's fastest (fastestPerPass, bench_rows.h).
// Three is where a light sweep at 640x360 stopped having flagged configurations here
// (bench/RESULTS.md); --quick keeps one frame, to stay a quick look.
inline constexpr uint32_t kDefaultBestOf = 3;
inline constexpr uint32_t kQuickBestOf = 1;

struct BenchConfig {
    std::string series;
    // A built-in scene of the series' own, lit by its own lights (spot and point are then 0);
    // nullptr: the bench's scene with the first `spot` + `point` generated lights at `lightRange`.
    const BuiltinScene* scene = nullptr;
    uint64_t triangles = 0;  // a sized built-in scene's size (BuiltinScene::sized); 0: its default
    render::LightListMethod method = render::LightListMethod::Tiled;
    uint32_t spot = 0;
    uint32_t point = 0;
    float lightRange = kBenchLightRange;  // generated lights only
    // The scale series: the lights generated for the configuration itself (past the bench's 96),
    // at constant density (--light-range auto) or, false, at lightRange.
    bool ownLights = false;
    bool constantDensity = false;
    uint32_t width = 0;                    // 0: the run's --size
    uint32_t height = 0;
    ShadowSettings shadows;
    bool validateShadows = false;
    bool coarseTiles = true;  // the grid methods' coarse pass (--coarse-tiles)
    render::LightListForm lightLists = render::LightListForm::Masks;  // the grid methods' (--light-lists)
};

struct BenchSeries {
    const char* name;
    std::string description;  // one line of --help; the methods and filters named from their tables
};
// Every series, in run order, and the failure study's pseudo-series "failures" last.
const std::vector<BenchSeries>& benchSeries();

// Every configuration of every series (quick: fewer values per series), in run order; the
// configurations of one group are consecutive.
std::vector<BenchConfig> benchPlan(bool quick);

// The group a configuration is measured with: its series and scene (a sized scene's each size).
std::string benchGroupKey(const BenchConfig& config);

// A unique, readable name (results.csv's `config`).
std::string benchConfigName(const BenchConfig& config);

// The series --series names, comma-separated; throws Error("--series", ...) naming the known ones.
std::vector<std::string> parseBenchSeries(const std::string& text);

}  // namespace punctual::bench
