#include "render/pass_timings.h"

#include "metrics/round_statistics.h"

namespace punctual::render {

double PassTimings::of(std::string_view name) const {
    for (const auto& [passName, ms] : passes) {
        if (passName == name) return ms;
    }
    return 0.0;
}

PassTimings medianTimings(const std::vector<PassTimings>& frames) {
    PassTimings median;
    if (frames.empty()) return median;
    auto medianOver = [&](auto&& value) {
        std::vector<double> values;
        for (const PassTimings& frame : frames) values.push_back(value(frame));
        return medianOf(values);
    };
    for (size_t i = 0; i < frames.front().passes.size(); ++i) {
        median.passes.emplace_back(frames.front().passes[i].first,
                                   medianOver([&](const PassTimings& frame) { return frame.passes[i].second; }));
    }
    median.total = medianOver([](const PassTimings& frame) { return frame.total; });
    return median;
}

}  // namespace punctual::render
