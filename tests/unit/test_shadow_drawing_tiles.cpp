// Known answers for the drawing tiles (lights/shadow_drawing_tiles.h): a view no larger than the
// drawing square is one tile with every caster; a larger one is cut into tiles of its side, each
// drawing the casters whose projected bounds reach it (within a texel); and the drawing square's
// memory, which the device's limits count beside the atlas (shadow_atlas.h).
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "lights/shadow_atlas.h"
#include "lights/shadow_drawing_tiles.h"

namespace punctual {
namespace {

// A scene of axis-aligned boxes, each an object with world bounds [min, max].
Scene boxes(const std::vector<std::pair<glm::vec3, glm::vec3>>& bounds) {
    Scene scene;
    for (const auto& [low, high] : bounds) {
        Object object;
        object.worldBounds.extend(low);
        object.worldBounds.extend(high);
        scene.objects.push_back(object);
    }
    return scene;
}

// An orthographic view down -z of world x, y in [-4, 4] (NDC = world / 4), `side` texels wide,
// casting every object of the scene.
ShadowView orthoView(uint32_t side, uint32_t objects) {
    ShadowView view;
    view.resolution = side;
    view.rect = {0, 0, side};
    view.gpu.viewProjection = glm::orthoRH_ZO(-4.0f, 4.0f, -4.0f, 4.0f, 0.1f, 100.0f);
    for (uint32_t o = 0; o < objects; ++o) view.casters.push_back(o);
    return view;
}

std::vector<std::pair<uint32_t, uint32_t>> placesOf(const std::vector<DrawingTile>& tiles, uint32_t object) {
    std::vector<std::pair<uint32_t, uint32_t>> places;
    for (const DrawingTile& tile : tiles) {
        for (const uint32_t caster : tile.casters) {
            if (caster == object) places.emplace_back(tile.column, tile.row);
        }
    }
    return places;
}

using Places = std::vector<std::pair<uint32_t, uint32_t>>;

TEST(DrawingTiles, AViewThatFitsTheSquareIsOneTileWithEveryCaster) {
    EXPECT_EQ(kDrawingSquareSide, 1024u);
    EXPECT_EQ(drawingTileSide(256), 256u);
    EXPECT_EQ(drawingTileSide(1024), 1024u);
    EXPECT_EQ(drawingTileSide(4096), 1024u);
    const Scene scene = boxes({{glm::vec3(-3.0f, -3.0f, -2.0f), glm::vec3(-2.0f, -2.0f, -1.0f)},
                               {glm::vec3(2.0f, 2.0f, -2.0f), glm::vec3(3.0f, 3.0f, -1.0f)}});
    const std::vector<DrawingTile> tiles = drawingTiles(orthoView(1024, 2), scene);
    ASSERT_EQ(tiles.size(), 1u);
    EXPECT_EQ(tiles[0].column, 0u);
    EXPECT_EQ(tiles[0].row, 0u);
    EXPECT_EQ(tiles[0].casters, (std::vector<uint32_t>{0, 1}));
}

TEST(DrawingTiles, ALargerViewDrawsEachCasterInTheTilesItReaches) {
    // 4096 texels: 4 x 4 tiles of 1024, each 2 world units (NDC 0.5) wide: tile column c covers
    // world x in [-4 + 2c, -2 + 2c], row r world y in [-4 + 2r, -2 + 2r] (NDC y = -1 is row 0).
    const Scene scene = boxes({
        {glm::vec3(-3.5f, -3.5f, -2.0f), glm::vec3(-2.5f, -2.5f, -1.0f)},  // inside tile (0, 0)
        {glm::vec3(-0.5f, 2.5f, -2.0f), glm::vec3(0.5f, 3.5f, -1.0f)},     // across x = 0: tiles (1, 3), (2, 3)
        {glm::vec3(0.001f, -1.0f, -2.0f), glm::vec3(1.0f, -0.5f, -1.0f)},  // within a texel of x = 0: (1, 1), (2, 1)
        {glm::vec3(2.5f, -1.0f, -2.0f), glm::vec3(3.0f, 1.0f, -1.0f)},     // across y = 0: (3, 1), (3, 2)
    });
    const std::vector<DrawingTile> tiles = drawingTiles(orthoView(4096, 4), scene);
    ASSERT_EQ(tiles.size(), 16u);  // every tile, reached or not: each must be cleared in its square
    for (size_t i = 0; i < tiles.size(); ++i) {
        EXPECT_EQ(tiles[i].column, i % 4);
        EXPECT_EQ(tiles[i].row, i / 4);
    }
    EXPECT_EQ(placesOf(tiles, 0), (Places{{0, 0}}));
    EXPECT_EQ(placesOf(tiles, 1), (Places{{1, 3}, {2, 3}}));
    // x = 0.001 is NDC 0.00025, a texel is NDC 2 / 4096 = 0.00049: the bounds come within a texel
    // of column 1.
    EXPECT_EQ(placesOf(tiles, 2), (Places{{1, 1}, {2, 1}}));
    EXPECT_EQ(placesOf(tiles, 3), (Places{{3, 1}, {3, 2}}));
    EXPECT_EQ(drawingTileDraws(orthoView(4096, 4), scene), 7u);
}

TEST(DrawingTiles, ACasterBehindThePerspectiveEyeReachesEveryTile) {
    // A spot at the origin looking down -z: a box around the eye has corners with w <= 0, which
    // have no place on the view, so it is drawn in all 4 tiles of a 2048 view. A box in front,
    // left of the axis and below it, reaches the lower-left tile only (row 0 is NDC y = -1).
    ShadowView view;
    view.resolution = 2048;
    view.rect = {0, 0, 2048};
    view.gpu.viewProjection = glm::perspectiveRH_ZO(glm::radians(90.0f), 1.0f, 0.1f, 100.0f);
    view.casters = {0, 1};
    const Scene scene = boxes({{glm::vec3(-1.0f, -1.0f, -1.0f), glm::vec3(1.0f, 1.0f, 1.0f)},
                               {glm::vec3(-4.0f, -4.0f, -10.0f), glm::vec3(-1.0f, -1.0f, -9.0f)}});
    const std::vector<DrawingTile> tiles = drawingTiles(view, scene);
    ASSERT_EQ(tiles.size(), 4u);
    EXPECT_EQ(placesOf(tiles, 0), (Places{{0, 0}, {1, 0}, {0, 1}, {1, 1}}));
    EXPECT_EQ(placesOf(tiles, 1), (Places{{0, 0}}));
}

TEST(DrawingTiles, TheDrawingSquareIsTheLargestViewsTile) {
    EXPECT_EQ(drawingSquareTexels({}), 0u);
    EXPECT_EQ(drawingSquareTexels({0, 0}), 0u);
    EXPECT_EQ(drawingSquareTexels({512, 256, 0}), 512u * 512u);
    EXPECT_EQ(drawingSquareTexels({16, 4096}), 1024u * 1024u);
}

}  // namespace
}  // namespace punctual
