#pragma once
// Depth prepass: every object into a D32 depth buffer, no colour. The forward pass then shades
// each pixel once (EQUAL test, no depth writes), and the culling passes read this depth.
#include <vulkan/vulkan.h>

#include "vk/handle.h"

namespace punctual::vk {
class Context;
class Image;
}  // namespace punctual::vk

namespace punctual::render {

class FrameBindings;
class SceneGpu;

class DepthPrepass {
public:
    // `depth` ends in DEPTH_STENCIL_READ_ONLY_OPTIMAL: readable by later attachments and shaders.
    DepthPrepass(const vk::Context& context, const FrameBindings& bindings, const vk::Image& depth);
    void record(VkCommandBuffer cmd, const SceneGpu& scene, const FrameBindings& bindings) const;

    static constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
    static constexpr VkImageLayout kFinalLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL;

private:
    vk::Handle<VkRenderPass> renderPass_;
    vk::Handle<VkFramebuffer> framebuffer_;
    vk::Handle<VkPipeline> pipeline_;
    uint32_t width_ = 0;
    uint32_t height_ = 0;
};

}  // namespace punctual::render
