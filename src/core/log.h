#pragma once
// Warnings go to stderr, one line each, and are also counted so tests can assert that a
// fallback (e.g. an undecodable texture) warned exactly once.
#include <functional>
#include <string>

namespace punctual::log {

void warn(const std::string& message);
void info(const std::string& message);

// Replaces the sink (tests capture warnings); returns the previous one. nullptr restores stderr.
using Sink = std::function<void(const std::string& level, const std::string& message)>;
Sink setSink(Sink sink);

// Number of warnings issued since program start.
int warningCount();

}  // namespace punctual::log
