// punctual: a headless Vulkan renderer for many spot and point lights, built to measure how fast
// and how correct light-culling and shadow methods are.
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "cli/options.h"
#include "app/reference_command.h"
#include "app/bench_command.h"
#include "app/compare_command.h"
#include "app/play_command.h"
#include "app/render_command.h"
#include "app/validate_command.h"
#include "core/error.h"
#include "core/input_files_read.h"
#include "vk/context.h"

namespace {

// Exit statuses (README, "Exit status"): a script can tell a bad scene or option (1) from a
// command line that names no command at all (2) and from a bug in punctual (3).
constexpr int kExitSuccess = 0;
constexpr int kExitUserError = 1;  // punctual::Error: a bad file, option or light; one clear line
constexpr int kExitUsage = 2;      // no command, or an unknown one: the usage text
constexpr int kExitInternal = 3;   // anything else escaping a command: a bug, e.g. a PUNCTUAL_CHECK

constexpr const char* kUsage = R"(usage: punctual <command> [options]

commands:
  render [SCENE] [options]   render a frame on the GPU and print per-pass GPU times
  reference [SCENE] [opts]   ray trace the CPU reference image with Embree (see --help)
  validate [SCENE] [options] --out-dir DIR
                             compare the GPU's shadows with Embree's ray-cast visibility
  compare [SCENE] [options]  every light-list method side by side: time, error against brute
                             force, shadow accuracy against Embree
  play [SCENE] [options] --out-dir DIR [--fps F] [--seconds S]
                             render the scene's animation or path frame by frame: per-frame
                             statistics, p50/p95/p99 frame times, a chart and index.html
  bench [SCENE] [--quick] --out-dir DIR
                             sweep light counts, methods and shadow settings into results.csv
  devices                    list the Vulkan devices (index, name, type)
  help                       this text; `punctual render --help` for the render options

SCENE is a glTF file (.gltf, .glb). Without one a command uses a built-in scene: --scene NAME
picks one (`punctual render --help` lists them; the first is the default).
)";

int listDevices() {
    for (const auto& device : punctual::vk::Context::listDevices()) {
        std::printf("%u: %s (%s)%s%s\n", device.index, device.name.c_str(), device.type.c_str(),
                    device.usable ? "" : " not usable: ", device.whyNotUsable.c_str());
    }
    return kExitSuccess;
}

}  // namespace

int main(int argc, char** argv) {
    const std::vector<std::string> args(argv + 1, argv + argc);
    // Every file the command reads is noted, and no output may replace one (core/input_files_read.h).
    const punctual::InputFileLog inputsRead;
    try {
        if (args.empty() || args[0] == "help" || args[0] == "--help" || args[0] == "-h") {
            std::fputs(kUsage, args.empty() ? stderr : stdout);
            return args.empty() ? kExitUsage : kExitSuccess;
        }
        const std::vector<std::string> rest(args.begin() + 1, args.end());
        if (args[0] == "render") return punctual::app::runRenderCommand(rest);
        if (args[0] == "reference") return punctual::app::runReferenceCommand(rest);
        if (args[0] == "validate") return punctual::app::runValidateCommand(rest);
        if (args[0] == "bench") return punctual::app::runBenchCommand(rest);
        if (args[0] == "compare") return punctual::app::runCompareCommand(rest);
        if (args[0] == "play") return punctual::app::runPlayCommand(rest);
        if (args[0] == "devices") return listDevices();
        std::fprintf(stderr, "punctual: error: unknown command '%s' (try punctual help)\n", args[0].c_str());
        return kExitUsage;
    } catch (const punctual::Error& error) {
        std::fprintf(stderr, "punctual: error: %s\n", error.what());
        return kExitUserError;
    } catch (const std::exception& error) {
        std::fprintf(stderr, "punctual: internal error: %s\n", error.what());
        return kExitInternal;
    } catch (...) {
        std::fprintf(stderr, "punctual: internal error: an exception of unknown type\n");
        return kExitInternal;
    }
}
