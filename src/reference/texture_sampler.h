#pragma once
// Texture lookups on the CPU, as Vulkan defines them for the GPU's samplers (render/scene_gpu.cpp:
// VK_FORMAT_R8G8B8A8_SRGB, the material's glTF sampler, no anisotropy). The format decodes each
// texel's colour with the sRGB EOTF *before* filtering, so filtering happens in linear space;
// alpha is stored linearly.
#include <glm/glm.hpp>

#include "scene/scene.h"

namespace punctual::reference {

// The sRGB EOTF (IEC 61966-2-1) of an 8-bit code, as float: the value a Vulkan SRGB format
// decodes that code to.
float srgbToLinear(uint8_t code);

// Bilinear sample of level 0 at `uv` (glTF convention: (0,0) is the first texel of the first
// row), as Vulkan defines VK_FILTER_LINEAR: u' = u * width - 0.5, the texels floor(u') and
// floor(u') + 1, each wrapped with REPEAT, weighted by frac(u'); the same along v. Linear RGBA.
glm::vec4 sampleBilinearRepeat(const Texture& texture, glm::vec2 uv);

// The level of detail Vulkan computes from the screen-space derivatives of `uv` (isotropic rule,
// spec "Scale Factor Operation"): rho = max(|duv/dx|, |duv/dy|) in level-0 texels, lambda =
// log2(rho). -inf for a zero footprint.
float textureLod(const Texture& texture, glm::vec2 uvDx, glm::vec2 uvDy);

// A full sample at level of detail `lod`, as Vulkan's texel filtering does: lod <= 0 magnifies
// (magFilter on level 0); above it minifies with minFilter, on one level (mipFilter NEAREST:
// d = ceil(lod + 0.5) - 1) or two (LINEAR: floor(lod) and the next, mixed by frac(lod)); lod is
// clamped to the texture's last level, and to 0 without mipmaps. Each axis wraps by its mode.
glm::vec4 sampleTexture(const Texture& texture, const TextureSampler& sampler, glm::vec2 uv, float lod);

}  // namespace punctual::reference
