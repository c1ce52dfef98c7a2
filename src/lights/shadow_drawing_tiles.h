#pragma once
// Where the shadow pass draws an atlas view before copying it into its square (render/
// shadow_pass.h): at the origin of the drawing square, so that where the square lies in the atlas
// cannot round one bit of its depth. The drawing square is at most kDrawingSquareSide texels a
// side; a larger view is drawn in tiles of that side, each a viewport moved by the tile's place in
// the view (so a view's tiles depend on its side alone, never on its square), each drawing only
// the casters whose bounds reach it.
//
// Why 1024: the square is memory beside the atlas, counted with it against the device's limits
// and in the shadow memory reported (drawingSquareTexels, shadow_atlas.h), though not against
// --shadow-budget, which is the atlas's. At 1024 it is 2 MiB of 16-bit depth, 3% of the default
// 64 MiB budget, and the hall's default tiers (up to 1024 at 1280x720) draw in one tile; a 4096
// view pays 16 tiles, each with the casters that reach it.
#include <cstdint>
#include <vector>

#include "lights/shadow_setup.h"
#include "scene/scene.h"

namespace punctual {

inline constexpr uint32_t kDrawingSquareSide = 1024;

// The side of the tiles a view of `viewSide` texels is drawn in.
inline uint32_t drawingTileSide(uint32_t viewSide) { return viewSide < kDrawingSquareSide ? viewSide : kDrawingSquareSide; }

struct DrawingTile {
    uint32_t column = 0;            // the tile's place in the view, in tiles from its top-left
    uint32_t row = 0;
    std::vector<uint32_t> casters;  // the view's casters whose bounds reach the tile, in the view's order
};

// The tiles `view` (rendered, with an atlas square) is drawn in, row by row, with their casters
// (a tile no caster reaches is still cleared and copied: its square must hold the far plane). One
// tile with every caster when the view fits the drawing square.
std::vector<DrawingTile> drawingTiles(const ShadowView& view, const Scene& scene);

// The draws of drawingTiles(view, scene): one per tile and caster.
uint64_t drawingTileDraws(const ShadowView& view, const Scene& scene);

}  // namespace punctual
