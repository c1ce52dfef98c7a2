#pragma once
// PNG images decoded row by row and reduced as they arrive, so a file that declares a huge image
// (a 254 KiB PNG of 16384^2 texels is 1 GiB of RGBA8; stb_image holds that and its inflated rows
// at once, 1.3 GB) never exists at full size. libpng delivers one row at a time; rows are summed
// in blocks of k x k texels (k a power of two) in linear light, so only one row and one row of
// sums live at a time, and the result is at most twice the wanted size per side (then fitted by
// the same box filter as every other texture, texture_limit.h).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "scene/texture_limit.h"

namespace punctual {

// True when the bytes start with the PNG signature.
bool isPng(const unsigned char* bytes, size_t size);

struct ReducedImage {
    TextureSize size;          // after the k x k reduction
    TextureSize original;      // as the file declares it
    std::vector<uint8_t> rgba;  // sRGB colour, linear alpha
};

// The largest power of two k such that the image reduced by k (sides rounded up) still has at
// least `wanted` texels per side; 1 when `wanted` is no smaller than `original`.
uint32_t reductionFactor(TextureSize original, TextureSize wanted);

// Decodes a non-interlaced PNG reduced by reductionFactor(original, wanted): each output texel
// is the average of its k x k block (fewer at the right and bottom edges), colour in linear light
// weighted by alpha as texture_limit's filter weighs it, alpha plain. Returns false with the
// reason in `failure` (a corrupt file, or an interlaced one: Adam7 passes need the whole image).
bool decodePngReduced(const unsigned char* bytes, size_t size, TextureSize wanted, ReducedImage& image,
                      std::string& failure);

}  // namespace punctual
