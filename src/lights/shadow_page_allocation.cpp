#include "lights/shadow_page_allocation.h"

#include <algorithm>
#include <bit>
#include <numeric>

#include "core/error.h"
#include "shadow_pages.h"

namespace punctual {
namespace {

constexpr uint32_t kPage = PUNCTUAL_VIRTUAL_SHADOW_PAGE;
constexpr uint32_t kLevels = PUNCTUAL_VIRTUAL_SHADOW_LEVELS;
constexpr uint32_t kSlot = PUNCTUAL_VIRTUAL_SHADOW_SLOT;

uint32_t pagesAcross(uint32_t level) {
    return gpu::virtualShadowPagesAcross(level, PUNCTUAL_VIRTUAL_SHADOW_SIZE, kPage);
}

// The first page index of each level within a view's marks (virtualShadowPageIndex of page 0).
std::array<uint32_t, kLevels + 1> levelStarts() {
    std::array<uint32_t, kLevels + 1> starts{};
    for (uint32_t level = 0; level < kLevels; ++level) starts[level + 1] = starts[level] + pagesAcross(level) * pagesAcross(level);
    return starts;
}

bool marked(std::span<const uint32_t> marks, uint32_t firstWord, uint32_t index) {
    return (marks[firstWord + index / 32] >> (index % 32) & 1u) != 0;
}

gpu::GpuVirtualShadowView noPages(uint32_t firstWord, uint32_t coarser) {
    gpu::GpuVirtualShadowView view{};
    view.marks = glm::uvec4(firstWord, coarser, 0u, 0u);
    for (glm::uvec4& level : view.levels) level = glm::uvec4(PUNCTUAL_NO_SHADOW_PAGE, 0u, 0u, 0u);
    return view;
}

uint32_t coarserOf(std::span<const uint32_t> coarser, size_t view) { return view < coarser.size() ? coarser[view] : 0u; }

}  // namespace

ShadowPageMarkLayout ShadowPageMarkLayout::of(const ShadowPlan& plan) {
    ShadowPageMarkLayout layout;
    for (const ShadowView& view : plan.views) {
        const bool hasMap = !view.isCascade && view.rendered();
        layout.firstWord.push_back(hasMap ? layout.words : PUNCTUAL_NO_SHADOW_PAGE);
        if (hasMap) layout.words += kWordsPerView;
    }
    return layout;
}

uint64_t ShadowPageCounts::total() const { return std::accumulate(perLevel.begin(), perLevel.end(), uint64_t(0)); }

ShadowPageCounts countMarkedPages(const ShadowPageMarkLayout& layout, std::span<const uint32_t> marks) {
    const std::array<uint32_t, kLevels + 1> starts = levelStarts();
    ShadowPageCounts counts;
    counts.perView.assign(layout.firstWord.size(), 0);
    for (size_t v = 0; v < layout.firstWord.size(); ++v) {
        const uint32_t first = layout.firstWord[v];
        if (first == PUNCTUAL_NO_SHADOW_PAGE) continue;
        for (uint32_t level = 0; level < kLevels; ++level) {
            uint64_t pages = 0;
            for (uint32_t index = starts[level]; index < starts[level + 1]; ++index) pages += marked(marks, first, index);
            counts.perLevel[level] += pages;
            counts.perView[v] += pages;
        }
    }
    return counts;
}

std::vector<gpu::GpuVirtualShadowView> unallocatedPageViews(const ShadowPageMarkLayout& layout,
                                                            std::span<const uint32_t> coarser) {
    std::vector<gpu::GpuVirtualShadowView> views;
    for (size_t v = 0; v < layout.firstWord.size(); ++v) views.push_back(noPages(layout.firstWord[v], coarserOf(coarser, v)));
    return views;
}

ShadowPageAllocation allocateShadowPages(const ShadowPageMarkLayout& layout, std::span<const uint32_t> marks,
                                         std::span<const uint32_t> coarser) {
    const std::array<uint32_t, kLevels + 1> starts = levelStarts();
    ShadowPageAllocation allocation;
    allocation.views = unallocatedPageViews(layout, coarser);
    for (size_t v = 0; v < layout.firstWord.size(); ++v) {
        const uint32_t first = layout.firstWord[v];
        if (first == PUNCTUAL_NO_SHADOW_PAGE) continue;
        for (uint32_t level = 0; level < kLevels; ++level) {
            const uint32_t across = pagesAcross(level);
            // The rectangle of the level's marked pages: the table covers it, no more.
            glm::uvec2 low(across), high(0u);
            for (uint32_t index = starts[level]; index < starts[level + 1]; ++index) {
                if (!marked(marks, first, index)) continue;
                const glm::uvec2 page((index - starts[level]) % across, (index - starts[level]) / across);
                low = glm::min(low, page);
                high = glm::max(high, page);
            }
            if (low.x > high.x) continue;  // no page at this level
            const glm::uvec2 size = high - low + 1u;
            allocation.views[v].levels[level] = glm::uvec4(uint32_t(allocation.table.size()), low.x | low.y << 16,
                                                           size.x | size.y << 16, 0u);
            for (uint32_t row = low.y; row <= high.y; ++row) {
                for (uint32_t column = low.x; column <= high.x; ++column) {
                    if (!marked(marks, first, starts[level] + row * across + column)) {
                        allocation.table.push_back(PUNCTUAL_NO_SHADOW_PAGE);
                        continue;
                    }
                    allocation.table.push_back(uint32_t(allocation.pages.size()));
                    allocation.pages.push_back({uint32_t(v), level, column, row});
                    ++allocation.pagesPerLevel[level];
                }
            }
        }
    }
    return allocation;
}

void placeShadowPagePool(ShadowPlan& plan, ShadowPageAllocation& allocation, uint32_t maxSide) {
    const uint64_t slots = allocation.slots();
    const uint32_t firstRow = plan.atlas.height;
    uint32_t across = plan.atlas.width >= kSlot ? plan.atlas.width / kSlot : uint32_t(std::min<uint64_t>(slots, 64));
    auto rows = [&] { return uint32_t((slots + across - 1) / across); };
    while (uint64_t(firstRow) + uint64_t(rows()) * kSlot > maxSide && uint64_t(across) * 2 * kSlot <= maxSide) across *= 2;
    if (uint64_t(firstRow) + uint64_t(rows()) * kSlot > maxSide) {
        throw Error("--shadow-res virtual", std::to_string(slots) + " shadow pages do not fit the device's largest 2D image (" +
                                                std::to_string(maxSide) + " texels a side)");
    }
    allocation.pagesAcross = across;
    allocation.firstRow = firstRow;
    plan.atlas.width = std::max(plan.atlas.width, across * kSlot);
    plan.atlas.height = firstRow + rows() * kSlot;
}

uint64_t shadowPagePoolCapacity(const ShadowPlan& plan, uint64_t budgetBytes, uint32_t texelBytes) {
    const uint64_t cascades = plan.atlas.texels() * texelBytes;
    const uint64_t slots = budgetBytes > cascades ? (budgetBytes - cascades) / (uint64_t(kSlot) * kSlot * texelBytes) : 0;
    return slots > 0 ? slots - 1 : 0;  // one slot is the lit page's
}

std::vector<uint32_t> coarsenViewsForBudget(const ShadowPlan& plan, std::span<const uint32_t> ranks,
                                            const ShadowPageCounts& counts, std::vector<uint32_t> coarser,
                                            uint64_t capacity, const std::string& budgetName) {
    coarser.resize(plan.views.size(), 0);
    // Views from the least important light's down (a light's views stay together: same rank).
    std::vector<uint32_t> order(plan.views.size());
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return ranks[a] > ranks[b]; });
    uint64_t estimate = counts.total();
    bool changed = false;
    for (size_t i = 0; i < order.size() && estimate > capacity;) {
        // The whole light: its views share its rank and follow each other.
        size_t end = i;
        while (end < order.size() && ranks[order[end]] == ranks[order[i]]) ++end;
        for (; i < end; ++i) {
            const uint32_t v = order[i];
            if (counts.perView[v] == 0 || coarser[v] + 1 >= kLevels) continue;
            ++coarser[v];
            changed = true;
            estimate -= counts.perView[v] - std::max<uint64_t>((counts.perView[v] + 3) / 4, 1);
        }
    }
    if (!changed) {
        throw Error(budgetName, "too small for virtual shadow pages: " + std::to_string(counts.total()) +
                                    " pages are needed at every view's coarsest level, " + std::to_string(capacity) +
                                    " fit beside the cascades");
    }
    return coarser;
}

namespace {

// A caster's rectangle in its view's NDC (min xy, max xy): its bounds' eight corners projected; a
// corner at or behind the light's plane (w <= 0) makes it the whole view.
glm::vec4 casterNdcRect(const Bounds& bounds, const glm::mat4& viewProjection) {
    glm::vec4 rect(1.0f, 1.0f, -1.0f, -1.0f);
    for (uint32_t corner = 0; corner < 8; ++corner) {
        const glm::vec3 p((corner & 1) ? bounds.max.x : bounds.min.x, (corner & 2) ? bounds.max.y : bounds.min.y,
                          (corner & 4) ? bounds.max.z : bounds.min.z);
        const glm::vec4 clip = viewProjection * glm::vec4(p, 1.0f);
        if (!(clip.w > 1e-6f)) return glm::vec4(-1.0f, -1.0f, 1.0f, 1.0f);
        const glm::vec2 ndc = glm::vec2(clip) / clip.w;
        rect = glm::vec4(glm::min(glm::vec2(rect), ndc), glm::max(glm::vec2(rect.z, rect.w), ndc));
    }
    return rect;
}

}  // namespace

ShadowPageDraws shadowPageDraws(const Scene& scene, const ShadowPlan& plan, const ShadowPageAllocation& allocation) {
    // The pages of each view, in slot order.
    std::vector<std::vector<uint32_t>> slotsOfView(plan.views.size());
    for (uint32_t slot = 0; slot < allocation.pages.size(); ++slot) slotsOfView[allocation.pages[slot].view].push_back(slot);
    ShadowPageDraws result;
    for (uint32_t v = 0; v < plan.views.size(); ++v) {
        if (slotsOfView[v].empty()) continue;
        const ShadowView& view = plan.views[v];
        for (const uint32_t object : view.casters) {
            const glm::vec4 rect = casterNdcRect(scene.objects[object].worldBounds, view.gpu.viewProjection);
            ShadowPageDraws::Draw draw{v, object, uint32_t(result.instances.size()), 0};
            for (const uint32_t slot : slotsOfView[v]) {
                const ShadowPage& page = allocation.pages[slot];
                const glm::vec3 square = gpu::virtualShadowPageNdc(page.level, glm::uvec2(page.column, page.row));
                // Widened by a texel (the slot's half side is `square.z`, the slot 33 texels): a
                // triangle that only grazes the slot still covers the texel centres it must.
                const float reach = square.z * (1.0f + 2.0f / float(kSlot));
                if (rect.x > square.x + reach || rect.z < square.x - reach || rect.y > square.y + reach ||
                    rect.w < square.y - reach) {
                    continue;
                }
                result.instances.emplace_back(v, page.level, page.column | page.row << 16, slot);
                ++draw.instanceCount;
            }
            if (draw.instanceCount > 0) result.draws.push_back(draw);
        }
    }
    return result;
}

}  // namespace punctual
