#include "bench/bench_report.h"

#include <unistd.h>

#include <cstdlib>
#include <filesystem>

#include "core/run_program.h"

namespace punctual::bench {
namespace {

// Debian's interpreter, the one python3-matplotlib installs into (a python3 earlier on PATH, a
// virtual environment say, may lack it).
constexpr const char* kPython = "/usr/bin/python3";

}  // namespace

std::string benchScriptDir() {
    if (const char* fromEnvironment = std::getenv("PUNCTUAL_BENCH_SCRIPTS"); fromEnvironment && *fromEnvironment) {
        return fromEnvironment;
    }
#ifdef PUNCTUAL_BENCH_SCRIPT_DIR
    if (std::filesystem::exists(std::string(PUNCTUAL_BENCH_SCRIPT_DIR) + "/plot_results.py")) return PUNCTUAL_BENCH_SCRIPT_DIR;
#endif
    return "bench";
}

bool chartsAvailable(std::string& why) {
    if (access(kPython, X_OK) != 0) {
        why = std::string(kPython) + " is missing (apt-get install python3-matplotlib)";
        return false;
    }
    if (runProgram(kPython, {"-c", "import matplotlib"}) != 0) {
        why = "matplotlib is missing (apt-get install python3-matplotlib)";
        return false;
    }
    return true;
}

bool drawBenchReport(const std::string& outDir, bool failures, std::string& problem) {
    const std::string scripts = benchScriptDir();
    std::vector<std::string> names = {"plot_results.py"};
    if (failures) names.emplace_back("plot_failures.py");
    for (const std::string& name : names) {
        const std::string script = scripts + "/" + name;
        const int status = runProgram(kPython, {script, outDir});
        if (status == 1) {
            problem.clear();  // the script named the file and the problem in its one line
            return false;
        }
        if (status != 0) {
            endAsTheChildEnded(status);
            problem = script + " exited with status " + std::to_string(status);
            return false;
        }
    }
    return true;
}

}  // namespace punctual::bench
