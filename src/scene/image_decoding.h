#pragma once
// Image files -> RGBA8 pixels fitted to a texel limit: PNG, JPEG and the other formats stb_image
// reads, and WebP (EXT_texture_webp) through libwebp. The format is recognised from the bytes,
// not from a mimeType a file may state wrongly.
//
// Memory in proportion to what the frame needs: the image's dimensions are read from its header
// before any pixel is decoded. An image whose whole RGBA8 decode fits kWholeDecodeBytes is decoded
// whole and then fitted (texture_limit.h). A larger one is decoded at a reduced size where the
// library allows: PNG row by row with a running k x k box reduction (png_reduced.h), WebP by
// libwebp's own scaling during decoding. Any other format that large is refused (the image is
// then unreadable: its materials use their base colour, with one warning). A 254 KiB PNG that
// declares 16384^2 texels so never allocates its 1 GiB.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "scene/texture_limit.h"

namespace punctual {

// 64 MiB: a 4096^2 RGBA8 image, the largest decoded whole. stb_image holds the inflated file and
// the pixels at once (about 2x this at peak), so whole decodes stay under ~150 MiB.
constexpr uint64_t kWholeDecodeBytes = 64ull << 20;

struct FittedImage {
    TextureSize size;       // after fitting under the limit
    TextureSize original;   // as the file declares it
    std::vector<uint8_t> rgba;
};

// Decodes `size` bytes to RGBA8 (rows top to bottom) fitted under `maxSide` (0: no limit), or
// returns false with the reason in `failure`.
bool decodeFittedRgba8(const unsigned char* bytes, size_t size, uint32_t maxSide, FittedImage& image,
                       std::string& failure);

// True when the bytes start with a RIFF container of WebP data.
bool isWebp(const unsigned char* bytes, size_t size);

}  // namespace punctual
