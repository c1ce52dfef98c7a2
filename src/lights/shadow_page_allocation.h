#pragma once
// Virtual shadow pages (--shadow-res virtual), the allocation: from the marking pass's bits to the
// pool's slots, the page table the forward pass reads, and the pages the shadow pass draws, each
// with the casters whose bounds meet it.
//
// Marks: one bit per page of every level (shaders/shared/shadow_pages.h: level 0's pages first, row
// by row), per view with a map (a spot view or point face with casters); a view without one has
// no marks and is lit everywhere, as in every mode.
//
// Pool: the allocated pages are 33 x 33 squares of the atlas (PUNCTUAL_VIRTUAL_SHADOW_SLOT: a page
// and its neighbours' first column and row), around the sun's cascades (virtualShadowSlotOrigin),
// then the lit page; slot i is page i in (view, level, row, column) order, unless the shadow cache
// keeps pages where they were (assignPageSlots). Each page is drawn at the same origin whatever its
// slot (render/shadow_page_layers.h), so where it lies changes no texel. The page table covers, per
// view and level with a marked page, the rectangle of its marked pages (not the whole level: a
// view's level 0 alone has 512 x 512 pages), each entry a slot or PUNCTUAL_NO_SHADOW_PAGE.
//
// Budget: when the marked pages do not fit what --shadow-budget leaves beside the cascades, the
// views of the least important lights read one level coarser (GpuVirtualShadowView::marks.y), all
// six faces of a point light together, and the frame is marked again: every page a receiver reads
// is then marked and allocated, at the coarser level (coarsenViewsForBudget).
#include <algorithm>
#include <array>
#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "gpu_types.h"
#include "lights/light_setup.h"
#include "lights/shadow_setup.h"
#include "scene/scene.h"

namespace punctual {

// Where each view's marks are in the marking pass's buffer.
struct ShadowPageMarkLayout {
    std::vector<uint32_t> firstWord;  // per plan view: its first word, PUNCTUAL_NO_SHADOW_PAGE without a map
    uint32_t words = 0;               // over every view

    static constexpr uint32_t kPagesPerView = [] {
        uint32_t pages = 0;
        for (uint32_t level = 0; level < PUNCTUAL_VIRTUAL_SHADOW_LEVELS; ++level) {
            // virtualShadowPagesAcross, evaluated at compile time
            const uint32_t across = std::max((PUNCTUAL_VIRTUAL_SHADOW_SIZE >> level) / PUNCTUAL_VIRTUAL_SHADOW_PAGE, 1u);
            pages += across * across;
        }
        return pages;
    }();
    static constexpr uint32_t kWordsPerView = (kPagesPerView + 31) / 32;

    // One block of kWordsPerView words for each spot view and point face of `plan` with casters.
    static ShadowPageMarkLayout of(const ShadowPlan& plan);
};

struct ShadowPage {
    uint32_t view = 0;  // plan view
    uint32_t level = 0;
    uint32_t column = 0;
    uint32_t row = 0;
};

// The pages marked in `marks`, per level (over every view), and per view.
struct ShadowPageCounts {
    std::array<uint64_t, PUNCTUAL_VIRTUAL_SHADOW_LEVELS> perLevel{};
    std::vector<uint64_t> perView;
    uint64_t total() const;
};
ShadowPageCounts countMarkedPages(const ShadowPageMarkLayout& layout, std::span<const uint32_t> marks);

struct ShadowPageAllocation {
    std::vector<gpu::GpuVirtualShadowView> views;  // per plan view (cascades and views without a map: no pages)
    std::vector<uint32_t> table;                   // the page table's entries: slots
    std::vector<ShadowPage> pages;                 // the marked pages, in (view, level, row, column) order
    std::vector<uint32_t> slotOfPage;              // per page: its slot (page i's is i, unless assignPageSlots)
    uint32_t pageSlots = 0;                        // the pool's slots for pages: pages.size(), or the cache's
    std::array<uint64_t, PUNCTUAL_VIRTUAL_SHADOW_LEVELS> pagesPerLevel{};
    // Where the slots are (shaders/shared/shadow_pages.h, virtualShadowSlotOrigin): beside the
    // cascades' squares (`squares` texels at the atlas's top left), `besideAcross` slots a row,
    // then below them, `belowAcross` a row.
    glm::uvec2 squares{0u};
    uint32_t besideAcross = 0;
    uint32_t belowAcross = 1;

    // The pool's slots: the pages', then the lit page's (cleared, never drawn), which the lookups
    // read where a page has none (shadow_pages.glsl, PageBlock).
    uint64_t slots() const { return uint64_t(pageSlots) + 1; }
    uint32_t litSlot() const { return pageSlots; }
    uint64_t physicalBytes(uint32_t texelBytes) const {
        return slots() * PUNCTUAL_VIRTUAL_SHADOW_SLOT * PUNCTUAL_VIRTUAL_SHADOW_SLOT * texelBytes;
    }
    uint64_t tableBytes() const { return (table.size() + views.size() * sizeof(gpu::GpuVirtualShadowView) / 4) * 4; }
};

// Hysteresis in a sequence: fills plan.virtualReads' previous marks from settings.previousPageMarks
// (the views of this frame's plan whose light and face the previous frame marked) and its keep
// (2^settings.tierHysteresis). Nothing without virtual pages, hysteresis or previous marks.
void usePreviousPageMarks(ShadowPlan& plan, const FrameLights& lights, const ShadowSettings& settings);

// `marks` (a frame's, in `plan`'s layout) by (scene light index, face), for the next frame's
// ShadowSettings::previousPageMarks.
std::map<std::pair<uint32_t, uint32_t>, std::vector<uint32_t>> pageMarksByView(const ShadowPlan& plan,
                                                                              const FrameLights& lights,
                                                                              std::span<const uint32_t> marks);

// The records of a frame with no pages yet (every lookup lit), which the marking pass reads:
// each view's marks and its coarsening (`coarser`, per plan view; empty: none).
std::vector<gpu::GpuVirtualShadowView> unallocatedPageViews(const ShadowPageMarkLayout& layout,
                                                            std::span<const uint32_t> coarser);

// Gives every marked page a slot and builds the table; `coarser` as above.
ShadowPageAllocation allocateShadowPages(const ShadowPageMarkLayout& layout, std::span<const uint32_t> marks,
                                         std::span<const uint32_t> coarser);

// Puts page i in slot `slotOfPage[i]` of a pool of `pageSlots` slots (each slot at most one page's;
// the shadow cache's, render/shadow_cache.h): the table's entries follow. `allocation` must be as
// allocateShadowPages made it.
void assignPageSlots(ShadowPageAllocation& allocation, std::vector<uint32_t> slotOfPage, uint32_t pageSlots);

// Places the pool around what the atlas already holds (the cascades' squares; plan.atlas): rows
// of the atlas's width below them (64 slots when it has none), the width doubled while the pool
// would pass `maxSide`, which opens a band beside them that the pool fills first. Grows plan.atlas
// to hold it and moves the squares' views (their atlas UV) to the grown atlas. Throws Error when
// the pool cannot fit maxSide x maxSide.
void placeShadowPagePool(ShadowPlan& plan, ShadowPageAllocation& allocation, uint32_t maxSide);

// The pages the pool can hold beside the cascades: what remains of `budgetBytes` after plan.atlas,
// in slots of 33 x 33 texels of `texelBytes`, less the lit page's.
uint64_t shadowPagePoolCapacity(const ShadowPlan& plan, uint64_t budgetBytes, uint32_t texelBytes);

// When `counts` exceed `capacity`: one more coarser level for the views of the least important
// lights (`ranks`: per plan view, 0 the most important), a light's views together, until the
// estimate (a view's pages quartered, at least one) fits; returns the new `coarser`. Throws Error
// naming `budgetName` when every view already reads its coarsest level.
std::vector<uint32_t> coarsenViewsForBudget(const ShadowPlan& plan, std::span<const uint32_t> ranks,
                                            const ShadowPageCounts& counts, std::vector<uint32_t> coarser,
                                            uint64_t capacity, const std::string& budgetName);

// Per page of `allocation` (its index in pages): the casters of its view whose bounds meet it, in
// the view's order. A caster meets a page when its world bounds, projected through the view (bounds
// reaching behind the light meet every page), overlap the page's square (virtualShadowPageNdc)
// widened by a texel.
std::vector<std::vector<uint32_t>> shadowPageCasters(const Scene& scene, const ShadowPlan& plan,
                                                     const ShadowPageAllocation& allocation);

// The shadow pass's instanced draws (shaders/shared/shadow_page_draw.glsl), in batches: each batch's
// pages are drawn into the layers of an array, one page a layer, then copied into their slots
// (render/shadow_page_layers.h). In a batch, one draw per (view, caster) meeting any of the view's
// pages there, each instance one such page.
struct ShadowPageDraws {
    std::vector<glm::uvec4> instances;  // per instance: view, level, column | row << 16, layer in its batch
    struct Draw {
        uint32_t view = 0;
        uint32_t object = 0;
        uint32_t firstInstance = 0;
        uint32_t instanceCount = 0;
    };
    std::vector<Draw> draws;  // by batch, then by view, then by caster in the view's order
    struct Batch {
        std::vector<uint32_t> slots;  // layer i is copied into slot slots[i]
        size_t firstDraw = 0;
        size_t drawCount = 0;
    };
    std::vector<Batch> batches;  // at least one (the first also writes the lit slot)
    uint64_t pagesDrawn = 0;     // pages drawn (with or without a caster)
    uint64_t pagesWithCasters = 0;
    uint32_t largestBatch() const;
};

// The draws of the pages `drawn` marks (per page of `allocation`; empty: every page), with their
// casters (shadowPageCasters), in page order, at most `layersPerBatch` pages a batch.
ShadowPageDraws shadowPageDraws(const ShadowPlan& plan, const ShadowPageAllocation& allocation,
                                const std::vector<std::vector<uint32_t>>& pageCasters, const std::vector<bool>& drawn,
                                uint32_t layersPerBatch);

}  // namespace punctual
