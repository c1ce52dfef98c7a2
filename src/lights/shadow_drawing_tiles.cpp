#include "lights/shadow_drawing_tiles.h"

#include <algorithm>
#include <cmath>

namespace punctual {
namespace {

// The tiles (columns x, rows y, inclusive) that object `bounds` reaches in a view of `tiles` tiles
// and `texels` texels a side: its eight corners projected through the view's matrix. A corner at or behind the view's
// eye plane (w <= 0) has no place on the view: every tile then, the safe answer.
glm::uvec4 tilesReached(const Bounds& bounds, const glm::mat4& viewProjection, uint32_t tiles, uint32_t texels) {
    glm::vec2 low(1.0f);
    glm::vec2 high(-1.0f);
    for (uint32_t corner = 0; corner < 8; ++corner) {
        const glm::vec3 p((corner & 1u) ? bounds.max.x : bounds.min.x, (corner & 2u) ? bounds.max.y : bounds.min.y,
                          (corner & 4u) ? bounds.max.z : bounds.min.z);
        const glm::vec4 clip = viewProjection * glm::vec4(p, 1.0f);
        if (!(clip.w > 0.0f)) return {0, 0, tiles - 1, tiles - 1};
        const glm::vec2 ndc = glm::vec2(clip) / clip.w;
        low = glm::min(low, ndc);
        high = glm::max(high, ndc);
    }
    // NDC x, y in [-1, 1] span the view's width and height (the viewport maps y = -1 to row 0).
    // A tile is reached when the bounds overlap it or come within a texel (2 / texels in NDC) of
    // it: a triangle covers the texels whose centres it holds, and its projected corners carry
    // float rounding far below a texel.
    const float perTile = 0.5f * float(tiles);  // tiles per NDC unit
    const float margin = 2.0f / float(texels);
    auto tileOf = [&](float ndc) {
        return uint32_t(std::clamp(std::floor((ndc + 1.0f) * perTile), 0.0f, float(tiles - 1)));
    };
    return {tileOf(low.x - margin), tileOf(low.y - margin), tileOf(high.x + margin), tileOf(high.y + margin)};
}

}  // namespace

std::vector<DrawingTile> drawingTiles(const ShadowView& view, const Scene& scene) {
    const uint32_t side = drawingTileSide(view.rect.size);
    const uint32_t tiles = side > 0 ? view.rect.size / side : 0;
    if (tiles <= 1) return {DrawingTile{0, 0, view.casters}};
    std::vector<DrawingTile> grid(size_t(tiles) * tiles);
    for (uint32_t row = 0; row < tiles; ++row) {
        for (uint32_t column = 0; column < tiles; ++column) grid[size_t(row) * tiles + column] = {column, row, {}};
    }
    for (const uint32_t object : view.casters) {
        const glm::uvec4 reach =
            tilesReached(scene.objects[object].worldBounds, view.gpu.viewProjection, tiles, view.rect.size);
        for (uint32_t row = reach.y; row <= reach.w; ++row) {
            for (uint32_t column = reach.x; column <= reach.z; ++column) {
                grid[size_t(row) * tiles + column].casters.push_back(object);
            }
        }
    }
    return grid;
}

uint64_t drawingTileDraws(const ShadowView& view, const Scene& scene) {
    uint64_t draws = 0;
    for (const DrawingTile& tile : drawingTiles(view, scene)) draws += tile.casters.size();
    return draws;
}

}  // namespace punctual
