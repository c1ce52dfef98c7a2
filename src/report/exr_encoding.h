#pragma once
// OpenEXR files encoded in memory, so they go through OutputFiles like every other output (all
// or nothing, never a fixed temporary path another run or user could be using).
#include <cstdint>
#include <string>
#include <vector>

namespace punctual::report {

// The bytes of an uncompressed-float EXR of `components` (1 or 3) interleaved channels, as
// tinyexr's SaveEXR writes them to a file (ZIP compressed unless smaller than 16 x 16). Throws
// punctual::Error naming `name` when encoding fails.
std::string encodeExr(const std::vector<float>& data, uint32_t width, uint32_t height, int components,
                      const std::string& name);

}  // namespace punctual::report
