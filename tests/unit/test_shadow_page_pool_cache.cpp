// The cached page pool (lights/shadow_page_pool_cache.h): pages keep their slots while marked,
// keep their depth while their signature holds, and newcomers take the lowest free slots.
#include <algorithm>

#include <gtest/gtest.h>

#include "lights/shadow_page_pool_cache.h"

namespace punctual {
namespace {

CachedPageRequest page(uint32_t light, uint32_t column, uint64_t signature) {
    return {ShadowPageKey{light, 0u, 3u, column, 0u}, signature};
}

TEST(ShadowPagePoolCache, AFirstFrameLaysOutWithSlackWithinTheBudget) {
    ShadowPagePoolCache pool;
    const std::vector<CachedPageRequest> eight = {page(0, 0, 1), page(0, 1, 1), page(0, 2, 1), page(0, 3, 1),
                                                  page(1, 0, 1), page(1, 1, 1), page(1, 2, 1), page(1, 3, 1)};
    const ShadowPagePoolFrame first = pool.place(eight, glm::uvec2(0u), 1000);
    EXPECT_TRUE(first.laidOut);
    EXPECT_EQ(first.capacity, 10u);  // ceil(8 x 1.25)
    EXPECT_EQ(first.slots, (std::vector<uint32_t>{0, 1, 2, 3, 4, 5, 6, 7}));
    EXPECT_EQ(std::count(first.kept.begin(), first.kept.end(), true), 0);
    // The budget leaves 9 slots: 9 it is; it leaves 5: never fewer than the pages, 8.
    ShadowPagePoolCache tight;
    EXPECT_EQ(tight.place(eight, glm::uvec2(0u), 9).capacity, 9u);
    ShadowPagePoolCache tighter;
    EXPECT_EQ(tighter.place(eight, glm::uvec2(0u), 5).capacity, 8u);
}

TEST(ShadowPagePoolCache, MarkedPagesKeepTheirSlotsAndUnchangedOnesTheirDepth) {
    ShadowPagePoolCache pool;
    pool.place({page(0, 0, 1), page(0, 1, 1), page(0, 2, 1), page(0, 3, 1)}, glm::uvec2(0u), 100);  // capacity 5
    // Page 0 is gone (slot 0 free), page 2's casters changed, page 9 is new: it takes slot 0, and
    // page 10 the next free, slot 4.
    const ShadowPagePoolFrame second =
        pool.place({page(0, 1, 1), page(0, 2, 2), page(0, 3, 1), page(0, 9, 1), page(0, 10, 1)}, glm::uvec2(0u), 100);
    EXPECT_FALSE(second.laidOut);
    EXPECT_EQ(second.capacity, 5u);
    EXPECT_EQ(second.slots, (std::vector<uint32_t>{1, 2, 3, 0, 4}));
    EXPECT_EQ(second.kept, (std::vector<bool>{true, false, true, false, false}));
    // Unchanged again: everything kept where it is.
    const ShadowPagePoolFrame third =
        pool.place({page(0, 1, 1), page(0, 2, 2), page(0, 3, 1), page(0, 9, 1), page(0, 10, 1)}, glm::uvec2(0u), 100);
    EXPECT_EQ(third.slots, second.slots);
    EXPECT_EQ(third.kept, std::vector<bool>(5, true));
    // Another light's page with the same place is another page.
    const ShadowPagePoolFrame fourth = pool.place({page(1, 1, 1)}, glm::uvec2(0u), 100);
    EXPECT_EQ(fourth.kept, std::vector<bool>{false});
}

TEST(ShadowPagePoolCache, OutgrowingThePoolOrMovingCascadesLaysOutAfresh) {
    ShadowPagePoolCache pool;
    pool.place({page(0, 0, 1), page(0, 1, 1)}, glm::uvec2(0u), 100);  // capacity 3
    EXPECT_TRUE(pool.laidOutBeside(glm::uvec2(0u)));
    EXPECT_FALSE(pool.laidOutBeside(glm::uvec2(1024u, 512u)));
    const ShadowPagePoolFrame grown =
        pool.place({page(0, 0, 1), page(0, 1, 1), page(0, 2, 1), page(0, 3, 1)}, glm::uvec2(0u), 100);
    EXPECT_TRUE(grown.laidOut);
    EXPECT_EQ(grown.capacity, 5u);
    EXPECT_EQ(grown.kept, std::vector<bool>(4, false));
    const ShadowPagePoolFrame moved =
        pool.place({page(0, 0, 1), page(0, 1, 1), page(0, 2, 1), page(0, 3, 1)}, glm::uvec2(1024u, 512u), 100);
    EXPECT_TRUE(moved.laidOut);
    EXPECT_EQ(moved.kept, std::vector<bool>(4, false));
}

}  // namespace
}  // namespace punctual
