#include "render/light_culling_pass.h"

#include <array>

#include "core/error.h"
#include "gpu_types.h"
#include "render/frame_bindings.h"
#include "shaders/compute_cluster_slices_comp_spv.h"
#include "shaders/compute_depth_range_comp_spv.h"
#include "shaders/compute_light_culling_comp_spv.h"
#include "vk/context.h"
#include "vk/image.h"
#include "vk/pipeline.h"

namespace punctual::render {

namespace {
constexpr uint32_t kDepthRangeGroup = 32;  // pixels a side covered by one depth_range.comp group
}

LightGridLayout LightGridLayout::forFrame(uint32_t width, uint32_t height, uint32_t tileSize, uint32_t slices) {
    LightGridLayout layout;
    layout.tileSize = tileSize;
    layout.tilesX = (width + tileSize - 1) / tileSize;
    layout.tilesY = (height + tileSize - 1) / tileSize;
    layout.slices = slices;
    return layout;
}

LightGridBuffers::LightGridBuffers(const vk::Context& context, const LightGridLayout& layout, bool culled)
    : grid(context, VkDeviceSize(culled ? layout.cellCount() * PUNCTUAL_GRID_WORDS : 1) * sizeof(uint32_t),
           VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT, vk::MemoryUse::DeviceLocal,
           "light grid"),
      depthRange(context, sizeof(gpu::GpuDepthRange),
                 VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                     VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                 vk::MemoryUse::DeviceLocal, "depth range") {}

LightCullingPass::LightCullingPass(const vk::Context& context, const FrameBindings& bindings,
                                   const LightGridLayout& layout, uint32_t width, uint32_t height)
    : layout_(layout), width_(width), height_(height) {
    if (layout.slices < 1 || layout.slices > PUNCTUAL_MAX_CLUSTER_SLICES) {
        throw Error("--slices", "must be from 1 to " + std::to_string(PUNCTUAL_MAX_CLUSTER_SLICES));
    }
    const std::array<uint32_t, 2> values = {layout.tileSize, layout.slices};
    const std::array<VkSpecializationMapEntry, 2> entries = {{
        {PUNCTUAL_SPEC_TILE_SIZE, 0, sizeof(uint32_t)},
        {PUNCTUAL_SPEC_SLICE_COUNT, sizeof(uint32_t), sizeof(uint32_t)},
    }};
    const VkSpecializationInfo specialization{uint32_t(entries.size()), entries.data(), sizeof(values), values.data()};
    cullingPipeline_ = vk::createComputePipeline(context.device(), bindings.pipelineLayout(),
                                                 compute_light_culling_comp_spv, &specialization);
    if (layout.slices > 1) {
        depthRangePipeline_ =
            vk::createComputePipeline(context.device(), bindings.pipelineLayout(), compute_depth_range_comp_spv);
        const VkSpecializationMapEntry sliceEntry{PUNCTUAL_SPEC_SLICE_COUNT, 0, sizeof(uint32_t)};
        const VkSpecializationInfo sliceSpecialization{1, &sliceEntry, sizeof(uint32_t), &layout.slices};
        sliceBoundariesPipeline_ = vk::createComputePipeline(context.device(), bindings.pipelineLayout(),
                                                             compute_cluster_slices_comp_spv, &sliceSpecialization);
    }
}

void LightCullingPass::record(VkCommandBuffer cmd, const FrameBindings& bindings,
                              const LightGridBuffers& buffers) const {
    bindings.bind(cmd, VK_PIPELINE_BIND_POINT_COMPUTE);
    // Start from an empty range: min = all ones, max = 0 (each fill writes one repeated word).
    // Tiled culling never reads it, but it stays defined.
    vkCmdFillBuffer(cmd, buffers.depthRange.handle(), 0, sizeof(uint32_t), 0xFFFFFFFFu);
    vkCmdFillBuffer(cmd, buffers.depthRange.handle(), sizeof(uint32_t), sizeof(uint32_t), 0u);
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                      VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
    if (depthRangePipeline_) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, depthRangePipeline_);
        vkCmdDispatch(cmd, (width_ + kDepthRangeGroup - 1) / kDepthRangeGroup,
                      (height_ + kDepthRangeGroup - 1) / kDepthRangeGroup, 1);
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                          VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, sliceBoundariesPipeline_);
        vkCmdDispatch(cmd, 1, 1, 1);
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                          VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
    }
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, cullingPipeline_);
    vkCmdDispatch(cmd, layout_.tilesX, layout_.tilesY, 1);
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                      VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                      VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT);
}

}  // namespace punctual::render
