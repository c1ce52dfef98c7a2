#include "render/frame_bindings.h"

#include <utility>
#include <vector>

#include "gpu_types.h"
#include "render/scene_gpu.h"
#include "vk/descriptors.h"
#include "vk/context.h"

namespace punctual::render {

FrameBindings::FrameBindings(const vk::Context& context, const SceneGpu& scene, const FrameBindingResources& resources)
    {
    const VkDevice device = context.device();
    const VkShaderStageFlags raster = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
    const VkShaderStageFlags all = raster | VK_SHADER_STAGE_COMPUTE_BIT;
    const std::vector<VkDescriptorSetLayoutBinding> bindings = {
        {PUNCTUAL_BINDING_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, all, nullptr},
        {PUNCTUAL_BINDING_LIGHTS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
        {PUNCTUAL_BINDING_OBJECTS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, raster, nullptr},
        {PUNCTUAL_BINDING_MATERIALS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr},
        {PUNCTUAL_BINDING_DEPTH, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
        {PUNCTUAL_BINDING_LIGHT_GRID, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
        {PUNCTUAL_BINDING_DEPTH_RANGE, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
        {PUNCTUAL_BINDING_OBJECT_LIGHTS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr},
        {PUNCTUAL_BINDING_LIGHT_STATS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr},
        {PUNCTUAL_BINDING_CULL_LIGHTS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
        {PUNCTUAL_BINDING_SHADOW_VIEWS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr},
        {PUNCTUAL_BINDING_SPOT_SHADOWS, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr},
        {PUNCTUAL_BINDING_POINT_SHADOWS, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr},
        {PUNCTUAL_BINDING_POINT_SLICES, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr},
        {PUNCTUAL_BINDING_SHADOW_DEBUG, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr},
    };
    setLayout_ = vk::createDescriptorSetLayout(device, bindings);
    pipelineLayout_ = vk::createPipelineLayout(device, {setLayout_.get(), scene.materialSetLayout()},
                                               {raster, 0, sizeof(uint32_t)});
    descriptors_ = vk::allocateDescriptorSet(device, setLayout_, bindings);

    const VkDescriptorBufferInfo frameInfo{resources.frameUniform.handle(), 0, VK_WHOLE_SIZE};
    const VkDescriptorBufferInfo lightInfo{resources.lights.handle(), 0, VK_WHOLE_SIZE};
    const VkDescriptorBufferInfo gridInfo{resources.lightGrid.handle(), 0, VK_WHOLE_SIZE};
    const VkDescriptorBufferInfo depthRangeInfo{resources.depthRange.handle(), 0, VK_WHOLE_SIZE};
    const VkDescriptorBufferInfo objectLightsInfo{resources.objectLights.handle(), 0, VK_WHOLE_SIZE};
    const VkDescriptorBufferInfo statsInfo{resources.lightStats.handle(), 0, VK_WHOLE_SIZE};
    const VkDescriptorBufferInfo cullLightsInfo{resources.cullLights.handle(), 0, VK_WHOLE_SIZE};
    const VkDescriptorBufferInfo shadowViewsInfo{resources.shadowViews.handle(), 0, VK_WHOLE_SIZE};
    const VkDescriptorBufferInfo shadowDebugInfo{resources.shadowDebug.handle(), 0, VK_WHOLE_SIZE};
    const VkImageLayout readOnly = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    const VkDescriptorImageInfo spotShadowsInfo{resources.shadowSampler, resources.spotShadows, readOnly};
    const VkDescriptorImageInfo pointShadowsInfo{resources.shadowSampler, resources.pointShadows, readOnly};
    const VkDescriptorImageInfo pointSlicesInfo{resources.shadowSampler, resources.pointSlices, readOnly};
    const VkDescriptorImageInfo depthInfo{resources.depthSampler, resources.depthView,
                                          VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL};
    const VkDescriptorBufferInfo objectInfo{scene.objectBuffer().handle(), 0, VK_WHOLE_SIZE};
    const VkDescriptorBufferInfo materialInfo{scene.materialBuffer().handle(), 0, VK_WHOLE_SIZE};
    const VkDescriptorSet set = descriptors_.set;
    std::vector<VkWriteDescriptorSet> writes = {
        vk::imageWrite(set, PUNCTUAL_BINDING_DEPTH, &depthInfo),
        vk::imageWrite(set, PUNCTUAL_BINDING_SPOT_SHADOWS, &spotShadowsInfo),
        vk::imageWrite(set, PUNCTUAL_BINDING_POINT_SHADOWS, &pointShadowsInfo),
        vk::imageWrite(set, PUNCTUAL_BINDING_POINT_SLICES, &pointSlicesInfo),
        vk::bufferWrite(set, PUNCTUAL_BINDING_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, &frameInfo),
    };
    const std::pair<uint32_t, const VkDescriptorBufferInfo*> storage[] = {
        {PUNCTUAL_BINDING_LIGHTS, &lightInfo},
        {PUNCTUAL_BINDING_OBJECTS, &objectInfo},
        {PUNCTUAL_BINDING_MATERIALS, &materialInfo},
        {PUNCTUAL_BINDING_LIGHT_GRID, &gridInfo},
        {PUNCTUAL_BINDING_DEPTH_RANGE, &depthRangeInfo},
        {PUNCTUAL_BINDING_OBJECT_LIGHTS, &objectLightsInfo},
        {PUNCTUAL_BINDING_LIGHT_STATS, &statsInfo},
        {PUNCTUAL_BINDING_CULL_LIGHTS, &cullLightsInfo},
        {PUNCTUAL_BINDING_SHADOW_VIEWS, &shadowViewsInfo},
        {PUNCTUAL_BINDING_SHADOW_DEBUG, &shadowDebugInfo},
    };
    for (const auto& [binding, info] : storage) {
        writes.push_back(vk::bufferWrite(set, binding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, info));
    }
    vkUpdateDescriptorSets(device, uint32_t(writes.size()), writes.data(), 0, nullptr);
}

void FrameBindings::bind(VkCommandBuffer cmd, VkPipelineBindPoint bindPoint) const {
    bind(cmd, bindPoint, pipelineLayout_);
}

void FrameBindings::bind(VkCommandBuffer cmd, VkPipelineBindPoint bindPoint, VkPipelineLayout layout) const {
    vkCmdBindDescriptorSets(cmd, bindPoint, layout, 0, 1, &descriptors_.set, 0, nullptr);
}

}  // namespace punctual::render
