#pragma once
// Image files -> RGBA8 pixels: PNG, JPEG and the other formats stb_image reads, and WebP
// (EXT_texture_webp) through libwebp. The format is recognised from the bytes, not from a
// mimeType a file may state wrongly.
#include <cstdint>
#include <memory>
#include <string>

namespace punctual {

using DecodedPixels = std::unique_ptr<uint8_t, void (*)(void*)>;

// Decodes `size` bytes to width x height RGBA8 pixels (rows top to bottom), or returns null with
// the decoder's reason in `failure`.
DecodedPixels decodeRgba8(const unsigned char* bytes, int size, int& width, int& height, std::string& failure);

// True when the bytes start with a RIFF container of WebP data.
bool isWebp(const unsigned char* bytes, int size);

}  // namespace punctual
