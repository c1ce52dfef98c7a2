#include "vk/descriptors.h"

#include <map>
#include <vector>

#include "vk/check.h"

namespace punctual::vk {

Handle<VkDescriptorSetLayout> createDescriptorSetLayout(VkDevice device,
                                                        std::span<const VkDescriptorSetLayoutBinding> bindings) {
    VkDescriptorSetLayoutCreateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    info.bindingCount = uint32_t(bindings.size());
    info.pBindings = bindings.data();
    VkDescriptorSetLayout layout = VK_NULL_HANDLE;
    check(vkCreateDescriptorSetLayout(device, &info, nullptr, &layout), "vkCreateDescriptorSetLayout");
    return {device, layout, vkDestroyDescriptorSetLayout};
}

Handle<VkPipelineLayout> createPipelineLayout(VkDevice device, std::initializer_list<VkDescriptorSetLayout> setLayouts,
                                              VkPushConstantRange pushConstants) {
    VkPipelineLayoutCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    info.setLayoutCount = uint32_t(setLayouts.size());
    info.pSetLayouts = setLayouts.begin();
    info.pushConstantRangeCount = pushConstants.size > 0 ? 1 : 0;
    info.pPushConstantRanges = &pushConstants;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    check(vkCreatePipelineLayout(device, &info, nullptr, &layout), "vkCreatePipelineLayout");
    return {device, layout, vkDestroyPipelineLayout};
}

DescriptorSet allocateDescriptorSet(VkDevice device, VkDescriptorSetLayout layout,
                                    std::span<const VkDescriptorSetLayoutBinding> bindings) {
    std::map<VkDescriptorType, uint32_t> counts;
    for (const VkDescriptorSetLayoutBinding& binding : bindings) counts[binding.descriptorType] += binding.descriptorCount;
    std::vector<VkDescriptorPoolSize> sizes;
    for (const auto& [type, count] : counts) sizes.push_back({type, count});
    VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    poolInfo.maxSets = 1;
    poolInfo.poolSizeCount = uint32_t(sizes.size());
    poolInfo.pPoolSizes = sizes.data();
    VkDescriptorPool pool = VK_NULL_HANDLE;
    check(vkCreateDescriptorPool(device, &poolInfo, nullptr, &pool), "vkCreateDescriptorPool");
    DescriptorSet result;
    result.pool = Handle<VkDescriptorPool>(device, pool, vkDestroyDescriptorPool);

    VkDescriptorSetAllocateInfo allocInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    allocInfo.descriptorPool = pool;
    allocInfo.descriptorSetCount = 1;
    allocInfo.pSetLayouts = &layout;
    check(vkAllocateDescriptorSets(device, &allocInfo, &result.set), "vkAllocateDescriptorSets");
    return result;
}

VkWriteDescriptorSet bufferWrite(VkDescriptorSet set, uint32_t binding, VkDescriptorType type,
                                 const VkDescriptorBufferInfo* info) {
    VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    write.dstSet = set;
    write.dstBinding = binding;
    write.descriptorCount = 1;
    write.descriptorType = type;
    write.pBufferInfo = info;
    return write;
}

VkWriteDescriptorSet imageWrite(VkDescriptorSet set, uint32_t binding, const VkDescriptorImageInfo* infos,
                                uint32_t count) {
    VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    write.dstSet = set;
    write.dstBinding = binding;
    write.descriptorCount = count;
    write.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    write.pImageInfo = infos;
    return write;
}

Handle<VkSampler> createSampler(VkDevice device, VkFilter filter, VkSamplerAddressMode addressMode) {
    VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    info.magFilter = filter;
    info.minFilter = filter;
    info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
    info.addressModeU = addressMode;
    info.addressModeV = addressMode;
    info.addressModeW = addressMode;
    info.maxLod = 0.0f;
    VkSampler sampler = VK_NULL_HANDLE;
    check(vkCreateSampler(device, &info, nullptr, &sampler), "vkCreateSampler");
    return {device, sampler, vkDestroySampler};
}

}  // namespace punctual::vk
