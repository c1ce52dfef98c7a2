#include "render/shadow_maps.h"

#include "vk/check.h"
#include "vk/context.h"

namespace punctual::render {
namespace {

vk::Image depthArray(const vk::Context& context, uint32_t resolution, uint32_t layers, bool cube, const char* name) {
    vk::ImageDesc desc;
    desc.format = ShadowMaps::kFormat;
    desc.width = resolution;
    desc.height = resolution;
    desc.layers = layers;
    desc.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    desc.viewType = cube ? VK_IMAGE_VIEW_TYPE_CUBE_ARRAY : VK_IMAGE_VIEW_TYPE_2D_ARRAY;
    desc.flags = cube ? VK_IMAGE_CREATE_CUBE_COMPATIBLE_BIT : 0;
    desc.debugName = name;
    return vk::Image(context, desc);
}

}  // namespace

ShadowMaps::ShadowMaps(const vk::Context& context, const ShadowPlan& plan, const ShadowSettings& settings) {
    const uint32_t res = settings.resolution;
    const bool cubes = settings.pointLayout == PointShadowLayout::Cube;
    // Only what the frame uses: a 1x1 placeholder (six layers for a cube) for an empty array.
    spots_ = plan.shadowedSpots > 0 ? depthArray(context, res, plan.shadowedSpots, false, "spot shadows")
                                    : depthArray(context, 1, 1, false, "spot shadows (placeholder)");
    pointCubes_ = cubes && plan.shadowedPoints > 0
                      ? depthArray(context, res, 6 * plan.shadowedPoints, true, "point shadow cubes")
                      : depthArray(context, 1, 6, true, "point shadow cubes (placeholder)");
    pointSlices_ = !cubes && plan.shadowedPoints > 0
                       ? depthArray(context, res, 6 * plan.shadowedPoints, false, "point shadow slices")
                       : depthArray(context, 1, 1, false, "point shadow slices (placeholder)");

    // Compare sampler: bilinear, so one tap is the hardware's 2x2 PCF; outside the map is "far"
    // (the white border), i.e. lit.
    VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    info.magFilter = VK_FILTER_LINEAR;
    info.minFilter = VK_FILTER_LINEAR;
    info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
    info.addressModeU = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER;
    info.addressModeV = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER;
    info.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER;
    info.borderColor = VK_BORDER_COLOR_FLOAT_OPAQUE_WHITE;
    info.compareEnable = VK_TRUE;
    info.compareOp = VK_COMPARE_OP_LESS_OR_EQUAL;  // lit when the receiver is no deeper than the caster
    VkSampler sampler = VK_NULL_HANDLE;
    vk::check(vkCreateSampler(context.device(), &info, nullptr, &sampler), "vkCreateSampler");
    sampler_ = vk::Handle<VkSampler>(context.device(), sampler, vkDestroySampler);
}

uint64_t ShadowMaps::allocatedBytes() const {
    return spots_.allocatedBytes() + pointCubes_.allocatedBytes() + pointSlices_.allocatedBytes();
}

}  // namespace punctual::render
