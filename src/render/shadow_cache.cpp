#include "render/shadow_cache.h"

#include <algorithm>
#include <chrono>
#include <limits>

#include "core/check.h"
#include "core/error.h"
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
    if (settings.virtualPages()) {
        throw Error("--shadow-cache", "caches whole views (--shadow-res auto or N); virtual pages are allocated afresh "
                                      "from each frame's marks and are not cached");
    }
}

void ShadowCache::prepare(ShadowPlan& plan, const Scene& scene, const FrameLights& lights) {
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
    // (The cube array's layers count the shadowed points only where it exists; otherwise it is a
    // placeholder whatever the points.)
    const MapsShape shape{plan.atlas.width, plan.atlas.height, plan.cubeResolution,
                          plan.cubeResolution > 0 ? plan.shadowedPoints : 0};
    const bool madeAnew = !maps_ || !shape.sameAtlas(shape_);
    if (madeAnew) {
        maps_.emplace(context_, plan, settings_);
    } else if (!shape.sameCubes(shape_)) {
        maps_->remakePointCubes(context_, plan, settings_);  // drawn every frame: nothing kept there
    }
    shape_ = shape;
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

}  // namespace punctual::render
