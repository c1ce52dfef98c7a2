#pragma once
// Descriptor set 0, shared by every pass of a frame: the frame uniform, the packed lights,
// objects, materials, the depth buffer, the light lists and the shadow maps (see the
// PUNCTUAL_BINDING_* numbers in gpu_types.h), plus the pipeline layout (set 0, the scene's
// per-material texture set 1, and the per-draw object index push constant).
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
    const vk::Buffer& shadowViews;
    VkImageView spotShadows;     // 2D array
    VkImageView pointShadows;    // cube array
    VkImageView pointSlices;     // 2D array
    VkSampler shadowSampler;     // compare sampler
    const vk::Buffer& shadowDebug;  // validation variant output
};

class FrameBindings {
public:
    FrameBindings(const vk::Context& context, const SceneGpu& scene, const FrameBindingResources& resources);

    VkDescriptorSetLayout setLayout() const { return setLayout_; }
    VkPipelineLayout pipelineLayout() const { return pipelineLayout_; }
    void bind(VkCommandBuffer cmd, VkPipelineBindPoint bindPoint) const;
    // Binds set 0 through another layout that shares it (e.g. with other push constants).
    void bind(VkCommandBuffer cmd, VkPipelineBindPoint bindPoint, VkPipelineLayout layout) const;

private:
    vk::Handle<VkDescriptorSetLayout> setLayout_;
    vk::Handle<VkPipelineLayout> pipelineLayout_;
    vk::DescriptorSet descriptors_;
};

}  // namespace punctual::render
