// Virtual shadow pages' allocation (lights/shadow_page_allocation.h): known answers for the page
// table, the pool's place in the atlas, the budget's coarsening and the casters each page draws.
#include <gtest/gtest.h>

#include "core/error.h"
#include "lights/shadow_page_allocation.h"
#include "scene/study_scenes.h"
#include "shadow_pages.h"

namespace punctual {
namespace {

constexpr uint32_t kWords = ShadowPageMarkLayout::kWordsPerView;

// A plan of `views` spot views, each with one caster (object 0) and a map.
ShadowPlan planOfViews(uint32_t views) {
    ShadowPlan plan;
    for (uint32_t v = 0; v < views; ++v) {
        ShadowView view;
        view.casters = {0};
        view.resolution = PUNCTUAL_VIRTUAL_SHADOW_SIZE;
        view.packedLight = v;
        view.tanSpan = 2.0f;
        view.gpu.viewProjection = glm::mat4(1.0f);  // NDC = world xy, w = 1
        plan.views.push_back(view);
    }
    return plan;
}

void mark(std::vector<uint32_t>& marks, const ShadowPageMarkLayout& layout, uint32_t view, uint32_t level, uint32_t x,
          uint32_t y) {
    const uint32_t index = gpu::virtualShadowPageIndex(glm::uvec2(x, y), level, PUNCTUAL_VIRTUAL_SHADOW_SIZE,
                                                       PUNCTUAL_VIRTUAL_SHADOW_PAGE);
    marks[layout.firstWord[view] + index / 32] |= 1u << (index % 32);
}

TEST(ShadowPageAllocation, TheLayoutCountsEveryPageOfEveryLevel) {
    // 16384 / 32 = 512 pages across level 0, then 256, ..., 1: (4^10 - 1) / 3 pages.
    EXPECT_EQ(ShadowPageMarkLayout::kPagesPerView, 349525u);
    EXPECT_EQ(ShadowPageMarkLayout::kWordsPerView, 10923u);
    ShadowPlan plan = planOfViews(3);
    plan.views[1].casters.clear();  // no caster: no map, no marks
    const ShadowPageMarkLayout layout = ShadowPageMarkLayout::of(plan);
    EXPECT_EQ(layout.firstWord, (std::vector<uint32_t>{0u, PUNCTUAL_NO_SHADOW_PAGE, kWords}));
    EXPECT_EQ(layout.words, 2 * kWords);
}

TEST(ShadowPageAllocation, TheTableCoversEachLevelsRectangleOfMarkedPages) {
    const ShadowPlan plan = planOfViews(2);
    const ShadowPageMarkLayout layout = ShadowPageMarkLayout::of(plan);
    std::vector<uint32_t> marks(layout.words, 0u);
    // View 0, level 4 (32 pages across): an L of three pages from (5, 7) to (6, 8).
    mark(marks, layout, 0, 4, 5, 7);
    mark(marks, layout, 0, 4, 5, 8);
    mark(marks, layout, 0, 4, 6, 8);
    // View 1, level 9 (one page).
    mark(marks, layout, 1, 9, 0, 0);
    const ShadowPageCounts counts = countMarkedPages(layout, marks);
    EXPECT_EQ(counts.total(), 4u);
    EXPECT_EQ(counts.perLevel[4], 3u);
    EXPECT_EQ(counts.perView, (std::vector<uint64_t>{3u, 1u}));

    const ShadowPageAllocation allocation = allocateShadowPages(layout, marks, {});
    ASSERT_EQ(allocation.pages.size(), 4u);
    // Slots in (view, level, row, column) order.
    EXPECT_EQ(allocation.pages[0].column, 5u);
    EXPECT_EQ(allocation.pages[0].row, 7u);
    EXPECT_EQ(allocation.pages[1].column, 5u);
    EXPECT_EQ(allocation.pages[2].column, 6u);
    EXPECT_EQ(allocation.pages[3].view, 1u);
    // View 0's level 4: a 2 x 2 rectangle from (5, 7), its (6, 7) entry empty.
    EXPECT_EQ(allocation.views[0].levels[4], glm::uvec4(0u, 5u | 7u << 16, 2u | 2u << 16, 0u));
    EXPECT_EQ(allocation.table[0], 0u);
    EXPECT_EQ(allocation.table[1], PUNCTUAL_NO_SHADOW_PAGE);
    EXPECT_EQ(allocation.table[2], 1u);
    EXPECT_EQ(allocation.table[3], 2u);
    EXPECT_EQ(allocation.views[0].levels[3].x, PUNCTUAL_NO_SHADOW_PAGE);
    EXPECT_EQ(allocation.views[1].levels[9], glm::uvec4(4u, 0u, 1u | 1u << 16, 0u));
    EXPECT_EQ(allocation.table[4], 3u);
    EXPECT_EQ(allocation.pagesPerLevel[4], 3u);
    EXPECT_EQ(allocation.litSlot(), 4u);
    // Five 33 x 33 slots (the lit page's too) of D16.
    EXPECT_EQ(allocation.physicalBytes(2), 5u * 33u * 33u * 2u);
}

TEST(ShadowPageAllocation, ThePoolFillsWhatTheCascadesLeave) {
    ShadowPlan plan = planOfViews(1);
    ShadowPageAllocation allocation;
    allocation.pageSlots = 99;  // 100 slots with the lit page
    placeShadowPagePool(plan, allocation, 16384);
    EXPECT_EQ(allocation.belowAcross, 64u);
    EXPECT_EQ(allocation.besideAcross, 0u);
    EXPECT_EQ(plan.atlas.width, 64u * 33u);
    EXPECT_EQ(plan.atlas.height, 2u * 33u);
    EXPECT_EQ(gpu::virtualShadowSlotOrigin(65, allocation.squares, allocation.besideAcross, allocation.belowAcross),
              glm::uvec2(33u, 33u));

    // Below cascades 2048 wide and 1024 tall: 62 slots a row (2048 / 33).
    ShadowPlan withCascades = planOfViews(1);
    withCascades.atlas.width = 2048;
    withCascades.atlas.height = 1024;
    // The cascades' 2048 x 1024 at 2 bytes leave (64 MiB - 4 MiB) for 33 x 33 slots, one the lit page's.
    EXPECT_EQ(shadowPagePoolCapacity(withCascades, 64ull << 20, 2), (60ull << 20) / (33 * 33 * 2) - 1);
    placeShadowPagePool(withCascades, allocation, 16384);
    EXPECT_EQ(allocation.belowAcross, 62u);
    EXPECT_EQ(withCascades.atlas.width, 2048u);
    EXPECT_EQ(withCascades.atlas.height, 1024u + 2u * 33u);
    EXPECT_EQ(gpu::virtualShadowSlotOrigin(0, allocation.squares, 0, 62), glm::uvec2(0u, 1024u));

    // 6,000 slots are too tall at 2048 (97 rows of 62 below 1024: 4,225 > 4,096): the width
    // doubles, and the band beside the cascades (62 slots a row, 31 rows of 33 in 1024) fills
    // first with 1,922 slots; the other 4,078 go below, 124 a row (33 rows).
    ShadowPlan doubled = planOfViews(1);
    doubled.atlas.width = 2048;
    doubled.atlas.height = 1024;
    allocation.pageSlots = 5999;
    placeShadowPagePool(doubled, allocation, 4096);
    EXPECT_EQ(doubled.atlas.width, 4096u);
    EXPECT_EQ(allocation.besideAcross, 62u);
    EXPECT_EQ(allocation.belowAcross, 124u);
    EXPECT_EQ(doubled.atlas.height, 1024u + 33u * 33u);
    EXPECT_EQ(gpu::virtualShadowSlotOrigin(63, allocation.squares, 62, 124), glm::uvec2(2048u + 33u, 33u));
    EXPECT_EQ(gpu::virtualShadowSlotOrigin(1922 + 125, allocation.squares, 62, 124), glm::uvec2(33u, 1024u + 33u));

    ShadowPlan tight = planOfViews(1);
    allocation.pageSlots = 20000;
    EXPECT_THROW(placeShadowPagePool(tight, allocation, 512), Error);
}

TEST(ShadowPageAllocation, CoarseningTakesTheLeastImportantLightsFirstAndWholeLights) {
    const ShadowPlan plan = planOfViews(4);
    ShadowPageCounts counts;
    counts.perView = {400, 400, 400, 400};
    counts.perLevel[3] = 1600;
    // Ranks: views 2 and 3 are one light's (rank 3), view 1 the next least important.
    const std::vector<uint32_t> ranks = {1, 2, 3, 3};
    // Coarsening one view saves 300 pages: 1300 needs the whole light of views 2 and 3 (1000).
    std::vector<uint32_t> coarser = coarsenViewsForBudget(plan, ranks, counts, {}, 1300, "--shadow-budget 1");
    EXPECT_EQ(coarser, (std::vector<uint32_t>{0, 0, 1, 1}));
    coarser = coarsenViewsForBudget(plan, ranks, counts, {}, 900, "--shadow-budget 1");
    EXPECT_EQ(coarser, (std::vector<uint32_t>{0, 1, 1, 1}));
    // Every view at its coarsest already: nothing left to give.
    const std::vector<uint32_t> coarsest(4, PUNCTUAL_VIRTUAL_SHADOW_LEVELS - 1);
    EXPECT_THROW(coarsenViewsForBudget(plan, ranks, counts, coarsest, 10, "--shadow-budget 1"), Error);
}

TEST(ShadowPageAllocation, ASlotsSquareIsItsPageAndTheNeighboursFirstTexels) {
    // Level 9 is 32 texels across, the whole view: page (0, 0)'s slot spans 33 texels from NDC -1.
    const glm::vec3 whole = gpu::virtualShadowPageNdc(9, glm::uvec2(0, 0));
    EXPECT_FLOAT_EQ(whole.z, 33.0f / 32.0f);
    EXPECT_FLOAT_EQ(whole.x, -1.0f + 33.0f / 32.0f);
    // Level 0: 16384 texels; page (3, 5) starts at texels (96, 160).
    const glm::vec3 page = gpu::virtualShadowPageNdc(0, glm::uvec2(3, 5));
    EXPECT_FLOAT_EQ(page.z, 33.0f / 16384.0f);
    EXPECT_FLOAT_EQ(page.x, -1.0f + 2.0f * 96.0f / 16384.0f + 33.0f / 16384.0f);
    EXPECT_FLOAT_EQ(page.y, -1.0f + 2.0f * 160.0f / 16384.0f + 33.0f / 16384.0f);
}

TEST(ShadowPageAllocation, EachCasterDrawsOnlyThePagesItsBoundsMeet) {
    // Identity projection: a view's NDC is world xy. One small box at NDC (0.5, 0.5).
    Scene scene;
    study::addBox(scene, glm::vec3(0.5f, 0.5f, 0.5f), glm::vec3(0.01f));
    scene.computeBounds();
    const ShadowPlan plan = planOfViews(1);
    const ShadowPageMarkLayout layout = ShadowPageMarkLayout::of(plan);
    std::vector<uint32_t> marks(layout.words, 0u);
    // Level 8 (2 pages across): page (1, 1) holds NDC (0.5, 0.5); page (0, 0) does not.
    mark(marks, layout, 0, 8, 0, 0);
    mark(marks, layout, 0, 8, 1, 1);
    const ShadowPageAllocation allocation = allocateShadowPages(layout, marks, {});
    const std::vector<std::vector<uint32_t>> casters = shadowPageCasters(scene, plan, allocation);
    EXPECT_EQ(casters, (std::vector<std::vector<uint32_t>>{{}, {0u}}));
    const ShadowPageDraws draws = shadowPageDraws(plan, allocation, casters, {}, 2048);
    ASSERT_EQ(draws.draws.size(), 1u);
    EXPECT_EQ(draws.draws[0].instanceCount, 1u);
    // Page 1 is drawn into layer 1 of the one batch, whose layers go to slots 0 and 1.
    EXPECT_EQ(draws.instances.at(0), glm::uvec4(0u, 8u, 1u | 1u << 16, 1u));
    ASSERT_EQ(draws.batches.size(), 1u);
    EXPECT_EQ(draws.batches[0].slots, (std::vector<uint32_t>{0u, 1u}));
    EXPECT_EQ(draws.pagesDrawn, 2u);
    EXPECT_EQ(draws.pagesWithCasters, 1u);
}

TEST(ShadowPageAllocation, PagesGoToTheirSlotsInBatchesOfLayers) {
    // Four pages of level 8, every one met by the caster (bounds over the whole view).
    Scene scene;
    study::addBox(scene, glm::vec3(0.0f, 0.0f, 0.5f), glm::vec3(2.0f, 2.0f, 0.01f));
    scene.computeBounds();
    const ShadowPlan plan = planOfViews(1);
    const ShadowPageMarkLayout layout = ShadowPageMarkLayout::of(plan);
    std::vector<uint32_t> marks(layout.words, 0u);
    for (uint32_t row = 0; row < 2; ++row) {
        for (uint32_t column = 0; column < 2; ++column) mark(marks, layout, 0, 8, column, row);
    }
    ShadowPageAllocation allocation = allocateShadowPages(layout, marks, {});
    ASSERT_EQ(allocation.pages.size(), 4u);
    // A cache's slots: pages 0..3 in slots 7, 2, 5, 0 of a pool of 8; the table follows.
    assignPageSlots(allocation, {7u, 2u, 5u, 0u}, 8u);
    EXPECT_EQ(allocation.table, (std::vector<uint32_t>{7u, 2u, 5u, 0u}));
    EXPECT_EQ(allocation.litSlot(), 8u);
    EXPECT_EQ(allocation.physicalBytes(2), 9u * 33u * 33u * 2u);
    // Pages 0, 2 and 3 drawn (1 kept), two layers a batch: {0, 2} then {3}, a draw a batch.
    const std::vector<std::vector<uint32_t>> casters = shadowPageCasters(scene, plan, allocation);
    const ShadowPageDraws draws = shadowPageDraws(plan, allocation, casters, {true, false, true, true}, 2);
    ASSERT_EQ(draws.batches.size(), 2u);
    EXPECT_EQ(draws.batches[0].slots, (std::vector<uint32_t>{7u, 5u}));
    EXPECT_EQ(draws.batches[1].slots, (std::vector<uint32_t>{0u}));
    ASSERT_EQ(draws.draws.size(), 2u);
    EXPECT_EQ(draws.batches[1].firstDraw, 1u);
    EXPECT_EQ(draws.instances.at(1), glm::uvec4(0u, 8u, 0u | 1u << 16, 1u));  // page 2, layer 1
    EXPECT_EQ(draws.instances.at(2), glm::uvec4(0u, 8u, 1u | 1u << 16, 0u));  // page 3, layer 0
    EXPECT_EQ(draws.largestBatch(), 2u);
    EXPECT_EQ(draws.pagesDrawn, 3u);
    // Nothing drawn: one empty batch all the same (it writes the lit slot).
    const ShadowPageDraws none = shadowPageDraws(plan, allocation, casters, std::vector<bool>(4, false), 2);
    ASSERT_EQ(none.batches.size(), 1u);
    EXPECT_TRUE(none.batches[0].slots.empty());
    EXPECT_TRUE(none.draws.empty());
    // A slot given twice is refused.
    ShadowPageAllocation again = allocateShadowPages(layout, marks, {});
    EXPECT_ANY_THROW(assignPageSlots(again, {1u, 1u, 2u, 3u}, 4u));
}

}  // namespace
}  // namespace punctual
