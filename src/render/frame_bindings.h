#pragma once
// Descriptor set 0, shared by every pass of a frame, and the pipeline layout (set 0, the scene's
// per-material texture set 1, and the per-draw object index push constant).
//
// Set 0 is built from a BindingTable: the renderer adds the frame's own buffers (frame uniform,
// lights, objects, materials, per-object lists, debug outputs) and every pass adds the resources it
// owns (the depth prepass its depth buffer, light culling its grid, the shadow stage its maps), each
// under its PUNCTUAL_BINDING_* number from gpu_types.h. A new binding is one row where its resource
// lives.
#include <vector>

#include <vulkan/vulkan.h>

#include "render/pass.h"
#include "vk/descriptors.h"
#include "vk/handle.h"

namespace punctual::vk {
class Buffer;
class Context;
class Image;
}  // namespace punctual::vk

namespace punctual::render {

class SceneGpu;

// Stage sets the bindings use.
inline constexpr VkShaderStageFlags kRasterStages = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
inline constexpr VkShaderStageFlags kAllStages = kRasterStages | VK_SHADER_STAGE_COMPUTE_BIT;

class BindingTable {
public:
    // A whole buffer (uniform or storage).
    void addBuffer(uint32_t binding, VkDescriptorType type, VkShaderStageFlags stages, const vk::Buffer& buffer);
    // A combined image sampler of `image`'s view, read in `layout`.
    void addImage(uint32_t binding, VkShaderStageFlags stages, VkSampler sampler, const vk::Image& image,
                  VkImageLayout layout);

    // The images of the set, each in the layout its binding reads it in, with the stages that may
    // sample it: what a pass whose shaders sample them (Pass::boundImageStages) needs.
    std::vector<BoundImage> boundImages() const;

private:
    friend class FrameBindings;
    struct Row {
        VkDescriptorSetLayoutBinding layout;
        VkDescriptorBufferInfo buffer;  // buffers
        VkDescriptorImageInfo image;    // combined image samplers
        const vk::Image* source = nullptr;  // their image
    };
    std::vector<Row> rows_;
};

class FrameBindings {
public:
    // Throws an internal error when two rows name the same binding.
    FrameBindings(const vk::Context& context, const SceneGpu& scene, const BindingTable& table);

    VkDescriptorSetLayout setLayout() const { return setLayout_; }
    VkPipelineLayout pipelineLayout() const { return pipelineLayout_; }
    // Set 1: the scene's per-material textures (SceneGpu::materialSetLayout).
    VkDescriptorSetLayout materialSetLayout() const { return materialSetLayout_; }
    void bind(VkCommandBuffer cmd, VkPipelineBindPoint bindPoint) const;
    // Binds set 0 through another layout that shares it (e.g. with other push constants).
    void bind(VkCommandBuffer cmd, VkPipelineBindPoint bindPoint, VkPipelineLayout layout) const;

private:
    // The layouts: the context's object cache (vk/object_cache.h) owns them.
    VkDescriptorSetLayout setLayout_ = VK_NULL_HANDLE;
    VkDescriptorSetLayout materialSetLayout_ = VK_NULL_HANDLE;
    VkPipelineLayout pipelineLayout_ = VK_NULL_HANDLE;
    vk::DescriptorSet descriptors_;
};

}  // namespace punctual::render
