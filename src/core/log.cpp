#include "core/log.h"

#include <atomic>
#include <cstdio>
#include <mutex>

namespace punctual::log {
namespace {
std::mutex gMutex;
Sink gSink;
std::atomic<int> gWarnings{0};

void emit(const char* level, const std::string& message) {
    std::lock_guard lock(gMutex);
    if (gSink) {
        gSink(level, message);
    } else {
        std::fprintf(stderr, "punctual: %s: %s\n", level, message.c_str());
    }
}
}  // namespace

void warn(const std::string& message) {
    ++gWarnings;
    emit("warning", message);
}

void info(const std::string& message) { emit("info", message); }

Sink setSink(Sink sink) {
    std::lock_guard lock(gMutex);
    Sink previous = std::move(gSink);
    gSink = std::move(sink);
    return previous;
}

int warningCount() { return gWarnings.load(); }

}  // namespace punctual::log
