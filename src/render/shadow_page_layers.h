#pragma once
// Virtual shadow pages drawn where they lie changes nothing (--shadow-res virtual): each page is
// drawn into a layer of its own of a 33 x 33 depth array, at the layer's origin, then copied into
// its slot of the pool (one vkCmdCopyImage with a region a page).
//
// Why not draw each page in its slot: the rasterizer evaluates coverage and depth from window
// coordinates, in floating point (x_window = x_ndc * width / 2 + x_offset, then snapped to the
// sub-pixel grid; lavapipe evaluates each depth plane from the framebuffer's origin), so the same
// page drawn in another slot rounds some edges and depths otherwise. The shadow cache keeps pages
// in the slots they had (lights/shadow_page_pool_cache.h) while the frame's own allocation moves
// them with every page marked before them; both give the same frame, bit for bit, only if a page's
// texels do not depend on its slot. Layers do not enter the rasterizer's arithmetic; the viewport
// (the whole layer) is the same for every page. It is the drawing square of whole views
// (render/shadow_pass.h) made for thousands of small squares drawn by instancing: a layer a page,
// chosen in the vertex shader (gl_Layer), so the draws stay one per (view, caster) a batch.
//
// Batches: pages are drawn batch after batch into the same array, at most kMostLayers - 1 a batch
// (and never more than the device's maxFramebufferLayers and maxImageArrayLayers allow: 2048 on
// lavapipe and desktop GPUs, at least 256 anywhere). The array's last layer is never drawn:
// cleared with the first batch, it is copied into the lit slot (the page every lookup without a
// page reads: the far plane). Memory: 33 x 33 x 2 bytes (d16) a layer, more where the driver pads
// layers (lavapipe: about 4.2 KiB a layer). Measured on the hall at 1280x720 (9,256 pages, one
// frame): batches of 2047 pages take 8.9 MiB and 1,074 draws, of 511 2.2 MiB and 1,126 draws, of
// 127 0.6 MiB and 1,308 draws; the shadow stage's time did not tell them apart within its noise
// (bench/RESULTS.md, "Frames in motion, fifth part"). 512 layers it is.
#include <cstdint>
#include <functional>

#include <glm/glm.hpp>
#include <vulkan/vulkan.h>

#include "lights/shadow_page_allocation.h"
#include "vk/handle.h"
#include "vk/image.h"

namespace punctual::vk {
class Context;
}

namespace punctual::render {

class ShadowPageLayers {
public:
    static constexpr uint32_t kMostLayers = 512;

    // The most pages a batch draws on `context`'s device: its framebuffer and array limits, less
    // the layer kept clear for the lit slot.
    static uint32_t layersPerBatch(const vk::Context& context);

    // An array with a layer for each page of `draws`' largest batch, and the clear one, drawn
    // through `renderPass` (a depth attachment of `format` cleared to the far plane).
    ShadowPageLayers(const vk::Context& context, VkFormat format, VkRenderPass renderPass, const ShadowPageDraws& draws);

    // Each batch of `draws`: the array cleared and `drawBatch(batch)` recorded in the render pass
    // (its viewport the whole layer), then every drawn layer copied into its slot of `atlas`, which
    // must be in TRANSFER_DST_OPTIMAL; the first batch also copies the clear layer into the lit slot.
    // `pool` places the slots (virtualShadowSlotOrigin).
    void record(VkCommandBuffer cmd, const ShadowPageDraws& draws, const ShadowPageAllocation& pool, const vk::Image& atlas,
                const std::function<void(const ShadowPageDraws::Batch&)>& drawBatch) const;

    uint64_t memoryBytes() const { return layers_.allocatedBytes(); }

private:
    vk::Image layers_;
    vk::Handle<VkFramebuffer> framebuffer_;
    VkRenderPass renderPass_;
};

}  // namespace punctual::render
