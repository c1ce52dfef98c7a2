#include "render/forward_pass.h"

#include <array>
#include <cstddef>
#include <utility>

#include "gpu_types.h"
#include "render/depth_prepass.h"
#include "render/frame_bindings.h"
#include "render/scene_gpu.h"
#include "shaders/raster_forward_frag_SHADOW_PAGES_spv.h"
#include "shaders/raster_forward_frag_spv.h"
#include "shaders/raster_mesh_vert_spv.h"
#include "vk/buffer.h"
#include "vk/context.h"
#include "vk/image.h"
#include "vk/pipeline.h"

namespace punctual::render {

ForwardPass::ForwardPass(const vk::Context& context, const vk::Image& radiance, const vk::Image& depth,
                         const ForwardVariant& variant, std::vector<uint32_t> drawOrder, const vk::Buffer* debugOutput)
    : variant_(variant),
      drawOrder_(std::move(drawOrder)),
      debugOutput_(debugOutput),
      radiance_(radiance),
      depth_(depth),
      width_(radiance.desc().width),
      height_(radiance.desc().height) {
    const VkDevice device = context.device();
    vk::RenderPassDesc passDesc;
    passDesc.colorFormat = kRadianceFormat;
    passDesc.colorFinalLayout = kRadianceLayout;
    passDesc.colorInitialLayout = radianceExpected();
    if (variant.transparent) passDesc.colorLoad = VK_ATTACHMENT_LOAD_OP_LOAD;  // over the opaque pass's image
    passDesc.depthFormat = DepthPrepass::kDepthFormat;
    passDesc.depthLoad = VK_ATTACHMENT_LOAD_OP_LOAD;
    passDesc.depthStore = VK_ATTACHMENT_STORE_OP_STORE;
    passDesc.depthInitialLayout = DepthPrepass::kFinalLayout;
    passDesc.depthFinalLayout = DepthPrepass::kFinalLayout;
    renderPass_ = context.objects().renderPass(passDesc);
    const std::array<VkImageView, 2> views = {radiance.view(), depth.view()};
    framebuffer_ = vk::createFramebuffer(device, renderPass_, views, width_, height_);
}

std::vector<ImageUse> ForwardPass::imageUses() const {
    if (blendsNothing()) return {};
    std::vector<ImageUse> uses = {{&radiance_, radianceExpected(), kRadianceLayout},
                                  {&depth_, DepthPrepass::kFinalLayout, DepthPrepass::kFinalLayout}};
    for (const vk::Image* image : undrawnImages_) uses.push_back({image, VK_IMAGE_LAYOUT_UNDEFINED, undrawnReadLayout_});
    return uses;
}

void ForwardPass::createPipelines(const vk::Context& context, const FrameBindings& bindings) {
    const ForwardVariant& variant = variant_;
    // The forward shader is the frame's largest: lavapipe takes 0.1-0.3 s to build each pipeline.
    if (blendsNothing()) return;

    struct Constants {
        uint32_t lightSource;
        uint32_t tileSize;
        uint32_t slices;
        VkBool32 writeLightStats;
        VkBool32 shadows;
        uint32_t shadowKernel;
        uint32_t shadowFilterSize;
        uint32_t shadowSamples;
        uint32_t pointShadowLayout;
        VkBool32 writeShadowFactors;
        VkBool32 shadowReceiverPlane;
        uint32_t cascadeBlend;
        VkBool32 transparent;
        uint32_t gridWords;
        uint32_t listForm;
        uint32_t shadowPages;
    };
    const Constants constants{variant.lightSource, variant.tileSize, variant.slices,
                              variant.writeLightStats ? VK_TRUE : VK_FALSE, variant.shadows ? VK_TRUE : VK_FALSE,
                              variant.shadowKernel, variant.shadowFilterSize, variant.shadowSamples, variant.pointShadowLayout,
                              variant.writeShadowFactors ? VK_TRUE : VK_FALSE,
                              variant.shadowReceiverPlane ? VK_TRUE : VK_FALSE, variant.cascadeBlend,
                              variant.transparent ? VK_TRUE : VK_FALSE, variant.gridWords, variant.listForm,
                              variant.shadowPages};
    const std::array<VkSpecializationMapEntry, 16> entries = {{
        {PUNCTUAL_SPEC_LIGHT_SOURCE, offsetof(Constants, lightSource), sizeof(uint32_t)},
        {PUNCTUAL_SPEC_TILE_SIZE, offsetof(Constants, tileSize), sizeof(uint32_t)},
        {PUNCTUAL_SPEC_SLICE_COUNT, offsetof(Constants, slices), sizeof(uint32_t)},
        {PUNCTUAL_SPEC_WRITE_LIGHT_STATS, offsetof(Constants, writeLightStats), sizeof(VkBool32)},
        {PUNCTUAL_SPEC_SHADOWS, offsetof(Constants, shadows), sizeof(VkBool32)},
        {PUNCTUAL_SPEC_SHADOW_KERNEL, offsetof(Constants, shadowKernel), sizeof(uint32_t)},
        {PUNCTUAL_SPEC_SHADOW_FILTER_SIZE, offsetof(Constants, shadowFilterSize), sizeof(uint32_t)},
        {PUNCTUAL_SPEC_SHADOW_SAMPLES, offsetof(Constants, shadowSamples), sizeof(uint32_t)},
        {PUNCTUAL_SPEC_POINT_SHADOW_LAYOUT, offsetof(Constants, pointShadowLayout), sizeof(uint32_t)},
        {PUNCTUAL_SPEC_WRITE_SHADOW_FACTORS, offsetof(Constants, writeShadowFactors), sizeof(VkBool32)},
        {PUNCTUAL_SPEC_SHADOW_RECEIVER_PLANE, offsetof(Constants, shadowReceiverPlane), sizeof(VkBool32)},
        {PUNCTUAL_SPEC_CASCADE_BLEND, offsetof(Constants, cascadeBlend), sizeof(uint32_t)},
        {PUNCTUAL_SPEC_TRANSPARENT, offsetof(Constants, transparent), sizeof(VkBool32)},
        {PUNCTUAL_SPEC_GRID_WORDS, offsetof(Constants, gridWords), sizeof(uint32_t)},
        {PUNCTUAL_SPEC_LIGHT_LIST_FORM, offsetof(Constants, listForm), sizeof(uint32_t)},
        {PUNCTUAL_SPEC_SHADOW_PAGES, offsetof(Constants, shadowPages), sizeof(uint32_t)},
    }};
    const VkSpecializationInfo specialization{uint32_t(entries.size()), entries.data(), sizeof(constants), &constants};

    vk::GraphicsPipelineDesc pipelineDesc;
    pipelineDesc.layout = bindings.pipelineLayout();
    pipelineDesc.renderPass = renderPass_;
    pipelineDesc.vertexSpirv = raster_mesh_vert_spv;
    // The virtual-pages build only where the variant reads or marks pages (cmake/Shaders.cmake).
    pipelineDesc.fragmentSpirv = variant.shadowPages == PUNCTUAL_SHADOW_PAGES_OFF ? std::span<const uint32_t>(raster_forward_frag_spv)
                                                                                  : std::span<const uint32_t>(raster_forward_frag_SHADOW_PAGES_spv);
    pipelineDesc.fragmentSpecialization = &specialization;
    pipelineDesc.vertexStride = SceneGpu::vertexStride();
    pipelineDesc.vertexAttributes = SceneGpu::vertexAttributes();
    pipelineDesc.hasColorAttachment = true;
    pipelineDesc.depthWrite = false;
    // Opaque: exactly the prepass's surface. Transparent: in front of it (reversed depth).
    pipelineDesc.depthCompare = variant.transparent ? VK_COMPARE_OP_GREATER : VK_COMPARE_OP_EQUAL;
    pipelineDesc.alphaBlend = variant.transparent;
    pipeline_ = context.objects().graphicsPipeline(pipelineDesc);
}

void ForwardPass::record(const FrameContext& frame) const {
    const VkCommandBuffer cmd = frame.cmd;
    if (debugOutput_ && !variant_.transparent) {  // the transparent variant adds to what the opaque one wrote
        vkCmdFillBuffer(cmd, debugOutput_->handle(), 0, VK_WHOLE_SIZE, 0u);
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                          VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT);
    }
    if (blendsNothing()) return;
    for (const vk::Image* image : undrawnImages_) {
        vk::imageBarrier(cmd, *image, VK_IMAGE_LAYOUT_UNDEFINED, undrawnReadLayout_, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, 0,
                         VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
    }
    if (variant_.transparent) {
        // The opaque pass's colour writes land before these blend over them.
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
                          VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                          VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT);
    }
    std::array<VkClearValue, 2> clears{};
    clears[0].color = {{0.0f, 0.0f, 0.0f, 1.0f}};
    vk::beginRenderPass(cmd, renderPass_, framebuffer_, width_, height_, clears);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_);
    frame.bindings.bind(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS);
    frame.scene.drawObjects(cmd, frame.bindings.pipelineLayout(), drawOrder_, 0, kRasterStages, /*withTextures=*/true);
    vkCmdEndRenderPass(cmd);
    if (debugOutput_) {
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                          VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
    }
}

}  // namespace punctual::render
