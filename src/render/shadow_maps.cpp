#include "render/shadow_maps.h"

#include <algorithm>
#include <cstring>
#include <vector>

#include "vk/check.h"
#include "vk/context.h"

namespace punctual::render {
namespace {

// Drawn (pages and cube faces), copied into (the atlas's views, from the shadow pass's drawing
// square) and sampled.
constexpr VkImageUsageFlags kUsage =
    VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;

vk::Image depthImage(const vk::Context& context, VkFormat format, uint32_t width, uint32_t height, uint32_t layers,
                     bool cube, const char* name) {
    vk::ImageDesc desc;
    desc.format = format;
    desc.width = width;
    desc.height = height;
    desc.layers = layers;
    desc.usage = kUsage;
    desc.viewType = cube ? VK_IMAGE_VIEW_TYPE_CUBE_ARRAY : VK_IMAGE_VIEW_TYPE_2D;
    desc.flags = cube ? VK_IMAGE_CREATE_CUBE_COMPATIBLE_BIT : 0;
    desc.debugName = name;
    return vk::Image(context, desc);
}

// maxResourceSize of one shadow image (a cube array when `cube`).
uint64_t maxImageBytes(const vk::Context& context, VkFormat format, bool cube) {
    VkImageFormatProperties properties{};
    vk::check(vkGetPhysicalDeviceImageFormatProperties(context.physicalDevice(), format, VK_IMAGE_TYPE_2D,
                                                       VK_IMAGE_TILING_OPTIMAL, kUsage,
                                                       cube ? VK_IMAGE_CREATE_CUBE_COMPATIBLE_BIT : 0, &properties),
              "vkGetPhysicalDeviceImageFormatProperties");
    return properties.maxResourceSize;
}

bool supportsDeviceExtension(VkPhysicalDevice device, const char* name) {
    uint32_t count = 0;
    vk::check(vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr), "vkEnumerateDeviceExtensionProperties");
    std::vector<VkExtensionProperties> extensions(count);
    vk::check(vkEnumerateDeviceExtensionProperties(device, nullptr, &count, extensions.data()),
              "vkEnumerateDeviceExtensionProperties");
    return std::any_of(extensions.begin(), extensions.end(),
                       [&](const VkExtensionProperties& e) { return std::strcmp(e.extensionName, name) == 0; });
}

}  // namespace

ShadowMemoryLimits ShadowMaps::memoryLimits(const vk::Context& context, const ShadowSettings& settings) {
    // A physical-device query: the budget structure needs the extension supported, not enabled.
    VkPhysicalDeviceMemoryBudgetPropertiesEXT budget{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MEMORY_BUDGET_PROPERTIES_EXT};
    VkPhysicalDeviceMemoryProperties2 properties{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MEMORY_PROPERTIES_2};
    const bool hasBudget = supportsDeviceExtension(context.physicalDevice(), VK_EXT_MEMORY_BUDGET_EXTENSION_NAME);
    if (hasBudget) properties.pNext = &budget;
    vkGetPhysicalDeviceMemoryProperties2(context.physicalDevice(), &properties);
    const VkPhysicalDeviceMemoryProperties& memory = properties.memoryProperties;
    bool anyDeviceLocal = false;
    for (uint32_t i = 0; i < memory.memoryHeapCount; ++i) {
        anyDeviceLocal |= (memory.memoryHeaps[i].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT) != 0;
    }
    ShadowMemoryLimits limits;
    limits.total = 0;
    for (uint32_t i = 0; i < memory.memoryHeapCount; ++i) {
        if (anyDeviceLocal && (memory.memoryHeaps[i].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT) == 0) continue;
        uint64_t bytes = memory.memoryHeaps[i].size;
        const char* name = "the device's largest heap";
        // A budget of 0 would be a driver that fills nothing in: keep the heap's size then.
        if (hasBudget && budget.heapBudget[i] > 0 && budget.heapBudget[i] < bytes) {
            bytes = budget.heapBudget[i];
            name = "the device's memory budget";
        }
        if (bytes > limits.total) {
            limits.total = bytes;
            limits.totalName = name;
        }
    }
    VkPhysicalDeviceProperties device{};
    vkGetPhysicalDeviceProperties(context.physicalDevice(), &device);
    limits.atlasSide = device.limits.maxImageDimension2D;
    limits.atlasBytes = maxImageBytes(context, format(settings.format), false);
    limits.cubeArrayBytes = maxImageBytes(context, format(settings.format), true);
    return limits;
}

ShadowMaps::ShadowMaps(const vk::Context& context, const ShadowPlan& plan, const ShadowSettings& settings) {
    const VkFormat depthFormat = format(settings.format);
    // Only what the frame uses: a 1x1 placeholder (six layers for a cube) for an empty image.
    atlas_ = plan.atlas.width > 0
                 ? depthImage(context, depthFormat, plan.atlas.width, plan.atlas.height, 1, false, "shadow atlas")
                 : depthImage(context, depthFormat, 1, 1, 1, false, "shadow atlas (placeholder)");
    remakePointCubes(context, plan, settings);

    // Compare sampler (the cube array's; the atlas is gathered raw, shadows.h's bilinearCompare):
    // bilinear, so one tap is the hardware's 2x2 PCF; outside the map is "far"
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

    info.magFilter = VK_FILTER_NEAREST;
    info.minFilter = VK_FILTER_NEAREST;
    info.compareEnable = VK_FALSE;
    VkSampler depthSampler = VK_NULL_HANDLE;
    vk::check(vkCreateSampler(context.device(), &info, nullptr, &depthSampler), "vkCreateSampler");
    depthSampler_ = vk::Handle<VkSampler>(context.device(), depthSampler, vkDestroySampler);
}

void ShadowMaps::remakePointCubes(const vk::Context& context, const ShadowPlan& plan, const ShadowSettings& settings) {
    const VkFormat depthFormat = format(settings.format);
    pointCubes_ = plan.cubeResolution > 0 ? depthImage(context, depthFormat, plan.cubeResolution, plan.cubeResolution,
                                                       6 * plan.shadowedPoints, true, "point shadow cubes")
                                          : depthImage(context, depthFormat, 1, 1, 6, true, "point shadow cubes (placeholder)");
}

uint64_t ShadowMaps::allocatedBytes() const {
    return atlas_.allocatedBytes() + pointCubes_.allocatedBytes();
}

}  // namespace punctual::render
