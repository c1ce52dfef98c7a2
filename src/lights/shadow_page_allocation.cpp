#include "lights/shadow_page_allocation.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <numeric>

#include "core/check.h"
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

gpu::GpuVirtualShadowView noPages(uint32_t firstWord, uint32_t coarser) {
    gpu::GpuVirtualShadowView view{};
    view.marks = glm::uvec4(firstWord, coarser, PUNCTUAL_NO_SHADOW_PAGE, 0u);  // (no previous marks: no hysteresis)
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

void usePreviousPageMarks(ShadowPlan& plan, const FrameLights& lights, const ShadowSettings& settings) {
    VirtualPageReads& reads = plan.virtualReads;
    if (!reads.enabled || !(settings.tierHysteresis > 0.0f) || settings.previousPageMarks.empty()) return;
    const ShadowPageMarkLayout layout = ShadowPageMarkLayout::of(plan);
    reads.keep = std::exp2(settings.tierHysteresis);
    reads.previousMarks.assign(std::max(layout.words, 1u), 0u);
    reads.previousFirstWord.assign(plan.views.size(), PUNCTUAL_NO_SHADOW_PAGE);
    for (size_t v = 0; v < plan.views.size(); ++v) {
        const uint32_t first = layout.firstWord[v];
        if (first == PUNCTUAL_NO_SHADOW_PAGE) continue;
        const ShadowView& view = plan.views[v];
        const auto previous = settings.previousPageMarks.find({lights.sceneLightIndex.at(view.packedLight), view.face});
        if (previous == settings.previousPageMarks.end()) continue;
        PUNCTUAL_CHECK(previous->second.size() == ShadowPageMarkLayout::kWordsPerView, "a view's previous page marks");
        std::copy(previous->second.begin(), previous->second.end(), reads.previousMarks.begin() + first);
        reads.previousFirstWord[v] = first;
    }
}

std::map<std::pair<uint32_t, uint32_t>, std::vector<uint32_t>> pageMarksByView(const ShadowPlan& plan,
                                                                              const FrameLights& lights,
                                                                              std::span<const uint32_t> marks) {
    const ShadowPageMarkLayout layout = ShadowPageMarkLayout::of(plan);
    std::map<std::pair<uint32_t, uint32_t>, std::vector<uint32_t>> byView;
    for (size_t v = 0; v < plan.views.size(); ++v) {
        const uint32_t first = layout.firstWord[v];
        if (first == PUNCTUAL_NO_SHADOW_PAGE || first + ShadowPageMarkLayout::kWordsPerView > marks.size()) continue;
        const ShadowView& view = plan.views[v];
        byView[{lights.sceneLightIndex.at(view.packedLight), view.face}] =
            std::vector<uint32_t>(marks.begin() + first, marks.begin() + first + ShadowPageMarkLayout::kWordsPerView);
    }
    return byView;
}

uint64_t ShadowPageCounts::total() const { return std::accumulate(perLevel.begin(), perLevel.end(), uint64_t(0)); }

namespace {

// Calls visit(level, page index within the level) for each marked page of the view whose marks
// start at `first`, in index order (level by level, row by row): set bits only, a word at a time
// (the marks are sparse: 9,000 pages of 84 million bits on the default scene).
template <typename Visit>
void forEachMarkedPage(std::span<const uint32_t> marks, uint32_t first, const std::array<uint32_t, kLevels + 1>& starts,
                       const Visit& visit) {
    uint32_t level = 0;
    for (uint32_t word = 0; word < ShadowPageMarkLayout::kWordsPerView; ++word) {
        for (uint32_t bits = marks[first + word]; bits != 0; bits &= bits - 1) {
            const uint32_t index = word * 32 + uint32_t(std::countr_zero(bits));
            while (index >= starts[level + 1]) ++level;
            visit(level, index - starts[level]);
        }
    }
}

}  // namespace

ShadowPageCounts countMarkedPages(const ShadowPageMarkLayout& layout, std::span<const uint32_t> marks) {
    const std::array<uint32_t, kLevels + 1> starts = levelStarts();
    ShadowPageCounts counts;
    counts.perView.assign(layout.firstWord.size(), 0);
    for (size_t v = 0; v < layout.firstWord.size(); ++v) {
        if (layout.firstWord[v] == PUNCTUAL_NO_SHADOW_PAGE) continue;
        forEachMarkedPage(marks, layout.firstWord[v], starts, [&](uint32_t level, uint32_t) {
            ++counts.perLevel[level];
            ++counts.perView[v];
        });
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
        if (layout.firstWord[v] == PUNCTUAL_NO_SHADOW_PAGE) continue;
        std::array<std::vector<glm::uvec2>, kLevels> marked;  // each level's marked pages, row by row
        forEachMarkedPage(marks, layout.firstWord[v], starts, [&](uint32_t level, uint32_t index) {
            marked[level].emplace_back(index % pagesAcross(level), index / pagesAcross(level));
        });
        for (uint32_t level = 0; level < kLevels; ++level) {
            if (marked[level].empty()) continue;  // no page at this level
            // The rectangle of the level's marked pages: the table covers it, no more.
            glm::uvec2 low(pagesAcross(level)), high(0u);
            for (const glm::uvec2& page : marked[level]) {
                low = glm::min(low, page);
                high = glm::max(high, page);
            }
            const glm::uvec2 size = high - low + 1u;
            const size_t base = allocation.table.size();
            allocation.views[v].levels[level] = glm::uvec4(uint32_t(base), low.x | low.y << 16, size.x | size.y << 16, 0u);
            allocation.table.resize(base + size_t(size.x) * size.y, PUNCTUAL_NO_SHADOW_PAGE);
            for (const glm::uvec2& page : marked[level]) {  // row by row: slots in (row, column) order
                const uint32_t slot = uint32_t(allocation.pages.size());
                allocation.table[base + size_t(page.y - low.y) * size.x + (page.x - low.x)] = slot;
                allocation.pages.push_back({uint32_t(v), level, page.x, page.y});
                allocation.slotOfPage.push_back(slot);
                ++allocation.pagesPerLevel[level];
            }
        }
    }
    allocation.pageSlots = uint32_t(allocation.pages.size());
    return allocation;
}

void assignPageSlots(ShadowPageAllocation& allocation, std::vector<uint32_t> slotOfPage, uint32_t pageSlots) {
    PUNCTUAL_CHECK(slotOfPage.size() == allocation.pages.size() && allocation.pageSlots == allocation.pages.size(),
                   "page slots assigned to an allocation as allocateShadowPages made it");
    std::vector<bool> taken(pageSlots, false);
    for (const uint32_t slot : slotOfPage) {
        PUNCTUAL_CHECK(slot < pageSlots && !taken[slot], "a page slot given twice or outside the pool");
        taken[slot] = true;
    }
    for (uint32_t& entry : allocation.table) {
        if (entry != PUNCTUAL_NO_SHADOW_PAGE) entry = slotOfPage[entry];  // entries were page indices
    }
    allocation.slotOfPage = std::move(slotOfPage);
    allocation.pageSlots = pageSlots;
}

void placeShadowPagePool(ShadowPlan& plan, ShadowPageAllocation& allocation, uint32_t maxSide) {
    const uint64_t slots = allocation.slots();
    const glm::uvec2 squares(plan.atlas.width, plan.atlas.height);  // the cascades' (0 x 0 without)
    // The squares' width, or without squares up to 64 slots; doubled while the pool would reach
    // past maxSide (each doubling opens a band beside the squares).
    uint64_t width = squares.x > 0 ? squares.x : std::min<uint64_t>(slots, 64) * kSlot;
    for (;;) {
        const uint64_t beside = squares.y >= kSlot && width > squares.x ? (width - squares.x) / kSlot : 0;
        const uint64_t across = width / kSlot;
        const uint64_t besideSlots = beside * (squares.y / kSlot);
        const uint64_t below = slots > besideSlots ? slots - besideSlots : 0;
        const uint64_t height = squares.y + (below + across - 1) / across * kSlot;
        if (height <= maxSide) {
            allocation.squares = squares;
            allocation.besideAcross = uint32_t(beside);
            allocation.belowAcross = uint32_t(across);
            plan.atlas.width = uint32_t(width);
            plan.atlas.height = uint32_t(height);
            break;
        }
        if (width * 2 > maxSide) {
            throw Error("--shadow-res virtual", std::to_string(slots) + " shadow pages do not fit the device's largest 2D image (" +
                                                    std::to_string(maxSide) + " texels a side)");
        }
        width *= 2;
    }
    // The views that keep a square (the cascades) find it in atlas UV: the atlas grew under them.
    for (ShadowView& view : plan.views) {
        if (view.rect.size > 0) view.gpu.atlasRect = atlasRectInUv(view.rect, plan.atlas);
    }
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

std::vector<std::vector<uint32_t>> shadowPageCasters(const Scene& scene, const ShadowPlan& plan,
                                                     const ShadowPageAllocation& allocation) {
    std::vector<std::vector<uint32_t>> pagesOfView(plan.views.size());
    for (uint32_t page = 0; page < allocation.pages.size(); ++page) pagesOfView[allocation.pages[page].view].push_back(page);
    std::vector<std::vector<uint32_t>> casters(allocation.pages.size());
    for (uint32_t v = 0; v < plan.views.size(); ++v) {
        if (pagesOfView[v].empty()) continue;
        const ShadowView& view = plan.views[v];
        for (const uint32_t object : view.casters) {
            const glm::vec4 rect = casterNdcRect(scene.objects[object].worldBounds, view.gpu.viewProjection);
            for (const uint32_t index : pagesOfView[v]) {
                const ShadowPage& page = allocation.pages[index];
                const glm::vec3 square = gpu::virtualShadowPageNdc(page.level, glm::uvec2(page.column, page.row));
                // Widened by a texel (the slot's half side is `square.z`, the slot 33 texels): a
                // triangle that only grazes the slot still covers the texel centres it must.
                const float reach = square.z * (1.0f + 2.0f / float(kSlot));
                if (rect.x > square.x + reach || rect.z < square.x - reach || rect.y > square.y + reach ||
                    rect.w < square.y - reach) {
                    continue;
                }
                casters[index].push_back(object);
            }
        }
    }
    return casters;
}

uint32_t ShadowPageDraws::largestBatch() const {
    size_t largest = 0;
    for (const Batch& batch : batches) largest = std::max(largest, batch.slots.size());
    return uint32_t(largest);
}

namespace {

// One batch's draws: for each run of pages of one view (pages `order[first, end)`), each caster of
// the view over the pages of the run it meets (layer = the page's place in the batch).
void addBatchDraws(const ShadowPlan& plan, const ShadowPageAllocation& allocation,
                   const std::vector<std::vector<uint32_t>>& pageCasters, const std::vector<uint32_t>& order,
                   size_t first, size_t end, ShadowPageDraws& result) {
    for (size_t run = first; run < end;) {
        const uint32_t v = allocation.pages[order[run]].view;
        size_t runEnd = run;
        while (runEnd < end && allocation.pages[order[runEnd]].view == v) ++runEnd;
        std::map<uint32_t, std::vector<size_t>> pagesOfCaster;  // object: its pages (places in order)
        for (size_t k = run; k < runEnd; ++k) {
            for (const uint32_t object : pageCasters[order[k]]) pagesOfCaster[object].push_back(k);
        }
        for (const uint32_t object : plan.views[v].casters) {
            const auto found = pagesOfCaster.find(object);
            if (found == pagesOfCaster.end()) continue;
            result.draws.push_back({v, object, uint32_t(result.instances.size()), uint32_t(found->second.size())});
            for (const size_t k : found->second) {
                const ShadowPage& page = allocation.pages[order[k]];
                result.instances.emplace_back(v, page.level, page.column | page.row << 16, uint32_t(k - first));
            }
        }
        run = runEnd;
    }
}

}  // namespace

ShadowPageDraws shadowPageDraws(const ShadowPlan& plan, const ShadowPageAllocation& allocation,
                                const std::vector<std::vector<uint32_t>>& pageCasters, const std::vector<bool>& drawn,
                                uint32_t layersPerBatch) {
    PUNCTUAL_CHECK(layersPerBatch > 0 && pageCasters.size() == allocation.pages.size() &&
                       (drawn.empty() || drawn.size() == allocation.pages.size()),
                   "page draws of an allocation's pages");
    std::vector<uint32_t> order;  // the pages drawn, in page order (a view's pages together)
    for (uint32_t page = 0; page < allocation.pages.size(); ++page) {
        if (drawn.empty() || drawn[page]) order.push_back(page);
    }
    ShadowPageDraws result;
    result.pagesDrawn = order.size();
    for (const uint32_t page : order) result.pagesWithCasters += !pageCasters[page].empty();
    size_t first = 0;
    do {
        const size_t end = std::min(order.size(), first + layersPerBatch);
        ShadowPageDraws::Batch batch;
        batch.firstDraw = result.draws.size();
        addBatchDraws(plan, allocation, pageCasters, order, first, end, result);
        batch.drawCount = result.draws.size() - batch.firstDraw;
        for (size_t k = first; k < end; ++k) batch.slots.push_back(allocation.slotOfPage[order[k]]);
        result.batches.push_back(std::move(batch));
        first = end;
    } while (first < order.size());
    return result;
}

}  // namespace punctual
