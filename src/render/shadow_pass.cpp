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
    const VkFormat format = ShadowMaps::format(settings.format);
    vk::RenderPassDesc passDesc;
    passDesc.depthFormat = format;
    passDesc.depthLoad = VK_ATTACHMENT_LOAD_OP_CLEAR;
    passDesc.depthInitialLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
    passDesc.depthFinalLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
    renderPass_ = vk::createRenderPass(device, passDesc);
    auto addTarget = [&](const vk::Image& image, uint32_t layer, uint32_t width, uint32_t height) -> Target& {
        VkImageViewCreateInfo viewInfo{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
        viewInfo.image = image.handle();
        viewInfo.viewType = VK_IMAGE_VIEW_TYPE_2D;
        viewInfo.format = format;
        viewInfo.subresourceRange = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 1, layer, 1};
        VkImageView layerView = VK_NULL_HANDLE;
        vk::check(vkCreateImageView(device, &viewInfo, nullptr, &layerView), "vkCreateImageView");
        Target target;
        target.view = vk::Handle<VkImageView>(device, layerView, vkDestroyImageView);
        target.framebuffer = vk::createFramebuffer(device, renderPass_, {&layerView, 1}, width, height);
        target.width = width;
        target.height = height;
        targets_.push_back(std::move(target));
        return targets_.back();
    };
    if (plan.atlas.width > 0) {
        Target& atlas = addTarget(maps_.atlas(), 0, plan.atlas.width, plan.atlas.height);
        for (uint32_t i = 0; i < plan.views.size(); ++i) {
            const ShadowView& view = plan.views[i];
            if (view.rendered() && view.rect.size > 0) atlas.planViews.push_back(i);
        }
    }
    if (plan.cubeResolution > 0) {
        for (uint32_t i = 0; i < plan.views.size(); ++i) {
            const ShadowView& view = plan.views[i];
            if (!view.isPoint) continue;
            Target& face = addTarget(maps_.pointCubes(), view.cubeLayer, plan.cubeResolution, plan.cubeResolution);
            if (view.rendered()) face.planViews.push_back(i);
        }
    }
}

void ShadowPass::addBindings(BindingTable& table) const {
    const VkImageLayout readOnly = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    table.addBuffer(PUNCTUAL_BINDING_SHADOW_VIEWS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_FRAGMENT_BIT,
                    views_);
    table.addImage(PUNCTUAL_BINDING_SHADOW_ATLAS, VK_SHADER_STAGE_FRAGMENT_BIT, maps_.sampler(), maps_.atlas().view(),
                   readOnly);
    table.addImage(PUNCTUAL_BINDING_SHADOW_ATLAS_DEPTH, VK_SHADER_STAGE_FRAGMENT_BIT, maps_.depthSampler(),
                   maps_.atlas().view(), readOnly);
    table.addImage(PUNCTUAL_BINDING_POINT_SHADOWS, VK_SHADER_STAGE_FRAGMENT_BIT, maps_.sampler(),
                   maps_.pointCubes().view(), readOnly);
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

    // Cascades pancake (the seed's "pancaking"), with the depth clamp where the device has it: the
    // vertex clamp bends the depth of triangles that cross the near plane, the depth clamp does
    // not. The failure study turns it off to show what clipping loses.
    if (plan_.cascades.count > 0) {
        const bool pancake = settings_.cascades.depthClamp;
        const bool clamp = pancake && context.enabledFeatures().depthClamp == VK_TRUE;
        const VkBool32 vertexPancaking = pancake && !clamp ? VK_TRUE : VK_FALSE;
        const VkSpecializationInfo cascadeSpecialization{1, &pancakingEntry, sizeof(VkBool32), &vertexPancaking};
        pipelineDesc.vertexSpecialization = &cascadeSpecialization;
        pipelineDesc.depthClamp = clamp;
        cascadePipeline_ = vk::createGraphicsPipeline(device, pipelineDesc);
    }
}

void ShadowPass::drawView(const FrameContext& frame, const ShadowView& view) const {
    const VkCommandBuffer cmd = frame.cmd;
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, view.isCascade ? cascadePipeline_ : pipeline_);
    frame.bindings.bind(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipelineLayout_);
    vkCmdPushConstants(cmd, pipelineLayout_, VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(glm::mat4), &view.gpu.viewProjection);
    frame.scene.drawObjects(cmd, pipelineLayout_, view.casters, kObjectIndexOffset, VK_SHADER_STAGE_VERTEX_BIT);
}

void ShadowPass::record(const FrameContext& frame) const {
    const VkCommandBuffer cmd = frame.cmd;
    const std::array<const vk::Image*, 2> images = {&maps_.atlas(), &maps_.pointCubes()};
    for (const vk::Image* image : images) {
        // Last frame's contents are not needed: every read texel is cleared or rendered below.
        vk::imageBarrier(cmd, *image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL,
                         VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, 0,
                         VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
                         VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);
    }
    VkClearValue clear{};
    clear.depthStencil = {1.0f, 0};
    for (const Target& target : targets_) {
        vk::beginRenderPass(cmd, renderPass_, target.framebuffer, target.width, target.height, {&clear, 1});
        for (uint32_t index : target.planViews) {
            const ShadowView& view = plan_.views[index];
            if (view.isPoint && settings_.pointLayout == PointShadowLayout::Cube) {
                drawView(frame, view);  // the whole face; beginRenderPass set its viewport
                continue;
            }
            // The view's square of the atlas: the viewport maps its clip space onto the square, the
            // scissor keeps every fragment inside it.
            const VkViewport viewport{float(view.rect.x), float(view.rect.y), float(view.rect.size),
                                      float(view.rect.size), 0.0f, 1.0f};
            const VkRect2D scissor{{int32_t(view.rect.x), int32_t(view.rect.y)}, {view.rect.size, view.rect.size}};
            vkCmdSetViewport(cmd, 0, 1, &viewport);
            vkCmdSetScissor(cmd, 0, 1, &scissor);
            drawView(frame, view);
        }
        vkCmdEndRenderPass(cmd);
    }
    for (const vk::Image* image : images) {
        vk::imageBarrier(cmd, *image, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL,
                         VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
                         VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
                         VK_ACCESS_SHADER_READ_BIT);
    }
}

}  // namespace punctual::render
