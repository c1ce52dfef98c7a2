#include "render/light_culling_pass.h"

#include <algorithm>
#include <array>
#include <span>

#include "core/check.h"
#include "gpu_types.h"
#include "render/frame_bindings.h"
#include "render/render_settings.h"
#include "shaders/compute_cluster_culling_comp_spv.h"
#include "shaders/compute_coarse_culling_comp_spv.h"
#include "shaders/compute_depth_range_comp_spv.h"
#include "shaders/compute_light_culling_comp_spv.h"
#include "shaders/compute_tile_culling_comp_spv.h"
#include "vk/context.h"
#include "vk/image.h"
#include "vk/pipeline.h"

namespace punctual::render {

LightGridLayout LightGridLayout::forMethod(const LightListMethodInfo& method, uint32_t width, uint32_t height,
                                           uint32_t tileSize, uint32_t clusterSlices, bool coarse, uint32_t threads,
                                           bool subgroupArithmetic) {
    LightGridLayout layout;
    layout.tileSize = tileSize;
    layout.tilesX = (width + tileSize - 1) / tileSize;
    layout.tilesY = (height + tileSize - 1) / tileSize;
    layout.slices = method.depthSlices ? clusterSlices : 1u;
    layout.cullFlags = method.cullFlags;
    layout.zBins = method.zBins();
    const uint32_t perCoarseTile = kCoarseTilePixels / tileSize;
    layout.coarseTiles = coarse && method.usesLightGrid() && perCoarseTile >= 2 ? perCoarseTile : 0u;
    // One subgroup a tile: subgroup sizes are powers of two (the Vulkan specification); one above
    // the cap is cut to it (the workgroup is then part of a subgroup), one under 4 raised to it (the
    // kernels write each three mask words with one invocation each).
    const bool powerOfTwo = threads != 0 && (threads & (threads - 1)) == 0;
    layout.tileThreads = powerOfTwo ? std::clamp<uint32_t>(threads, 4, PUNCTUAL_MAX_TILE_THREADS) : PUNCTUAL_MAX_TILE_THREADS;
    // A one-subgroup kernel culls where it implements every flag of the method (culling.h); the
    // general kernel implements them all.
    const uint32_t subgroupKernelFlags =
        layout.slices > 1 ? PUNCTUAL_CLUSTER_KERNEL_CULL_FLAGS : PUNCTUAL_TILE_KERNEL_CULL_FLAGS;
    layout.subgroupKernel = subgroupArithmetic && (layout.cullFlags & ~subgroupKernelFlags) == 0;
    return layout;
}

LightCullingPass::LightCullingPass(vk::Context& context, const LightGridLayout& layout, bool culled, uint32_t width,
                                   uint32_t height, const std::vector<gpu::CullLight>& cullLights, const ZBins* zBins)
    : layout_(layout),
      culled_(culled),
      width_(width),
      height_(height),
      grid_(context, VkDeviceSize(culled ? layout.gridBufferWords() : 1) * sizeof(uint32_t),
            VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
            vk::MemoryUse::DeviceLocal, "light grid"),
      // The counter and one word: the counting frame's lists all overflow (sizeIndexLists).
      lightIndices_(indexListBuffer(context, culled && layout.indexLists ? 1 : 0)),
      depthRange_(context, sizeof(gpu::GpuDepthRange) + sizeof(uint32_t) * PUNCTUAL_MAX_CLUSTER_SLICES * layout.gridWords,
                  VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                      VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                  vk::MemoryUse::DeviceLocal, "depth range"),
      // Sized to the lights this frame really uses; one slot when there are none.
      cullLights_(context, std::max<size_t>(cullLights.size(), 1) * sizeof(gpu::CullLight),
                  VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUse::Upload, "cull lights"),
      zBins_(context, zBins ? zBins->bytes(layout.indexLists) : sizeof(uint32_t),
             VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT, vk::MemoryUse::Upload, "z-bins"),
      coarseGrid_(context,
                  VkDeviceSize(culled && layout.coarseTiles ? layout.coarseTilesX() * layout.coarseTilesY() * layout.gridWords
                                                            : 1) *
                      sizeof(uint32_t),
                  VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT, vk::MemoryUse::DeviceLocal,
                  "coarse light grid") {
    if (!cullLights.empty()) cullLights_.write(cullLights.data(), cullLights.size() * sizeof(gpu::CullLight));
    if (zBins) {
        zBins_.write(&zBins->gpu, sizeof(gpu::GpuZBins));
        // Masks: each bin's mask, ANDed with the cell's; index lists: each light's rank in depth
        // order, tested against the bin's range (lights/z_bins.h).
        const std::vector<uint32_t>& words = layout.indexLists ? zBins->rankWords : zBins->binMasks;
        zBins_.write(words.data(), words.size() * sizeof(uint32_t), sizeof(gpu::GpuZBins));
    }
    // Cells no pixel occupies are never written, and no pixel the frame shades reads one. Zeroed
    // once all the same, so that a study that breaks that rule on purpose (culling by the opaque
    // depth alone, RenderSettings::opaqueCullingDepth) reads "no lights", the same every run,
    // rather than whatever the allocation held.
    // (Index lists: every header "no lights".)
    const uint32_t empty = layout.indexLists ? PUNCTUAL_LIGHT_LIST_NONE : 0u;
    context.submitAndWait([&](VkCommandBuffer cmd) { vkCmdFillBuffer(cmd, grid_.handle(), 0, VK_WHOLE_SIZE, empty); });
}

vk::Buffer LightCullingPass::indexListBuffer(vk::Context& context, uint64_t words) {
    return vk::Buffer(context, VkDeviceSize(1 + std::max<uint64_t>(words, 1)) * sizeof(uint32_t),
                      VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                          VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                      vk::MemoryUse::DeviceLocal, "light indices");
}

void LightCullingPass::sizeIndexLists(vk::Context& context, uint64_t words) {
    PUNCTUAL_CHECK(layout_.indexLists, "index lists sized for a grid of masks");
    lightIndices_ = indexListBuffer(context, words);
}

void LightCullingPass::addBindings(BindingTable& table) const {
    table.addBuffer(PUNCTUAL_BINDING_LIGHT_GRID, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kAllStages, grid_);
    table.addBuffer(PUNCTUAL_BINDING_DEPTH_RANGE, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kAllStages, depthRange_);
    table.addBuffer(PUNCTUAL_BINDING_CULL_LIGHTS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT,
                    cullLights_);
    table.addBuffer(PUNCTUAL_BINDING_ZBINS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kAllStages, zBins_);
    table.addBuffer(PUNCTUAL_BINDING_COARSE_GRID, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT,
                    coarseGrid_);
    table.addBuffer(PUNCTUAL_BINDING_LIGHT_INDICES, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kAllStages, lightIndices_);
}

uint64_t LightCullingPass::memoryBytes() const {
    return grid_.size() + lightIndices_.size() + depthRange_.size() + cullLights_.size() + zBins_.size() +
           coarseGrid_.size();
}

void LightCullingPass::createPipelines(const vk::Context& context, const FrameBindings& bindings) {
    if (!culled_) return;
    // One map for every kernel: an entry whose constant a shader lacks does not affect it (the
    // Vulkan specification), and tile_culling.comp lacks SLICE_COUNT, cluster_culling.comp
    // CULL_FLAGS (it implements none).
    const std::array<uint32_t, 7> values = {layout_.tileSize,    layout_.slices,      layout_.cullFlags,
                                            layout_.coarseTiles, layout_.tileThreads, layout_.gridWords,
                                            layout_.listForm()};
    const std::array<VkSpecializationMapEntry, 7> entries = {{
        {PUNCTUAL_SPEC_TILE_SIZE, 0, sizeof(uint32_t)},
        {PUNCTUAL_SPEC_SLICE_COUNT, sizeof(uint32_t), sizeof(uint32_t)},
        {PUNCTUAL_SPEC_CULL_FLAGS, 2 * sizeof(uint32_t), sizeof(uint32_t)},
        {PUNCTUAL_SPEC_COARSE_TILES, 3 * sizeof(uint32_t), sizeof(uint32_t)},
        {PUNCTUAL_SPEC_TILE_THREADS, 4 * sizeof(uint32_t), sizeof(uint32_t)},
        {PUNCTUAL_SPEC_GRID_WORDS, 5 * sizeof(uint32_t), sizeof(uint32_t)},
        {PUNCTUAL_SPEC_LIGHT_LIST_FORM, 6 * sizeof(uint32_t), sizeof(uint32_t)},
    }};
    const VkSpecializationInfo specialization{uint32_t(entries.size()), entries.data(), sizeof(values), values.data()};
    const std::span<const uint32_t> kernel = !layout_.subgroupKernel ? std::span<const uint32_t>(compute_light_culling_comp_spv)
                                             : layout_.slices > 1      ? std::span<const uint32_t>(compute_cluster_culling_comp_spv)
                                                                       : std::span<const uint32_t>(compute_tile_culling_comp_spv);
    cullingPipeline_ = context.objects().computePipeline(bindings.pipelineLayout(), kernel, &specialization);
    if (layout_.coarseTiles) {
        // The coarse kernel reads the tile size, the coarse-tile side, its workgroup size and the
        // grid's words.
        const std::array<VkSpecializationMapEntry, 4> coarseEntries = {{
            {PUNCTUAL_SPEC_TILE_SIZE, 0, sizeof(uint32_t)},
            {PUNCTUAL_SPEC_COARSE_TILES, 3 * sizeof(uint32_t), sizeof(uint32_t)},
            {PUNCTUAL_SPEC_TILE_THREADS, 4 * sizeof(uint32_t), sizeof(uint32_t)},
            {PUNCTUAL_SPEC_GRID_WORDS, 5 * sizeof(uint32_t), sizeof(uint32_t)},
        }};
        const VkSpecializationInfo coarseSpecialization{uint32_t(coarseEntries.size()), coarseEntries.data(),
                                                        sizeof(values), values.data()};
        coarsePipeline_ = context.objects().computePipeline(bindings.pipelineLayout(),
                                                    compute_coarse_culling_comp_spv, &coarseSpecialization);
    }
    if (layout_.slices > 1) {
        // The range pass's last subgroup also cuts the slices: it reads the slice count and the
        // grid's words (each slice's lights).
        const std::array<VkSpecializationMapEntry, 2> sliceEntries = {{
            {PUNCTUAL_SPEC_SLICE_COUNT, sizeof(uint32_t), sizeof(uint32_t)},
            {PUNCTUAL_SPEC_GRID_WORDS, 5 * sizeof(uint32_t), sizeof(uint32_t)},
        }};
        const VkSpecializationInfo sliceSpecialization{uint32_t(sliceEntries.size()), sliceEntries.data(),
                                                       sizeof(values), values.data()};
        depthRangePipeline_ = context.objects().computePipeline(bindings.pipelineLayout(),
                                                        compute_depth_range_comp_spv, &sliceSpecialization);
    }
}

void LightCullingPass::record(const FrameContext& frame) const {
    if (!culled_) return;
    const VkCommandBuffer cmd = frame.cmd;
    frame.bindings.bind(cmd, VK_PIPELINE_BIND_POINT_COMPUTE);
    // Start from an empty range: min = all ones, max = 0, and no subgroup of the range pass
    // finished (each fill writes one repeated word). Tiled culling never reads it, but it stays
    // defined.
    vkCmdFillBuffer(cmd, depthRange_.handle(), 0, sizeof(uint32_t), 0xFFFFFFFFu);
    vkCmdFillBuffer(cmd, depthRange_.handle(), sizeof(uint32_t), 3 * sizeof(uint32_t), 0u);
    // Index lists: no word used yet.
    if (layout_.indexLists) vkCmdFillBuffer(cmd, lightIndices_.handle(), 0, sizeof(uint32_t), 0u);
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                      VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
    // The depth range (with the slices its last subgroup cuts) and the coarse pass read nothing of
    // each other's: one barrier after both, so that a GPU may run them side by side (on the H200
    // they took 9.1 and 7.6 us one after the other, bench/RESULTS.md).
    if (depthRangePipeline_) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, depthRangePipeline_);
        // One invocation a square of PUNCTUAL_DEPTH_RANGE_SIDE pixels, a row of workgroups a row of squares.
        const uint32_t squaresAcross = (width_ + PUNCTUAL_DEPTH_RANGE_SIDE - 1) / PUNCTUAL_DEPTH_RANGE_SIDE;
        vkCmdDispatch(cmd, (squaresAcross + PUNCTUAL_DEPTH_RANGE_THREADS - 1) / PUNCTUAL_DEPTH_RANGE_THREADS,
                      (height_ + PUNCTUAL_DEPTH_RANGE_SIDE - 1) / PUNCTUAL_DEPTH_RANGE_SIDE, 1);
    }
    if (coarsePipeline_) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, coarsePipeline_);
        vkCmdDispatch(cmd, layout_.coarseTilesX(), layout_.coarseTilesY(), 1);
    }
    if (depthRangePipeline_ || coarsePipeline_) {
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
