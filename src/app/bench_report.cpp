#include "app/bench_report.h"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <filesystem>

extern char** environ;

namespace punctual::app {
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

int runProgram(const std::string& program, const std::vector<std::string>& args) {
    std::vector<std::string> owned = {program};
    owned.insert(owned.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (std::string& arg : owned) argv.push_back(arg.data());
    argv.push_back(nullptr);
    pid_t child = 0;
    if (posix_spawn(&child, program.c_str(), nullptr, nullptr, argv.data(), environ) != 0) return 127;
    int status = 0;
    while (waitpid(child, &status, 0) < 0) {
        if (errno != EINTR) return 127;
    }
    if (WIFEXITED(status)) return WEXITSTATUS(status);
    return 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
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
        if (status != 0) {
            problem = script + " exited with status " + std::to_string(status);
            return false;
        }
    }
    return true;
}

}  // namespace punctual::app
