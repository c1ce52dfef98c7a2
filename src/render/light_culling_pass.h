#pragma once
// Tiled and clustered light culling (compute). Tiled: one workgroup per tile tests every light
// against the tile's depth extent. Clustered: a depth-range pass first finds the frame's nearest
// and farthest geometry, then the same kernel splits each tile into logarithmic depth slices
// fitted to that range. The light grid holds PUNCTUAL_GRID_WORDS words per cell and is sized to
// the frame's real tile count (times the slices for clustered).
#include <cstdint>

#include <vulkan/vulkan.h>

#include "vk/buffer.h"
#include "vk/handle.h"

namespace punctual::vk {
class Context;
}

namespace punctual::render {

class FrameBindings;

struct LightGridLayout {
    uint32_t tileSize = 16;
    uint32_t tilesX = 0;
    uint32_t tilesY = 0;
    uint32_t slices = 1;  // 1: tiled

    uint32_t cellCount() const { return tilesX * tilesY * slices; }
    static LightGridLayout forFrame(uint32_t width, uint32_t height, uint32_t tileSize, uint32_t slices);
};

// The grid and depth-range buffers live outside the pass so the frame's descriptor set can be
// built before the pipelines.
struct LightGridBuffers {
    LightGridBuffers(const vk::Context& context, const LightGridLayout& layout, bool culled);
    vk::Buffer grid;        // cellCount * PUNCTUAL_GRID_WORDS words (one word when not culled)
    vk::Buffer depthRange;  // gpu::GpuDepthRange
};

class LightCullingPass {
public:
    LightCullingPass(const vk::Context& context, const FrameBindings& bindings, const LightGridLayout& layout,
                     uint32_t width, uint32_t height);
    // Records the depth-range pass (clustered only) and the culling kernel, with the barriers
    // that make the grid visible to the forward pass's fragment shader.
    void record(VkCommandBuffer cmd, const FrameBindings& bindings, const LightGridBuffers& buffers) const;

private:
    LightGridLayout layout_;
    uint32_t width_ = 0;
    uint32_t height_ = 0;
    vk::Handle<VkPipeline> depthRangePipeline_;        // clustered: nearest/farthest geometry
    vk::Handle<VkPipeline> sliceBoundariesPipeline_;   // clustered: slice start depths
    vk::Handle<VkPipeline> cullingPipeline_;
};

}  // namespace punctual::render
