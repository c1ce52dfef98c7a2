#pragma once
#include <string>
#include <vector>

namespace punctual::app {

// `punctual reference [SCENE] [options] --out FILE.png [--no-shadows]`: ray traces the CPU
// reference image with Embree. Returns the process exit code. Throws punctual::Error on bad input.
int runReferenceCommand(const std::vector<std::string>& args);

std::string referenceUsage();

}  // namespace punctual::app
