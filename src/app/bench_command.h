#pragma once
#include <string>
#include <vector>

namespace punctual::app {

// `punctual bench [SCENE] [--quick] --out-dir DIR`: sweeps light counts, light-list methods,
// shadows on/off, shadow resolutions and filters; writes DIR/results.csv, DIR/results.json and
// sample images under DIR/images. Returns the exit code; throws punctual::Error on bad input.
int runBenchCommand(const std::vector<std::string>& args);

}  // namespace punctual::app
