#pragma once
// 8-bit RGBA images and their PNG I/O. Writing goes through OutputFiles (core/output_files.h):
// atomic, and safe for whatever the path names (a symbolic link, /dev/null, a FIFO).
#include <cstdint>
#include <string>
#include <vector>

namespace punctual {

struct ImageRgba8 {
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<uint8_t> pixels;  // width * height * 4 bytes, rows top to bottom

    const uint8_t* at(uint32_t x, uint32_t y) const { return &pixels[(size_t(y) * width + x) * 4]; }
    uint8_t* at(uint32_t x, uint32_t y) { return &pixels[(size_t(y) * width + x) * 4]; }
};

// Throws punctual::Error naming `path` when it cannot be written.
void writePng(const std::string& path, const ImageRgba8& image);
// The PNG file's bytes, for writing later (see OutputFiles).
std::string encodePng(const ImageRgba8& image);
ImageRgba8 readPng(const std::string& path);

// Writes `contents` to `path` as OutputFiles does (atomically for a regular file).
void writeFileAtomically(const std::string& path, const std::string& contents);

}  // namespace punctual
