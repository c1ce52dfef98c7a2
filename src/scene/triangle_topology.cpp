#include "scene/triangle_topology.h"

namespace punctual {
namespace {

void appendUnlessDegenerate(std::vector<uint32_t>& list, uint32_t a, uint32_t b, uint32_t c) {
    if (a == b || b == c || a == c) return;
    list.insert(list.end(), {a, b, c});
}

}  // namespace

std::vector<uint32_t> triangleListFromStrip(std::span<const uint32_t> strip) {
    std::vector<uint32_t> list;
    if (strip.size() < 3) return list;
    list.reserve((strip.size() - 2) * 3);
    for (size_t i = 0; i + 2 < strip.size(); ++i) {
        // Odd triangles swap their last two vertices: the strip alternates its winding.
        if (i % 2 == 0) appendUnlessDegenerate(list, strip[i], strip[i + 1], strip[i + 2]);
        else appendUnlessDegenerate(list, strip[i], strip[i + 2], strip[i + 1]);
    }
    return list;
}

std::vector<uint32_t> triangleListFromFan(std::span<const uint32_t> fan) {
    std::vector<uint32_t> list;
    if (fan.size() < 3) return list;
    list.reserve((fan.size() - 2) * 3);
    for (size_t i = 0; i + 2 < fan.size(); ++i) appendUnlessDegenerate(list, fan[i + 1], fan[i + 2], fan[0]);
    return list;
}

}  // namespace punctual
