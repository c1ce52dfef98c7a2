#pragma once
// Where each shadow view lives in the shadow atlas: one 2D depth texture holding every spot view
// and every point-light face (as six 2D slices), each a square of its own power-of-two size.
//
// Why an atlas rather than one array per tier: one texture and one sampler binding whatever the
// tiers (the shader maps a view's UV into its rectangle, no per-tier descriptors to choose
// between per pixel), and storage that is exactly the sum of the views' squares, rounded up to
// whole pages (below), plus one drawing square: each view is drawn at its origin and copied into
// its square, so that where a square lies cannot round its depth (render/shadow_pass.h). URP and Godot store
// their punctual shadows the same way. A cube map cannot live in an atlas, so the cube layout
// keeps its cube array and exists only with a fixed resolution (--shadow-res N).
//
// Packing: the squares, sorted from largest to smallest, fill shelves across the atlas. A shelf is
// as tall as its first square and holds square blocks of that side, left to right; each block is
// filled in Morton (Z) order. Power-of-two squares sorted that way never leave a hole in Z order:
// every square starts where the previous one ended, at a multiple of its own area, so a block is
// full before the next one starts. Only the last block and the end of the last shelf can be left
// empty. The atlas's width is the power of two (from the largest square up to the device's
// largest 2D image side) that gives the fewest texels; its height is the shelves' total, any
// whole number of texels.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace punctual {

struct AtlasRect {
    uint32_t x = 0;     // texels from the atlas's left edge
    uint32_t y = 0;     // texels from its top edge
    uint32_t size = 0;  // texels a side; 0: the view has no storage
};

struct AtlasLayout {
    uint32_t width = 0;   // texels; 0 when no view has storage
    uint32_t height = 0;
    std::vector<AtlasRect> rects;  // one per input size, in input order

    uint64_t texels() const { return uint64_t(width) * height; }
};

// A square of the atlas in its UV (GpuShadowView::atlasRect): corner (xy) and side (zw). Sides and
// corners are whole texels over a power-of-two width, so the shader's texel positions in a square
// come out the same wherever the square lies (the cache moves squares: render/shadow_cache.h).
inline glm::vec4 atlasRectInUv(const AtlasRect& rect, const AtlasLayout& atlas) {
    const glm::vec2 atlasSize(float(atlas.width), float(atlas.height));
    return glm::vec4(glm::vec2(float(rect.x), float(rect.y)) / atlasSize, glm::vec2(float(rect.size)) / atlasSize);
}

// Packs squares of the given sizes (each 0 or a power of two). Throws Error when they do not fit
// in maxSide x maxSide.
AtlasLayout packShadowAtlas(const std::vector<uint32_t>& sizes, uint32_t maxSide);

// Whether packShadowAtlas(sizes, maxSide) fits, without throwing.
bool shadowAtlasFits(const std::vector<uint32_t>& sizes, uint32_t maxSide);

// Texels of the drawing square the shadow pass draws each of these squares in before copying it
// into the atlas (lights/shadow_drawing_tiles.h): the largest side's tile, squared (0 for none).
// The device's limits count it with the atlas; --shadow-budget is the atlas's alone.
uint64_t drawingSquareTexels(const std::vector<uint32_t>& sizes);

}  // namespace punctual
