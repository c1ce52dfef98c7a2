#pragma once
// Image helpers shared by the CPU and the GPU tests: brightness measures of an 8-bit image, and
// saving what a test drew for a person to look at. CPU only, like everything in tests/support.
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/image.h"

namespace punctual::testing {

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

}  // namespace punctual::testing
