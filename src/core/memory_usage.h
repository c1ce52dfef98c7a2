#pragma once
// The process's host memory, for the stats and the bench: its peak resident set.
#include <cstdint>

namespace punctual {

// The most resident memory the process has held since it started (getrusage's ru_maxrss), bytes.
uint64_t peakResidentBytes();

// For a series measuring one configuration after another in one process: restarts the kernel's
// high-water mark of the resident set at what is resident now (Linux: "5" into
// /proc/self/clear_refs). False where that is not possible; then peakResidentSinceReset() is the
// whole run's peak.
bool resetPeakResident();
// The most resident memory since resetPeakResident() (VmHWM of /proc/self/status), bytes; the
// whole run's peak (peakResidentBytes) where the kernel does not report it.
uint64_t peakResidentSinceReset();

}  // namespace punctual
