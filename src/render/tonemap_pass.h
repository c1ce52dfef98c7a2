#pragma once
// Tone mapping (compute): radiance -> exposure -> ACES -> sRGB -> packed RGBA8 words in a buffer.
#include <vulkan/vulkan.h>

#include "render/pass.h"
#include "vk/buffer.h"
#include "vk/descriptors.h"
#include "vk/handle.h"

namespace punctual::vk {
class Image;
}  // namespace punctual::vk

namespace punctual::render {

class TonemapPass final : public Pass {
public:
    // `radiance` must be in kRadianceLayout when the pass runs (imageUses). The pass has its own
    // descriptor set (the radiance and its output), not set 0.
    TonemapPass(const vk::Context& context, const vk::Image& radiance, float exposure);

    const char* name() const override { return "tonemap"; }
    // Waits for the forward pass's colour writes, then tone maps; its output is visible to
    // transfers (the renderer's readback) when it ends.
    void record(const FrameContext& frame) const override;
    uint64_t memoryBytes() const override { return output_.size(); }
    // Samples the radiance in the layout the forward passes leave it in.
    std::vector<ImageUse> imageUses() const override { return {{&radiance_, kRadianceLayout, kRadianceLayout}}; }
    static constexpr VkImageLayout kRadianceLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    // The packed pixels (width * height words), written by record().
    const vk::Buffer& output() const { return output_; }

private:
    const vk::Image& radiance_;
    vk::Handle<VkSampler> sampler_;
    // The layouts and pipeline: the context's object cache (vk/object_cache.h) owns them.
    VkDescriptorSetLayout setLayout_ = VK_NULL_HANDLE;
    VkPipelineLayout pipelineLayout_ = VK_NULL_HANDLE;
    vk::DescriptorSet descriptors_;
    VkPipeline pipeline_ = VK_NULL_HANDLE;
    vk::Buffer output_;
    uint32_t width_ = 0;
    uint32_t height_ = 0;
    float exposure_ = 1.0f;
};

}  // namespace punctual::render
