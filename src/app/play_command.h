#pragma once
#include <string>
#include <vector>

namespace punctual::app {

// `punctual play [SCENE] [render options] --out-dir DIR [--fps F] [--seconds S] [--save-frames]`:
// renders the scene posed at every 1/F s of its animation or path and writes the per-frame
// statistics, their percentiles, a frame-time chart and an index.html into DIR
// (report/sequence_report.h). Returns the process exit code; throws punctual::Error on bad input.
int runPlayCommand(const std::vector<std::string>& args);

}  // namespace punctual::app
