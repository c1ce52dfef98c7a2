#include "render/frame_bindings.h"

#include <utility>
#include <vector>

#include "gpu_types.h"
#include "render/scene_gpu.h"
#include "vk/check.h"
#include "vk/context.h"

namespace punctual::render {

FrameBindings::FrameBindings(const vk::Context& context, const SceneGpu& scene, const FrameBindingResources& resources)
    : textureCount_(uint32_t(scene.textures().size())) {
    const VkDevice device = context.device();
    const VkShaderStageFlags raster = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
    const VkShaderStageFlags all = raster | VK_SHADER_STAGE_COMPUTE_BIT;
    const std::vector<VkDescriptorSetLayoutBinding> bindings = {
        {PUNCTUAL_BINDING_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, all, nullptr},
        {PUNCTUAL_BINDING_LIGHTS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
        {PUNCTUAL_BINDING_OBJECTS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, raster, nullptr},
        {PUNCTUAL_BINDING_MATERIALS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr},
        {PUNCTUAL_BINDING_TEXTURES, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, textureCount_,
         VK_SHADER_STAGE_FRAGMENT_BIT, nullptr},
        {PUNCTUAL_BINDING_DEPTH, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
        {PUNCTUAL_BINDING_LIGHT_GRID, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
        {PUNCTUAL_BINDING_DEPTH_RANGE, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
        {PUNCTUAL_BINDING_OBJECT_LIGHTS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr},
        {PUNCTUAL_BINDING_LIGHT_STATS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr},
        {PUNCTUAL_BINDING_CULL_LIGHTS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
    };
    VkDescriptorSetLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    layoutInfo.bindingCount = uint32_t(bindings.size());
    layoutInfo.pBindings = bindings.data();
    VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
    vk::check(vkCreateDescriptorSetLayout(device, &layoutInfo, nullptr, &setLayout), "vkCreateDescriptorSetLayout");
    setLayout_ = vk::Handle<VkDescriptorSetLayout>(device, setLayout, vkDestroyDescriptorSetLayout);

    VkPushConstantRange push{raster, 0, sizeof(uint32_t)};
    VkPipelineLayoutCreateInfo pipelineInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    pipelineInfo.setLayoutCount = 1;
    pipelineInfo.pSetLayouts = &setLayout;
    pipelineInfo.pushConstantRangeCount = 1;
    pipelineInfo.pPushConstantRanges = &push;
    VkPipelineLayout pipelineLayout = VK_NULL_HANDLE;
    vk::check(vkCreatePipelineLayout(device, &pipelineInfo, nullptr, &pipelineLayout), "vkCreatePipelineLayout");
    pipelineLayout_ = vk::Handle<VkPipelineLayout>(device, pipelineLayout, vkDestroyPipelineLayout);

    const std::vector<VkDescriptorPoolSize> sizes = {
        {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1},
        {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 8},
        {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, textureCount_ + 1},
    };
    VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    poolInfo.maxSets = 1;
    poolInfo.poolSizeCount = uint32_t(sizes.size());
    poolInfo.pPoolSizes = sizes.data();
    VkDescriptorPool pool = VK_NULL_HANDLE;
    vk::check(vkCreateDescriptorPool(device, &poolInfo, nullptr, &pool), "vkCreateDescriptorPool");
    pool_ = vk::Handle<VkDescriptorPool>(device, pool, vkDestroyDescriptorPool);

    VkDescriptorSetAllocateInfo allocInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    allocInfo.descriptorPool = pool;
    allocInfo.descriptorSetCount = 1;
    allocInfo.pSetLayouts = &setLayout;
    vk::check(vkAllocateDescriptorSets(device, &allocInfo, &set_), "vkAllocateDescriptorSets");

    const VkDescriptorBufferInfo frameInfo{resources.frameUniform.handle(), 0, VK_WHOLE_SIZE};
    const VkDescriptorBufferInfo lightInfo{resources.lights.handle(), 0, VK_WHOLE_SIZE};
    const VkDescriptorBufferInfo gridInfo{resources.lightGrid.handle(), 0, VK_WHOLE_SIZE};
    const VkDescriptorBufferInfo depthRangeInfo{resources.depthRange.handle(), 0, VK_WHOLE_SIZE};
    const VkDescriptorBufferInfo objectLightsInfo{resources.objectLights.handle(), 0, VK_WHOLE_SIZE};
    const VkDescriptorBufferInfo statsInfo{resources.lightStats.handle(), 0, VK_WHOLE_SIZE};
    const VkDescriptorBufferInfo cullLightsInfo{resources.cullLights.handle(), 0, VK_WHOLE_SIZE};
    const VkDescriptorImageInfo depthInfo{resources.depthSampler, resources.depthView,
                                          VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL};
    const VkDescriptorBufferInfo objectInfo{scene.objectBuffer().handle(), 0, VK_WHOLE_SIZE};
    const VkDescriptorBufferInfo materialInfo{scene.materialBuffer().handle(), 0, VK_WHOLE_SIZE};
    std::vector<VkDescriptorImageInfo> textureInfos;
    for (const vk::Image& texture : scene.textures()) {
        textureInfos.push_back({scene.sampler(), texture.view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL});
    }
    auto write = [&](uint32_t binding, VkDescriptorType type, uint32_t count) {
        VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        w.dstSet = set_;
        w.dstBinding = binding;
        w.descriptorCount = count;
        w.descriptorType = type;
        return w;
    };
    std::vector<VkWriteDescriptorSet> writes;
    writes.push_back(write(PUNCTUAL_BINDING_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1));
    writes.back().pBufferInfo = &frameInfo;
    writes.push_back(write(PUNCTUAL_BINDING_LIGHTS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1));
    writes.back().pBufferInfo = &lightInfo;
    writes.push_back(write(PUNCTUAL_BINDING_OBJECTS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1));
    writes.back().pBufferInfo = &objectInfo;
    writes.push_back(write(PUNCTUAL_BINDING_MATERIALS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1));
    writes.back().pBufferInfo = &materialInfo;
    writes.push_back(write(PUNCTUAL_BINDING_TEXTURES, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, textureCount_));
    writes.back().pImageInfo = textureInfos.data();
    writes.push_back(write(PUNCTUAL_BINDING_DEPTH, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1));
    writes.back().pImageInfo = &depthInfo;
    const std::pair<uint32_t, const VkDescriptorBufferInfo*> storage[] = {
        {PUNCTUAL_BINDING_LIGHT_GRID, &gridInfo},
        {PUNCTUAL_BINDING_DEPTH_RANGE, &depthRangeInfo},
        {PUNCTUAL_BINDING_OBJECT_LIGHTS, &objectLightsInfo},
        {PUNCTUAL_BINDING_LIGHT_STATS, &statsInfo},
        {PUNCTUAL_BINDING_CULL_LIGHTS, &cullLightsInfo},
    };
    for (const auto& [binding, info] : storage) {
        writes.push_back(write(binding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1));
        writes.back().pBufferInfo = info;
    }
    vkUpdateDescriptorSets(device, uint32_t(writes.size()), writes.data(), 0, nullptr);
}

void FrameBindings::bind(VkCommandBuffer cmd, VkPipelineBindPoint bindPoint) const {
    vkCmdBindDescriptorSets(cmd, bindPoint, pipelineLayout_, 0, 1, &set_, 0, nullptr);
}

}  // namespace punctual::render
