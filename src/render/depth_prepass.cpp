#include "render/depth_prepass.h"

#include <utility>

#include "culling.h"
#include "gpu_types.h"
#include "render/frame_bindings.h"
#include "render/scene_gpu.h"
#include "shaders/raster_alpha_mask_frag_spv.h"
#include "shaders/raster_mesh_vert_spv.h"
#include "vk/context.h"
#include "vk/descriptors.h"
#include "vk/pipeline.h"

namespace punctual::render {
namespace {

vk::Image depthImage(const vk::Context& context, uint32_t width, uint32_t height) {
    vk::ImageDesc desc;
    desc.format = DepthPrepass::kDepthFormat;
    desc.width = width;
    desc.height = height;
    // Sampled by the culling kernels, copied out by Renderer::readDepth.
    desc.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
                 VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    desc.debugName = "depth";
    return vk::Image(context, desc);
}

}  // namespace

DepthPrepass::DepthPrepass(const vk::Context& context, uint32_t width, uint32_t height,
                           std::array<std::vector<uint32_t>, kPrepassDrawKinds> drawLists)
    : depth_(depthImage(context, width, height)),
      sampler_(vk::createSampler(context.device(), VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE)),
      drawLists_(std::move(drawLists)),
      width_(width),
      height_(height) {
    vk::RenderPassDesc passDesc;
    passDesc.depthFormat = kDepthFormat;
    passDesc.depthLoad = VK_ATTACHMENT_LOAD_OP_CLEAR;
    passDesc.depthInitialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    passDesc.depthFinalLayout = kFinalLayout;
    renderPass_ = context.objects().renderPass(passDesc);
    const VkImageView view = depth_.view();
    framebuffer_ = vk::createFramebuffer(context.device(), renderPass_, {&view, 1}, width_, height_);
}

void DepthPrepass::addBindings(BindingTable& table) const {
    table.addImage(PUNCTUAL_BINDING_DEPTH, VK_SHADER_STAGE_COMPUTE_BIT, sampler_, depth_, kFinalLayout);
}

void DepthPrepass::createPipelines(const vk::Context& context, const FrameBindings& bindings) {
    vk::GraphicsPipelineDesc pipelineDesc;
    pipelineDesc.layout = bindings.pipelineLayout();
    pipelineDesc.renderPass = renderPass_;
    pipelineDesc.vertexSpirv = raster_mesh_vert_spv;
    pipelineDesc.vertexStride = SceneGpu::vertexStride();
    pipelineDesc.vertexAttributes = SceneGpu::vertexAttributes();
    // Reversed Z (Camera::projection): nearer is greater. Strictly greater, so that of two
    // fragments at the same depth the first drawn stays, as LESS did with the usual mapping.
    pipelineDesc.depthCompare = VK_COMPARE_OP_GREATER;
    pipelines_[uint32_t(DepthDrawKind::OpaqueTwoSided)] = context.objects().graphicsPipeline(pipelineDesc);
    pipelineDesc.cullMode = VK_CULL_MODE_BACK_BIT;
    pipelines_[uint32_t(DepthDrawKind::OpaqueCullBackCcw)] = context.objects().graphicsPipeline(pipelineDesc);
    pipelineDesc.frontFace = VK_FRONT_FACE_CLOCKWISE;
    pipelines_[uint32_t(DepthDrawKind::OpaqueCullBackCw)] = context.objects().graphicsPipeline(pipelineDesc);

    // Masked objects: alpha_mask.frag drops masked-out fragments and, for single-sided materials,
    // back faces (whichever way the object's transform winds them).
    pipelineDesc.cullMode = VK_CULL_MODE_NONE;
    pipelineDesc.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    pipelineDesc.fragmentSpirv = raster_alpha_mask_frag_spv;
    const VkBool32 cullBackFaces = VK_TRUE;
    const VkSpecializationMapEntry entry{0, 0, sizeof(VkBool32)};
    const VkSpecializationInfo specialization{1, &entry, sizeof(VkBool32), &cullBackFaces};
    pipelineDesc.fragmentSpecialization = &specialization;
    pipelines_[uint32_t(DepthDrawKind::Masked)] = context.objects().graphicsPipeline(pipelineDesc);
}

void DepthPrepass::record(const FrameContext& frame) const {
    VkClearValue clear{};
    clear.depthStencil = {PUNCTUAL_DEPTH_CLEAR, 0};  // the far plane of the reversed mapping
    vk::beginRenderPass(frame.cmd, renderPass_, framebuffer_, width_, height_, {&clear, 1});
    frame.bindings.bind(frame.cmd, VK_PIPELINE_BIND_POINT_GRAPHICS);
    for (uint32_t kind = 0; kind < kPrepassDrawKinds; ++kind) {
        const std::vector<uint32_t>& objects = drawLists_[kind];
        if (objects.empty()) continue;
        vkCmdBindPipeline(frame.cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipelines_[kind]);
        frame.scene.drawObjects(frame.cmd, frame.bindings.pipelineLayout(), objects, 0, kRasterStages,
                                /*withTextures=*/DepthDrawKind(kind) == DepthDrawKind::Masked);
    }
    vkCmdEndRenderPass(frame.cmd);
    // Depth writes must land before the culling kernel samples them and the forward pass's EQUAL
    // test reads them.
    vk::memoryBarrier(frame.cmd, VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT, VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                      VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT |
                          VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                      VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_SHADER_READ_BIT);
}

}  // namespace punctual::render
