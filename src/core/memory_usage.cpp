#include "core/memory_usage.h"

#include <sys/resource.h>

#include <fstream>
#include <string>

namespace punctual {

uint64_t peakResidentBytes() {
    rusage usage{};
    if (getrusage(RUSAGE_SELF, &usage) != 0) return 0;
    return uint64_t(usage.ru_maxrss) * 1024;  // kibibytes on Linux
}

bool resetPeakResident() {
    std::ofstream clearRefs("/proc/self/clear_refs");
    if (!clearRefs) return false;
    clearRefs << "5";
    clearRefs.flush();
    return bool(clearRefs);
}

uint64_t peakResidentSinceReset() {
    std::ifstream status("/proc/self/status");
    std::string key;
    while (status >> key) {
        if (key == "VmHWM:") {
            uint64_t kibibytes = 0;
            if (status >> kibibytes) return kibibytes * 1024;
            break;
        }
        status.ignore(1 << 16, '\n');
    }
    return peakResidentBytes();
}

}  // namespace punctual
