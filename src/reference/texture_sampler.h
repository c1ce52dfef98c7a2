#pragma once
// Base-colour texture lookups on the CPU, matching the GPU's sampler for those textures
// (src/render/scene_gpu.cpp): VK_FORMAT_R8G8B8A8_SRGB, VK_FILTER_LINEAR, REPEAT wrapping, no
// mipmaps. The format decodes each texel's colour with the sRGB EOTF *before* filtering, so
// filtering happens in linear space; alpha is stored linearly.
#include <glm/glm.hpp>

#include "scene/scene.h"

namespace punctual::reference {

// The sRGB EOTF (IEC 61966-2-1) of an 8-bit code, as float: the value a Vulkan SRGB format
// decodes that code to.
float srgbToLinear(uint8_t code);

// Bilinear sample at `uv` (glTF convention: (0,0) is the first texel of the first row), as
// Vulkan defines VK_FILTER_LINEAR: u' = u * width - 0.5, the texels floor(u') and floor(u') + 1,
// each wrapped with REPEAT, weighted by frac(u'); the same along v. Returns linear RGBA.
glm::vec4 sampleBilinearRepeat(const Texture& texture, glm::vec2 uv);

}  // namespace punctual::reference
