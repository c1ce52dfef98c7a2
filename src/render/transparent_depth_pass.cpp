#include "render/transparent_depth_pass.h"

#include <utility>

#include "gpu_types.h"
#include "render/depth_prepass.h"
#include "render/frame_bindings.h"
#include "render/scene_gpu.h"
#include "shaders/raster_mesh_vert_spv.h"
#include "shaders/raster_transparent_depth_frag_spv.h"
#include "vk/context.h"
#include "vk/image.h"
#include "vk/pipeline.h"

namespace punctual::render {

TransparentDepthPass::TransparentDepthPass(const vk::Context& context, const vk::Image& depth,
                                           std::vector<uint32_t> blended, bool needed, uint32_t width,
                                           uint32_t height)
    : depth_(depth),
      blended_(std::move(blended)),
      needed_(needed && !blended_.empty()),
      width_(width),
      height_(height),
      span_(context, needed_ ? VkDeviceSize(width) * height * 2 * sizeof(uint32_t) : sizeof(uint32_t),
            VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryUse::DeviceLocal,
            "transparent depth") {
    if (!needed_) return;
    vk::RenderPassDesc passDesc;
    passDesc.depthFormat = DepthPrepass::kDepthFormat;
    passDesc.depthLoad = VK_ATTACHMENT_LOAD_OP_LOAD;
    passDesc.depthStore = VK_ATTACHMENT_STORE_OP_STORE;
    passDesc.depthInitialLayout = DepthPrepass::kFinalLayout;
    passDesc.depthFinalLayout = DepthPrepass::kFinalLayout;
    renderPass_ = context.objects().renderPass(passDesc);
    const VkImageView view = depth.view();
    framebuffer_ = vk::createFramebuffer(context.device(), renderPass_, {&view, 1}, width, height);
}

std::vector<ImageUse> TransparentDepthPass::imageUses() const {
    if (!needed_) return {};
    return {{&depth_, DepthPrepass::kFinalLayout, DepthPrepass::kFinalLayout}};
}

void TransparentDepthPass::addBindings(BindingTable& table) const {
    table.addBuffer(PUNCTUAL_BINDING_TRANSPARENT_DEPTH, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                    VK_SHADER_STAGE_FRAGMENT_BIT | VK_SHADER_STAGE_COMPUTE_BIT, span_);
}

void TransparentDepthPass::createPipelines(const vk::Context& context, const FrameBindings& bindings) {
    if (!needed_) return;
    vk::GraphicsPipelineDesc pipelineDesc;
    pipelineDesc.layout = bindings.pipelineLayout();
    pipelineDesc.renderPass = renderPass_;
    pipelineDesc.vertexSpirv = raster_mesh_vert_spv;
    pipelineDesc.fragmentSpirv = raster_transparent_depth_frag_spv;
    pipelineDesc.vertexStride = SceneGpu::vertexStride();
    pipelineDesc.vertexAttributes = SceneGpu::vertexAttributes();
    pipelineDesc.depthWrite = false;
    pipelineDesc.depthCompare = VK_COMPARE_OP_GREATER;  // in front of the opaque surface (reversed depth)
    pipeline_ = context.objects().graphicsPipeline(pipelineDesc);
}

void TransparentDepthPass::record(const FrameContext& frame) const {
    if (!needed_) return;
    const VkCommandBuffer cmd = frame.cmd;
    const VkDeviceSize half = VkDeviceSize(width_) * height_ * sizeof(uint32_t);
    // Last frame's kernels are done reading before the span is cleared again.
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT,
                      VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
    vkCmdFillBuffer(cmd, span_.handle(), 0, half, 0u);               // nearest: none (the far plane)
    vkCmdFillBuffer(cmd, span_.handle(), half, half, 0xFFFFFFFFu);   // farthest: none
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                      VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
    vk::beginRenderPass(cmd, renderPass_, framebuffer_, width_, height_, {});
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_);
    frame.bindings.bind(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS);
    frame.scene.drawObjects(cmd, frame.bindings.pipelineLayout(), blended_, 0, kRasterStages);
    vkCmdEndRenderPass(cmd);
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                      VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
}

}  // namespace punctual::render
