#include "lights/shadow_atlas_cache.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/check.h"
#include "core/error.h"

namespace punctual {
namespace {

// The order views are placed in: largest first, then by key (deterministic).
bool placedBefore(const CachedViewRequest& a, const CachedViewRequest& b) {
    return a.size != b.size ? a.size > b.size : a.key < b.key;
}

}  // namespace

ShadowAtlasCache::ShadowAtlasCache(uint32_t maxSide, uint32_t largestView)
    : maxSide_(maxSide), largestView_(largestView) {}

std::vector<size_t> ShadowAtlasCache::largestFirst(const std::vector<CachedViewRequest>& requests) {
    std::vector<size_t> order;
    for (size_t i = 0; i < requests.size(); ++i) {
        if (requests[i].size > 0) order.push_back(i);
    }
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return placedBefore(requests[a], requests[b]); });
    return order;
}

bool ShadowAtlasCache::allocate(uint32_t size, AtlasRect& rect) {
    // The smallest free block at least `size` a side, top-left first.
    auto found = free_.lower_bound(size);
    while (found != free_.end() && found->second.empty()) ++found;
    if (found == free_.end()) return false;
    uint32_t side = found->first;
    const auto [y, x] = *found->second.begin();
    found->second.erase(found->second.begin());
    // Split down to `size`: keep the top-left quarter, free the other three.
    while (side > size) {
        side /= 2;
        free_[side].insert({y, x + side});
        free_[side].insert({y + side, x});
        free_[side].insert({y + side, x + side});
    }
    rect = {x, y, size};
    return true;
}

void ShadowAtlasCache::release(const AtlasRect& rect) {
    uint32_t side = rect.size;
    uint32_t x = rect.x;
    uint32_t y = rect.y;
    // Merge with the buddies while all four quarters of the parent are free (roots sit at
    // multiples of root_, so a parent inside a root is aligned to its own side).
    while (side < root_) {
        const uint32_t parentX = x & ~(2 * side - 1);
        const uint32_t parentY = y & ~(2 * side - 1);
        std::set<std::pair<uint32_t, uint32_t>>& blocks = free_[side];
        const std::pair<uint32_t, uint32_t> quarters[4] = {
            {parentY, parentX}, {parentY, parentX + side}, {parentY + side, parentX}, {parentY + side, parentX + side}};
        bool allFree = true;
        for (const auto& q : quarters) allFree = allFree && (q == std::pair{y, x} || blocks.count(q) > 0);
        if (!allFree) break;
        for (const auto& q : quarters) blocks.erase(q);
        side *= 2;
        x = parentX;
        y = parentY;
    }
    free_[side].insert({y, x});
}

bool ShadowAtlasCache::evictForBlock(uint32_t size, const std::set<ShadowViewKey>& placedNow,
                                     std::vector<ShadowViewKey>& evicted) {
    // Each view lies inside one aligned block of side `size` (when no larger), or covers whole ones.
    const uint32_t across = width_ / size;
    const uint32_t rows = height_ / size;
    std::vector<uint64_t> held(size_t(across) * rows, 0);
    std::vector<bool> barred(held.size(), false);
    for (const auto& [key, entry] : entries_) {
        const AtlasRect& r = entry.rect;
        const bool movable = r.size <= size && placedNow.count(key) == 0;
        for (uint32_t y = r.y / size; y < (r.y + r.size + size - 1) / size; ++y) {
            for (uint32_t x = r.x / size; x < (r.x + r.size + size - 1) / size; ++x) {
                const size_t block = size_t(y) * across + x;
                held[block] += uint64_t(r.size) * r.size;
                barred[block] = barred[block] || !movable;
            }
        }
    }
    size_t best = held.size();
    for (size_t block = 0; block < held.size(); ++block) {
        if (!barred[block] && (best == held.size() || held[block] < held[best])) best = block;
    }
    if (best == held.size()) return false;
    const uint32_t bx = uint32_t(best % across) * size;
    const uint32_t by = uint32_t(best / across) * size;
    for (auto it = entries_.begin(); it != entries_.end();) {
        const AtlasRect& r = it->second.rect;
        if (r.x >= bx && r.x < bx + size && r.y >= by && r.y < by + size) {
            evicted.push_back(it->first);
            release(r);
            it = entries_.erase(it);
        } else {
            ++it;
        }
    }
    return true;
}

void ShadowAtlasCache::layOut(const std::vector<CachedViewRequest>& requests) {
    entries_.clear();
    free_.clear();
    width_ = height_ = root_ = 0;
    const std::vector<size_t> order = largestFirst(requests);
    if (order.empty()) return;
    const uint32_t largest = requests[order.front()].size;
    root_ = std::max(largest, std::min(2 * largest, largestView_));
    double texels = 0.0;
    for (const size_t i : order) texels += double(requests[i].size) * double(requests[i].size);
    // The grid: roots across (a power of two, as square as the device allows), rows as needed.
    // With the slack where it fits the device, else without.
    for (const double slack : {kSlack, 1.0}) {
        const uint64_t roots = std::max<uint64_t>(1, uint64_t(std::ceil(texels * slack / (double(root_) * root_))));
        uint64_t across = 1;
        while (across * across < roots && uint64_t(root_) * across * 2 <= maxSide_) across *= 2;
        const uint64_t rows = (roots + across - 1) / across;
        if (uint64_t(root_) * rows <= maxSide_ && uint64_t(root_) * across <= maxSide_) {
            width_ = uint32_t(root_ * across);
            height_ = uint32_t(root_ * rows);
            break;
        }
    }
    if (width_ == 0) {
        throw Error("--shadow-cache", "the shadow views (" + std::to_string(uint64_t(texels)) +
                                          " texels) do not fit the device's largest 2D image (" + std::to_string(maxSide_) +
                                          " texels a side)");
    }
    for (uint32_t y = 0; y < height_; y += root_) {
        for (uint32_t x = 0; x < width_; x += root_) free_[root_].insert({y, x});
    }
    for (const size_t i : order) {
        AtlasRect rect;
        // Power-of-two squares, largest first, into blocks that hold them all: never fails.
        PUNCTUAL_CHECK(allocate(requests[i].size, rect), "a fresh shadow cache layout must hold its views");
        entries_[requests[i].key] = {rect, requests[i].signature};
    }
}

ShadowAtlasCacheFrame ShadowAtlasCache::place(const std::vector<CachedViewRequest>& requests) {
    std::map<ShadowViewKey, size_t> requested;  // the views with storage
    for (size_t i = 0; i < requests.size(); ++i) {
        if (requests[i].size == 0) continue;
        PUNCTUAL_CHECK(requested.emplace(requests[i].key, i).second, "two shadow views with one cache key");
    }
    // Squares of views gone or resized go back first, so the new sizes can use them.
    for (auto it = entries_.begin(); it != entries_.end();) {
        const auto r = requested.find(it->first);
        if (r == requested.end() || requests[r->second].size != it->second.rect.size) {
            release(it->second.rect);
            it = entries_.erase(it);
        } else {
            ++it;
        }
    }
    ShadowAtlasCacheFrame frame;
    std::set<ShadowViewKey> placedNow;
    double texels = 0.0;
    for (const auto& [key, i] : requested) texels += double(requests[i].size) * double(requests[i].size);
    bool fits = requested.empty() || (width_ > 0 && texels <= double(width_) * double(height_));
    // The views without a square, largest first; a view moved out of a block joins them, in its
    // place in that order (it is no larger than the block that moved it).
    std::vector<size_t> pending;
    for (const size_t i : largestFirst(requests)) {
        if (!entries_.count(requests[i].key)) pending.push_back(i);
    }
    for (size_t p = 0; fits && p < pending.size(); ++p) {
        const CachedViewRequest& request = requests[pending[p]];
        AtlasRect rect;
        fits = request.size <= root_;
        if (fits && !allocate(request.size, rect)) {
            std::vector<ShadowViewKey> evicted;
            fits = evictForBlock(request.size, placedNow, evicted) && allocate(request.size, rect);
            for (const ShadowViewKey& key : evicted) {
                const size_t moved = requested.at(key);
                const auto at = std::upper_bound(pending.begin() + ptrdiff_t(p) + 1, pending.end(), moved,
                                                 [&](size_t a, size_t b) { return placedBefore(requests[a], requests[b]); });
                pending.insert(at, moved);
                ++frame.moved;
            }
        }
        if (fits) {
            entries_[request.key] = {rect, request.signature};
            placedNow.insert(request.key);
        }
    }
    if (!fits) {
        frame.moved = 0;
        layOut(requests);
        frame.laidOut = true;
    }
    frame.layout.width = width_;
    frame.layout.height = height_;
    frame.layout.rects.resize(requests.size());
    frame.kept.assign(requests.size(), false);
    for (const auto& [key, i] : requested) {
        Entry& entry = entries_.at(key);
        frame.layout.rects[i] = entry.rect;
        frame.kept[i] = !frame.laidOut && placedNow.count(key) == 0 && entry.signature == requests[i].signature;
        entry.signature = requests[i].signature;
    }
    return frame;
}

}  // namespace punctual
