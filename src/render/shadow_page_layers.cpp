#include "render/shadow_page_layers.h"

#include <algorithm>
#include <vector>

#include "shadow_pages.h"
#include "vk/context.h"
#include "vk/pipeline.h"

namespace punctual::render {
namespace {

constexpr uint32_t kSlot = PUNCTUAL_VIRTUAL_SHADOW_SLOT;
constexpr VkImageLayout kDrawLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;

VkImageCopy layerToSlot(uint32_t layer, const glm::uvec2& origin) {
    VkImageCopy copy{};
    copy.srcSubresource = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, layer, 1};
    copy.dstSubresource = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 0, 1};
    copy.dstOffset = {int32_t(origin.x), int32_t(origin.y), 0};
    copy.extent = {kSlot, kSlot, 1};
    return copy;
}

}  // namespace

uint32_t ShadowPageLayers::layersPerBatch(const vk::Context& context) {
    const VkPhysicalDeviceLimits& limits = context.properties().limits;
    return std::min(kMostLayers, std::max(std::min(limits.maxFramebufferLayers, limits.maxImageArrayLayers), 2u)) - 1u;
}

ShadowPageLayers::ShadowPageLayers(const vk::Context& context, VkFormat format, VkRenderPass renderPass,
                                   const ShadowPageDraws& draws)
    : renderPass_(renderPass) {
    vk::ImageDesc desc;
    desc.format = format;
    desc.width = kSlot;
    desc.height = kSlot;
    desc.layers = draws.largestBatch() + 1;  // and the clear one
    desc.viewType = VK_IMAGE_VIEW_TYPE_2D_ARRAY;
    desc.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    desc.debugName = "shadow page layers";
    layers_ = vk::Image(context, desc);
    const VkImageView view = layers_.view();
    framebuffer_ = vk::createFramebuffer(context.device(), renderPass, {&view, 1}, kSlot, kSlot, desc.layers);
}

void ShadowPageLayers::record(VkCommandBuffer cmd, const ShadowPageDraws& draws, const ShadowPageAllocation& pool,
                              const vk::Image& atlas,
                              const std::function<void(const ShadowPageDraws::Batch&)>& drawBatch) const {
    auto slotOrigin = [&](uint32_t slot) {
        return gpu::virtualShadowSlotOrigin(slot, pool.squares, pool.besideAcross, pool.belowAcross);
    };
    const uint32_t clearLayer = layers_.desc().layers - 1;
    const VkClearValue clear{.depthStencil = {1.0f, 0}};
    for (size_t b = 0; b < draws.batches.size(); ++b) {
        const ShadowPageDraws::Batch& batch = draws.batches[b];
        // The last batch's copies read the layers before this batch clears them.
        vk::imageBarrier(cmd, layers_, VK_IMAGE_LAYOUT_UNDEFINED, kDrawLayout, VK_PIPELINE_STAGE_TRANSFER_BIT, 0,
                         VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
                         VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);
        vk::beginRenderPass(cmd, renderPass_, framebuffer_, kSlot, kSlot, {&clear, 1});
        drawBatch(batch);
        vkCmdEndRenderPass(cmd);
        vk::imageBarrier(cmd, layers_, kDrawLayout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                         VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT, VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                         VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
        std::vector<VkImageCopy> copies;
        for (uint32_t layer = 0; layer < batch.slots.size(); ++layer) {
            copies.push_back(layerToSlot(layer, slotOrigin(batch.slots[layer])));
        }
        if (b == 0) copies.push_back(layerToSlot(clearLayer, slotOrigin(pool.litSlot())));
        if (!copies.empty()) {
            vkCmdCopyImage(cmd, layers_.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, atlas.handle(),
                           VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, uint32_t(copies.size()), copies.data());
        }
    }
}

}  // namespace punctual::render
