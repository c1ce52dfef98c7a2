#pragma once
// Descriptor set layouts, pipeline layouts and single-set pools: the setup every pass with its
// own bindings repeats, in one place. Passes ask for set and pipeline layouts through
// Context::objects() (vk/object_cache.h), which builds each definition once with these.
#include <initializer_list>
#include <span>

#include <vulkan/vulkan.h>

#include "vk/handle.h"

namespace punctual::vk {

Handle<VkDescriptorSetLayout> createDescriptorSetLayout(VkDevice device,
                                                        std::span<const VkDescriptorSetLayoutBinding> bindings);
// Set layouts 0, 1, ... and at most one push-constant range (size 0: none).
Handle<VkPipelineLayout> createPipelineLayout(VkDevice device, std::initializer_list<VkDescriptorSetLayout> setLayouts,
                                              VkPushConstantRange pushConstants);

// A pool sized for exactly one set of `bindings`, and that set (freed with the pool).
struct DescriptorSet {
    Handle<VkDescriptorPool> pool;
    VkDescriptorSet set = VK_NULL_HANDLE;
};
DescriptorSet allocateDescriptorSet(VkDevice device, VkDescriptorSetLayout layout,
                                    std::span<const VkDescriptorSetLayoutBinding> bindings);

VkWriteDescriptorSet bufferWrite(VkDescriptorSet set, uint32_t binding, VkDescriptorType type,
                                 const VkDescriptorBufferInfo* info);
VkWriteDescriptorSet imageWrite(VkDescriptorSet set, uint32_t binding, const VkDescriptorImageInfo* infos,
                                uint32_t count = 1);

Handle<VkSampler> createSampler(VkDevice device, VkFilter filter, VkSamplerAddressMode addressMode);

}  // namespace punctual::vk
