#include "render/shadow_pass.h"

#include <algorithm>
#include <array>

#include "gpu_types.h"
#include "render/frame_bindings.h"
#include "render/scene_gpu.h"
#include "shaders/raster_shadow_vert_spv.h"
#include "vk/check.h"
#include "vk/context.h"
#include "vk/descriptors.h"
#include "vk/pipeline.h"

namespace punctual::render {
namespace {

struct ShadowDrawConstants {
    glm::mat4 viewProjection;
    uint32_t objectIndex;
};
constexpr uint32_t kObjectIndexOffset = offsetof(ShadowDrawConstants, objectIndex);

}  // namespace

ShadowPass::ShadowPass(const vk::Context& context, const ShadowPlan& plan, const ShadowSettings& settings)
    : plan_(plan),
      settings_(settings),
      maps_(context, plan, settings),
      views_(context, std::max<size_t>(plan.views.size(), 1) * sizeof(gpu::GpuShadowView),
             VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUse::Upload, "shadow views") {
    std::vector<gpu::GpuShadowView> views;
    for (const ShadowView& view : plan.views) views.push_back(view.gpu);
    if (!views.empty()) views_.write(views.data(), views.size() * sizeof(gpu::GpuShadowView));

    const VkDevice device = context.device();
    vk::RenderPassDesc passDesc;
    passDesc.depthFormat = ShadowMaps::kFormat;
    passDesc.depthLoad = VK_ATTACHMENT_LOAD_OP_CLEAR;
    passDesc.depthInitialLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
    passDesc.depthFinalLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
    renderPass_ = vk::createRenderPass(device, passDesc);
    for (uint32_t i = 0; i < plan.views.size(); ++i) {
        const ShadowView& view = plan.views[i];
        if (!view.isPoint && view.casters.empty()) continue;  // never sampled
        const vk::Image& image = !view.isPoint ? maps_.spots()
                                 : settings.pointLayout == PointShadowLayout::Cube ? maps_.pointCubes()
                                                                                    : maps_.pointSlices();
        VkImageViewCreateInfo viewInfo{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
        viewInfo.image = image.handle();
        viewInfo.viewType = VK_IMAGE_VIEW_TYPE_2D;
        viewInfo.format = ShadowMaps::kFormat;
        viewInfo.subresourceRange = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 1, view.layer, 1};
        VkImageView layerView = VK_NULL_HANDLE;
        vk::check(vkCreateImageView(device, &viewInfo, nullptr, &layerView), "vkCreateImageView");
        Target target;
        target.view = vk::Handle<VkImageView>(device, layerView, vkDestroyImageView);
        target.framebuffer =
            vk::createFramebuffer(device, renderPass_, {&layerView, 1}, settings.resolution, settings.resolution);
        target.planView = i;
        targets_.push_back(std::move(target));
    }
}

void ShadowPass::addBindings(BindingTable& table) const {
    const VkImageLayout readOnly = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    table.addBuffer(PUNCTUAL_BINDING_SHADOW_VIEWS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_FRAGMENT_BIT,
                    views_);
    table.addImage(PUNCTUAL_BINDING_SPOT_SHADOWS, VK_SHADER_STAGE_FRAGMENT_BIT, maps_.sampler(), maps_.spots().view(),
                   readOnly);
    table.addImage(PUNCTUAL_BINDING_POINT_SHADOWS, VK_SHADER_STAGE_FRAGMENT_BIT, maps_.sampler(),
                   maps_.pointCubes().view(), readOnly);
    table.addImage(PUNCTUAL_BINDING_POINT_SLICES, VK_SHADER_STAGE_FRAGMENT_BIT, maps_.sampler(),
                   maps_.pointSlices().view(), readOnly);
}

void ShadowPass::createPipelines(const vk::Context& context, const FrameBindings& bindings) {
    const VkDevice device = context.device();
    pipelineLayout_ = vk::createPipelineLayout(device, {bindings.setLayout()},
                                               {VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(ShadowDrawConstants)});
    vk::GraphicsPipelineDesc pipelineDesc;
    pipelineDesc.layout = pipelineLayout_;
    pipelineDesc.renderPass = renderPass_;
    pipelineDesc.vertexSpirv = raster_shadow_vert_spv;
    pipelineDesc.vertexStride = SceneGpu::vertexStride();
    pipelineDesc.vertexAttributes = {SceneGpu::vertexAttributes().front()};  // position only
    pipelineDesc.depthCompare = VK_COMPARE_OP_LESS;
    // Pancaking exists only for the failure study; spot and point shadows never use it.
    const VkBool32 pancaking = settings_.pancaking ? VK_TRUE : VK_FALSE;
    const VkSpecializationMapEntry pancakingEntry{0, 0, sizeof(VkBool32)};
    const VkSpecializationInfo vertexSpecialization{1, &pancakingEntry, sizeof(VkBool32), &pancaking};
    pipelineDesc.vertexSpecialization = &vertexSpecialization;
    pipeline_ = vk::createGraphicsPipeline(device, pipelineDesc);
}

void ShadowPass::record(const FrameContext& frame) const {
    const VkCommandBuffer cmd = frame.cmd;
    const std::array<const vk::Image*, 3> arrays = {&maps_.spots(), &maps_.pointCubes(), &maps_.pointSlices()};
    for (const vk::Image* image : arrays) {
        // Last frame's contents are not needed: every read layer is cleared or rendered below.
        vk::imageBarrier(cmd, *image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL,
                         VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, 0,
                         VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
                         VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);
    }
    VkClearValue clear{};
    clear.depthStencil = {1.0f, 0};
    for (const Target& target : targets_) {
        const ShadowView& view = plan_.views[target.planView];
        vk::beginRenderPass(cmd, renderPass_, target.framebuffer, settings_.resolution, settings_.resolution, {&clear, 1});
        if (!view.casters.empty()) {
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_);
            frame.bindings.bind(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipelineLayout_);
            vkCmdPushConstants(cmd, pipelineLayout_, VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(glm::mat4),
                               &view.gpu.viewProjection);
            frame.scene.drawObjects(cmd, pipelineLayout_, view.casters, kObjectIndexOffset, VK_SHADER_STAGE_VERTEX_BIT);
        }
        vkCmdEndRenderPass(cmd);
    }
    for (const vk::Image* image : arrays) {
        vk::imageBarrier(cmd, *image, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL,
                         VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
                         VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
                         VK_ACCESS_SHADER_READ_BIT);
    }
}

}  // namespace punctual::render
