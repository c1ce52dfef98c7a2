#pragma once
// Descriptor set 0, shared by every raster pass of a frame: the frame uniform, the packed lights,
// objects, materials, base-colour textures, the depth buffer and the light lists (see the
// PUNCTUAL_BINDING_* numbers in gpu_types.h), plus the pipeline layout with the per-draw object index push constant.
#include <vulkan/vulkan.h>

#include "vk/buffer.h"
#include "vk/descriptors.h"
#include "vk/handle.h"

namespace punctual::vk {
class Context;
}

namespace punctual::render {

class SceneGpu;

// What set 0 points at, besides the scene's own buffers and textures.
struct FrameBindingResources {
    const vk::Buffer& frameUniform;
    const vk::Buffer& lights;
    VkImageView depthView;      // depth prepass target, sampled by the culling passes
    VkSampler depthSampler;     // nearest, for texelFetch
    const vk::Buffer& lightGrid;
    const vk::Buffer& depthRange;
    const vk::Buffer& objectLights;
    const vk::Buffer& lightStats;
    const vk::Buffer& cullLights;
};

class FrameBindings {
public:
    FrameBindings(const vk::Context& context, const SceneGpu& scene, const FrameBindingResources& resources);

    VkDescriptorSetLayout setLayout() const { return setLayout_; }
    VkPipelineLayout pipelineLayout() const { return pipelineLayout_; }
    uint32_t textureCount() const { return textureCount_; }
    void bind(VkCommandBuffer cmd, VkPipelineBindPoint bindPoint) const;

private:
    vk::Handle<VkDescriptorSetLayout> setLayout_;
    vk::Handle<VkPipelineLayout> pipelineLayout_;
    vk::DescriptorSet descriptors_;
    uint32_t textureCount_ = 1;
};

}  // namespace punctual::render
