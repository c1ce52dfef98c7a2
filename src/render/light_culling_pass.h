#pragma once
// Tiled and clustered light culling (compute). With the coarse pass on, one workgroup per big tile
// first culls the lights to its frustum column (coarse_culling.comp), and the kernels below start
// from those. Tiled: one workgroup per tile tests every light against the tile's depth extent
// (zbin: the same, its z-bins uploaded here for the forward pass; zbin-2d: against the tile at every
// depth, the bins holding depth), one subgroup a tile (tile_culling.comp) where the device has
// compute subgroup arithmetic, else through shared memory (light_culling.comp). Both kernels run
// one subgroup a tile (LightGridLayout::tileThreads). tiled-2.5d: the same kernels, also against
// the tile's depth mask. Clustered: a depth-range pass (depth_range.comp) first finds the frame's
// nearest and farthest geometry, and its last subgroup fits logarithmic depth slices to that range
// (and lists each slice's lights by depth); then cluster_culling.comp (one subgroup a tile, where
// the device allows; else light_culling.comp) culls each tile's occupied slices. The range and
// coarse passes run side by side, behind one barrier. The light grid holds gridWords words per cell
// (one bit per light the frame keeps), or with index lists one header word per cell and an index
// array as long as the frame's lists (culling.h), and is sized to the frame's real tile count
// (times the slices for clustered).
#include <cstdint>
#include <vector>

#include <vulkan/vulkan.h>

#include "culling.h"
#include "lights/z_bins.h"
#include "render/light_list_method.h"
#include "render/pass.h"
#include "vk/buffer.h"
#include "vk/handle.h"

namespace punctual::render {

struct LightGridLayout {
    uint32_t tileSize = 16;
    uint32_t tilesX = 0;
    uint32_t tilesY = 0;
    uint32_t slices = 1;  // 1: tiled
    uint32_t gridWords = 3;  // words a cell: gpu::gridWordsOf(the frame's lights); the kernels' GRID_WORDS
    // --light-lists indices: a cell is one header word, its lights a list in the index array
    // (culling.h, "Index lists"); otherwise gridWords mask words.
    bool indexLists = false;
    uint32_t cullFlags = 0;  // the method's PUNCTUAL_CULL_* flags (culling.h): tiled-2.5d's depth mask, ...
    bool zBins = false;      // zbin, zbin-2d: the forward pass ANDs the tile's mask with its z-bin's
    uint32_t coarseTiles = 0;  // fine tiles a side of a coarse tile; 0: no coarse pass
    // Invocations per tile of the culling kernel: the device's compute subgroup size, at least 4
    // and at most PUNCTUAL_MAX_TILE_THREADS (one subgroup a tile where the device's size fits).
    uint32_t tileThreads = 64;
    // Whether a one-subgroup kernel culls, where the device has compute subgroup arithmetic and
    // RenderSettings::subgroupTiles is on: tile_culling.comp for the methods with one depth extent
    // per tile (tiled, tiled-2.5d, zbin, zbin-2d), cluster_culling.comp for clustered, where the
    // kernel implements every culling flag of the method. Otherwise light_culling.comp, with
    // shared memory.
    bool subgroupKernel = false;
    uint32_t cellCount() const { return tilesX * tilesY * slices; }
    uint64_t gridWordCount() const { return uint64_t(cellCount()) * gridWords; }  // the masks' words
    uint64_t gridBufferWords() const { return indexLists ? cellCount() : gridWordCount(); }  // masks or headers
    uint32_t listForm() const { return indexLists ? PUNCTUAL_LIGHT_LIST_INDICES : PUNCTUAL_LIGHT_LIST_MASKS; }
    bool hasCullFlag(uint32_t flag) const { return (cullFlags & flag) != 0; }
    uint32_t coarseTilesX() const { return coarseTiles ? (tilesX + coarseTiles - 1) / coarseTiles : 0; }
    uint32_t coarseTilesY() const { return coarseTiles ? (tilesY + coarseTiles - 1) / coarseTiles : 0; }
    // The grid `method` culls to: `clusterSlices` depth slices where it has them (clustered), one
    // otherwise; its culling flags (the kernels' specialization constant) and z-bins;
    // with `coarse`, kCoarseTilePixels / tileSize fine tiles a side per coarse tile where that is
    // at least two. `threads`: invocations per tile (the device's subgroup size; a size that is not
    // a power of two, never a Vulkan one, gets 64); `subgroupArithmetic`: whether the one-subgroup
    // kernels (tile_culling.comp, cluster_culling.comp) may cull.
    static LightGridLayout forMethod(const LightListMethodInfo& method, uint32_t width, uint32_t height,
                                     uint32_t tileSize, uint32_t clusterSlices, bool coarse, uint32_t threads,
                                     bool subgroupArithmetic);
};

class LightCullingPass final : public Pass {
public:
    // `culled`: whether the frame's method reads the light grid (tiled, clustered). Otherwise the
    // pass records nothing and its buffers are one-word placeholders (a descriptor cannot point at
    // nothing). `cullLights` are the frame's lights in view space (gpu::makeCullLight), made once
    // on the CPU rather than by every workgroup.
    // `zBins`: the z-bin method's bins (uploaded for the forward pass), null for other methods.
    LightCullingPass(vk::Context& context, const LightGridLayout& layout, bool culled, uint32_t width, uint32_t height,
                     const std::vector<gpu::CullLight>& cullLights, const ZBins* zBins);

    const char* name() const override { return "culling"; }
    void addBindings(BindingTable& table) const override;
    void createPipelines(const vk::Context& context, const FrameBindings& bindings) override;
    bool timed() const override { return culled_; }
    // Records the depth-range pass (clustered only) and the culling kernel, with the barriers
    // that make the grid visible to the forward pass's fragment shader.
    void record(const FrameContext& frame) const override;
    uint64_t memoryBytes() const override;
    MemoryKind memoryKind() const override { return MemoryKind::LightGrid; }
    // The kernels sample the prepass's depth.
    VkShaderStageFlags boundImageStages() const override { return culled_ ? VK_SHADER_STAGE_COMPUTE_BIT : 0; }

    const vk::Buffer& grid() const { return grid_; }              // gridBufferWords() words
    // Index lists: the words used (the kernels' counter), then the lists (culling.h).
    const vk::Buffer& lightIndices() const { return lightIndices_; }
    // Index lists: makes the index array `words` words long (the lists a counting frame used), for
    // the next frames; the caller rebuilds the frame's bindings, which hold the old buffer.
    void sizeIndexLists(vk::Context& context, uint64_t words);
    // The light lists' own memory: the grid (masks, or headers) and the index array.
    uint64_t listBytes() const { return grid_.size() + (layout_.indexLists ? lightIndices_.size() : 0); }
    // gpu::GpuDepthRange, then PUNCTUAL_MAX_CLUSTER_SLICES x gridWords words: each slice's lights
    const vk::Buffer& depthRange() const { return depthRange_; }
    const vk::Buffer& coarseGrid() const { return coarseGrid_; }  // the coarse pass's masks

private:
    // The index array: the words-used counter, then `words` words (at least one).
    static vk::Buffer indexListBuffer(vk::Context& context, uint64_t words);

    LightGridLayout layout_;
    bool culled_ = false;
    uint32_t width_ = 0;
    uint32_t height_ = 0;
    vk::Buffer grid_;
    vk::Buffer lightIndices_;  // index lists: the words-used counter and the lists; one word with masks
    vk::Buffer depthRange_;
    vk::Buffer cullLights_;
    vk::Buffer zBins_;  // gpu::GpuZBins and the bins' masks, or one word for the methods without bins
    vk::Buffer coarseGrid_;  // coarse tiles x gridWords words, or one word without the coarse pass
    // The pipelines: the context's object cache (vk/object_cache.h) owns them.
    VkPipeline cullingPipeline_ = VK_NULL_HANDLE;     // tile_, cluster_ or light_culling.comp
    VkPipeline coarsePipeline_ = VK_NULL_HANDLE;      // the coarse pass (coarse_culling.comp)
    VkPipeline depthRangePipeline_ = VK_NULL_HANDLE;  // clustered: nearest/farthest geometry, then the slices
};

}  // namespace punctual::render
