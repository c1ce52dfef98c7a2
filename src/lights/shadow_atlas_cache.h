#pragma once
// Where cached shadow views live from frame to frame (--shadow-cache on, issue 34): an atlas whose
// squares stay put while their views keep their size, so that a view whose light and casters did
// not move keeps last frame's depth and is not drawn again (HDRP's cached shadow atlas, Unreal's
// cached virtual pages).
//
// The frame's own packing (lights/shadow_atlas.h) cannot be kept: it sorts the squares by size,
// so one view changing tier moves every smaller one. Here each square is a block of a buddy
// allocator instead. The atlas is a grid of root squares, each as large as the largest view when
// it was laid out; a view of side s takes a free block of side s, or splits the smallest larger
// free block into quarters until one is s (each quarter aligned to its own side); a freed block
// merges with its three buddies into their parent when all four are free. Power-of-two squares
// placed from largest to smallest never leave a hole that way, so a layout made afresh always
// fits what its roots hold. Later frames' changes fragment it: a request that finds no free block
// then takes the aligned block of its side whose views hold the fewest texels, and those views
// move (drawn again this frame, where they find room). Only when the views' texels outgrow the
// grid, a view outgrows the roots or no block can be emptied (each holds part of a larger view,
// or of one placed this frame) is every view laid out afresh (all of them drawn that frame).
//
// Laying out afresh makes the roots twice the largest view's side (up to the largest a view can
// take), so a view growing a tier past the others still finds a block, and sizes the grid for
// kSlack times the views' texels, so that views growing a tier find room without a new layout:
// memory traded for frames that keep their views (both are reported, bench/RESULTS.md "Frames in
// motion, second part").
#include <compare>
#include <cstddef>
#include <cstdint>
#include <map>
#include <set>
#include <utility>
#include <vector>

#include "lights/shadow_atlas.h"

namespace punctual {

// A view across frames: the scene light (its index in Scene::lights, which does not change as
// the frame's lights are ranked) and its face (0 for a spot, the cube face, or the cascade).
struct ShadowViewKey {
    uint32_t light = 0;
    uint32_t face = 0;
    auto operator<=>(const ShadowViewKey&) const = default;
};

// A view this frame: its key, its side (0: no storage) and what its depth is made of
// (shadowViewSignature, render/shadow_cache.h): equal signatures draw equal depths.
struct CachedViewRequest {
    ShadowViewKey key;
    uint32_t size = 0;
    uint64_t signature = 0;
};

struct ShadowAtlasCacheFrame {
    AtlasLayout layout;        // the cache's atlas: its size, and each request's square (request order)
    std::vector<bool> kept;    // per request: its square holds last frame's depth of the same signature
    bool laidOut = false;      // every view placed afresh this frame (first frame, or no block found)
    uint32_t moved = 0;        // views moved out of a block another view needed (drawn again)
};

class ShadowAtlasCache {
public:
    // `maxSide`: the device's largest 2D image side; `largestView`: the largest side a view can take
    // (auto's largest tier, or the fixed resolution).
    ShadowAtlasCache(uint32_t maxSide, uint32_t largestView);

    // Places this frame's views: each keeps its square while its size does, and is kept (not drawn)
    // where its signature is also unchanged. Views of earlier frames that are not requested give
    // their squares back. Throws Error when the views do not fit the device's largest atlas.
    ShadowAtlasCacheFrame place(const std::vector<CachedViewRequest>& requests);

    // Extra room a fresh layout leaves for views that grow (see above).
    static constexpr double kSlack = 1.25;

private:
    struct Entry {
        AtlasRect rect;
        uint64_t signature = 0;
    };
    // Block (x, y) of side `size`, free or taken.
    bool allocate(uint32_t size, AtlasRect& rect);
    void release(const AtlasRect& rect);
    // Empties the aligned block of side `size` whose views (none of `placedNow`, none larger) hold
    // the fewest texels, top-left first among equals: those views lose their squares and are
    // returned. False where every block holds part of a larger or just placed view.
    bool evictForBlock(uint32_t size, const std::set<ShadowViewKey>& placedNow, std::vector<ShadowViewKey>& evicted);
    // Every requested view placed afresh in a grid sized for them (kSlack).
    void layOut(const std::vector<CachedViewRequest>& requests);
    // The requests with storage, largest first (then by key): the order that never fragments.
    static std::vector<size_t> largestFirst(const std::vector<CachedViewRequest>& requests);

    uint32_t maxSide_;
    uint32_t largestView_;
    uint32_t width_ = 0;
    uint32_t height_ = 0;
    uint32_t root_ = 0;  // the side of the grid's root squares
    std::map<ShadowViewKey, Entry> entries_;
    std::map<uint32_t, std::set<std::pair<uint32_t, uint32_t>>> free_;  // by side: (y, x), top-left first
};

}  // namespace punctual
