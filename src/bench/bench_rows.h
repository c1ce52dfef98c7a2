#pragma once
// One row of results.csv (docs/BENCH_RESULTS.md): a configuration's settings, its timings over
// the rounds, the counters that hold on any device, and its accuracy.
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench/bench_plan.h"
#include "metrics/round_statistics.h"
#include "render/renderer.h"

namespace punctual::reference {
class EmbreeScene;
}

namespace punctual::bench {

using BenchRow = std::map<std::string, std::string>;

// A configuration is flagged when its frame time's IQR exceeds this share of its median.
inline constexpr double kSpreadFlagLimit = 0.15;

std::string benchNumber(double value);

// Every column, in order: the configuration, then P_ms, P_iqr_ms and P_cv for every pass P in
// frame order and the frame (so a new pass gets its columns with no edit here), then the flags,
// counters and accuracy.
std::vector<std::string> benchColumns(const std::vector<std::string>& passes);

// The configuration's columns (what was rendered).
void addConfiguration(BenchRow& row, const BenchConfig& config, const Scene& scene, const render::Renderer& renderer,
                      uint32_t rounds, uint32_t bestOf);

// A round's sample from K frames rendered back to back: each pass's fastest time, and the
// fastest frame total (taken apart, so the total can be below the sum of the passes' times).
// Interference (other threads, the host) only ever adds time to a frame, so the fastest of a
// few frames is the least disturbed estimate of what the pass costs (Chen and Revels, "Robust
// benchmarking in noisy environments", 2016); docs/BENCH_RESULTS.md. Empty input: empty output.
render::PassTimings fastestPerPass(const std::vector<render::PassTimings>& frames);

// The median, IQR and CV of every pass and of the frame over `rounds`, and the flag. Returns the
// frame's summary.
RoundSummary addTimings(BenchRow& row, const std::vector<render::PassTimings>& rounds);

// The counters: pixel work from the statistics variant (rendered once more, untimed), draws and
// triangles per pass, shadow texels, memory by kind.
void addCounters(BenchRow& row, render::Renderer& renderer, const LightStatsImage* pixelWork);

// The shadows' agreement with Embree (edge band one texel, and one screen pixel). `perLight` and
// `perCascade` get results.json's "shadow_lights" and "sun_cascades"; `mismatch` the first
// light's mismatch map, when there is one.
struct ShadowValidationRows {
    nlohmann::json perLight = nlohmann::json::array();
    nlohmann::json perCascade;  // null without a sun
    std::optional<ImageRgba8> mismatch;
};
ShadowValidationRows addShadowValidation(BenchRow& row, render::Renderer& renderer,
                                         const reference::EmbreeScene& geometry, const Scene& scene);

}  // namespace punctual::bench
