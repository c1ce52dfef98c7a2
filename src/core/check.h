#pragma once
// Internal assertions: a broken promise between parts of punctual (a caller asking for data it did
// not request, a table declaring a binding twice), never a user's mistake. It throws
// InternalError, which main() reports as "internal error: FILE:LINE: ..." with exit code 3, apart
// from the user errors (punctual::Error, exit 1) that bad input and options cause.
#include <stdexcept>
#include <string>
#include <string_view>

namespace punctual {

class InternalError : public std::logic_error {
public:
    using std::logic_error::logic_error;
};

// `file` is __FILE__: reported from src/ on, so the message names the source file, not the
// folder the binary was built in.
[[noreturn]] inline void failCheck(std::string_view file, int line, const char* condition, const std::string& message) {
    const size_t src = file.rfind("src/");
    if (src != std::string_view::npos) file.remove_prefix(src);
    throw InternalError(std::string(file) + ":" + std::to_string(line) + ": " + message + " (" + condition + ")");
}

}  // namespace punctual

// Checked in every build type: the cost is a branch, and a silent misuse would corrupt results.
#define PUNCTUAL_CHECK(condition, message)                                             \
    do {                                                                               \
        if (!(condition)) ::punctual::failCheck(__FILE__, __LINE__, #condition, message); \
    } while (false)
