// validate's OpenEXR files are encoded in memory (so they go through OutputFiles, never through
// a fixed temporary path): the bytes must be exactly those tinyexr's SaveEXR writes to a file.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <tinyexr.h>

#include "report/exr_encoding.h"
#include "gpu_test_support.h"

namespace punctual {
namespace {

std::string savedByTinyexr(const testing::TempFolder& folder, const std::vector<float>& data, int width, int height,
                           int components) {
    const std::string path = folder.file("saved.exr");
    const char* error = nullptr;
    EXPECT_EQ(SaveEXR(data.data(), width, height, components, 0, path.c_str(), &error), TINYEXR_SUCCESS);
    if (error) FreeEXRErrorMessage(error);
    return testing::readText(path);
}

TEST(ExrEncoding, BytesMatchSaveExr) {
    testing::TempFolder folder;
    for (const auto& [width, height] : {std::pair{40, 24}, std::pair{7, 5}}) {  // ZIP compressed, and not
        for (int components : {1, 3}) {
            std::vector<float> data(size_t(width * height * components));
            for (size_t i = 0; i < data.size(); ++i) data[i] = float(i % 97) * 0.25f - 3.0f;
            data[1] = std::numeric_limits<float>::quiet_NaN();
            const std::string encoded = report::encodeExr(data, uint32_t(width), uint32_t(height), components, "x.exr");
            EXPECT_EQ(encoded, savedByTinyexr(folder, data, width, height, components))
                << width << "x" << height << ", " << components << " channel(s)";
        }
    }
}

}  // namespace
}  // namespace punctual
