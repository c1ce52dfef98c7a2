#include "render/shadow_pass.h"

#include <algorithm>
#include <array>
#include <bit>
#include <optional>
#include <utility>

#include "core/check.h"
#include "core/error.h"
#include "gpu_types.h"
#include "render/frame_bindings.h"
#include "render/scene_gpu.h"
#include "shaders/raster_alpha_mask_frag_spv.h"
#include "shaders/raster_shadow_masked_vert_spv.h"
#include "shaders/raster_shadow_paged_masked_vert_spv.h"
#include "shaders/raster_shadow_paged_vert_spv.h"
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

// Every texel a view does not draw: depth 1, the far plane (lit).
constexpr VkClearValue kClearToFar{.depthStencil = {1.0f, 0}};

}  // namespace

ShadowPass::ShadowPass(const vk::Context& context, const ShadowPlan& plan, const Scene& scene,
                       const ShadowSettings& settings, const ShadowCache* cache)
    : plan_(plan),
      settings_(settings),
      cache_(cache),
      views_(context, std::max<size_t>(plan.views.size(), 1) * sizeof(gpu::GpuShadowView),
             VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUse::Upload, "shadow views"),
      pageViews_(context, std::max<size_t>(plan.views.size(), 1) * sizeof(gpu::GpuVirtualShadowView),
                 VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUse::Upload, "shadow page views"),
      pageTable_(context, sizeof(uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUse::Upload,
                 "shadow page table"),
      pageInstances_(context, sizeof(glm::uvec4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUse::Upload,
                     "shadow page instances") {
    if (settings.virtualPages() && settings.enabled && !context.shaderOutputLayer()) {
        throw Error("--shadow-res virtual", "the device (" + context.deviceName() +
                                                ") lacks shaderOutputLayer, which drawing each page into a layer needs");
    }
    if (!cache_) ownMaps_.emplace(context, plan, settings);
    uploadViews();
    // No pages until the renderer allocates them (virtual mode), and none at all otherwise.
    setUnallocatedPages(unallocatedPageViews(ShadowPageMarkLayout::of(plan), {}));
    const uint32_t noEntry = PUNCTUAL_NO_SHADOW_PAGE;
    pageTable_.write(&noEntry, sizeof(noEntry));

    vk::RenderPassDesc passDesc;
    passDesc.depthFormat = ShadowMaps::format(settings.format);
    passDesc.depthLoad = VK_ATTACHMENT_LOAD_OP_CLEAR;
    passDesc.depthInitialLayout = kDrawLayout;
    passDesc.depthFinalLayout = kDrawLayout;
    renderPass_ = context.objects().renderPass(passDesc);
    // Mixed caching draws dynamic casters over static depth copied into the drawing square: the
    // same pass loading it (compatible with renderPass_, so the same pipelines and framebuffer).
    passDesc.depthLoad = VK_ATTACHMENT_LOAD_OP_LOAD;
    loadingRenderPass_ = context.objects().renderPass(passDesc);
    createTargets(context);
    createDrawingSquare(context, scene);
}

void ShadowPass::createDrawingSquare(const vk::Context& context, const Scene& scene) {
    uint32_t side = 0;
    drawingTiles_.assign(plan_.views.size(), {});
    for (uint32_t v = 0; v < plan_.views.size(); ++v) {
        const ShadowView& view = plan_.views[v];
        if (!view.rendered()) continue;
        if (view.rect.size == 0) {  // no square: a cube face (drawn whole into its layer), or virtual pages
            if (view.isPoint && plan_.cubeResolution > 0) drawingTiles_[v] = {DrawingTile{0, 0, view.casters}};
            continue;
        }
        side = std::max(side, drawingTileSide(view.rect.size));
        drawingTiles_[v] = drawingTiles(view, scene);
    }
    if (side == 0) return;
    vk::ImageDesc desc;
    desc.format = ShadowMaps::format(settings_.format);
    desc.width = side;
    desc.height = side;
    desc.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                 VK_IMAGE_USAGE_TRANSFER_DST_BIT;  // (mixed caching copies static depth into it)
    desc.debugName = "shadow drawing square";
    drawingSquare_.emplace(context, desc);
    const VkImageView view = drawingSquare_->view();
    drawingFramebuffer_ = vk::createFramebuffer(context.device(), renderPass_, {&view, 1}, side, side);
}

uint64_t ShadowPass::memoryBytes() const {
    const vk::Image* staticDepth = cache_ ? cache_->staticDepth() : nullptr;
    return maps().allocatedBytes() + (drawingSquare_ ? drawingSquare_->allocatedBytes() : 0) +
           (pageLayers_ ? pageLayers_->memoryBytes() : 0) +
           (staticDepth ? staticDepth->allocatedBytes() : 0) + pageViews_.size() + pageTable_.size();
}

void ShadowPass::createTargets(const vk::Context& context) {
    targets_.clear();
    const VkDevice device = context.device();
    const VkFormat format = ShadowMaps::format(settings_.format);
    const ShadowPlan& plan = plan_;
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
        // The atlas is only copied into (views from the drawing square, pages from their layers):
        // no view or framebuffer of it, whose size the device's framebuffer limits would also bound.
        targets_.push_back(Target{{}, {}, plan.atlas.width, plan.atlas.height, {}});
        Target& atlas = targets_.back();
        for (uint32_t i = 0; i < plan.views.size(); ++i) {
            const ShadowView& view = plan.views[i];
            if (view.rendered() && view.rect.size > 0) atlas.planViews.push_back(i);
        }
    }
    if (plan.cubeResolution > 0) {
        for (uint32_t i = 0; i < plan.views.size(); ++i) {
            const ShadowView& view = plan.views[i];
            if (!view.isPoint) continue;
            Target& face = addTarget(maps().pointCubes(), view.cubeLayer, plan.cubeResolution, plan.cubeResolution);
            if (view.rendered()) face.planViews.push_back(i);
        }
    }
}

void ShadowPass::uploadViews() {
    std::vector<gpu::GpuShadowView> views;
    for (const ShadowView& view : plan_.views) views.push_back(view.gpu);
    if (!views.empty()) views_.write(views.data(), views.size() * sizeof(gpu::GpuShadowView));
}

void ShadowPass::setUnallocatedPages(std::vector<gpu::GpuVirtualShadowView> views) {
    // Hysteresis in a sequence: where each view's previous marks are, and how far it holds a level.
    const VirtualPageReads& reads = plan_.virtualReads;
    for (size_t v = 0; v < views.size() && v < reads.previousFirstWord.size(); ++v) {
        views[v].marks.z = reads.previousFirstWord[v];
        views[v].marks.w = std::bit_cast<uint32_t>(reads.keep);
    }
    if (!views.empty()) pageViews_.write(views.data(), views.size() * sizeof(gpu::GpuVirtualShadowView));
}

void ShadowPass::usePages(const vk::Context& context, const ShadowPageAllocation& allocation, ShadowPageDraws draws) {
    if (!cache_) ownMaps_.emplace(context, plan_, settings_);  // (a cache has made its maps for the pool)
    createTargets(context);
    uploadViews();  // the cascades' squares moved with the grown atlas
    setUnallocatedPages(allocation.views);
    auto upload = [&](const void* data, size_t bytes, const char* name) {
        vk::Buffer buffer(context, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUse::Upload, name);
        buffer.write(data, bytes);
        return buffer;
    };
    const std::vector<uint32_t> table = allocation.table.empty() ? std::vector<uint32_t>{PUNCTUAL_NO_SHADOW_PAGE}
                                                                 : allocation.table;
    pageTable_ = upload(table.data(), table.size() * sizeof(uint32_t), "shadow page table");
    if (!draws.instances.empty()) {
        pageInstances_ = upload(draws.instances.data(), draws.instances.size() * sizeof(glm::uvec4), "shadow page instances");
    }
    pageDraws_ = std::move(draws);
    pagePool_ = allocation;
    pagePool_.table.clear();  // (the pool's place and slots are what recording needs)
    pageLayers_.emplace(context, ShadowMaps::format(settings_.format), renderPass_, pageDraws_);
}

void ShadowPass::addBindings(BindingTable& table) const {
    // The casters' vertex shaders read the views and the instances of the pages they draw.
    table.addBuffer(PUNCTUAL_BINDING_SHADOW_VIEWS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                    VK_SHADER_STAGE_FRAGMENT_BIT | VK_SHADER_STAGE_VERTEX_BIT, views_);
    table.addBuffer(PUNCTUAL_BINDING_SHADOW_PAGE_DRAWS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_VERTEX_BIT,
                    pageInstances_);
    table.addBuffer(PUNCTUAL_BINDING_SHADOW_PAGE_VIEWS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_FRAGMENT_BIT,
                    pageViews_);
    table.addBuffer(PUNCTUAL_BINDING_SHADOW_PAGE_TABLE, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_FRAGMENT_BIT,
                    pageTable_);
    const ShadowMaps& maps = this->maps();
    table.addImage(PUNCTUAL_BINDING_SHADOW_ATLAS_DEPTH, VK_SHADER_STAGE_FRAGMENT_BIT, maps.depthSampler(), maps.atlas(),
                   kReadLayout);
    table.addImage(PUNCTUAL_BINDING_POINT_SHADOWS, VK_SHADER_STAGE_FRAGMENT_BIT, maps.sampler(), maps.pointCubes(),
                   kReadLayout);
}

void ShadowPass::createPipelines(const vk::Context& context, const FrameBindings& bindings) {
    pipelineLayout_ = context.objects().pipelineLayout({bindings.setLayout(), bindings.materialSetLayout()},
                                               {VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(ShadowDrawConstants)});
    vk::GraphicsPipelineDesc opaque;
    opaque.layout = pipelineLayout_;
    opaque.renderPass = renderPass_;
    opaque.vertexSpirv = raster_shadow_vert_spv;
    opaque.vertexStride = SceneGpu::vertexStride();
    opaque.vertexAttributes = {SceneGpu::vertexAttributes().front()};  // position only
    opaque.depthCompare = VK_COMPARE_OP_LESS;
    // Alpha-masked casters: their texture coordinates, and alpha_mask.frag's test. Two-sided like
    // every caster (no back-face test: CULL_SINGLE_SIDED_BACK_FACES stays false).
    vk::GraphicsPipelineDesc masked = opaque;
    masked.vertexSpirv = raster_shadow_masked_vert_spv;
    masked.vertexAttributes = SceneGpu::maskedCasterAttributes();
    masked.fragmentSpirv = raster_alpha_mask_frag_spv;
    // Transparent (alphaMode BLEND) casters in dither mode pass alpha against the noise instead of
    // the cutoff (alpha_mask.frag); constant 0 (the prepass's back-face test) stays off.
    const VkBool32 dither = settings_.transparent == TransparentShadows::Dither ? VK_TRUE : VK_FALSE;
    const VkSpecializationMapEntry ditherEntry{1, 0, sizeof(VkBool32)};
    const VkSpecializationInfo fragmentSpecialization{1, &ditherEntry, sizeof(VkBool32), &dither};
    masked.fragmentSpecialization = &fragmentSpecialization;

    // Pancaking exists only for the failure study; spot and point shadows never use it.
    const VkBool32 pancaking = settings_.pancaking ? VK_TRUE : VK_FALSE;
    const VkSpecializationMapEntry pancakingEntry{0, 0, sizeof(VkBool32)};
    const VkSpecializationInfo vertexSpecialization{1, &pancakingEntry, sizeof(VkBool32), &pancaking};
    opaque.vertexSpecialization = &vertexSpecialization;
    masked.vertexSpecialization = &vertexSpecialization;
    pipelines_.opaque = context.objects().graphicsPipeline(opaque);
    pipelines_.masked = context.objects().graphicsPipeline(masked);
    if (settings_.virtualPages()) {
        vk::GraphicsPipelineDesc pagedOpaque = opaque;
        vk::GraphicsPipelineDesc pagedMasked = masked;
        pagedOpaque.vertexSpirv = raster_shadow_paged_vert_spv;
        pagedMasked.vertexSpirv = raster_shadow_paged_masked_vert_spv;
        pagedOpaque.vertexSpecialization = nullptr;
        pagedMasked.vertexSpecialization = nullptr;
        pagePipelines_.opaque = context.objects().graphicsPipeline(pagedOpaque);
        pagePipelines_.masked = context.objects().graphicsPipeline(pagedMasked);
    }

    // Cascades pancake (the seed's "pancaking"), with the depth clamp where the device has it: the
    // vertex clamp bends the depth of triangles that cross the near plane, the depth clamp does
    // not. The failure study turns it off to show what clipping loses.
    if (plan_.cascades.count > 0) {
        const bool pancake = settings_.cascades.depthClamp;
        const bool clamp = pancake && context.enabledFeatures().depthClamp == VK_TRUE;
        const VkBool32 vertexPancaking = pancake && !clamp ? VK_TRUE : VK_FALSE;
        const VkSpecializationInfo cascadeSpecialization{1, &pancakingEntry, sizeof(VkBool32), &vertexPancaking};
        opaque.vertexSpecialization = &cascadeSpecialization;
        masked.vertexSpecialization = &cascadeSpecialization;
        opaque.depthClamp = clamp;
        masked.depthClamp = clamp;
        cascadePipelines_.opaque = context.objects().graphicsPipeline(opaque);
        cascadePipelines_.masked = context.objects().graphicsPipeline(masked);
    }
}

std::optional<bool> ShadowPass::casterIsMasked(const FrameContext& frame, uint32_t object) const {
    if (!frame.scene.blended(object)) return frame.scene.masked(object);
    switch (settings_.transparent) {  // the seed's shadow modes (lights/transparent_shadows.h)
        case TransparentShadows::On: return false;
        case TransparentShadows::Clip:
        case TransparentShadows::Dither: return true;
        case TransparentShadows::Off: return std::nullopt;
    }
    return std::nullopt;
}

void ShadowPass::drawView(const FrameContext& frame, const ShadowView& view, const glm::mat4& viewProjection,
                          const std::vector<uint32_t>& casters) const {
    const VkCommandBuffer cmd = frame.cmd;
    const Pipelines& pipelines = view.isCascade ? cascadePipelines_ : pipelines_;
    std::vector<uint32_t> opaque;
    std::vector<uint32_t> masked;
    for (const uint32_t object : casters) {
        const std::optional<bool> isMasked = casterIsMasked(frame, object);
        if (isMasked) (*isMasked ? masked : opaque).push_back(object);
    }
    frame.bindings.bind(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipelineLayout_);
    vkCmdPushConstants(cmd, pipelineLayout_, VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(glm::mat4), &viewProjection);
    if (!opaque.empty()) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipelines.opaque);
        frame.scene.drawObjects(cmd, pipelineLayout_, opaque, kObjectIndexOffset, VK_SHADER_STAGE_VERTEX_BIT);
    }
    if (!masked.empty()) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipelines.masked);
        frame.scene.drawObjects(cmd, pipelineLayout_, masked, kObjectIndexOffset, VK_SHADER_STAGE_VERTEX_BIT,
                                /*withTextures=*/true);
    }
}

// A batch's casters, each instanced over the pages it meets (shadow_page_draw.glsl), each instance
// into its page's layer; the viewport and scissor (beginRenderPass's) are the whole layer.
void ShadowPass::drawPages(const FrameContext& frame, const ShadowPageDraws::Batch& batch) const {
    if (batch.drawCount == 0) return;
    const VkCommandBuffer cmd = frame.cmd;
    frame.bindings.bind(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipelineLayout_);
    frame.scene.bindGeometry(cmd);
    const std::span<const ShadowPageDraws::Draw> draws(pageDraws_.draws.data() + batch.firstDraw, batch.drawCount);
    for (const bool maskedPass : {false, true}) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, maskedPass ? pagePipelines_.masked : pagePipelines_.opaque);
        for (const ShadowPageDraws::Draw& draw : draws) {
            const std::optional<bool> masked = casterIsMasked(frame, draw.object);
            if (!masked || *masked != maskedPass) continue;
            frame.scene.drawObjectInstances(cmd, pipelineLayout_, draw.object, kObjectIndexOffset, VK_SHADER_STAGE_VERTEX_BIT,
                                            maskedPass, draw.instanceCount, draw.firstInstance);
        }
    }
}

std::vector<ImageUse> ShadowPass::imageUses() const {
    // Both maps every frame, rendered or placeholders: the forward pass reads them either way.
    // (UNDEFINED: the pass asks nothing of the layout it finds. A cached atlas is the exception the
    // layout check cannot see: its barrier names the layout the cache knows the last frame left,
    // ShadowCache::atlasLayoutBefore, which every frame of these passes leaves it in.)
    return {{&maps().atlas(), VK_IMAGE_LAYOUT_UNDEFINED, kReadLayout},
            {&maps().pointCubes(), VK_IMAGE_LAYOUT_UNDEFINED, kReadLayout}};
}

void ShadowPass::recordAtlasView(const FrameContext& frame, uint32_t index) const {
    for (const DrawingTile& tile : drawingTiles_[index]) recordDrawingTile(frame, index, tile);
}

void ShadowPass::drawIntoSquare(const FrameContext& frame, const ShadowView& view, const glm::uvec2& origin,
                                const std::vector<uint32_t>& casters, VkRenderPass renderPass) const {
    // The tile's texels over the far plane (every texel no caster draws: lit) or over what the
    // square holds (loading), and the view drawn through a viewport moved so that the tile's texels
    // fall on the drawing square's (the scissor beginRenderPass sets keeps the rest out).
    const uint32_t side = drawingTileSide(view.rect.size);
    const VkClearValue clear = kClearToFar;
    vk::beginRenderPass(frame.cmd, renderPass, drawingFramebuffer_, side, side, {&clear, 1});
    const VkViewport viewport{-float(origin.x), -float(origin.y), float(view.rect.size), float(view.rect.size), 0.0f, 1.0f};
    vkCmdSetViewport(frame.cmd, 0, 1, &viewport);
    drawView(frame, view, view.gpu.viewProjection, casters);
    vkCmdEndRenderPass(frame.cmd);
}

// The drawing square's texels [0, side)^2 and the same square at `texel` of `image`, one way or
// the other (the square in TRANSFER_SRC or TRANSFER_DST, the image in `imageLayout`).
void ShadowPass::copySquare(VkCommandBuffer cmd, const vk::Image& image, VkImageLayout imageLayout,
                            const glm::uvec2& texel, uint32_t side, bool intoImage) const {
    VkImageCopy copy{};
    copy.srcSubresource = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 0, 1};
    copy.dstSubresource = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 0, 1};
    (intoImage ? copy.dstOffset : copy.srcOffset) = {int32_t(texel.x), int32_t(texel.y), 0};
    copy.extent = {side, side, 1};
    if (intoImage) {
        vkCmdCopyImage(cmd, drawingSquare_->handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, image.handle(), imageLayout, 1,
                       &copy);
    } else {
        vkCmdCopyImage(cmd, image.handle(), imageLayout, drawingSquare_->handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                       &copy);
    }
}

void ShadowPass::squareDrawnToCopied(VkCommandBuffer cmd) const {
    vk::imageBarrier(cmd, *drawingSquare_, kDrawLayout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                     VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT, VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                     VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
}

void ShadowPass::squareCopiedToDrawn(VkCommandBuffer cmd, VkImageLayout copyLayout) const {
    // The next draw waits for the copy: its reads (an execution dependency) or its writes.
    const VkAccessFlags copyAccess = copyLayout == VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL ? VK_ACCESS_TRANSFER_WRITE_BIT : 0;
    vk::imageBarrier(cmd, *drawingSquare_, copyLayout, kDrawLayout, VK_PIPELINE_STAGE_TRANSFER_BIT, copyAccess,
                     VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
                     VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);
}

void ShadowPass::drawOverStaticDepth(const FrameContext& frame, uint32_t index, const DrawingTile& tile,
                                     bool storeStatic) const {
    const VkCommandBuffer cmd = frame.cmd;
    const ShadowView& view = plan_.views[index];
    const uint32_t side = drawingTileSide(view.rect.size);
    const glm::uvec2 origin = glm::uvec2(tile.column, tile.row) * side;
    std::vector<uint32_t> statics;
    std::vector<uint32_t> dynamics;
    for (const uint32_t object : tile.casters) (cache_->dynamic(object) ? dynamics : statics).push_back(object);
    const AtlasRect& rect = cache_->staticRect(index);
    const glm::uvec2 staticTexel = glm::uvec2(rect.x, rect.y) + origin;
    const vk::Image& staticDepth = *cache_->staticDepth();
    if (storeStatic) {
        drawIntoSquare(frame, view, origin, statics, renderPass_);
        squareDrawnToCopied(cmd);
        // The static atlas rests in TRANSFER_SRC (read by the copies back), written in TRANSFER_DST.
        vk::imageBarrier(cmd, staticDepth, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                         VK_PIPELINE_STAGE_TRANSFER_BIT, 0, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
        copySquare(cmd, staticDepth, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, staticTexel, side, /*intoImage=*/true);
        vk::imageBarrier(cmd, staticDepth, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                         VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                         VK_ACCESS_TRANSFER_READ_BIT);
        squareCopiedToDrawn(cmd, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    } else {
        vk::imageBarrier(cmd, *drawingSquare_, kDrawLayout, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                         VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT, 0,
                         VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
        copySquare(cmd, staticDepth, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, staticTexel, side, /*intoImage=*/false);
        squareCopiedToDrawn(cmd, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    }
    drawIntoSquare(frame, view, origin, dynamics, loadingRenderPass_);
}

void ShadowPass::recordDrawingTile(const FrameContext& frame, uint32_t index, const DrawingTile& tile) const {
    const VkCommandBuffer cmd = frame.cmd;
    const ShadowView& view = plan_.views[index];
    const uint32_t side = drawingTileSide(view.rect.size);
    const glm::uvec2 origin = glm::uvec2(tile.column, tile.row) * side;  // the tile's texel in the view
    const ViewDrawing drawing = cache_ ? cache_->drawing(index) : ViewDrawing::Whole;
    if (drawing == ViewDrawing::Whole) {
        drawIntoSquare(frame, view, origin, tile.casters, renderPass_);
    } else {
        drawOverStaticDepth(frame, index, tile, drawing == ViewDrawing::StoreStatic);
    }
    squareDrawnToCopied(cmd);
    copySquare(cmd, maps().atlas(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, glm::uvec2(view.rect.x, view.rect.y) + origin, side,
               /*intoImage=*/true);
    squareCopiedToDrawn(cmd, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
}

VkImageLayout ShadowPass::atlasLayoutBefore() const {
    // A cached atlas keeps the squares it does not draw, in the layout the last frame left it in;
    // otherwise nothing of the last frame is needed.
    return cache_ ? cache_->atlasLayoutBefore() : VK_IMAGE_LAYOUT_UNDEFINED;
}

void ShadowPass::recordAtlas(const FrameContext& frame, const Target& atlas) const {
    const VkCommandBuffer cmd = frame.cmd;
    const vk::Image& image = maps().atlas();
    const VkImageLayout before = atlasLayoutBefore();
    vk::imageBarrier(cmd, image, before, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, 0,
                     VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
    if (pageLayers_) {
        // Virtual pages (once allocated; the marking frame before reads none): each page drawn
        // into its layer and copied into its slot, with the lit slot (every page the cache keeps
        // is left as it is), then the cascades' squares copied in beside the pool.
        pageLayers_->record(cmd, pageDraws_, pagePool_, image,
                            [&](const ShadowPageDraws::Batch& batch) { drawPages(frame, batch); });
    }
    if (!atlas.planViews.empty()) {
        vk::imageBarrier(cmd, *drawingSquare_, VK_IMAGE_LAYOUT_UNDEFINED, kDrawLayout, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0,
                         VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
                         VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);
    }
    // Mixed caching: the static atlas made this frame moves into the layout it rests in (last
    // frame's copies into it each ended in a barrier to that layout).
    const vk::Image* staticDepth = cache_ ? cache_->staticDepth() : nullptr;
    if (staticDepth && cache_->staticLayoutBefore() == VK_IMAGE_LAYOUT_UNDEFINED) {
        vk::imageBarrier(cmd, *staticDepth, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                         VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
    }
    for (const uint32_t index : atlas.planViews) {
        if (!cache_ || !cache_->kept(index)) recordAtlasView(frame, index);
    }
    vk::imageBarrier(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, kReadLayout, VK_PIPELINE_STAGE_TRANSFER_BIT,
                     VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
}

void ShadowPass::record(const FrameContext& frame) const {
    const VkCommandBuffer cmd = frame.cmd;
    const vk::Image& cubes = maps().pointCubes();
    // Last frame's faces are not needed: each is cleared and drawn below.
    vk::imageBarrier(cmd, cubes, VK_IMAGE_LAYOUT_UNDEFINED, kDrawLayout, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, 0,
                     VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
                     VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);
    const VkClearValue clear = kClearToFar;
    const bool hasAtlas = plan_.atlas.width > 0;
    for (const Target& target : targets_) {
        if (&target == &targets_.front() && hasAtlas) {
            recordAtlas(frame, target);
            continue;
        }
        // The whole face; beginRenderPass sets its viewport.
        vk::beginRenderPass(cmd, renderPass_, target.framebuffer, target.width, target.height, {&clear, 1});
        for (const uint32_t index : target.planViews) {
            const ShadowView& view = plan_.views[index];
            drawView(frame, view, view.gpu.viewProjection, view.casters);
        }
        vkCmdEndRenderPass(cmd);
    }
    // The placeholder atlas (no view has storage) only moves into the layout the forward pass reads.
    if (!hasAtlas) {
        vk::imageBarrier(cmd, maps().atlas(), atlasLayoutBefore(), kReadLayout, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, 0,
                         VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
    }
    vk::imageBarrier(cmd, cubes, kDrawLayout, kReadLayout, VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
                     VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
                     VK_ACCESS_SHADER_READ_BIT);
}

}  // namespace punctual::render
