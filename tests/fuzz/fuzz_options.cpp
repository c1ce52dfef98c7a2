// Fuzz target: the render options parser (parseRenderOptions), which render, compare and
// validate run on the command line. The input is split at '\n' into arguments, so the seeds in
// corpus/options read as one argument per line.
//
// The contract under test: parseRenderOptions either returns options or throws punctual::Error
// naming the option. Anything else (a crash, a sanitizer report, an internal error or another
// exception) is a bug.
#include <string>
#include <vector>

#include "cli/options.h"
#include "core/error.h"
#include "fuzz_target.h"

extern "C" int LLVMFuzzerInitialize(int* /*argc*/, char*** /*argv*/) { return 0; }

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    std::vector<std::string> args;
    size_t start = 0;
    while (start <= text.size()) {
        size_t end = text.find('\n', start);
        if (end == std::string::npos) end = text.size();
        args.push_back(text.substr(start, end - start));
        start = end + 1;
    }
    // A seed file ends with a newline, which is not an empty last argument.
    if (!text.empty() && text.back() == '\n') args.pop_back();
    try {
        const punctual::cli::RenderOptions options = punctual::cli::parseRenderOptions(args);
        // What the commands do next with parsed options.
        (void)punctual::cli::renderSettingsFrom(options);
    } catch (const punctual::Error&) {
        // A clean error naming the option: what bad arguments must give.
    }
    return 0;
}
