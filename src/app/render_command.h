#pragma once
#include <string>
#include <vector>

namespace punctual::app {

// `punctual render ...`: returns the process exit code. Throws punctual::Error on bad input.
int runRenderCommand(const std::vector<std::string>& args);

}  // namespace punctual::app
