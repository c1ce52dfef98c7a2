#include "scene/image_decoding.h"

#include <cstring>
#include <limits>

#include <stb_image.h>
#include <webp/decode.h>

#include "scene/png_reduced.h"

namespace punctual {
namespace {

using DecodedPixels = std::unique_ptr<uint8_t, void (*)(void*)>;

std::string mebibytes(uint64_t bytes) { return std::to_string((bytes + (1u << 20) - 1) >> 20) + " MiB"; }

// The declared size, from the header only (nothing decoded). False for an unreadable header.
bool headerSize(const unsigned char* bytes, size_t size, TextureSize& declared, std::string& failure) {
    int width = 0;
    int height = 0;
    if (isWebp(bytes, size)) {
        if (!WebPGetInfo(bytes, size, &width, &height)) {
            failure = "corrupt WebP header";
            return false;
        }
    } else if (isPng(bytes, size)) {
        // The IHDR chunk comes first (PNG spec 5.6): signature, length, "IHDR", width, height, both
        // big-endian. Read here because stb_image's header check refuses images over 2^30 bytes
        // as an "unknown image type", and those are the ones the reduced decoder is for.
        const auto bigEndian = [&](size_t at) {
            return uint32_t(bytes[at]) << 24 | uint32_t(bytes[at + 1]) << 16 | uint32_t(bytes[at + 2]) << 8 | bytes[at + 3];
        };
        if (size < 24 || std::memcmp(bytes + 12, "IHDR", 4) != 0 || bigEndian(16) > 0x7fffffffu ||
            bigEndian(20) > 0x7fffffffu) {
            failure = "corrupt PNG header";
            return false;
        }
        width = int(bigEndian(16));
        height = int(bigEndian(20));
    } else {
        int channels = 0;
        if (size > size_t(std::numeric_limits<int>::max()) ||
            !stbi_info_from_memory(bytes, int(size), &width, &height, &channels)) {
            const char* reason = stbi_failure_reason();
            failure = reason ? reason : "unknown image format";
            return false;
        }
    }
    if (width <= 0 || height <= 0) {
        failure = "the image has no texels";
        return false;
    }
    declared = {uint32_t(width), uint32_t(height)};
    return true;
}

// Small enough to decode whole: stb or libwebp at full size, then fitted.
bool decodeWhole(const unsigned char* bytes, size_t size, TextureSize to, FittedImage& image, std::string& failure) {
    int width = 0;
    int height = 0;
    DecodedPixels pixels(nullptr, &std::free);
    if (isWebp(bytes, size)) {
        pixels = DecodedPixels(WebPDecodeRGBA(bytes, size, &width, &height), &WebPFree);
        if (!pixels) failure = "corrupt WebP data";
    } else {
        int channelsInFile = 0;
        pixels = DecodedPixels(stbi_load_from_memory(bytes, int(size), &width, &height, &channelsInFile, STBI_rgb_alpha),
                               &stbi_image_free);
        if (!pixels) {
            const char* reason = stbi_failure_reason();
            failure = reason ? reason : "unknown error";
        }
    }
    if (!pixels) return false;
    const TextureSize from{uint32_t(width), uint32_t(height)};
    image.original = from;
    image.size = to;
    if (to.width != from.width || to.height != from.height) {
        image.rgba = resizedRgba8Srgb(pixels.get(), from, to);
    } else {
        image.rgba.assign(pixels.get(), pixels.get() + size_t(width) * size_t(height) * 4);
    }
    return true;
}

// libwebp scales while it decodes (its own resampler, row by row): the full image never exists.
bool decodeWebpScaled(const unsigned char* bytes, size_t size, TextureSize to, FittedImage& image,
                      std::string& failure) {
    WebPDecoderConfig config;
    if (!WebPInitDecoderConfig(&config)) {
        failure = "libwebp version mismatch";
        return false;
    }
    config.options.use_scaling = 1;
    config.options.scaled_width = int(to.width);
    config.options.scaled_height = int(to.height);
    config.output.colorspace = MODE_RGBA;
    image.rgba.resize(size_t(to.width) * to.height * 4);
    config.output.is_external_memory = 1;
    config.output.u.RGBA.rgba = image.rgba.data();
    config.output.u.RGBA.stride = int(to.width * 4);
    config.output.u.RGBA.size = image.rgba.size();
    const VP8StatusCode status = WebPDecode(bytes, size, &config);
    WebPFreeDecBuffer(&config.output);
    if (status != VP8_STATUS_OK) {
        failure = "corrupt WebP data";
        image.rgba.clear();
        return false;
    }
    image.size = to;
    return true;
}

}  // namespace

bool isWebp(const unsigned char* bytes, size_t size) {
    // RIFF header: "RIFF", 4-byte length, "WEBP".
    return bytes != nullptr && size >= 12 && std::memcmp(bytes, "RIFF", 4) == 0 && std::memcmp(bytes + 8, "WEBP", 4) == 0;
}

bool decodeFittedRgba8(const unsigned char* bytes, size_t size, uint32_t maxSide, FittedImage& image,
                       std::string& failure) {
    image = FittedImage{};
    if (bytes == nullptr || size == 0) {
        failure = "no image data";
        return false;
    }
    TextureSize declared;
    if (!headerSize(bytes, size, declared, failure)) return false;
    image.original = declared;
    const TextureSize to = fittedTextureSize(declared.width, declared.height, maxSide);
    const uint64_t wholeBytes = uint64_t(declared.width) * declared.height * 4;
    if (wholeBytes <= kWholeDecodeBytes) return decodeWhole(bytes, size, to, image, failure);
    if (isWebp(bytes, size)) return decodeWebpScaled(bytes, size, to, image, failure);
    if (isPng(bytes, size)) {
        ReducedImage reduced;
        if (!decodePngReduced(bytes, size, to, reduced, failure)) return false;
        image.size = to;
        image.rgba = reduced.size.width == to.width && reduced.size.height == to.height
                         ? std::move(reduced.rgba)
                         : resizedRgba8Srgb(reduced.rgba.data(), reduced.size, to);
        return true;
    }
    failure = "a " + std::to_string(declared.width) + "x" + std::to_string(declared.height) + " image needs " +
              mebibytes(wholeBytes) + " to decode, more than the " + mebibytes(kWholeDecodeBytes) +
              " punctual decodes whole; only PNG and WebP are decoded at a reduced size";
    return false;
}

}  // namespace punctual
