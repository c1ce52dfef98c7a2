#pragma once
// The shadow stage's storage and its compare sampler: the atlas (lights/shadow_atlas.h), one 2D
// depth image holding every spot view and point slice at its own resolution, and, for the cube
// layout (fixed resolution only), a cube depth array with six faces per shadowed point. Each is
// sized to what the plan gives storage (a 1x1 placeholder when nothing does).
#include <cstdint>

#include <vulkan/vulkan.h>

#include "lights/shadow_setup.h"
#include "lights/shadow_sizing.h"
#include "vk/handle.h"
#include "vk/image.h"

namespace punctual::render {

class ShadowMaps {
public:
    // `plan` must be sized (sizeShadowViews, against memoryLimits()).
    ShadowMaps(const vk::Context& context, const ShadowPlan& plan, const ShadowSettings& settings);

    // What the device can hold: everything together in the largest device-local heap (the
    // largest heap, where none is device-local), or, where VK_EXT_memory_budget is supported,
    // that heap's budget for this process when smaller; the atlas's side up to
    // maxImageDimension2D; each image alone up to maxResourceSize for its format, usage and flags.
    static ShadowMemoryLimits memoryLimits(const vk::Context& context, const ShadowSettings& settings);

    static VkFormat format(ShadowFormat format) {
        return format == ShadowFormat::D16 ? VK_FORMAT_D16_UNORM : VK_FORMAT_D32_SFLOAT;
    }

    // The cube array anew for `plan` (its points' count or side changed), the atlas kept.
    void remakePointCubes(const vk::Context& context, const ShadowPlan& plan, const ShadowSettings& settings);

    const vk::Image& atlas() const { return atlas_; }
    const vk::Image& pointCubes() const { return pointCubes_; }
    VkSampler sampler() const { return sampler_; }
    // Non-compare sampler: textureGather of the atlas's raw depths (every atlas lookup compares in
    // the shader: receiver-plane compares per texel, bilinear compares per tap).
    VkSampler depthSampler() const { return depthSampler_; }
    // Device memory of the two images, placeholders included.
    uint64_t allocatedBytes() const;

private:
    vk::Image atlas_;
    vk::Image pointCubes_;
    vk::Handle<VkSampler> sampler_;
    vk::Handle<VkSampler> depthSampler_;
};

}  // namespace punctual::render
