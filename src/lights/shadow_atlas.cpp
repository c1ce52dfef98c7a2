#include "lights/shadow_atlas.h"

#include <algorithm>
#include <numeric>
#include <string>

#include "core/error.h"
#include "lights/shadow_drawing_tiles.h"

namespace punctual {
namespace {

// Morton decode: the even bits of `index` are x, the odd bits y.
uint32_t evenBits(uint64_t index) {
    uint32_t value = 0;
    for (uint32_t bit = 0; bit < 32; ++bit) value |= uint32_t((index >> (2 * bit)) & 1u) << bit;
    return value;
}

std::vector<uint32_t> largestFirst(const std::vector<uint32_t>& sizes) {
    std::vector<uint32_t> order(sizes.size());
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return sizes[a] > sizes[b]; });
    return order;
}

// Shelves of blocks in an atlas `width` wide (see shadow_atlas.h). Fills `rects` when given;
// returns the atlas's height.
uint64_t packShelves(const std::vector<uint32_t>& sizes, const std::vector<uint32_t>& order, uint32_t width,
                     std::vector<AtlasRect>* rects) {
    uint64_t shelfTop = 0;
    uint32_t shelfHeight = 0;  // 0: no shelf open
    uint32_t blockLeft = 0;
    uint64_t blockUsed = 0;  // texels^2 of the open block, in its Z order
    for (uint32_t index : order) {
        const uint32_t size = sizes[index];
        if (size == 0) break;
        const uint64_t area = uint64_t(size) * size;
        const uint64_t blockArea = uint64_t(shelfHeight) * shelfHeight;
        if (shelfHeight == 0 || blockUsed + area > blockArea) {
            // The open block is full (or there is none): the next block along the shelf, or a
            // new shelf as tall as this square when the shelf has no room left.
            const uint32_t nextLeft = shelfHeight == 0 ? 0 : blockLeft + shelfHeight;
            if (shelfHeight == 0 || uint64_t(nextLeft) + shelfHeight > width) {
                shelfTop += shelfHeight;
                shelfHeight = size;
                blockLeft = 0;
            } else {
                blockLeft = nextLeft;
            }
            blockUsed = 0;
        }
        if (rects) {
            // Z order in units of this square: its offset in the block is a multiple of its area.
            const uint64_t cell = blockUsed / area;
            (*rects)[index] = {blockLeft + evenBits(cell) * size, uint32_t(shelfTop + evenBits(cell >> 1) * size), size};
        }
        blockUsed += area;
    }
    return shelfTop + shelfHeight;
}

// The width (a power of two from the largest square up to maxSide) whose atlas has the fewest
// texels and a height within maxSide; 0 when none has.
uint32_t bestWidth(const std::vector<uint32_t>& sizes, const std::vector<uint32_t>& order, uint32_t maxSide) {
    if (order.empty() || sizes[order.front()] == 0) return 0;
    uint32_t best = 0;
    uint64_t bestTexels = UINT64_MAX;
    for (uint64_t width = sizes[order.front()]; width <= maxSide; width *= 2) {
        const uint64_t height = packShelves(sizes, order, uint32_t(width), nullptr);
        if (height > maxSide) continue;
        if (width * height < bestTexels) {
            bestTexels = width * height;
            best = uint32_t(width);
        }
    }
    return best;
}

}  // namespace

bool shadowAtlasFits(const std::vector<uint32_t>& sizes, uint32_t maxSide) {
    const std::vector<uint32_t> order = largestFirst(sizes);
    return order.empty() || sizes[order.front()] == 0 || bestWidth(sizes, order, maxSide) > 0;
}

AtlasLayout packShadowAtlas(const std::vector<uint32_t>& sizes, uint32_t maxSide) {
    for (uint32_t size : sizes) {
        if ((size & (size - 1)) != 0) throw Error("shadow atlas", "view size " + std::to_string(size) + " is not a power of two");
    }
    const std::vector<uint32_t> order = largestFirst(sizes);
    AtlasLayout layout;
    layout.rects.resize(sizes.size());
    if (order.empty() || sizes[order.front()] == 0) return layout;
    const uint32_t width = bestWidth(sizes, order, maxSide);
    if (width == 0) {
        uint64_t area = 0;
        for (uint32_t size : sizes) area += uint64_t(size) * size;
        throw Error("shadow atlas", "squares of " + std::to_string(area) + " texels in all do not fit in " +
                                        std::to_string(maxSide) + " x " + std::to_string(maxSide));
    }
    layout.width = width;
    layout.height = uint32_t(packShelves(sizes, order, width, &layout.rects));
    return layout;
}

uint64_t drawingSquareTexels(const std::vector<uint32_t>& sizes) {
    const uint64_t side = sizes.empty() ? 0 : drawingTileSide(*std::max_element(sizes.begin(), sizes.end()));
    return side * side;
}

}  // namespace punctual
