#pragma once
// Depth prepass: every object into a D32 (float) depth buffer, no colour; single-sided
// materials' back faces culled and alpha-masked fragments dropped, as the forward pass shades. The depth is reversed
// (1 at the near plane, cleared to 0 at the far one, GREATER wins; see Camera::projection and
// culling.h), which keeps its precision at any near plane. The forward pass then shades each
// pixel once (EQUAL test, no depth writes), and the culling passes read this depth (set 0,
// PUNCTUAL_BINDING_DEPTH).
#include <array>
#include <vector>

#include <vulkan/vulkan.h>

#include "render/pass.h"
#include "render/scene_gpu.h"
#include "vk/handle.h"
#include "vk/image.h"

namespace punctual::render {

class DepthPrepass final : public Pass {
public:
    // `drawLists`: per DepthDrawKind before Blended, the objects to draw (those the camera sees),
    // ascending.
    DepthPrepass(const vk::Context& context, uint32_t width, uint32_t height,
                 std::array<std::vector<uint32_t>, kPrepassDrawKinds> drawLists);

    const char* name() const override { return "depth"; }
    void addBindings(BindingTable& table) const override;
    void createPipelines(const vk::Context& context, const FrameBindings& bindings) override;
    // Ends with the depth in kFinalLayout and its writes visible to the culling kernels and the
    // forward pass's depth test.
    void record(const FrameContext& frame) const override;
    uint64_t memoryBytes() const override { return depth_.allocatedBytes(); }
    // The depth, from any layout (it is cleared) to kFinalLayout.
    std::vector<ImageUse> imageUses() const override { return {{&depth_, VK_IMAGE_LAYOUT_UNDEFINED, kFinalLayout}}; }

    const vk::Image& depth() const { return depth_; }

    static constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
    // Readable by later attachments and shaders.
    static constexpr VkImageLayout kFinalLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL;

private:
    vk::Image depth_;
    vk::Handle<VkSampler> sampler_;  // nearest, for texelFetch in the culling kernels
    // The render pass and pipelines: the context's object cache (vk/object_cache.h) owns them.
    VkRenderPass renderPass_ = VK_NULL_HANDLE;
    vk::Handle<VkFramebuffer> framebuffer_;
    // One per DepthDrawKind (render/scene_gpu.h): opaque two-sided, culled CCW, culled CW, masked.
    std::array<VkPipeline, kPrepassDrawKinds> pipelines_{};
    std::array<std::vector<uint32_t>, kPrepassDrawKinds> drawLists_;
    uint32_t width_ = 0;
    uint32_t height_ = 0;
};

}  // namespace punctual::render
