#include "lights/shadow_sizing.h"

#include <algorithm>
#include <limits>

#include "core/error.h"
#include "lights/shadow_drawing_tiles.h"
#include "lights/shadow_resolution.h"

namespace punctual {

namespace {

constexpr uint32_t kVirtualSliceGuardResolution = 512;

// Each view's light's rank (0 = the most important), for the budget. The sun's cascades come
// first: the sun reaches every pixel the frame shows.
std::vector<uint32_t> lightRanks(const ShadowPlan& plan, const Scene& scene, const FrameLights& lights,
                                 const glm::vec3& cameraPosition) {
    std::vector<uint32_t> packed;
    for (const ShadowView& view : plan.views) {
        if (view.isCascade) continue;
        if (packed.empty() || packed.back() != view.packedLight) packed.push_back(view.packedLight);
    }
    std::vector<uint32_t> byImportance = packed;
    std::stable_sort(byImportance.begin(), byImportance.end(), [&](uint32_t a, uint32_t b) {
        return lightImportance(scene.lights[lights.sceneLightIndex[a]], cameraPosition) >
               lightImportance(scene.lights[lights.sceneLightIndex[b]], cameraPosition);
    });
    std::vector<uint32_t> ranks;
    for (const ShadowView& view : plan.views) {
        ranks.push_back(view.isCascade ? 0u
                                       : 1u + uint32_t(std::find(byImportance.begin(), byImportance.end(), view.packedLight) -
                                                       byImportance.begin()));
    }
    return ranks;
}

}  // namespace

std::vector<uint32_t> shadowViewRanks(const ShadowPlan& plan, const Scene& scene, const FrameLights& lights,
                                      const glm::vec3& cameraPosition) {
    return lightRanks(plan, scene, lights, cameraPosition);
}

namespace {

bool usesCubeArray(const ShadowView& view, const ShadowSettings& settings) {
    return view.isPoint && settings.pointLayout == PointShadowLayout::Cube;
}

// The atlas sizes of the views at `resolution` (fixed mode): every view with a caster.
std::vector<uint32_t> fixedAtlasSizes(const ShadowPlan& plan, const ShadowSettings& settings, uint32_t resolution) {
    std::vector<uint32_t> sizes;
    for (const ShadowView& view : plan.views) {
        sizes.push_back(!usesCubeArray(view, settings) && !view.casters.empty() ? resolution : 0u);
    }
    return sizes;
}

// Fills each view's GPU record from its resolution and storage.
void finishViews(ShadowPlan& plan, const FrameLights& lights, const ShadowSettings& settings) {
    plan.viewsRendered = 0;
    plan.viewsSkipped = 0;
    for (ShadowView& view : plan.views) {
        const float resolution = float(std::max(view.resolution, 1u));
        if (view.isPoint) {
            const glm::vec3 position(lights.packed[view.packedLight].positionInvRangeSq);
            // Slices: widen each face so that a filter reaching `penumbraTexels` (plus one for the
            // bilinear footprint) past the face edge still reads the same slice (URP's guard angle).
            // Virtual pages: a receiver reads a level of the face, not the face's 16384 texels; the
            // band is sized for levels of 512 texels and finer, so only the coarsest levels, read by
            // receivers whose pixels span more than 1/512 of the face, clamp at the band's edge.
            const uint32_t guarded = settings.virtualPages() ? kVirtualSliceGuardResolution : view.resolution;
            const float scale = settings.pointLayout == PointShadowLayout::Slices
                                    ? 1.0f + 2.0f * (settings.penumbraTexels(guarded) + 1.0f) / float(std::max(guarded, 1u))
                                    : 1.0f;
            view.tanSpan = 2.0f * scale;
            view.gpu.viewProjection = cubeFaceViewProjection(position, view.face, view.nearPlane, view.farPlane, scale);
        }
        if (view.isCascade) finishCascadeView(view, plan.cascades, settings);
        (view.rendered() ? plan.viewsRendered : plan.viewsSkipped)++;
        view.gpu.params = glm::vec4(view.rendered() ? 1.0f : -1.0f, view.tanSpan, view.nearPlane, view.farPlane);
        if (usesCubeArray(view, settings)) {
            view.gpu.atlasRect = glm::vec4(float(view.cubeLayer / 6), 0.0f, 0.0f, 0.0f);
        } else if (plan.atlas.width > 0) {
            view.gpu.atlasRect = atlasRectInUv(view.rect, plan.atlas);
        }
        view.gpu.texel = glm::vec4(resolution, 1.0f / resolution,
                                   settings.biasPenumbraTexels(view.resolution, !usesCubeArray(view, settings)), 0.0f);
    }
    if (plan.cascades.count > 0) selectCascadesBy(plan, settings);
}

}  // namespace

std::vector<std::pair<uint32_t, uint32_t>> shadowTierCounts(const ShadowPlan& plan) {
    std::vector<std::pair<uint32_t, uint32_t>> tiers;
    for (const ShadowView& view : plan.views) {
        if (!view.rendered()) continue;
        auto it = std::find_if(tiers.begin(), tiers.end(), [&](const auto& t) { return t.first == view.resolution; });
        if (it == tiers.end()) {
            tiers.emplace_back(view.resolution, 1u);
        } else {
            ++it->second;
        }
    }
    std::sort(tiers.begin(), tiers.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    return tiers;
}

uint64_t shadowTexelsRendered(const ShadowPlan& plan) {
    uint64_t texels = 0;
    for (const ShadowView& view : plan.views) {
        if (view.rendered()) texels += uint64_t(view.resolution) * view.resolution;
    }
    return texels;
}

std::string describeShadowTiers(const ShadowPlan& plan) {
    std::string text;
    for (const auto& [resolution, count] : shadowTierCounts(plan)) {
        text += (text.empty() ? "" : ", ") + std::to_string(count) + " x " + std::to_string(resolution);
    }
    return text.empty() ? "none" : text;
}

namespace {

uint64_t cubeArrayBytes(const ShadowPlan& plan, const ShadowSettings& settings, uint32_t resolution) {
    return settings.pointLayout == PointShadowLayout::Cube
               ? 6ull * plan.shadowedPoints * resolution * resolution * settings.texelBytes()
               : 0;
}

}  // namespace

uint64_t shadowMapBytes(const ShadowPlan& plan, const ShadowSettings& settings, uint32_t resolution) {
    const std::vector<uint32_t> sizes = fixedAtlasSizes(plan, settings, resolution);
    const uint64_t atlas = packShadowAtlas(sizes, std::numeric_limits<uint32_t>::max()).texels() + drawingSquareTexels(sizes);
    return atlas * settings.texelBytes() + cubeArrayBytes(plan, settings, resolution);
}

namespace {

// Fixed mode: every view with a caster at settings.resolution, or one line saying what does not fit.
void sizeFixedViews(ShadowPlan& plan, const FrameLights& lights, const ShadowSettings& settings,
                    const ShadowMemoryLimits& limits) {
    // The first limit the maps at `resolution` exceed, described; empty when they fit.
    auto problemAt = [&](uint32_t resolution) -> std::string {
        const std::vector<uint32_t> sizes = fixedAtlasSizes(plan, settings, resolution);
        const uint64_t total = shadowMapBytes(plan, settings, resolution);
        if (total > limits.total) {
            return "the shadow maps of " + std::to_string(plan.shadowedSpots) + " spot and " +
                   std::to_string(plan.shadowedPoints) + " point lights need " + describeBytes(total) + ", " +
                   limits.totalName + " has " + describeBytes(limits.total);
        }
        if (!shadowAtlasFits(sizes, limits.atlasSide)) {
            return "the shadow atlas would be wider or taller than the device's largest 2D image (" +
                   std::to_string(limits.atlasSide) + " texels)";
        }
        const uint64_t atlas = packShadowAtlas(sizes, limits.atlasSide).texels() * settings.texelBytes();
        if (atlas > limits.atlasBytes) {
            return "the shadow atlas needs " + describeBytes(atlas) + ", the device's largest such image holds " +
                   describeBytes(limits.atlasBytes);
        }
        const uint64_t cubes = cubeArrayBytes(plan, settings, resolution);
        if (cubes > limits.cubeArrayBytes) {
            return "the point shadow cube array (" + std::to_string(6 * plan.shadowedPoints) + " layers) needs " +
                   describeBytes(cubes) + ", the device's largest such image holds " + describeBytes(limits.cubeArrayBytes);
        }
        if (atlas + cubes > limits.total) {
            return "the shadow maps of " + std::to_string(plan.shadowedSpots) + " spot and " +
                   std::to_string(plan.shadowedPoints) + " point lights need " + describeBytes(atlas + cubes) + ", " +
                   limits.totalName + " has " + describeBytes(limits.total);
        }
        return {};
    };
    std::string problem = problemAt(settings.resolution);
    if (!problem.empty()) {
        for (uint32_t resolution = settings.resolution / 2; resolution >= 16; resolution /= 2) {
            if (problemAt(resolution).empty()) {
                problem += " (at most --shadow-res " + std::to_string(resolution) + " fits)";
                break;
            }
        }
        throw Error("--shadow-res " + std::to_string(settings.resolution), problem);
    }
    const std::vector<uint32_t> sizes = fixedAtlasSizes(plan, settings, settings.resolution);
    plan.atlas = packShadowAtlas(sizes, limits.atlasSide);
    for (uint32_t v = 0; v < plan.views.size(); ++v) {
        ShadowView& view = plan.views[v];
        view.resolution = usesCubeArray(view, settings) || !view.casters.empty() ? settings.resolution : 0u;
        view.rect = plan.atlas.rects[v];
    }
    plan.cubeResolution = settings.pointLayout == PointShadowLayout::Cube && plan.shadowedPoints > 0 ? settings.resolution : 0;
    finishViews(plan, lights, settings);
}

}  // namespace

void sizeShadowViews(ShadowPlan& plan, const Scene& scene, const FrameLights& lights, const glm::vec3& cameraPosition,
                     uint32_t frameWidth, uint32_t frameHeight, const ShadowSettings& settings,
                     const ShadowMemoryLimits& limits, const LazyTriangleBvh* geometry) {
    if (plan.views.empty()) return;
    if (!settings.autoResolution()) {
        sizeFixedViews(plan, lights, settings, limits);
        return;
    }

    // Auto: the tier each view's visible receivers need, then the budget.
    const VisibleReceivers receivers = sampleVisibleReceivers(scene, frameWidth, frameHeight, geometry);
    plan.receiverSamples = uint32_t(receivers.samples.size());
    plan.sampleStep = receivers.step;
    const std::vector<float> demand = shadowViewDemand(plan, lights, receivers);
    std::vector<uint32_t> tiers;
    for (uint32_t v = 0; v < plan.views.size(); ++v) {
        ShadowView& view = plan.views[v];
        view.demand = demand[v];
        uint32_t previous = 0;
        if (!view.isCascade && !settings.previousTiers.empty()) {
            const auto known = settings.previousTiers.find({lights.sceneLightIndex[view.packedLight], view.face});
            if (known != settings.previousTiers.end()) previous = known->second;
        }
        view.demandedTier = shadowTierWithHysteresis(demand[v] * settings.texelsPerPixel, previous, settings.tierHysteresis,
                                                     settings.minTier, settings.maxTier);
        // A view with no caster is lit everywhere: it needs no storage whatever its receivers. With
        // virtual pages only the cascades take squares of the atlas; the pages come after marking.
        const bool paged = settings.virtualPages() && !view.isCascade;
        tiers.push_back(view.casters.empty() || paged ? 0u : view.demandedTier);
    }
    ShadowBudgetLimits budget;
    budget.texelBytes = settings.texelBytes();
    budget.minTier = settings.minTier;
    budget.maxSide = limits.atlasSide;
    // The budget is the atlas's (--shadow-budget); beside it the device holds the drawing square
    // (shadow_drawing_tiles.h), at most kDrawingSquareSide^2 texels.
    const uint64_t square = uint64_t(kDrawingSquareSide) * kDrawingSquareSide * settings.texelBytes();
    const uint64_t deviceBytes = std::min(limits.total > square ? limits.total - square : 0, limits.atlasBytes);
    if (settings.budgetBytes <= deviceBytes) {
        budget.bytes = settings.budgetBytes;
        budget.bytesName = "--shadow-budget " + std::to_string(settings.budgetBytes >> 20);
    } else {
        budget.bytes = deviceBytes;
        budget.bytesName = limits.total <= limits.atlasBytes ? limits.totalName : "the device's largest 2D image";
    }
    const ShadowAllocation allocation = fitShadowBudget(tiers, lightRanks(plan, scene, lights, cameraPosition), budget);
    plan.atlas = allocation.atlas;
    plan.budgetBytes = budget.bytes;
    plan.reductions = allocation.reductions;
    plan.reducedBy = allocation.limitName;
    for (uint32_t v = 0; v < plan.views.size(); ++v) {
        ShadowView& view = plan.views[v];
        view.resolution = allocation.resolutions[v];
        view.rect = plan.atlas.rects[v];
        // A virtual map with casters has a map (its pages come from the marks), but no square.
        if (settings.virtualPages() && !view.isCascade && !view.casters.empty()) view.resolution = PUNCTUAL_VIRTUAL_SHADOW_SIZE;
    }
    finishViews(plan, lights, settings);
}

}  // namespace punctual
