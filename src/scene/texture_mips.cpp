#include "scene/texture_mips.h"

#include <algorithm>

#include "scene/texture_limit.h"

namespace punctual {

uint32_t mipSide(uint32_t side, uint32_t level) { return level >= 32 ? 1u : std::max(side >> level, 1u); }

uint32_t fullMipCount(uint32_t width, uint32_t height) {
    uint32_t longest = std::max(width, height);
    uint32_t count = 1;
    while (longest > 1) {
        longest >>= 1;
        ++count;
    }
    return count;
}

void generateMipmaps(Texture& texture) {
    texture.mipLevels.clear();
    if (texture.width == 0 || texture.height == 0) return;
    const uint32_t count = fullMipCount(texture.width, texture.height);
    texture.mipLevels.reserve(count - 1);
    const uint8_t* above = texture.rgba.data();
    TextureSize aboveSize{texture.width, texture.height};
    for (uint32_t level = 1; level < count; ++level) {
        TextureLevel next;
        next.width = mipSide(texture.width, level);
        next.height = mipSide(texture.height, level);
        next.rgba = resizedRgba8Srgb(above, aboveSize, {next.width, next.height});
        texture.mipLevels.push_back(std::move(next));
        above = texture.mipLevels.back().rgba.data();
        aboveSize = {texture.mipLevels.back().width, texture.mipLevels.back().height};
    }
}

}  // namespace punctual
