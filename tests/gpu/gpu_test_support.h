#pragma once
// Shared by the GPU tests: a validation-enabled Vulkan context whose messages fail the test,
// and small image helpers.
#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <string>

#include "core/image.h"
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

// Mean of the Rec. 709 luma of the 8-bit (sRGB-encoded) pixels, in [0, 1].
inline double meanLuma(const ImageRgba8& image) {
    double sum = 0.0;
    for (size_t i = 0; i < image.pixels.size(); i += 4) {
        sum += 0.2126 * image.pixels[i] + 0.7152 * image.pixels[i + 1] + 0.0722 * image.pixels[i + 2];
    }
    return sum / (255.0 * double(image.width) * image.height);
}

// Fraction of pixels with any channel above `threshold`.
inline double fractionBrighterThan(const ImageRgba8& image, uint8_t threshold) {
    size_t count = 0;
    for (size_t i = 0; i < image.pixels.size(); i += 4) {
        if (image.pixels[i] > threshold || image.pixels[i + 1] > threshold || image.pixels[i + 2] > threshold) ++count;
    }
    return double(count) / (double(image.width) * image.height);
}

// When PUNCTUAL_TEST_OUTPUT_DIR is set, writes `image` there as NAME.png (for looking at what a
// test rendered); otherwise does nothing.
void saveTestImage(const std::string& name, const ImageRgba8& image);

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

}  // namespace punctual::testing
