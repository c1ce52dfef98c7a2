#pragma once
// The raster shadow stage: renders every shadow view of the plan with casters into its square of
// the atlas, or its face of the cube array (ShadowMaps), and binds them, with the views'
// records, for the forward pass. Each cube face is its own target. A view without casters or
// storage draws nothing (the shader never reads it).
//
// An atlas view is drawn at the origin of the drawing square (an image of the largest view's
// side, at most 1024 texels; a larger view is drawn tile by tile: lights/shadow_drawing_tiles.h)
// and copied into its square. Where a view lies then does not change one bit of its depth:
// the rasterizer evaluates coverage and depth from window coordinates, in floating point, and a
// square elsewhere rounds them otherwise (lavapipe evaluates each depth plane from the
// framebuffer's origin). So the shadow cache's atlas, which places views where they were last
// frame, gives the frames of the frame's own packing bit for bit (render/shadow_cache.h), and a
// packer's change moves squares without changing images. The cost: one copy of each drawn view's
// texels and the drawing square's memory; and on a GPU the copy waits for its draw and the next
// draw for the copy (one square; more squares in turn would overlap them, for their memory).
//
// Virtual pages (--shadow-res virtual): the atlas holds the cascades' squares and, below them,
// the page pool. Each caster is drawn once per view, instanced over the allocated pages its
// bounds meet (shadowPageDraws); each instance maps the page's square of the view onto a layer of
// its own, which is copied into its slot (render/shadow_page_layers.h, shadow_page_draw.glsl). Not one
// draw per page with its own viewport: that is a draw per (page, caster), 23,000 on the hall,
// and lavapipe spends about 50 us on a draw whatever it holds (1.2 s). Not atomics into an R32
// pool either: the pages stay D16 depth targets that the same filters read (R32 would double the
// memory), drawn by the same fixed-function depth test.
#include <cstdint>
#include <optional>
#include <vector>

#include <vulkan/vulkan.h>

#include "lights/shadow_drawing_tiles.h"
#include "lights/shadow_page_allocation.h"
#include "lights/shadow_setup.h"
#include "render/pass.h"
#include "render/shadow_cache.h"
#include "render/shadow_maps.h"
#include "render/shadow_page_layers.h"
#include "vk/buffer.h"
#include "vk/handle.h"
#include "vk/image.h"

namespace punctual::render {

class ShadowPass final : public Pass {
public:
    // `plan` must outlive the pass; `scene` is the plan's (its casters' bounds place them in the
    // drawing tiles). With `cache` (prepared with `plan`; it outlives the pass too), the views draw
    // into the cache's maps, and those it keeps are neither cleared nor drawn.
    ShadowPass(const vk::Context& context, const ShadowPlan& plan, const Scene& scene, const ShadowSettings& settings,
               const ShadowCache* cache = nullptr);

    const char* name() const override { return "shadows"; }
    void addBindings(BindingTable& table) const override;
    void createPipelines(const vk::Context& context, const FrameBindings& bindings) override;
    // With no shadowed light the stage only moves the placeholder maps into their layout: not a
    // pass worth timing.
    bool timed() const override { return !plan_.views.empty(); }
    // Renders every view with casters, each atlas view over a cleared square and every cube face
    // cleared (the cube's hardware filtering reads across face edges), and leaves both images in
    // kReadLayout for the forward pass. The atlas's texels outside the drawn squares are never read
    // (the lookups clamp to the view's square), so they are not cleared.
    void record(const FrameContext& frame) const override;
    uint64_t memoryBytes() const override;

    // Virtual pages: the records the marking pass reads before any page is allocated (each view's
    // marks and coarsening; every lookup lit).
    // Each view's previous marks (hysteresis, plan.virtualReads) are added here.
    void setUnallocatedPages(std::vector<gpu::GpuVirtualShadowView> views);
    // Virtual pages: `plan` (the one the pass was made with) now holds the pool in its atlas
    // (placeShadowPagePool); makes the maps anew, uploads the page table and draws each page with
    // its casters (shadowPageCasters). The caller binds the frame's set again and re-records.
    void usePages(const vk::Context& context, const ShadowPageAllocation& allocation, ShadowPageDraws draws);
    // What the pages' draws take: draws (one per view and caster) and instances (one per page and caster).
    uint64_t pageDraws() const { return pageDraws_.draws.size(); }
    uint64_t pageInstances() const { return pageDraws_.instances.size(); }
    // Pages with at least one caster drawn into them (the others stay cleared: lit).
    uint64_t pagesDrawn() const { return pageDraws_.pagesWithCasters; }
    const std::vector<ShadowPageDraws::Draw>& pageDrawList() const { return pageDraws_.draws; }
    // The tiles plan view `index` is drawn in (lights/shadow_drawing_tiles.h): an atlas view's in the
    // drawing square, a cube face's one tile of all its casters; none for virtual pages' views and
    // views not rendered.
    const std::vector<DrawingTile>& tilesOf(uint32_t index) const { return drawingTiles_.at(index); }
    MemoryKind memoryKind() const override { return MemoryKind::Shadows; }
    std::vector<ImageUse> imageUses() const override;

    // The maps' layout while the stage draws them, and the one it leaves them in (and set 0 reads).
    static constexpr VkImageLayout kDrawLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
    static constexpr VkImageLayout kReadLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;

    const ShadowMaps& maps() const { return cache_ ? cache_->maps() : *ownMaps_; }

private:
    struct Target {
        vk::Handle<VkImageView> view;
        vk::Handle<VkFramebuffer> framebuffer;
        uint32_t width = 0;
        uint32_t height = 0;
        std::vector<uint32_t> planViews;  // indices into plan_.views drawn into it
    };
    // Draws `casters` (objects) through `viewProjection` with `view`'s pipelines.
    void drawView(const FrameContext& frame, const ShadowView& view, const glm::mat4& viewProjection,
                  const std::vector<uint32_t>& casters) const;
    void drawPages(const FrameContext& frame, const ShadowPageDraws::Batch& batch) const;
    // Whether `object` casts through the masked pipeline (alpha-tested), the opaque one, or none
    // (a transparent caster with --transparent-shadows off).
    std::optional<bool> casterIsMasked(const FrameContext& frame, uint32_t object) const;
    void createTargets(const vk::Context& context);
    void uploadViews();  // every plan view's GpuShadowView into views_
    // The atlas's views: virtual pages drawn in one render pass over the cleared atlas, then each
    // view the cache does not keep drawn into the drawing square and copied into its square. Leaves
    // the atlas in TRANSFER_DST_OPTIMAL.
    void recordAtlas(const FrameContext& frame, const Target& atlas) const;
    // Draws plan view `index` at the drawing square's origin, tile by tile, each copied into its
    // place in the view's atlas square.
    void recordAtlasView(const FrameContext& frame, uint32_t index) const;
    // Draws `tile` of plan view `index` into the drawing square (over the static depth the cache
    // keeps, in mixed caching) and copies it into the atlas.
    void recordDrawingTile(const FrameContext& frame, uint32_t index, const DrawingTile& tile) const;
    // Draws `casters` of the tile of `view` at `origin` (its texel in the view) into the drawing
    // square, through `renderPass` (renderPass_ clears, loadingRenderPass_ draws over the square).
    void drawIntoSquare(const FrameContext& frame, const ShadowView& view, const glm::uvec2& origin,
                        const std::vector<uint32_t>& casters, VkRenderPass renderPass) const;
    // Mixed caching (render/shadow_cache.h): `tile`'s static casters drawn and stored in the static
    // atlas (`storeStatic`) or their stored depth copied back, then its dynamic casters drawn over.
    void drawOverStaticDepth(const FrameContext& frame, uint32_t index, const DrawingTile& tile, bool storeStatic) const;
    void copySquare(VkCommandBuffer cmd, const vk::Image& image, VkImageLayout imageLayout, const glm::uvec2& texel,
                    uint32_t side, bool intoImage) const;
    // The drawing square's barriers: drawn into to copied from, and copied from (TRANSFER_SRC) or
    // into (TRANSFER_DST) to drawn into.
    void squareDrawnToCopied(VkCommandBuffer cmd) const;
    void squareCopiedToDrawn(VkCommandBuffer cmd, VkImageLayout copyLayout) const;
    // The atlas's layout as the stage begins (a cached atlas's is kept; see ShadowCache).
    VkImageLayout atlasLayoutBefore() const;
    // The drawing square (lights/shadow_drawing_tiles.h; none when the atlas has no view) and each
    // atlas view's tiles.
    void createDrawingSquare(const vk::Context& context, const Scene& scene);
    const ShadowPlan& plan_;
    ShadowSettings settings_;
    const ShadowCache* cache_;
    std::optional<ShadowMaps> ownMaps_;  // without a cache
    vk::Buffer views_;  // GpuShadowView per plan view (one slot when there are none)
    vk::Buffer pageViews_;  // GpuVirtualShadowView per plan view (one slot when there are none)
    vk::Buffer pageTable_;  // the page table's entries (one word when there are none)
    vk::Buffer pageInstances_;  // ShadowPageDraws::instances (one slot when there are none)
    ShadowPageDraws pageDraws_;
    ShadowPageAllocation pagePool_;  // where the slots are (its table left out)
    std::optional<ShadowPageLayers> pageLayers_;  // once pages are allocated
    // The render pass, layout and pipelines: the context's object cache (vk/object_cache.h) owns them.
    VkRenderPass renderPass_ = VK_NULL_HANDLE;         // clears its target to the far plane
    VkRenderPass loadingRenderPass_ = VK_NULL_HANDLE;  // draws over what it holds
    VkPipelineLayout pipelineLayout_ = VK_NULL_HANDLE;
    struct Pipelines {
        VkPipeline opaque = VK_NULL_HANDLE;  // depth only, no fragment shader
        VkPipeline masked = VK_NULL_HANDLE;  // alpha-masked casters (alpha_mask.frag)
    };
    Pipelines pipelines_;
    // The sun's cascades: casters between the sun and a cascade's near plane are pancaked onto it
    // (depth clamp, or the vertex clamp where the device lacks it), never clipped.
    Pipelines cascadePipelines_;
    // Virtual pages' instanced draws (PAGED).
    Pipelines pagePipelines_;
    std::vector<Target> targets_;  // the atlas first (when it has storage), then the cube faces
    std::optional<vk::Image> drawingSquare_;  // where atlas views are drawn (see the top of this file)
    vk::Handle<VkFramebuffer> drawingFramebuffer_;
    std::vector<std::vector<DrawingTile>> drawingTiles_;  // per plan view: its tiles (none without a square)
};

}  // namespace punctual::render
