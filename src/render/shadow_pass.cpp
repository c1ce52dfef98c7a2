#include "render/shadow_pass.h"

#include <array>

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

vk::Image depthArray(const vk::Context& context, uint32_t resolution, uint32_t layers, bool cube, const char* name) {
    vk::ImageDesc desc;
    desc.format = ShadowMaps::kFormat;
    desc.width = resolution;
    desc.height = resolution;
    desc.layers = layers;
    desc.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    desc.viewType = cube ? VK_IMAGE_VIEW_TYPE_CUBE_ARRAY : VK_IMAGE_VIEW_TYPE_2D_ARRAY;
    desc.flags = cube ? VK_IMAGE_CREATE_CUBE_COMPATIBLE_BIT : 0;
    desc.debugName = name;
    return vk::Image(context, desc);
}

}  // namespace

ShadowMaps::ShadowMaps(const vk::Context& context, const ShadowPlan& plan, const ShadowSettings& settings) {
    const uint32_t res = settings.resolution;
    const bool cubes = settings.pointLayout == PointShadowLayout::Cube;
    // Only what the frame uses: a 1x1 placeholder (six layers for a cube) for an empty array.
    spots_ = plan.shadowedSpots > 0 ? depthArray(context, res, plan.shadowedSpots, false, "spot shadows")
                                    : depthArray(context, 1, 1, false, "spot shadows (placeholder)");
    pointCubes_ = cubes && plan.shadowedPoints > 0
                      ? depthArray(context, res, 6 * plan.shadowedPoints, true, "point shadow cubes")
                      : depthArray(context, 1, 6, true, "point shadow cubes (placeholder)");
    pointSlices_ = !cubes && plan.shadowedPoints > 0
                       ? depthArray(context, res, 6 * plan.shadowedPoints, false, "point shadow slices")
                       : depthArray(context, 1, 1, false, "point shadow slices (placeholder)");

    // Compare sampler: bilinear, so one tap is the hardware's 2x2 PCF; outside the map is "far"
    // (the white border), i.e. lit.
    VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    info.magFilter = VK_FILTER_LINEAR;
    info.minFilter = VK_FILTER_LINEAR;
    info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
    info.addressModeU = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER;
    info.addressModeV = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER;
    info.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER;
    info.borderColor = VK_BORDER_COLOR_FLOAT_OPAQUE_WHITE;
    info.compareEnable = VK_TRUE;
    info.compareOp = VK_COMPARE_OP_LESS_OR_EQUAL;  // lit when the receiver is no deeper than the caster
    VkSampler sampler = VK_NULL_HANDLE;
    vk::check(vkCreateSampler(context.device(), &info, nullptr, &sampler), "vkCreateSampler");
    sampler_ = vk::Handle<VkSampler>(context.device(), sampler, vkDestroySampler);
}

uint64_t ShadowMaps::allocatedBytes() const {
    return spots_.allocatedBytes() + pointCubes_.allocatedBytes() + pointSlices_.allocatedBytes();
}

ShadowPass::ShadowPass(const vk::Context& context, const FrameBindings& bindings, const ShadowMaps& maps,
                       const ShadowPlan& plan, const ShadowSettings& settings)
    : maps_(maps), plan_(plan), resolution_(settings.resolution) {
    const VkDevice device = context.device();
    vk::RenderPassDesc passDesc;
    passDesc.depthFormat = ShadowMaps::kFormat;
    passDesc.depthLoad = VK_ATTACHMENT_LOAD_OP_CLEAR;
    passDesc.depthInitialLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
    passDesc.depthFinalLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
    renderPass_ = vk::createRenderPass(device, passDesc);
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
    const VkBool32 pancaking = settings.pancaking ? VK_TRUE : VK_FALSE;
    const VkSpecializationMapEntry pancakingEntry{0, 0, sizeof(VkBool32)};
    const VkSpecializationInfo vertexSpecialization{1, &pancakingEntry, sizeof(VkBool32), &pancaking};
    pipelineDesc.vertexSpecialization = &vertexSpecialization;
    pipeline_ = vk::createGraphicsPipeline(device, pipelineDesc);

    for (uint32_t i = 0; i < plan.views.size(); ++i) {
        const ShadowView& view = plan.views[i];
        if (!view.isPoint && view.casters.empty()) continue;  // never sampled
        const vk::Image& image = !view.isPoint ? maps.spots()
                                 : settings.pointLayout == PointShadowLayout::Cube ? maps.pointCubes()
                                                                                    : maps.pointSlices();
        VkImageViewCreateInfo viewInfo{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
        viewInfo.image = image.handle();
        viewInfo.viewType = VK_IMAGE_VIEW_TYPE_2D;
        viewInfo.format = ShadowMaps::kFormat;
        viewInfo.subresourceRange = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 1, view.layer, 1};
        VkImageView layerView = VK_NULL_HANDLE;
        vk::check(vkCreateImageView(device, &viewInfo, nullptr, &layerView), "vkCreateImageView");
        Target target;
        target.view = vk::Handle<VkImageView>(device, layerView, vkDestroyImageView);
        target.framebuffer = vk::createFramebuffer(device, renderPass_, {&layerView, 1}, resolution_, resolution_);
        target.planView = i;
        targets_.push_back(std::move(target));
    }
}

void ShadowPass::record(VkCommandBuffer cmd, const SceneGpu& scene, const FrameBindings& bindings) const {
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
        vk::beginRenderPass(cmd, renderPass_, target.framebuffer, resolution_, resolution_, {&clear, 1});
        if (!view.casters.empty()) {
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_);
            bindings.bind(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipelineLayout_);
            vkCmdPushConstants(cmd, pipelineLayout_, VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(glm::mat4),
                               &view.gpu.viewProjection);
            scene.drawObjects(cmd, pipelineLayout_, view.casters, kObjectIndexOffset, VK_SHADER_STAGE_VERTEX_BIT);
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
