#pragma once
// Captures the warnings punctual logs (core/log.h) for the lifetime of the object, then restores
// the previous sink: tests assert that a fallback warned, and how often.
#include <string>
#include <vector>

#include "core/log.h"

namespace punctual::testing {

class WarningCapture {
public:
    WarningCapture()
        : previous_(log::setSink([this](const std::string& level, const std::string& message) {
              if (level == "warning") warnings.push_back(message);
          })) {}
    ~WarningCapture() { log::setSink(previous_); }
    WarningCapture(const WarningCapture&) = delete;
    WarningCapture& operator=(const WarningCapture&) = delete;
    std::vector<std::string> warnings;

private:
    log::Sink previous_;
};

}  // namespace punctual::testing
