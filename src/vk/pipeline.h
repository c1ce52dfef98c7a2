#pragma once
// Shader modules, pipelines and render passes: thin helpers that spell out every state a pass
// sets, so a pass file reads as a description of its pipeline. Passes ask for their pipelines and
// render passes through Context::objects() (vk/object_cache.h), which builds each definition once
// with these.
#include <cstdint>
#include <span>
#include <vector>

#include <vulkan/vulkan.h>

#include "vk/handle.h"

namespace punctual::vk {

Handle<VkShaderModule> createShaderModule(VkDevice device, std::span<const uint32_t> spirv);

struct GraphicsPipelineDesc {
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkRenderPass renderPass = VK_NULL_HANDLE;
    std::span<const uint32_t> vertexSpirv;
    std::span<const uint32_t> fragmentSpirv;  // empty: depth-only pipeline
    const VkSpecializationInfo* fragmentSpecialization = nullptr;
    const VkSpecializationInfo* vertexSpecialization = nullptr;
    uint32_t vertexStride = 0;
    std::vector<VkVertexInputAttributeDescription> vertexAttributes;
    bool hasColorAttachment = false;
    // "Over" compositing: rgb = src.rgb * src.a + dst.rgb * (1 - src.a) (the transparent pass).
    bool alphaBlend = false;
    bool depthTest = true;
    bool depthWrite = true;
    VkCompareOp depthCompare = VK_COMPARE_OP_LESS;
    VkCullModeFlags cullMode = VK_CULL_MODE_NONE;
    // Counter-clockwise is glTF's front face under punctual's projections (forward.frag's
    // gl_FrontFacing); clockwise culls the back faces of objects whose transform mirrors.
    VkFrontFace frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    bool depthBias = false;  // dynamic depth bias (vkCmdSetDepthBias)
    bool depthClamp = false;  // clamp depth to the viewport instead of clipping at near and far (feature depthClamp)
};

Handle<VkPipeline> createGraphicsPipeline(VkDevice device, const GraphicsPipelineDesc& desc);
Handle<VkPipeline> createComputePipeline(VkDevice device, VkPipelineLayout layout, std::span<const uint32_t> spirv,
                                         const VkSpecializationInfo* specialization = nullptr);

// A single-subpass render pass with an optional colour attachment and a depth attachment.
struct RenderPassDesc {
    VkFormat colorFormat = VK_FORMAT_UNDEFINED;  // UNDEFINED: no colour attachment
    VkImageLayout colorFinalLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    VkAttachmentLoadOp colorLoad = VK_ATTACHMENT_LOAD_OP_CLEAR;
    VkImageLayout colorInitialLayout = VK_IMAGE_LAYOUT_UNDEFINED;  // LOAD needs the layout it is in
    VkFormat depthFormat = VK_FORMAT_D32_SFLOAT;
    VkAttachmentLoadOp depthLoad = VK_ATTACHMENT_LOAD_OP_CLEAR;
    VkAttachmentStoreOp depthStore = VK_ATTACHMENT_STORE_OP_STORE;
    VkImageLayout depthInitialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    VkImageLayout depthFinalLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
};
Handle<VkRenderPass> createRenderPass(VkDevice device, const RenderPassDesc& desc);

// Begins `renderPass` over the whole `width` x `height` target and sets a matching viewport and
// scissor (both are dynamic state in every pipeline made by createGraphicsPipeline).
void beginRenderPass(VkCommandBuffer cmd, VkRenderPass renderPass, VkFramebuffer framebuffer, uint32_t width,
                     uint32_t height, std::span<const VkClearValue> clears);

Handle<VkFramebuffer> createFramebuffer(VkDevice device, VkRenderPass renderPass,
                                        std::span<const VkImageView> attachments, uint32_t width,
                                        uint32_t height, uint32_t layers = 1);

}  // namespace punctual::vk
