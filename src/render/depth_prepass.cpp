#include "render/depth_prepass.h"

#include "render/frame_bindings.h"
#include "render/scene_gpu.h"
#include "shaders/raster_mesh_vert_spv.h"
#include "vk/context.h"
#include "vk/image.h"
#include "vk/pipeline.h"

namespace punctual::render {

DepthPrepass::DepthPrepass(const vk::Context& context, const FrameBindings& bindings, const vk::Image& depth)
    : width_(depth.desc().width), height_(depth.desc().height) {
    const VkDevice device = context.device();
    vk::RenderPassDesc passDesc;
    passDesc.depthFormat = kDepthFormat;
    passDesc.depthLoad = VK_ATTACHMENT_LOAD_OP_CLEAR;
    passDesc.depthInitialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    passDesc.depthFinalLayout = kFinalLayout;
    renderPass_ = vk::createRenderPass(device, passDesc);
    const VkImageView view = depth.view();
    framebuffer_ = vk::createFramebuffer(device, renderPass_, {&view, 1}, width_, height_);

    vk::GraphicsPipelineDesc pipelineDesc;
    pipelineDesc.layout = bindings.pipelineLayout();
    pipelineDesc.renderPass = renderPass_;
    pipelineDesc.vertexSpirv = raster_mesh_vert_spv;
    pipelineDesc.vertexStride = SceneGpu::vertexStride();
    pipelineDesc.vertexAttributes = SceneGpu::vertexAttributes();
    pipelineDesc.depthCompare = VK_COMPARE_OP_LESS;
    pipeline_ = vk::createGraphicsPipeline(device, pipelineDesc);
}

void DepthPrepass::record(VkCommandBuffer cmd, const SceneGpu& scene, const FrameBindings& bindings) const {
    VkClearValue clear{};
    clear.depthStencil = {1.0f, 0};
    vk::beginRenderPass(cmd, renderPass_, framebuffer_, width_, height_, {&clear, 1});
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_);
    bindings.bind(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS);
    scene.drawObjects(cmd, bindings.pipelineLayout(), /*withTextures=*/false);
    vkCmdEndRenderPass(cmd);
}

}  // namespace punctual::render
