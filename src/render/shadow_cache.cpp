#include "render/shadow_cache.h"

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

static_assert(ShadowPass::kReadLayout == VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, "atlasLayoutBefore names it");

}  // namespace

ShadowCache::ShadowCache(const vk::Context& context, const ShadowSettings& settings, ShadowCacheMode mode)
    : context_(context),
      settings_(settings),
      keep_(mode == ShadowCacheMode::On),
      atlas_(ShadowMaps::memoryLimits(context, settings).atlasSide,
             settings.autoResolution() ? settings.maxTier : settings.resolution) {
    PUNCTUAL_CHECK(mode != ShadowCacheMode::Off, "a shadow cache that is off is no cache");
    if (settings.virtualPages()) {
        throw Error("--shadow-cache", "caches whole views (--shadow-res auto or N); virtual pages are allocated afresh "
                                      "from each frame's marks and are not cached");
    }
}

void ShadowCache::prepare(ShadowPlan& plan, const Scene& scene, const FrameLights& lights) {
    const auto start = std::chrono::steady_clock::now();
    const std::vector<uint64_t> fingerprints = casterFingerprints(scene, plan);
    std::vector<CachedViewRequest> requests;
    for (const ShadowView& view : plan.views) {
        const ShadowViewKey key = view.isCascade ? ShadowViewKey{kCascadeKey, view.face}
                                                 : ShadowViewKey{lights.sceneLightIndex.at(view.packedLight), view.face};
        // Atlas squares only: the cube layout's faces have none (size 0), and are drawn every frame.
        requests.push_back({key, view.rect.size, view.rect.size > 0 ? shadowViewSignature(view, fingerprints) : 0});
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
    for (size_t v = 0; v < plan.views.size(); ++v) {
        if (!plan.views[v].rendered()) continue;
        const bool keepable = !madeAnew && placed.kept[v];
        kept_[v] = keep_ && keepable;
        frame_.keepableViews += keepable;
        (kept_[v] ? frame_.keptViews : frame_.drawnViews)++;
    }
    frame_.laidOut = placed.laidOut || madeAnew;
    frame_.movedViews = placed.moved;
    frame_.atlasTexels = plan.atlas.texels();
    frame_.checkMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace punctual::render
