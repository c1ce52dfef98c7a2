#pragma once
// Where cached virtual shadow pages live from frame to frame (--shadow-cache on with --shadow-res
// virtual, issue 34): a pool whose slots keep their pages while those stay marked, so that a page
// whose light and casters did not move keeps last frame's depth and is not drawn again (Unreal's
// cached physical pages; HDRP has no virtual pages).
//
// The frame's own allocation (lights/shadow_page_allocation.h) gives slot i to the i-th marked page,
// so one page more or less moves every page after it. Here a page keeps its slot while it is
// marked, frame after frame; a page no longer marked frees its slot, and a newly marked one takes
// the lowest free slot. A page's depth does not depend on its slot (each is drawn at the same
// origin and copied, render/shadow_page_layers.h), so a kept page is the page the frame would
// draw, bit for bit.
//
// The pool's capacity is fixed between layouts: laying out afresh (the first frame, the cascades'
// squares beside the pool changed size, or the marked pages outgrew the pool) sizes it for kSlack
// times the marked pages, held to what --shadow-budget leaves where that is more than the pages,
// and every page is drawn that frame. Unmarked pages are not kept for later (no LRU): a walk seldom
// comes back to a page it left, and a kept unmarked page would hold a slot the budget counts.
#include <compare>
#include <cstdint>
#include <map>
#include <vector>

#include <glm/glm.hpp>

namespace punctual {

// A page across frames: the scene light, its face (0 for a spot), the level and the page.
struct ShadowPageKey {
    uint32_t light = 0;
    uint32_t face = 0;
    uint32_t level = 0;
    uint32_t column = 0;
    uint32_t row = 0;
    auto operator<=>(const ShadowPageKey&) const = default;
};

// A page this frame: its key and what its depth is made of (shadowPageSignature,
// lights/shadow_view_signature.h): equal signatures draw equal depths.
struct CachedPageRequest {
    ShadowPageKey key;
    uint64_t signature = 0;
};

struct ShadowPagePoolFrame {
    std::vector<uint32_t> slots;  // per request: its slot
    std::vector<bool> kept;       // per request: its slot holds last frame's depth of the same signature
    uint32_t capacity = 0;        // the pool's page slots
    bool laidOut = false;         // every page placed afresh this frame
};

class ShadowPagePoolCache {
public:
    static constexpr double kSlack = 1.25;

    // Places this frame's pages (`requests`, distinct keys) in the pool beside cascades' squares of
    // `squares` texels; `budgetSlots` is the most slots --shadow-budget leaves for pages.
    ShadowPagePoolFrame place(const std::vector<CachedPageRequest>& requests, glm::uvec2 squares, uint64_t budgetSlots);
    // Whether the pool is laid out beside cascades' squares of `squares` texels, and its capacity.
    bool laidOutBeside(glm::uvec2 squares) const { return hasLayout_ && squares == squares_; }
    uint32_t capacity() const { return capacity_; }

private:
    struct Resident {
        uint32_t slot = 0;
        uint64_t signature = 0;
    };
    ShadowPagePoolFrame layOut(const std::vector<CachedPageRequest>& requests, glm::uvec2 squares, uint64_t budgetSlots);
    std::map<ShadowPageKey, Resident> resident_;
    uint32_t capacity_ = 0;
    glm::uvec2 squares_{0u};
    bool hasLayout_ = false;
};

}  // namespace punctual
