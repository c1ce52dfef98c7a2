#pragma once
// Forward pass: shades each visible pixel of the opaque and masked objects once (depth EQUAL
// against the prepass, no writes) into an RGBA16F radiance target. Its transparent variant
// (ForwardVariant::transparent, the frame's "transparent" pass) then composites the alphaMode
// BLEND objects over it, back to front, with the same shader and the same light lists.
#include <vector>

#include <vulkan/vulkan.h>

#include "gpu_types.h"
#include "render/pass.h"
#include "vk/handle.h"

namespace punctual::vk {
class Buffer;
class Image;
}  // namespace punctual::vk

namespace punctual::render {

// The specialization of the one forward shader.
struct ForwardVariant {
    uint32_t lightSource = 0;  // PUNCTUAL_LIGHT_SOURCE_*: the method's source (LightListMethodInfo)
    uint32_t tileSize = 16;
    uint32_t slices = 1;
    uint32_t gridWords = 3;  // words a light-grid cell (LightGridLayout::gridWords)
    uint32_t listForm = 0;   // PUNCTUAL_LIGHT_LIST_*: how a cell holds its lights (LightListFormInfo)
    bool writeLightStats = false;  // debug variant: per-pixel light statistics
    bool shadows = false;
    uint32_t shadowKernel = 0;     // PUNCTUAL_SHADOW_KERNEL_*: the filter's kernel (ShadowFilterInfo)
    uint32_t shadowFilterSize = 1;  // and its size
    uint32_t shadowSamples = 16;   // disk filter
    uint32_t pointShadowLayout = 0;  // PUNCTUAL_POINT_SHADOW_*
    bool writeShadowFactors = false;  // validation variant: per-pixel shadow factors
    bool shadowReceiverPlane = true;  // per-texel receiver-plane compares (shadow_sampling.glsl)
    uint32_t cascadeBlend = 0;        // PUNCTUAL_CASCADE_BLEND_*
    // The transparent pass: the alphaMode BLEND objects, back to front, composited over the
    // opaque image by their base colour's alpha, depth-tested against the prepass (GREATER).
    bool transparent = false;
    // PUNCTUAL_SHADOW_PAGES_*: spot and point shadows from the atlas's squares or from virtual pages,
    // or the marking pass (the frame's "shadow_marks" pass), which writes `debugOutput`'s page marks.
    uint32_t shadowPages = PUNCTUAL_SHADOW_PAGES_OFF;
    bool marksShadowPages() const { return shadowPages == PUNCTUAL_SHADOW_PAGES_MARK; }
};

class ForwardPass final : public Pass {
public:
    // `radiance` ends in SHADER_READ_ONLY_OPTIMAL for the tone-mapping pass; `depth` must be in
    // DEPTH_STENCIL_READ_ONLY_OPTIMAL (the prepass leaves it so) and stays there. `debugOutput`
    // (the statistics and validation variants only): the buffer the variant writes, cleared to 0
    // before the pass and made visible to transfers after it.
    // `drawOrder`: the objects to draw, in order (the opaque pass: every unblended object in
    // object order; the transparent pass: the blended ones, farthest first).
    ForwardPass(const vk::Context& context, const vk::Image& radiance, const vk::Image& depth,
                const ForwardVariant& variant, std::vector<uint32_t> drawOrder,
                const vk::Buffer* debugOutput = nullptr);

    const char* name() const override {
        if (variant_.marksShadowPages()) return variant_.transparent ? "shadow_marks_transparent" : "shadow_marks";
        return variant_.transparent ? "transparent" : "forward";
    }
    bool timed() const override { return !drawOrder_.empty() || !variant_.transparent; }
    void createPipelines(const vk::Context& context, const FrameBindings& bindings) override;
    void record(const FrameContext& frame) const override;
    // The radiance (the opaque pass: from any layout, cleared; the transparent pass: over the
    // opaque pass's, in kRadianceLayout) and the prepass's depth, tested, not written.
    std::vector<ImageUse> imageUses() const override;
    // The fragment shader samples the shadow maps. The marking pass runs before they are drawn and
    // never reads them (its light walk returns before any lookup), but its pipeline's set 0 holds
    // them: it moves them, contents discarded, into the layout set 0 reads them in
    // (readUndrawnImages), so that the shadow stage finds them as it would anyway.
    VkShaderStageFlags boundImageStages() const override {
        return blendsNothing() || variant_.marksShadowPages() ? 0 : VK_SHADER_STAGE_FRAGMENT_BIT;
    }
    void readUndrawnImages(std::vector<const vk::Image*> images, VkImageLayout readLayout) {
        undrawnImages_ = std::move(images);
        undrawnReadLayout_ = readLayout;
    }

    static constexpr VkFormat kRadianceFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
    // The layout the pass leaves the radiance in, for the next forward pass and tone mapping.
    static constexpr VkImageLayout kRadianceLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;

private:
    // A transparent pass over a frame with nothing to blend: it records nothing and needs no
    // pipeline (the opaque image stays as it is).
    bool blendsNothing() const { return variant_.transparent && drawOrder_.empty(); }

    // The radiance's layout when the pass starts: anything for the opaque pass, which clears it;
    // the opaque pass's result for the transparent one, which blends over it.
    VkImageLayout radianceExpected() const {
        return variant_.transparent ? kRadianceLayout : VK_IMAGE_LAYOUT_UNDEFINED;
    }

    ForwardVariant variant_;
    std::vector<uint32_t> drawOrder_;
    std::vector<const vk::Image*> undrawnImages_;
    VkImageLayout undrawnReadLayout_ = VK_IMAGE_LAYOUT_UNDEFINED;
    const vk::Buffer* debugOutput_ = nullptr;
    const vk::Image& radiance_;
    const vk::Image& depth_;
    VkRenderPass renderPass_ = VK_NULL_HANDLE;  // with pipeline_, owned by the context's object cache
    vk::Handle<VkFramebuffer> framebuffer_;
    VkPipeline pipeline_ = VK_NULL_HANDLE;
    uint32_t width_ = 0;
    uint32_t height_ = 0;
};

}  // namespace punctual::render
