#include "scene/texture_limit.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <stb_image_resize.h>

#include "core/check.h"

namespace punctual {

TextureLimit textureLimitForFrame(uint32_t width, uint32_t height) {
    const uint32_t longest = std::max(width, height);
    uint64_t side = 1;
    while (side <= longest) side *= 2;
    TextureLimit limit;
    limit.maxSide = uint32_t(std::min<uint64_t>(side, std::numeric_limits<uint32_t>::max()));
    limit.reason = "enough for a " + std::to_string(width) + "x" + std::to_string(height) + " frame";
    return limit;
}

TextureSize fittedTextureSize(uint32_t width, uint32_t height, uint32_t maxSide) {
    if (maxSide == 0 || std::max(width, height) <= maxSide) return {width, height};
    // Exact integer rounding (no float): other = round(other * maxSide / longest).
    const auto scaled = [&](uint32_t side) {
        const uint64_t longest = std::max(width, height);
        return uint32_t(std::max<uint64_t>((uint64_t(side) * maxSide + longest / 2) / longest, 1));
    };
    return width >= height ? TextureSize{maxSide, scaled(height)} : TextureSize{scaled(width), maxSide};
}

std::vector<uint8_t> resizedRgba8Srgb(const uint8_t* rgba, TextureSize from, TextureSize to) {
    constexpr uint32_t kIntMax = uint32_t(std::numeric_limits<int>::max());
    PUNCTUAL_CHECK(from.width > 0 && from.height > 0 && to.width > 0 && to.height > 0, "empty texture size");
    PUNCTUAL_CHECK(from.width <= kIntMax / 4 && to.width <= kIntMax / 4 && from.height <= kIntMax && to.height <= kIntMax,
                   "texture too large for stb_image_resize");
    std::vector<uint8_t> out(size_t(to.width) * to.height * 4);
    // Alpha (channel 3) weights the colour average, so transparent texels do not bleed their
    // colour into opaque ones.
    const int ok = stbir_resize_uint8_generic(rgba, int(from.width), int(from.height), int(from.width * 4), out.data(),
                                              int(to.width), int(to.height), int(to.width * 4), 4, 3, 0,
                                              STBIR_EDGE_WRAP, STBIR_FILTER_BOX, STBIR_COLORSPACE_SRGB, nullptr);
    PUNCTUAL_CHECK(ok != 0, "stb_image_resize failed");
    return out;
}

Texture fittedTexture(const Texture& texture, uint32_t maxSide) {
    const TextureSize to = fittedTextureSize(texture.width, texture.height, maxSide);
    if (to.width == texture.width && to.height == texture.height) return texture;
    Texture fitted;
    fitted.name = texture.name;
    fitted.width = to.width;
    fitted.height = to.height;
    fitted.rgba = resizedRgba8Srgb(texture.rgba.data(), {texture.width, texture.height}, to);
    return fitted;
}

std::string downscaleWarning(const std::string& what, TextureSize from, TextureSize to, const std::string& why) {
    return what + " is " + std::to_string(from.width) + "x" + std::to_string(from.height) + " texels; downscaled to " +
           std::to_string(to.width) + "x" + std::to_string(to.height) + " (" + why + ")";
}

}  // namespace punctual
