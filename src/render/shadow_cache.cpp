#include "render/shadow_cache.h"

#include <algorithm>
#include <chrono>
#include <limits>

#include "core/check.h"
#include "core/error.h"
#include "lights/shadow_page_allocation.h"
#include "lights/shadow_view_signature.h"
#include "render/shadow_pass.h"
#include "vk/context.h"

namespace punctual::render {
namespace {

// The sun's cascades, keyed apart from every scene light's views.
constexpr uint32_t kCascadeKey = std::numeric_limits<uint32_t>::max();

// A buddy-allocated atlas for the views of `settings`: the device's largest side, and the largest
// side a view can take (auto's largest tier, or the fixed resolution).
ShadowAtlasCache atlasCacheFor(const vk::Context& context, const ShadowSettings& settings) {
    return ShadowAtlasCache(ShadowMaps::memoryLimits(context, settings).atlasSide,
                            settings.autoResolution() ? settings.maxTier : settings.resolution);
}

static_assert(ShadowPass::kReadLayout == VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, "atlasLayoutBefore names it");

}  // namespace

ShadowCache::ShadowCache(const vk::Context& context, const ShadowSettings& settings, ShadowCacheMode mode)
    : context_(context),
      settings_(settings),
      keep_(mode == ShadowCacheMode::On || mode == ShadowCacheMode::Mixed),
      mixed_(mode == ShadowCacheMode::Mixed),
      atlas_(atlasCacheFor(context, settings)),
      staticAtlas_(atlasCacheFor(context, settings)) {
    PUNCTUAL_CHECK(mode != ShadowCacheMode::Off, "a shadow cache that is off is no cache");
    if (settings.virtualPages() && mixed_) {
        throw Error("--shadow-cache", "mixed keeps whole views' static depth apart (--shadow-res auto or N); with "
                                      "virtual pages use on, which keeps each page that nothing in it moved");
    }
}

void ShadowCache::prepare(ShadowPlan& plan, const Scene& scene, const FrameLights& lights) {
    if (settings_.virtualPages()) {
        preparePagedFrame(plan);
        return;
    }
    const auto start = std::chrono::steady_clock::now();
    const std::vector<uint64_t> fingerprints = casterFingerprints(scene, plan);
    std::vector<ShadowViewKey> keys;
    std::vector<CachedViewRequest> requests;
    for (const ShadowView& view : plan.views) {
        keys.push_back(view.isCascade ? ShadowViewKey{kCascadeKey, view.face}
                                      : ShadowViewKey{lights.sceneLightIndex.at(view.packedLight), view.face});
        // Atlas squares only: the cube layout's faces have none (size 0), and are drawn every frame.
        requests.push_back({keys.back(), view.rect.size, view.rect.size > 0 ? shadowViewSignature(view, fingerprints) : 0});
    }
    const ShadowAtlasCacheFrame placed = atlas_.place(requests);
    frame_ = {};
    frame_.packedTexels = plan.atlas.texels();
    plan.atlas = placed.layout;
    for (size_t v = 0; v < plan.views.size(); ++v) {
        ShadowView& view = plan.views[v];
        if (view.rect.size == 0) continue;
        view.rect = placed.layout.rects[v];
        view.gpu.atlasRect = atlasRectInUv(view.rect, plan.atlas);
    }
    makeMapsFor(plan);
    const bool madeAnew = mapsMadeAnew_;
    atlasLayoutBefore_ = madeAnew ? VK_IMAGE_LAYOUT_UNDEFINED : VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    kept_.assign(plan.views.size(), false);
    std::vector<bool> keepable(plan.views.size(), false);
    for (size_t v = 0; v < plan.views.size(); ++v) {
        keepable[v] = plan.views[v].rendered() && !madeAnew && placed.kept[v];
        kept_[v] = keep_ && keepable[v];
    }
    drawing_.assign(plan.views.size(), ViewDrawing::Whole);
    staticRects_.assign(plan.views.size(), AtlasRect{});
    if (mixed_) prepareMixed(plan, keys, fingerprints);
    for (size_t v = 0; v < plan.views.size(); ++v) {
        if (!plan.views[v].rendered()) continue;
        frame_.keepableViews += keepable[v];
        (kept_[v] ? frame_.keptViews : frame_.drawnViews)++;
        frame_.overStaticViews += !kept_[v] && drawing_[v] == ViewDrawing::OverStatic;
        frame_.staticStoredViews += !kept_[v] && drawing_[v] == ViewDrawing::StoreStatic;
    }
    frame_.laidOut = placed.laidOut || madeAnew;
    frame_.movedViews = placed.moved;
    frame_.atlasTexels = plan.atlas.texels();
    frame_.checkMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

void ShadowCache::learnDynamicCasters(const std::vector<uint64_t>& fingerprints) {
    knownFingerprints_.resize(fingerprints.size(), 0);
    dynamic_.resize(fingerprints.size(), false);
    for (size_t object = 0; object < fingerprints.size(); ++object) {
        if (fingerprints[object] == 0) continue;  // no view draws it this frame: nothing seen
        if (knownFingerprints_[object] != 0 && knownFingerprints_[object] != fingerprints[object]) dynamic_[object] = true;
        knownFingerprints_[object] = fingerprints[object];
    }
    frame_.dynamicCasters = uint32_t(std::count(dynamic_.begin(), dynamic_.end(), true));
}

void ShadowCache::prepareMixed(const ShadowPlan& plan, const std::vector<ShadowViewKey>& keys,
                               const std::vector<uint64_t>& fingerprints) {
    learnDynamicCasters(fingerprints);
    // The views with a dynamic caster ask the static atlas for a square, signed by their static
    // casters alone.
    std::vector<CachedViewRequest> requests(plan.views.size());
    bool anyStatic = false;
    for (size_t v = 0; v < plan.views.size(); ++v) {
        const ShadowView& view = plan.views[v];
        requests[v].key = keys[v];
        if (!view.rendered() || view.rect.size == 0) continue;
        std::vector<uint32_t> statics;
        for (const uint32_t object : view.casters) {
            if (!dynamic(object)) statics.push_back(object);
        }
        if (statics.size() == view.casters.size()) continue;
        requests[v] = {keys[v], view.rect.size, shadowViewSignature(view, statics, fingerprints)};
        anyStatic = true;
    }
    const ShadowAtlasCacheFrame placed = staticAtlas_.place(requests);
    if (!anyStatic) {
        staticDepth_.reset();  // no view keeps static depth apart: no memory for it
        return;
    }
    const bool madeAnew = !staticDepth_ || staticDepth_->desc().width != placed.layout.width ||
                          staticDepth_->desc().height != placed.layout.height;
    if (madeAnew) {
        vk::ImageDesc desc;
        desc.format = ShadowMaps::format(settings_.format);
        desc.width = placed.layout.width;
        desc.height = placed.layout.height;
        desc.usage = VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
        desc.debugName = "static shadow depth";
        staticDepth_.emplace(context_, desc);
    }
    staticLayoutBefore_ = madeAnew ? VK_IMAGE_LAYOUT_UNDEFINED : VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    frame_.staticTexels = placed.layout.texels();
    for (size_t v = 0; v < plan.views.size(); ++v) {
        if (requests[v].size == 0) continue;
        staticRects_[v] = placed.layout.rects[v];
        const bool staticKept = !madeAnew && placed.kept[v];
        // A view kept whole whose static square is new (the static atlas laid out afresh, or the
        // view moved in it) is drawn all the same: otherwise that square would be signed with
        // depth it never received.
        if (!staticKept) kept_[v] = false;
        drawing_[v] = staticKept ? ViewDrawing::OverStatic : ViewDrawing::StoreStatic;
    }
}

void ShadowCache::makeMapsFor(const ShadowPlan& plan) {
    // (The cube array's layers count the shadowed points only where it exists; otherwise it is a
    // placeholder whatever the points. Its faces are drawn every frame: nothing kept there.)
    const MapsShape shape{plan.atlas.width, plan.atlas.height, plan.cubeResolution,
                          plan.cubeResolution > 0 ? plan.shadowedPoints : 0};
    mapsMadeAnew_ = !maps_ || !shape.sameAtlas(shape_);
    if (mapsMadeAnew_) {
        maps_.emplace(context_, plan, settings_);
    } else if (!shape.sameCubes(shape_)) {
        maps_->remakePointCubes(context_, plan, settings_);
    }
    shape_ = shape;
}

void ShadowCache::preparePagedFrame(ShadowPlan& plan) {
    // The marking frame comes first: the atlas it draws the cascades into is last frame's where the
    // pool stays as it was (the same cascades' squares beside it), so that it keeps the pages.
    frame_ = {};
    frame_.packedTexels = plan.atlas.texels();
    pageSquares_ = glm::uvec2(plan.atlas.width, plan.atlas.height);
    if (pagePool_.laidOutBeside(pageSquares_)) {
        ShadowPageAllocation pool;
        pool.pageSlots = pagePool_.capacity();
        placeShadowPagePool(plan, pool, ShadowMaps::memoryLimits(context_, settings_).atlasSide);
    }
    makeMapsFor(plan);
    atlasLayoutBefore_ = mapsMadeAnew_ ? VK_IMAGE_LAYOUT_UNDEFINED : VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    kept_.assign(plan.views.size(), false);  // the cascades: drawn every frame
    keptPages_.clear();
    drawing_.assign(plan.views.size(), ViewDrawing::Whole);
}

std::vector<bool> ShadowCache::placePages(ShadowPlan& plan, ShadowPageAllocation& allocation,
                                          const std::vector<std::vector<uint32_t>>& pageCasters, const Scene& scene,
                                          const FrameLights& lights) {
    const auto start = std::chrono::steady_clock::now();
    const bool madeForMarking = mapsMadeAnew_;
    const std::vector<uint64_t> fingerprints = casterFingerprints(scene, plan);
    std::vector<CachedPageRequest> requests;
    for (size_t i = 0; i < allocation.pages.size(); ++i) {
        const ShadowPage& page = allocation.pages[i];
        const ShadowView& view = plan.views[page.view];
        requests.push_back({{lights.sceneLightIndex.at(view.packedLight), view.face, page.level, page.column, page.row},
                            shadowPageSignature(view, page.level, page.column, page.row, pageCasters[i], fingerprints)});
    }
    // The pool beside the cascades' squares alone (the marking frame's atlas may have held it).
    plan.atlas.width = pageSquares_.x;
    plan.atlas.height = pageSquares_.y;
    const uint64_t budgetSlots = shadowPagePoolCapacity(plan, plan.budgetBytes, settings_.texelBytes());
    const ShadowPagePoolFrame placed = pagePool_.place(requests, pageSquares_, budgetSlots);
    assignPageSlots(allocation, placed.slots, placed.capacity);
    placeShadowPagePool(plan, allocation, ShadowMaps::memoryLimits(context_, settings_).atlasSide);
    makeMapsFor(plan);
    // A new atlas (this frame's, or the marking frame's) holds no page yet.
    const bool fresh = mapsMadeAnew_ || madeForMarking;
    // (Kept, the atlas is where the marking frame left it.)
    atlasLayoutBefore_ = mapsMadeAnew_ ? VK_IMAGE_LAYOUT_UNDEFINED : VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    std::vector<bool> drawn(requests.size(), true);
    for (size_t i = 0; i < requests.size(); ++i) {
        const bool keepable = placed.kept[i] && !fresh;
        drawn[i] = !(keep_ && keepable);
        frame_.keepablePages += keepable;
        (drawn[i] ? frame_.drawnPages : frame_.keptPages)++;
    }
    keptPages_.assign(drawn.size(), false);
    for (size_t i = 0; i < drawn.size(); ++i) keptPages_[i] = !drawn[i];
    frame_.laidOut = placed.laidOut || fresh;
    frame_.pageSlots = placed.capacity;
    frame_.atlasTexels = plan.atlas.texels();
    frame_.checkMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return drawn;
}

}  // namespace punctual::render
