#pragma once
// Where a bench run's numbers come from (results.json "provenance", docs/BENCH_RESULTS.md): the
// device and driver, the CPU, the commit built, the command line and the date. Two runs are only
// comparable with these beside them (`punctual bench --compare`).
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace punctual::vk {
class Context;
}

namespace punctual::bench {

struct BenchScene {
    std::string source;
    uint64_t triangles = 0;
};

nlohmann::json benchProvenance(const vk::Context& context, const std::vector<std::string>& benchArgs,
                               const BenchScene& scene, uint32_t width, uint32_t height);

// The CPU's model name (/proc/cpuinfo "model name"; "unknown" elsewhere).
std::string cpuModelName();

// The command line as a shell would take it back: "punctual bench" and each argument, quoted
// where it holds anything but [A-Za-z0-9_./,:=+-].
std::string shellCommandLine(const std::vector<std::string>& benchArgs);

}  // namespace punctual::bench
