#pragma once
// The shadow stage's depth arrays and their compare sampler: spot lights in a 2D array (one layer
// each), point lights in a cube array (six faces each) or six slices of a 2D array. Sized to the
// shadowed lights present (a 1x1 placeholder when there are none).
#include <cstdint>

#include <vulkan/vulkan.h>

#include "lights/shadow_setup.h"
#include "vk/handle.h"
#include "vk/image.h"

namespace punctual::render {

class ShadowMaps {
public:
    // Throws Error("--shadow-res N", ...) (checkShadowMapsFit) before allocating anything when
    // the arrays do not fit memoryLimits().
    ShadowMaps(const vk::Context& context, const ShadowPlan& plan, const ShadowSettings& settings);

    // What the device can hold: all arrays together in the largest device-local heap (the
    // largest heap, where none is device-local), or, where VK_EXT_memory_budget is supported,
    // that heap's budget for this process when smaller; each array alone up to maxResourceSize
    // for its format, usage and flags.
    static ShadowMemoryLimits memoryLimits(const vk::Context& context, PointShadowLayout pointLayout);

    const vk::Image& spots() const { return spots_; }
    const vk::Image& pointCubes() const { return pointCubes_; }
    const vk::Image& pointSlices() const { return pointSlices_; }
    VkSampler sampler() const { return sampler_; }
    // Device memory of the three arrays, placeholders included.
    uint64_t allocatedBytes() const;

    static constexpr VkFormat kFormat = VK_FORMAT_D32_SFLOAT;

private:
    vk::Image spots_;
    vk::Image pointCubes_;
    vk::Image pointSlices_;
    vk::Handle<VkSampler> sampler_;
};

}  // namespace punctual::render
