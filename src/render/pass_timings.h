#pragma once
// GPU milliseconds per pass of a frame, and their medians over timed frames.
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace punctual::render {

// GPU milliseconds per pass, in frame order, under the passes' own names (Pass::name(): "depth",
// "culling", "shadows", "forward", "tonemap"). A pass without work this frame reports 0.
struct PassTimings {
    std::vector<std::pair<std::string, double>> passes;
    double total = 0.0;  // first to last timestamp of the frame

    // The time of the pass named `name`; 0 for a name not in the frame.
    double of(std::string_view name) const;
};

// Per pass and for the total, the median over `frames` (each with the same passes in the same
// order); empty for no frames.
PassTimings medianTimings(const std::vector<PassTimings>& frames);

}  // namespace punctual::render
