#include "bench/bench_provenance.h"

#include <ctime>
#include <fstream>
#include <thread>

#include <vulkan/vulkan.h>

#include "punctual_git.h"  // generated at build time (cmake/GitCommit.cmake)
#include "vk/context.h"

namespace punctual::bench {
namespace {

std::string versionText(uint32_t version) {
    return std::to_string(VK_API_VERSION_MAJOR(version)) + "." + std::to_string(VK_API_VERSION_MINOR(version)) + "." +
           std::to_string(VK_API_VERSION_PATCH(version));
}

std::string utcNow() {
    const std::time_t now = std::time(nullptr);
    std::tm utc{};
    gmtime_r(&now, &utc);
    char text[32];
    std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
    return text;
}

}  // namespace

std::string cpuModelName() {
    std::ifstream cpuinfo("/proc/cpuinfo");
    std::string line;
    while (std::getline(cpuinfo, line)) {
        if (line.rfind("model name", 0) != 0) continue;
        const size_t colon = line.find(':');
        if (colon == std::string::npos) break;
        const size_t start = line.find_first_not_of(' ', colon + 1);
        return start == std::string::npos ? "unknown" : line.substr(start);
    }
    return "unknown";
}

std::string shellCommandLine(const std::vector<std::string>& benchArgs) {
    std::string line = "punctual bench";
    for (const std::string& arg : benchArgs) {
        const bool plain = !arg.empty() && arg.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz"
                                                                 "0123456789_./,:=+-") == std::string::npos;
        if (plain) {
            line += " " + arg;
            continue;
        }
        // Single quotes keep everything but a single quote, which closes, escapes and reopens.
        std::string quoted = "'";
        for (char c : arg) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
        line += " " + quoted + "'";
    }
    return line;
}

nlohmann::json benchProvenance(const vk::Context& context, const std::vector<std::string>& benchArgs,
                               const BenchScene& scene, uint32_t width, uint32_t height) {
    // The driver's own name and version string (core in Vulkan 1.2, which punctual requires).
    VkPhysicalDeviceDriverProperties driver{};
    driver.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES;
    VkPhysicalDeviceProperties2 properties{};
    properties.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2;
    properties.pNext = &driver;
    vkGetPhysicalDeviceProperties2(context.physicalDevice(), &properties);
    const VkPhysicalDeviceProperties& p = properties.properties;
    return {{"device",
             {{"name", p.deviceName},
              {"type", vk::deviceTypeName(p.deviceType)},
              {"vendor_id", p.vendorID},
              {"device_id", p.deviceID},
              {"api_version", versionText(p.apiVersion)},
              {"driver_version", p.driverVersion},
              {"driver_name", driver.driverName},
              {"driver_info", driver.driverInfo}}},
            {"cpu", {{"model", cpuModelName()}, {"logical_cores", std::thread::hardware_concurrency()}}},
            {"git_commit", PUNCTUAL_GIT_COMMIT},
            {"git_dirty", PUNCTUAL_GIT_DIRTY},
            {"command_line", shellCommandLine(benchArgs)},
            {"date", utcNow()},
            {"scene", {{"source", scene.source}, {"triangles", scene.triangles}}},
            {"size", {{"width", width}, {"height", height}}}};
}

}  // namespace punctual::bench
