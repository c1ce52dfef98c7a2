#pragma once
// The raster shadow stage: renders every shadow view of the plan with casters into its square of
// the atlas, or its face of the cube array (ShadowMaps), and binds them, with the views'
// records, for the forward pass. The atlas is cleared once and every view drawn in one render
// pass, its viewport and scissor moving from square to square; each cube face is its own target.
// A view without casters or storage draws nothing (the shader never reads it).
#include <cstdint>
#include <vector>

#include <vulkan/vulkan.h>

#include "lights/shadow_setup.h"
#include "render/pass.h"
#include "render/shadow_maps.h"
#include "vk/buffer.h"
#include "vk/handle.h"

namespace punctual::render {

class ShadowPass final : public Pass {
public:
    // `plan` must outlive the pass.
    ShadowPass(const vk::Context& context, const ShadowPlan& plan, const ShadowSettings& settings);

    const char* name() const override { return "shadows"; }
    void addBindings(BindingTable& table) const override;
    void createPipelines(const vk::Context& context, const FrameBindings& bindings) override;
    // With no shadowed light the stage only moves the placeholder maps into their layout: not a
    // pass worth timing.
    bool timed() const override { return !plan_.views.empty(); }
    // Renders every view with casters, clears the atlas and every cube face (the cube's hardware
    // filtering reads across face edges), and leaves both images in kReadLayout for the forward
    // pass.
    void record(const FrameContext& frame) const override;
    uint64_t memoryBytes() const override { return maps_.allocatedBytes(); }
    MemoryKind memoryKind() const override { return MemoryKind::Shadows; }
    std::vector<ImageUse> imageUses() const override;

    // The maps' layout while the stage draws them, and the one it leaves them in (and set 0 reads).
    static constexpr VkImageLayout kDrawLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
    static constexpr VkImageLayout kReadLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;

    const ShadowMaps& maps() const { return maps_; }

private:
    struct Target {
        vk::Handle<VkImageView> view;
        vk::Handle<VkFramebuffer> framebuffer;
        uint32_t width = 0;
        uint32_t height = 0;
        std::vector<uint32_t> planViews;  // indices into plan_.views drawn into it
    };
    void drawView(const FrameContext& frame, const ShadowView& view) const;
    const ShadowPlan& plan_;
    ShadowSettings settings_;
    ShadowMaps maps_;
    vk::Buffer views_;  // GpuShadowView per plan view (one slot when there are none)
    // The render pass, layout and pipelines: the context's object cache (vk/object_cache.h) owns them.
    VkRenderPass renderPass_ = VK_NULL_HANDLE;
    VkPipelineLayout pipelineLayout_ = VK_NULL_HANDLE;
    struct Pipelines {
        VkPipeline opaque = VK_NULL_HANDLE;  // depth only, no fragment shader
        VkPipeline masked = VK_NULL_HANDLE;  // alpha-masked casters (alpha_mask.frag)
    };
    Pipelines pipelines_;
    // The sun's cascades: casters between the sun and a cascade's near plane are pancaked onto it
    // (depth clamp, or the vertex clamp where the device lacks it), never clipped.
    Pipelines cascadePipelines_;
    std::vector<Target> targets_;  // the atlas first (when it has storage), then the cube faces
};

}  // namespace punctual::render
