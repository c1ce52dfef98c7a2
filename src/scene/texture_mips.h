#pragma once
// Mip chains, generated on the CPU at load so the GPU and the CPU reference sample the very same
// texels at every level (a GPU blit chain would filter differently per driver).
#include "scene/scene.h"

namespace punctual {

// Size of mip level `level` of a width x height texture, as Vulkan defines it:
// max(1, floor(side / 2^level)).
uint32_t mipSide(uint32_t side, uint32_t level);
// Levels down to 1x1: floor(log2(max(width, height))) + 1.
uint32_t fullMipCount(uint32_t width, uint32_t height);

// Fills texture.mipLevels with levels 1 .. fullMipCount - 1, each a box-filtered half of the one
// above (in linear light, alpha-weighted; texture_limit.h's resampler), replacing any it had.
void generateMipmaps(Texture& texture);

}  // namespace punctual
