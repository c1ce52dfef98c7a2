#pragma once
// How many texels per side a base-colour texture may keep, and the downscaling that enforces it.
//
// Two limits apply:
//  - The frame's (at load, scene/gltf_loader.h): textures are sampled bilinearly without mipmaps,
//    so a surface never shows more than one texel per pixel on average without skipping the
//    rest. A texture seen whole spans at most max(width, height) pixels per side; the limit is
//    the smallest power of two above that, which also leaves 1x to 2x of headroom for a texture
//    seen partly (a surface closer than "whole in view"). A 16384^2 texture (1 GiB of RGBA8)
//    rendered at 160x120 keeps 256^2 (256 KiB). Applied when decoding, so the CPU reference
//    and the GPU sample the same texels.
//  - The device's (VkPhysicalDeviceLimits::maxImageDimension2D, at upload in
//    render/scene_gpu.cpp): at least 4096 by the Vulkan spec, 16384 on lavapipe. With the frame
//    limit applied it only bites for frames wider or taller than half the device limit.
// Downscaling keeps the aspect ratio, filters in linear light (the texels are sRGB-encoded)
// with a box filter (an average, like a mip level) and wraps at the edges, as the sampler's
// REPEAT addressing does.
#include <cstdint>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace punctual {

struct TextureLimit {
    uint32_t maxSide = 0;  // 0: no limit
    std::string reason;    // why, for the warning, e.g. "enough for a 160x120 frame"
};

// The frame's limit (see above): the smallest power of two greater than max(width, height).
TextureLimit textureLimitForFrame(uint32_t width, uint32_t height);

struct TextureSize {
    uint32_t width = 0;
    uint32_t height = 0;
};

// The size a width x height texture gets under `maxSide` (0: no limit): unchanged when it fits,
// else the longer side becomes maxSide and the other keeps the aspect ratio (rounded, >= 1).
TextureSize fittedTextureSize(uint32_t width, uint32_t height, uint32_t maxSide);

// RGBA8 sRGB pixels (alpha linear) resampled to `to`. Deterministic: the same input gives the
// same bytes.
std::vector<uint8_t> resizedRgba8Srgb(const uint8_t* rgba, TextureSize from, TextureSize to);

// `texture` fitted under `maxSide`, or an unchanged copy when it fits.
Texture fittedTexture(const Texture& texture, uint32_t maxSide);

// The one-line warning for a downscaled texture: "<what> is WxH texels; downscaled to wxh (<why>)".
std::string downscaleWarning(const std::string& what, TextureSize from, TextureSize to, const std::string& why);

}  // namespace punctual
