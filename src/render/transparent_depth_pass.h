#pragma once
// The depth span of the transparent surfaces at each pixel (transparent_depth.frag), for the light
// culling kernels. Tiled and clustered lists are built from the depths of the surfaces a pixel
// shades; the depth prepass holds only the opaque ones, so a light near a pane of glass but far
// from the wall behind it would be missing from the glass's list. With this span the kernels'
// tile and cluster bounds reach from the opaque surface to the nearest transparent one, and the
// lists stay lossless for every surface the frame shades.
//
// Allocated only when the frame has alphaMode BLEND objects and culls into a light grid; then it
// is cleared and filled every frame (a one-word placeholder otherwise, which nothing reads:
// GpuFrame::transparentSpans tells the kernels).
#include <cstdint>
#include <vector>

#include <vulkan/vulkan.h>

#include "render/pass.h"
#include "vk/buffer.h"
#include "vk/handle.h"

namespace punctual::vk {
class Image;
}

namespace punctual::render {

class TransparentDepthPass final : public Pass {
public:
    // `depth`: the prepass's, in DepthPrepass::kFinalLayout. `blended`: the objects to draw.
    // `needed`: whether any kernel reads the span this frame (FramePlan::transparentSpans).
    TransparentDepthPass(const vk::Context& context, const vk::Image& depth, std::vector<uint32_t> blended,
                         bool needed, uint32_t width, uint32_t height);

    const char* name() const override { return "transparent_depth"; }
    void addBindings(BindingTable& table) const override;
    void createPipelines(const vk::Context& context, const FrameBindings& bindings) override;
    bool timed() const override { return needed_; }
    void record(const FrameContext& frame) const override;
    uint64_t memoryBytes() const override { return needed_ ? span_.size() : 0; }
    // Tests against the prepass's depth without writing it.
    std::vector<ImageUse> imageUses() const override;

private:
    const vk::Image& depth_;
    std::vector<uint32_t> blended_;
    bool needed_ = false;
    uint32_t width_ = 0;
    uint32_t height_ = 0;
    vk::Buffer span_;  // nearest depth bits per pixel, then farthest (gpu_types.h)
    VkRenderPass renderPass_ = VK_NULL_HANDLE;  // with pipeline_, owned by the context's object cache
    vk::Handle<VkFramebuffer> framebuffer_;
    VkPipeline pipeline_ = VK_NULL_HANDLE;
};

}  // namespace punctual::render
