#include "scene/image_decoding.h"

#include <cstring>
#include <limits>

#include <stb_image.h>
#include <webp/decode.h>

namespace punctual {

bool isWebp(const unsigned char* bytes, int size) {
    // RIFF header: "RIFF", 4-byte length, "WEBP".
    return bytes != nullptr && size >= 12 && std::memcmp(bytes, "RIFF", 4) == 0 && std::memcmp(bytes + 8, "WEBP", 4) == 0;
}

DecodedPixels decodeRgba8(const unsigned char* bytes, int size, int& width, int& height, std::string& failure) {
    width = 0;
    height = 0;
    if (bytes == nullptr || size <= 0) {
        failure = "no image data";
        return DecodedPixels(nullptr, &std::free);
    }
    if (isWebp(bytes, size)) {
        // WebPGetInfo reads the header only; it bounds the size before any pixel is allocated.
        if (!WebPGetInfo(bytes, size_t(size), &width, &height)) {
            failure = "corrupt WebP header";
            return DecodedPixels(nullptr, &std::free);
        }
        uint8_t* pixels = WebPDecodeRGBA(bytes, size_t(size), &width, &height);
        if (pixels == nullptr) failure = "corrupt WebP data";
        return DecodedPixels(pixels, &WebPFree);
    }
    int channelsInFile = 0;
    stbi_uc* pixels = stbi_load_from_memory(bytes, size, &width, &height, &channelsInFile, STBI_rgb_alpha);
    if (pixels == nullptr) {
        const char* reason = stbi_failure_reason();
        failure = reason ? reason : "unknown error";
    }
    return DecodedPixels(pixels, &stbi_image_free);
}

}  // namespace punctual
