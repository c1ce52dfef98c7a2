// The cached shadow atlas (lights/shadow_atlas_cache.h): a fresh layout worked by hand, views that
// keep their squares and their depth while nothing changes, a view whose signature or size changes
// drawn again without moving the others, freed blocks merging back, fresh layouts where no block
// is left, and over a long random sequence squares that never overlap or leave the atlas.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "core/error.h"
#include "lights/shadow_atlas_cache.h"

namespace punctual {
namespace {

CachedViewRequest view(uint32_t light, uint32_t size, uint64_t signature = 1) { return {{light, 0}, size, signature}; }

void expectRect(const AtlasRect& rect, uint32_t x, uint32_t y, uint32_t size) {
    EXPECT_EQ(rect.x, x);
    EXPECT_EQ(rect.y, y);
    EXPECT_EQ(rect.size, size);
}

// Sizes 1024, 512, 512, 256: 1,638,400 texels, times the slack 1.25 is 2,048,000, two roots of
// 1024^2 = 1,048,576: a 2 x 1 grid, 2048 x 1024. Largest first: the 1024 in the first root, the
// 512s (by key: lights 1, 2) in the second's top half, the 256 under the first 512.
TEST(ShadowAtlasCache, AFreshLayoutPlacesLargestFirstIntoBuddyBlocks) {
    ShadowAtlasCache cache(16384, 1024);
    const ShadowAtlasCacheFrame frame = cache.place({view(3, 256), view(2, 512), view(0, 1024), view(1, 512)});
    EXPECT_TRUE(frame.laidOut);
    EXPECT_EQ(frame.layout.width, 2048u);
    EXPECT_EQ(frame.layout.height, 1024u);
    expectRect(frame.layout.rects[2], 0, 0, 1024);
    expectRect(frame.layout.rects[3], 1024, 0, 512);
    expectRect(frame.layout.rects[1], 1536, 0, 512);
    expectRect(frame.layout.rects[0], 1024, 512, 256);
    EXPECT_EQ(frame.kept, (std::vector<bool>{false, false, false, false}));  // nothing drawn yet
}

TEST(ShadowAtlasCache, UnchangedViewsKeepTheirSquaresAndTheirDepth) {
    ShadowAtlasCache cache(16384, 1024);
    const std::vector<CachedViewRequest> views = {view(0, 1024), view(1, 512), view(2, 512), view(3, 256)};
    const ShadowAtlasCacheFrame first = cache.place(views);
    const ShadowAtlasCacheFrame second = cache.place(views);
    EXPECT_FALSE(second.laidOut);
    EXPECT_EQ(second.kept, (std::vector<bool>{true, true, true, true}));
    for (size_t i = 0; i < views.size(); ++i) {
        expectRect(second.layout.rects[i], first.layout.rects[i].x, first.layout.rects[i].y, first.layout.rects[i].size);
    }
    // A light or caster moved in view 1: its signature changed, so it alone is drawn again, in place.
    std::vector<CachedViewRequest> moved = views;
    moved[1].signature = 2;
    const ShadowAtlasCacheFrame third = cache.place(moved);
    EXPECT_EQ(third.kept, (std::vector<bool>{true, false, true, true}));
    expectRect(third.layout.rects[1], 1024, 0, 512);
    EXPECT_EQ(cache.place(moved).kept, (std::vector<bool>{true, true, true, true}));  // and kept after
}

// View 1 goes from 512 to 256 a side: it gives its block back (which cannot merge: view 2 holds a
// buddy) and takes the smallest free block that fits, the 256 beside view 3's under it; the others
// neither move nor are drawn.
TEST(ShadowAtlasCache, AViewThatChangesSizeMovesAloneAndIsDrawnAgain) {
    ShadowAtlasCache cache(16384, 1024);
    std::vector<CachedViewRequest> views = {view(0, 1024), view(1, 512), view(2, 512), view(3, 256)};
    cache.place(views);
    views[1].size = 256;
    const ShadowAtlasCacheFrame frame = cache.place(views);
    EXPECT_FALSE(frame.laidOut);
    EXPECT_EQ(frame.kept, (std::vector<bool>{true, false, true, true}));
    expectRect(frame.layout.rects[1], 1280, 512, 256);
    expectRect(frame.layout.rects[2], 1536, 0, 512);
    expectRect(frame.layout.rects[3], 1024, 512, 256);
}

// Views gone give their blocks back, and the four quarters of a block merge: after the 512s and
// the 256 leave, a second 1024 fits the second root without a new layout.
TEST(ShadowAtlasCache, FreedBlocksMergeWithTheirBuddies) {
    ShadowAtlasCache cache(16384, 1024);
    cache.place({view(0, 1024), view(1, 512), view(2, 512), view(3, 256)});
    const ShadowAtlasCacheFrame frame = cache.place({view(0, 1024), view(4, 1024)});
    EXPECT_FALSE(frame.laidOut);
    EXPECT_EQ(frame.kept, (std::vector<bool>{true, false}));
    expectRect(frame.layout.rects[1], 1024, 0, 1024);
}

// Roots are twice the largest view's side, up to the largest a view can take: four views of 512
// where 2048 is possible lay out on roots of 1024 (4 x 512^2 x 1.25 = 1.25 roots: 2 x 1), and one
// growing to 1024 finds a block there, moving nothing.
TEST(ShadowAtlasCache, RootsLeaveRoomForAViewToGrowATier) {
    ShadowAtlasCache cache(16384, 2048);
    std::vector<CachedViewRequest> views = {view(0, 512), view(1, 512), view(2, 512), view(3, 512)};
    const ShadowAtlasCacheFrame first = cache.place(views);
    EXPECT_EQ(first.layout.width, 2048u);
    EXPECT_EQ(first.layout.height, 1024u);
    views[3].size = 1024;
    const ShadowAtlasCacheFrame grown = cache.place(views);
    EXPECT_FALSE(grown.laidOut);
    EXPECT_EQ(grown.kept, (std::vector<bool>{true, true, true, false}));
    expectRect(grown.layout.rects[3], 1024, 0, 1024);
}

// A full grid (a device of 2048 a side: four roots of 1024) with 256-texel holes in four different
// 512 blocks: a new 512 takes the block whose views hold the fewest texels, top-left first (the
// one with three views left, at (1024, 0)), and those three move into the three holes left, top
// to bottom; every other view keeps its square and its depth.
TEST(ShadowAtlasCache, AViewWithoutAFreeBlockMovesTheFewestTexels) {
    ShadowAtlasCache cache(2048, 1024);
    std::vector<CachedViewRequest> views = {view(100, 1024)};
    for (uint32_t i = 0; i < 32; ++i) views.push_back(view(i, 256));  // the second and third roots, in Z order
    const ShadowAtlasCacheFrame first = cache.place(views);
    ASSERT_EQ(first.layout.width, 2048u);
    ASSERT_EQ(first.layout.height, 2048u);
    expectRect(first.layout.rects[1 + 5], 1792, 0, 256);
    expectRect(first.layout.rects[1 + 21], 768, 1024, 256);
    // Lights 0, 5, 16 and 21 leave (one hole in each of four 512 blocks); a 1024 fills the last root.
    std::vector<CachedViewRequest> next;
    for (const CachedViewRequest& v : views) {
        if (v.key.light != 0 && v.key.light != 5 && v.key.light != 16 && v.key.light != 21) next.push_back(v);
    }
    next.push_back(view(101, 1024));
    EXPECT_FALSE(cache.place(next).laidOut);
    next.push_back(view(102, 512));  // 4 Mi texels in all: the grid, exactly
    const ShadowAtlasCacheFrame frame = cache.place(next);
    EXPECT_FALSE(frame.laidOut);
    EXPECT_EQ(frame.moved, 3u);
    expectRect(frame.layout.rects.back(), 1024, 0, 512);
    size_t kept = 0;
    for (size_t i = 0; i < next.size(); ++i) {
        const uint32_t light = next[i].key.light;
        if (light == 1) expectRect(frame.layout.rects[i], 1792, 0, 256);
        if (light == 2) expectRect(frame.layout.rects[i], 0, 1024, 256);
        if (light == 3) expectRect(frame.layout.rects[i], 768, 1024, 256);
        const bool moved = light == 1 || light == 2 || light == 3 || light == 102;
        EXPECT_EQ(frame.kept[i], !moved) << light;
        kept += frame.kept[i];
    }
    EXPECT_EQ(kept, next.size() - 4);
}

// No block for a request: a view larger than the roots, or more texels than the grid holds. Every
// view is placed afresh and drawn.
TEST(ShadowAtlasCache, ARequestWithoutABlockLaysEveryViewOutAfresh) {
    ShadowAtlasCache cache(16384, 2048);
    cache.place({view(0, 512), view(1, 512)});
    const ShadowAtlasCacheFrame larger = cache.place({view(0, 512), view(1, 2048)});
    EXPECT_TRUE(larger.laidOut);
    EXPECT_EQ(larger.kept, (std::vector<bool>{false, false}));
    EXPECT_EQ(larger.layout.rects[1].size, 2048u);
    // (2048^2 + 512^2) x 1.25 texels = 1.33 roots of 2048: a 2 x 1 grid.
    EXPECT_EQ(larger.layout.width, 4096u);
    EXPECT_EQ(larger.layout.height, 2048u);
    std::vector<CachedViewRequest> many;
    for (uint32_t i = 0; i < 40; ++i) many.push_back(view(i, 2048));
    const ShadowAtlasCacheFrame full = cache.place(many);
    EXPECT_TRUE(full.laidOut);
    EXPECT_EQ(full.kept, std::vector<bool>(40, false));
}

TEST(ShadowAtlasCache, ViewsTooLargeForTheDeviceAreRefusedInOneLine) {
    ShadowAtlasCache cache(4096, 1024);
    std::vector<CachedViewRequest> many;
    for (uint32_t i = 0; i < 17; ++i) many.push_back(view(i, 1024));  // 17 roots: more than 4 x 4
    try {
        cache.place(many);
        FAIL() << "17 views of 1024 fit a 4096 atlas";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("--shadow-cache"), std::string::npos) << e.what();
    }
    // With 16 the slack does not fit, but the views do: laid out without it.
    many.pop_back();
    const ShadowAtlasCacheFrame frame = cache.place(many);
    EXPECT_EQ(frame.layout.width, 4096u);
    EXPECT_EQ(frame.layout.height, 4096u);
}

// 300 frames of views appearing, leaving, changing tier and signature at random (a fixed LCG):
// every square lies in the atlas, aligned to its own side, and overlaps no other; a view is kept
// only where its size and signature are last frame's; and most views are kept.
TEST(ShadowAtlasCache, SquaresNeverOverlapOverALongRandomSequence) {
    ShadowAtlasCache cache(16384, 1024);
    uint64_t state = 12345;
    auto next = [&](uint32_t n) {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        return uint32_t((state >> 33) % n);
    };
    std::vector<CachedViewRequest> views;
    for (uint32_t i = 0; i < 60; ++i) views.push_back(view(i, 64u << next(5), 1));
    size_t kept = 0;
    size_t placed = 0;
    for (int frame = 0; frame < 300; ++frame) {
        const std::vector<CachedViewRequest> before = views;
        for (CachedViewRequest& v : views) {
            const uint32_t roll = next(100);
            if (roll < 3) v.size = v.size == 0 ? 256 : 0;                   // leaves, or comes back
            else if (roll < 6 && v.size > 0) v.size = 64u << next(5);        // another tier
            else if (roll < 9) ++v.signature;                                // its light moved
        }
        const ShadowAtlasCacheFrame placedFrame = cache.place(views);
        const AtlasLayout& layout = placedFrame.layout;
        for (size_t i = 0; i < views.size(); ++i) {
            const AtlasRect& a = layout.rects[i];
            if (views[i].size == 0) continue;
            ++placed;
            kept += placedFrame.kept[i];
            ASSERT_EQ(a.size, views[i].size);
            ASSERT_LE(a.x + a.size, layout.width);
            ASSERT_LE(a.y + a.size, layout.height);
            ASSERT_EQ(a.x % a.size, 0u);
            ASSERT_EQ(a.y % a.size, 0u);
            if (placedFrame.kept[i]) {
                ASSERT_EQ(before[i].size, views[i].size);
                ASSERT_EQ(before[i].signature, views[i].signature);
            }
            for (size_t j = 0; j < i; ++j) {
                const AtlasRect& b = layout.rects[j];
                if (views[j].size == 0) continue;
                const bool apart = a.x + a.size <= b.x || b.x + b.size <= a.x || a.y + a.size <= b.y || b.y + b.size <= a.y;
                ASSERT_TRUE(apart) << "frame " << frame << ": views " << i << " and " << j;
            }
        }
    }
    EXPECT_GT(placed, 5'000u);
    EXPECT_GT(double(kept) / double(placed), 0.6);
}

}  // namespace
}  // namespace punctual
