#pragma once
// Shared by the GPU tests: a validation-enabled Vulkan context whose messages fail the test,
// running the punctual binary, and writing small glTF files. The image helpers, which the CPU
// tests use too, are in tests/support/image_test_support.h (included here).
#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "base64.h"  // testing::base64, for the glTF files below
#include "core/image.h"
#include "image_test_support.h"
#include "render/renderer.h"
#include "vk/context.h"

namespace punctual::testing {

// Every GPU test runs with the validation layers on; call expectNoValidationMessages() at the end.
inline std::unique_ptr<vk::Context> makeValidatedContext() {
    vk::ContextOptions options;
    options.validation = true;
    return std::make_unique<vk::Context>(options);
}

inline void expectNoValidationMessages(const vk::Context& context) {
    const auto messages = context.validationMessages();
    EXPECT_TRUE(messages.empty()) << messages.size() << " validation message(s), first: "
                                  << (messages.empty() ? "" : messages.front());
}

// Settings for a `width` x `height` frame, everything else at its default.
inline render::RenderSettings renderSettings(uint32_t width, uint32_t height) {
    render::RenderSettings settings;
    settings.width = width;
    settings.height = height;
    return settings;
}

// A folder under the system temp dir, unique per test, removed at the end.
class TempFolder {
public:
    TempFolder();
    ~TempFolder();
    const std::string& path() const { return path_; }
    std::string file(const std::string& name) const { return path_ + "/" + name; }

private:
    std::string path_;
};

// ---- the command line ----------------------------------------------------------------------------

// Concatenation through a stream: GCC 12 warns falsely (-Wrestrict, bug 105329) about some
// chains of std::string operator+.
template <typename... Parts>
std::string cat(const Parts&... parts) {
    std::ostringstream s;
    (s << ... << parts);
    return s.str();
}

// `path` in single quotes, for a shell command line.
inline std::string quoted(const std::string& path) { return cat("'", path, "'"); }

// The whole file, byte for byte (empty when it cannot be read).
std::string readText(const std::string& path);

// The number of '\n' in `text`.
size_t lineCount(const std::string& text);

struct RunResult {
    int exitCode = -1;  // -1 when the process did not exit normally
    std::string out;
    std::string err;
};

// Runs `punctual ARGS` through the shell (quote paths in `args` with quoted()), its stdout and
// stderr captured as stdout.txt and stderr.txt in `folder`.
RunResult runPunctual(const TempFolder& folder, const std::string& args);

// A failed run as users should meet it: a non-zero exit that is not an internal error (3), and
// exactly one line on stderr, starting "punctual: error: " and naming `mention`. `args` only
// labels the failures.
void expectOneClearError(const RunResult& run, const std::string& args, const std::string& mention);

// Nothing in `folder` but the captured stdout.txt and stderr.txt and the files whose names
// contain one of `kept` (the inputs a test wrote there): a failed run left no output behind, not
// even a temporary file.
void expectNothingLeftBehind(const TempFolder& folder, const std::string& args, const std::vector<std::string>& kept = {});

// ---- glTF files written by tests -----------------------------------------------------------------


// The "buffers", "bufferViews" and "accessors" members of a glTF file (no braces around them)
// holding a 2 x 2 m quad in the XZ plane: corners (-1, 0, 1), (1, 0, 1), (1, 0, -1), (-1, 0, -1),
// normals +Y, texture coordinates `uvs` (one pair a corner), two triangles. The buffer is a data
// URI. Accessors: 0 POSITION, 1 NORMAL, 2 TEXCOORD_0, 3 the indices.
std::string quadGltfBuffers(const std::vector<float>& uvs);

}  // namespace punctual::testing
