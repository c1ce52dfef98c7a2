#include "lights/virtual_pages.h"

#include <bit>
#include <cmath>
#include <numeric>

#include "lights/shadow_page_allocation.h"
#include "lights/shadow_resolution.h"
#include "shading.h"
#include "shadow_pages.h"
#include "shadows.h"

namespace punctual {

uint32_t VirtualPageLayout::levels() const { return gpu::virtualShadowLevels(virtualSize, pageSize); }

uint32_t VirtualPageLayout::pagesAcross(uint32_t level) const {
    return gpu::virtualShadowPagesAcross(level, virtualSize, pageSize);
}

uint32_t VirtualPageLayout::pagesPerView() const {
    uint32_t pages = 0;
    for (uint32_t level = 0; level < levels(); ++level) pages += pagesAcross(level) * pagesAcross(level);
    return pages;
}

std::vector<VirtualPageLayout> virtualPageLayoutsToCompare() {
    std::vector<VirtualPageLayout> layouts;
    for (uint32_t virtualSize : {4096u, 8192u, 16384u}) {
        for (uint32_t pageSize : {32u, 64u, 128u, 256u}) layouts.push_back({virtualSize, pageSize});
    }
    return layouts;
}

uint64_t VirtualPageDemand::markedPages() const {
    return std::accumulate(markedPerLevel.begin(), markedPerLevel.end(), uint64_t(0));
}

uint64_t VirtualPageDemand::physicalBytes(uint32_t texelBytes) const {
    return markedPages() * layout.pageSize * layout.pageSize * texelBytes;
}

uint64_t VirtualPageDemand::pageTableBytes() const { return viewsWithPages * layout.pagesPerView() * 4; }

namespace {

// The marked pages of one layout: a bit per page of every level, per view; with the filters'
// reach, and under the receivers alone.
struct PageMarks {
    VirtualPageLayout layout;
    std::vector<std::vector<uint64_t>> bits;        // per view (empty until a page of it is marked)
    std::vector<std::vector<uint64_t>> centreBits;  // the same, the pages under the receivers only
    uint64_t pairsCoarserThanAsked = 0;

    static void set(std::vector<uint64_t>& viewBits, uint32_t index, uint32_t pages) {
        if (viewBits.empty()) viewBits.assign((pages + 63) / 64, 0);
        viewBits[index / 64] |= uint64_t(1) << (index % 64);
    }

    // Pair (view, uv) needing `needed` texels a side, read by a filter reaching `reach(level's
    // resolution)` texels.
    template <typename Reach>
    void mark(uint32_t view, glm::vec2 uv, float needed, const Reach& reach) {
        const uint32_t level = gpu::virtualShadowLevel(needed, layout.virtualSize, layout.levels());
        if (level == 0 && needed > float(layout.virtualSize) * PUNCTUAL_SQRT2) ++pairsCoarserThanAsked;
        const uint32_t pages = layout.pagesPerView();
        const glm::uvec2 page = gpu::virtualShadowPage(uv, level, layout.virtualSize, layout.pageSize);
        set(centreBits[view], gpu::virtualShadowPageIndex(page, level, layout.virtualSize, layout.pageSize), pages);
        const glm::uvec4 footprint = gpu::virtualShadowFootprintPages(uv, reach(layout.virtualSize >> level), level,
                                                                      layout.virtualSize, layout.pageSize);
        for (uint32_t y = footprint.y; y <= footprint.w; ++y) {
            for (uint32_t x = footprint.x; x <= footprint.z; ++x) {
                set(bits[view], gpu::virtualShadowPageIndex(glm::uvec2(x, y), level, layout.virtualSize, layout.pageSize), pages);
            }
        }
    }

    VirtualPageDemand demand() const {
        VirtualPageDemand result;
        result.layout = layout;
        result.pairsCoarserThanAsked = pairsCoarserThanAsked;
        result.markedPerLevel.assign(layout.levels(), 0);
        for (const std::vector<uint64_t>& viewBits : centreBits) {
            for (uint64_t word : viewBits) result.centrePages += uint64_t(std::popcount(word));
        }
        for (const std::vector<uint64_t>& viewBits : bits) {
            if (viewBits.empty()) continue;
            ++result.viewsWithPages;
            uint32_t first = 0;  // the level's first page index
            for (uint32_t level = 0; level < layout.levels(); ++level) {
                const uint32_t count = layout.pagesAcross(level) * layout.pagesAcross(level);
                uint64_t marked = 0;
                for (uint32_t index = first; index < first + count; ++index) {
                    marked += (viewBits[index / 64] >> (index % 64)) & 1u;
                }
                result.markedPerLevel[level] += marked;
                result.usedLevelEntries += marked > 0 ? count : 0;
                first += count;
            }
        }
        return result;
    }
};

// View UV (0 .. 1 across) of a world point through a view's projection.
glm::vec2 viewUv(const glm::mat4& viewProjection, const glm::vec3& position) {
    const glm::vec4 clip = viewProjection * glm::vec4(position, 1.0f);
    return glm::vec2(clip) / clip.w * 0.5f + 0.5f;
}

}  // namespace

VirtualPageEstimate estimateVirtualPages(const Scene& scene, const FrameLights& lights, const ShadowPlan& plan,
                                         uint32_t width, uint32_t height, const ShadowSettings& settings,
                                         std::span<const VirtualPageLayout> layouts) {
    VirtualPageEstimate estimate;
    std::vector<PageMarks> marks;
    for (const VirtualPageLayout& layout : layouts) {
        const std::vector<std::vector<uint64_t>> none(plan.views.size());
        marks.push_back({layout, none, none, 0});
    }
    const auto reach = [&settings](uint32_t resolution) { return settings.penumbraTexels(resolution); };
    const float texelsPerPixel = settings.texelsPerPixel;
    // Each shadowed light's first view (a point light's six faces follow it), and each view's
    // projection onto its own virtual map: a point face's unwidened one, as a cube face's.
    std::vector<uint32_t> firstViews;
    std::vector<glm::mat4> projections(plan.views.size());
    for (uint32_t v = 0; v < plan.views.size(); ++v) {
        const ShadowView& view = plan.views[v];
        if (view.isCascade) continue;
        if (!view.isPoint || view.face == 0) firstViews.push_back(v);
        projections[v] = view.isPoint ? cubeFaceViewProjection(glm::vec3(lights.packed[view.packedLight].positionInvRangeSq),
                                                               view.face, view.nearPlane, view.farPlane)
                                      : view.gpu.viewProjection;
    }
    forEachVisibleReceiver(scene, width, height, 1, [&](uint32_t, uint32_t, const ReceiverSample& sample) {
        for (uint32_t first : firstViews) {
            const gpu::GpuPunctualLight& light = lights.packed[plan.views[first].packedLight];
            const uint32_t view = plan.views[first].isPoint
                                      ? first + gpu::cubeFaceOfDirection(sample.position - glm::vec3(light.positionInvRangeSq))
                                      : first;
            if (plan.views[view].casters.empty()) continue;  // no caster: always lit, no map
            // A point face's virtual map spans the face alone (2 at unit depth), not the atlas
            // slice's guard band (shadow_sizing.h), which resolutionNeededAt's span includes.
            const float spanRatio = plan.views[view].isPoint ? 2.0f / plan.views[view].tanSpan : 1.0f;
            const float needed = resolutionNeededAt(plan, view, light, sample) * spanRatio * texelsPerPixel;
            if (!(needed > 0.0f)) continue;
            ++estimate.shadedPairs;
            const glm::vec2 uv = viewUv(projections[view], sample.position);
            for (PageMarks& layoutMarks : marks) layoutMarks.mark(view, uv, needed, reach);
        }
    });
    for (const PageMarks& layoutMarks : marks) estimate.layouts.push_back(layoutMarks.demand());
    return estimate;
}

std::optional<VirtualRead> virtualReadOnCpu(const ShadowPlan& plan, const gpu::GpuPunctualLight& light,
                                            const glm::vec3& position, const glm::vec3& normal,
                                            const ShadowSettings& settings) {
    if (light.angleOffsetShadow.y < 0.0f) return std::nullopt;  // no shadow
    const gpu::LightSample arrival = gpu::sampleLight(light, position);
    if (!(arrival.attenuation > 0.0f) || !(glm::dot(normal, arrival.toLight) > 0.0f)) return std::nullopt;
    // shadowReadOf: the view sized at the receiver, the bias at its level's texel.
    const ShadowFilterInfo& filter = shadowFilterInfo(settings.filter);
    const uint32_t first = uint32_t(light.angleOffsetShadow.y);
    const glm::vec3 lightPosition(light.positionInvRangeSq);
    const bool spot = light.angleOffsetShadow.z > -1.0f;
    const glm::vec3 direction = position - lightPosition;
    const uint32_t sized = spot ? first : first + gpu::cubeFaceOfDirection(direction);
    const float linearDepth = spot ? std::abs(glm::dot(direction, glm::vec3(light.directionAngleScale)))
                                   : std::abs(glm::dot(direction, gpu::cubeFaceAxis(sized - first)));
    const float resolution = shadowResolutionRead(plan, sized, linearDepth, position);
    if (!(resolution > 0.0f)) return std::nullopt;
    const float texel = gpu::shadowTexelWorldSize(linearDepth, plan.views[sized].tanSpan, resolution);
    const bool receiverPlane = settings.receiverPlane && filter.footprint() > 0;
    const float penumbra = receiverPlane ? 0.0f : filter.reachTexels(settings.diskRadius * resolution);
    const glm::vec3 biased = gpu::applyShadowBias(position, normal, arrival.toLight, texel, penumbra, settings.bias);
    VirtualRead read;
    read.view = spot ? first : first + gpu::cubeFaceOfDirection(biased - lightPosition);
    if (!plan.views[read.view].rendered()) return std::nullopt;  // no caster: lit, no map
    const glm::vec4 clip = plan.views[read.view].gpu.viewProjection * glm::vec4(biased, 1.0f);
    if (!(clip.w > 0.0f)) return std::nullopt;
    read.uv = glm::vec2(clip) / clip.w * 0.5f + 0.5f;
    if (glm::any(glm::lessThan(read.uv, glm::vec2(0.0f))) || glm::any(glm::greaterThan(read.uv, glm::vec2(1.0f)))) {
        return std::nullopt;
    }
    read.level = uint32_t(std::lround(std::log2(float(PUNCTUAL_VIRTUAL_SHADOW_SIZE) / resolution)));
    read.reach = filter.reachTexels(settings.diskRadius * resolution);
    return read;
}

std::vector<uint32_t> markVirtualPagesOnCpu(const Scene& scene, const FrameLights& lights, const ShadowPlan& plan,
                                            uint32_t width, uint32_t height, const ShadowSettings& settings) {
    const ShadowPageMarkLayout layout = ShadowPageMarkLayout::of(plan);
    std::vector<uint32_t> marks(layout.words, 0u);
    const uint32_t spotsAndPoints = lights.spotCount + lights.pointCount;
    forEachVisibleReceiver(scene, width, height, 1, [&](uint32_t, uint32_t, const ReceiverSample& sample) {
        for (uint32_t i = 0; i < spotsAndPoints; ++i) {
            const std::optional<VirtualRead> read = virtualReadOnCpu(plan, lights.packed[i], sample.position, sample.normal, settings);
            if (!read) continue;
            const glm::uvec4 pages = gpu::virtualShadowFootprintPages(read->uv, read->reach + PUNCTUAL_VIRTUAL_SHADOW_MARK_MARGIN,
                                                                      read->level, PUNCTUAL_VIRTUAL_SHADOW_SIZE,
                                                                      PUNCTUAL_VIRTUAL_SHADOW_PAGE);
            for (uint32_t y = pages.y; y <= pages.w; ++y) {
                for (uint32_t x = pages.x; x <= pages.z; ++x) {
                    const uint32_t index = gpu::virtualShadowPageIndex(glm::uvec2(x, y), read->level, PUNCTUAL_VIRTUAL_SHADOW_SIZE,
                                                                       PUNCTUAL_VIRTUAL_SHADOW_PAGE);
                    marks[layout.firstWord[read->view] + index / 32] |= 1u << (index % 32);
                }
            }
        }
    });
    return marks;
}

}  // namespace punctual
