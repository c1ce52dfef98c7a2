#include "lights/shadow_page_pool_cache.h"

#include <algorithm>
#include <cmath>

namespace punctual {

ShadowPagePoolFrame ShadowPagePoolCache::place(const std::vector<CachedPageRequest>& requests, glm::uvec2 squares,
                                               uint64_t budgetSlots) {
    if (!hasLayout_ || squares != squares_ || requests.size() > capacity_) return layOut(requests, squares, budgetSlots);
    ShadowPagePoolFrame frame;
    frame.capacity = capacity_;
    frame.slots.assign(requests.size(), 0);
    frame.kept.assign(requests.size(), false);
    // The pages still marked keep their slots; the others' slots are free.
    std::vector<bool> taken(capacity_, false);
    std::vector<size_t> newcomers;
    for (size_t i = 0; i < requests.size(); ++i) {
        const auto found = resident_.find(requests[i].key);
        if (found == resident_.end()) {
            newcomers.push_back(i);
            continue;
        }
        frame.slots[i] = found->second.slot;
        frame.kept[i] = found->second.signature == requests[i].signature;
        taken[found->second.slot] = true;
    }
    uint32_t next = 0;  // the lowest free slot (capacity_ >= requests: one is left for each newcomer)
    for (const size_t i : newcomers) {
        while (taken[next]) ++next;
        frame.slots[i] = next;
        taken[next] = true;
    }
    resident_.clear();
    for (size_t i = 0; i < requests.size(); ++i) resident_[requests[i].key] = {frame.slots[i], requests[i].signature};
    return frame;
}

ShadowPagePoolFrame ShadowPagePoolCache::layOut(const std::vector<CachedPageRequest>& requests, glm::uvec2 squares,
                                                uint64_t budgetSlots) {
    // Room to grow, within the budget where the budget leaves it (never fewer slots than pages:
    // the frame has already been fitted to the budget, coarsening what did not fit).
    const uint64_t pages = requests.size();
    const uint64_t grown = uint64_t(std::ceil(double(pages) * kSlack));
    capacity_ = uint32_t(std::max<uint64_t>({pages, std::min(grown, budgetSlots), 1}));
    squares_ = squares;
    hasLayout_ = true;
    ShadowPagePoolFrame frame;
    frame.capacity = capacity_;
    frame.laidOut = true;
    frame.kept.assign(requests.size(), false);
    resident_.clear();
    for (size_t i = 0; i < requests.size(); ++i) {
        frame.slots.push_back(uint32_t(i));
        resident_[requests[i].key] = {uint32_t(i), requests[i].signature};
    }
    return frame;
}

}  // namespace punctual
