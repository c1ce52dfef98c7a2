#pragma once
#include <string>
#include <vector>

namespace punctual::app {

// `punctual validate [SCENE] [render options] --out-dir DIR [--export-exr]`: compares the GPU's
// shadows with Embree's ray-cast visibility and writes DIR/report.json, DIR/report.html and the
// images they show. Returns the process exit code; throws punctual::Error on bad input.
int runValidateCommand(const std::vector<std::string>& args);

}  // namespace punctual::app
