#pragma once
// The bench's report: after the numbers are written, `punctual bench` runs the chart scripts
// (bench/plot_results.py, bench/plot_failures.py) on the folder, and `bench --compare` runs
// bench/compare_runs.py. They need Debian's /usr/bin/python3 with python3-matplotlib; without it
// the bench says so in one line and keeps its CSV and JSON.
#include <string>
#include <vector>

namespace punctual::bench {

// Where the scripts are: $PUNCTUAL_BENCH_SCRIPTS, else the source tree's bench/ (fixed at build
// time), else bench/ beside the working directory.
std::string benchScriptDir();

// Whether /usr/bin/python3 can import matplotlib. When it cannot, `why` gets one line saying
// what to install.
bool chartsAvailable(std::string& why);

// Draws DIR's charts and index.html (and failures.html when `failures`). Returns false, with
// `problem` set to one line, when a script failed.
bool drawBenchReport(const std::string& outDir, bool failures, std::string& problem);

}  // namespace punctual::bench
