#pragma once
// The bench's failure study: one scene per known failure of a method, and the error measured
// against the parameter that provokes it (see README, "Where methods fail").
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace punctual::vk {
class Context;
}

namespace punctual::bench {

struct FailureRow {
    std::string study;      // e.g. "acne-vs-bias"
    std::string parameter;  // what is varied, e.g. "bias scale"
    double value = 0.0;     // its value
    std::string variant;    // e.g. the filter, layout or method
    std::string metric;     // what `error` measures, e.g. "false_shadow fraction"
    double error = 0.0;
    double totalMs = 0.0;   // GPU frame time of that configuration
};

// Runs every study at `width` x `height`; `onStep` is told each finished configuration.
std::vector<FailureRow> runFailureStudy(vk::Context& context, bool quick, uint32_t width, uint32_t height,
                                        const std::function<void(const std::string&)>& onStep);
size_t failureStudySize(vk::Context& context, bool quick);  // configurations run

std::string failuresCsv(const std::vector<FailureRow>& rows);

}  // namespace punctual::bench
