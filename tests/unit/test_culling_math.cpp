// Known answers for the shared culling math (shaders/shared/culling.h), computed by hand: the
// cluster slice search, the camera's (reversed) depth mapping, the spot light's bounding sphere,
// the light grid's word/bit mapping and the 2.5D depth mask's cells.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "culling.h"
#include "scene/scene.h"

namespace punctual {
namespace {

using gpu::allLightsWord;
using gpu::clusterSliceOfDepth;
using gpu::gridWordsOf;
using gpu::lightGridBit;
using gpu::lightGridFirstLight;
using gpu::lightGridWord;
using gpu::spotBoundingSphere;

// ---- cluster slice of a depth: the last slice whose start is >= depth ---------------------------
// The camera's depth is reversed (1 at the near plane, 0 at the far one), so slices run near to far
// with falling start depths and a depth belongs to the last slice starting at or nearer than it.

// Starts 1, 3/4, 1/2, 1/4 (slices 0-3, all exact in binary); the unused slices start at -1, below
// every depth, as depth_range.comp writes them.
std::vector<float> quarterStarts() {
    std::vector<float> starts(PUNCTUAL_MAX_CLUSTER_SLICES, -1.0f);
    for (int s = 0; s < 4; ++s) starts[size_t(s)] = 1.0f - 0.25f * float(s);
    return starts;
}

TEST(ClusterSlice, DepthsInsideSlices) {
    const std::vector<float> starts = quarterStarts();
    EXPECT_EQ(clusterSliceOfDepth(0.9f, starts.data(), 4), 0u);
    EXPECT_EQ(clusterSliceOfDepth(0.7f, starts.data(), 4), 1u);
    EXPECT_EQ(clusterSliceOfDepth(0.4f, starts.data(), 4), 2u);
    EXPECT_EQ(clusterSliceOfDepth(0.1f, starts.data(), 4), 3u);
}

TEST(ClusterSlice, ASliceStartBelongsToTheSliceItStarts) {
    // "at or nearer": depth 0.75 is slice 1's first depth; the float just above is still slice 0.
    const std::vector<float> starts = quarterStarts();
    EXPECT_EQ(clusterSliceOfDepth(1.0f, starts.data(), 4), 0u);
    EXPECT_EQ(clusterSliceOfDepth(0.75f, starts.data(), 4), 1u);
    EXPECT_EQ(clusterSliceOfDepth(std::nextafter(0.75f, 1.0f), starts.data(), 4), 0u);
    EXPECT_EQ(clusterSliceOfDepth(0.25f, starts.data(), 4), 3u);
}

TEST(ClusterSlice, DepthsBeyondTheLastStartStayInTheLastSlice) {
    // Only starts 1 .. sliceCount - 1 are read: depth -4 is past start[4] = -1 but slice 3 is the last.
    const std::vector<float> starts = quarterStarts();
    EXPECT_EQ(clusterSliceOfDepth(0.0f, starts.data(), 4), 3u);
    EXPECT_EQ(clusterSliceOfDepth(-4.0f, starts.data(), 4), 3u);
}

TEST(ClusterSlice, OneSliceIsAlwaysSliceZero) {
    // Tiled grids: no start is read, every depth is slice 0.
    const std::vector<float> starts = quarterStarts();
    for (float depth : {1.0f, 0.5f, 0.01f, -2.0f}) EXPECT_EQ(clusterSliceOfDepth(depth, starts.data(), 1), 0u);
}

TEST(ClusterSlice, EqualStartsGoToTheLastOfThem) {
    // Starts 1, 0.5, 0.5, 0.5, 0.25: depth 0.5 is at or past slices 1-3's start, so slice 3; a
    // depth above 0.5 is slice 0.
    std::vector<float> starts(PUNCTUAL_MAX_CLUSTER_SLICES, -1.0f);
    starts[0] = 1.0f;
    starts[1] = starts[2] = starts[3] = 0.5f;
    starts[4] = 0.25f;
    EXPECT_EQ(clusterSliceOfDepth(0.5f, starts.data(), 5), 3u);
    EXPECT_EQ(clusterSliceOfDepth(0.4f, starts.data(), 5), 3u);
    EXPECT_EQ(clusterSliceOfDepth(0.6f, starts.data(), 5), 0u);
    EXPECT_EQ(clusterSliceOfDepth(0.2f, starts.data(), 5), 4u);
}

TEST(ClusterSlice, EverySliceOfEveryCountIsFound) {
    // Starts 1 - s / 32 (exact): depth 1 - s / 32 is slice s, and 1 - s / 32 - 1/64 too, for every
    // count, odd counts included (the search's halving then leaves uneven parts).
    std::vector<float> starts(PUNCTUAL_MAX_CLUSTER_SLICES);
    for (uint32_t s = 0; s < PUNCTUAL_MAX_CLUSTER_SLICES; ++s) starts[s] = 1.0f - float(s) / 32.0f;
    for (uint32_t count = 1; count <= PUNCTUAL_MAX_CLUSTER_SLICES; ++count) {
        for (uint32_t s = 0; s < count; ++s) {
            EXPECT_EQ(clusterSliceOfDepth(1.0f - float(s) / 32.0f, starts.data(), count), s) << count;
            EXPECT_EQ(clusterSliceOfDepth(1.0f - float(s) / 32.0f - 1.0f / 64.0f, starts.data(), count), s) << count;
        }
    }
}

// ---- the camera's depth mapping ----------------------------------------------------------------

TEST(CameraDepth, ReversedDepthIsOneAtNearZeroAtFarAndRoundTrips) {
    // Near 0.5, far 100.5: b = n / (f - n) = 0.005, a = f n / (f - n) = 0.5025; depth = a / D - b:
    // 1 at D = 0.5, 0 at D = 100.5, 0.5025 / 2 - 0.005 = 0.24625 at D = 2.
    Camera camera;
    camera.znear = 0.5f;
    camera.zfar = 100.5f;
    const glm::mat4 p = camera.projection(1.0f);
    const glm::vec2 depthToView(p[3][2], p[2][2]);
    EXPECT_NEAR(depthToView.x, 0.5025f, 1e-6f);
    EXPECT_NEAR(depthToView.y, 0.005f, 1e-8f);
    auto depthAt = [&](float distance) {
        const glm::vec4 clip = p * glm::vec4(0.0f, 0.0f, -distance, 1.0f);
        return clip.z / clip.w;
    };
    EXPECT_NEAR(depthAt(0.5f), 1.0f, 1e-6f);
    EXPECT_NEAR(depthAt(100.5f), 0.0f, 1e-6f);
    EXPECT_NEAR(depthAt(2.0f), 0.24625f, 1e-6f);
    for (const float distance : {0.5f, 2.0f, 30.0f, 100.0f}) {
        EXPECT_NEAR(gpu::viewDistanceFromDepth(depthAt(distance), depthToView), distance, distance * 1e-6f);
        EXPECT_NEAR(gpu::depthFromViewDistance(distance, depthToView), depthAt(distance), 1e-6f);
    }
    EXPECT_TRUE(gpu::isBackgroundDepth(PUNCTUAL_DEPTH_CLEAR));
    EXPECT_FALSE(gpu::isBackgroundDepth(depthAt(100.0f)));
}

TEST(CameraDepth, ATinyNearPlaneKeepsDistancesApart) {
    // Near 1e-6 m, far 100 m: depth ~ 1e-6 / D. Surfaces 1 mm apart at 10, 30 and 90 m still get
    // different float depths (the usual mapping, 1 - 1e-6 / D, rounds all of them to 1.0).
    Camera camera;
    camera.znear = 1e-6f;
    camera.zfar = 100.0f;
    const glm::mat4 p = camera.projection(1.0f);
    auto depthAt = [&](float distance) {
        const glm::vec4 clip = p * glm::vec4(0.0f, 0.0f, -distance, 1.0f);
        return clip.z / clip.w;
    };
    for (const float distance : {10.0f, 30.0f, 90.0f}) {
        EXPECT_GT(depthAt(distance), depthAt(distance + 0.001f)) << distance;
        EXPECT_GT(depthAt(distance + 0.001f), 0.0f) << distance;
        EXPECT_LT(depthAt(distance), 1.0f) << distance;
    }
}

// ---- spot bounding sphere, vec4(centre, radius) ------------------------------------------------

TEST(SpotBoundingSphere, WideConeIsTheRimSphere) {
    // cos = 0.6, sin = 0.8 (a 3-4-5 triangle), range 5: rim centre 5 x 0.6 = 3 along the axis,
    // rim radius 5 x 0.8 = 4.
    const glm::vec4 sphere = spotBoundingSphere({1.0f, 2.0f, 3.0f}, {0.0f, 0.0f, -1.0f}, 5.0f, 0.6f);
    EXPECT_FLOAT_EQ(sphere.x, 1.0f);
    EXPECT_FLOAT_EQ(sphere.y, 2.0f);
    EXPECT_FLOAT_EQ(sphere.z, 0.0f);
    EXPECT_FLOAT_EQ(sphere.w, 4.0f);
}

TEST(SpotBoundingSphere, SixtyDegrees) {
    // cos 60 = 0.5, range 2: centre 1 along the axis, radius 2 sqrt(1 - 1/4) = sqrt(3), both
    // exact to the float (sqrt(3) = 2 sqrt(3/4), a power-of-two scaling).
    const glm::vec4 sphere = spotBoundingSphere({0.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}, 2.0f, 0.5f);
    EXPECT_EQ(sphere.x, 1.0f);
    EXPECT_EQ(sphere.y, 0.0f);
    EXPECT_EQ(sphere.z, 0.0f);
    EXPECT_EQ(sphere.w, std::sqrt(3.0f));
}

TEST(SpotBoundingSphere, NarrowConeIsTheSphereThroughApexAndRim) {
    // cos = 0.8, range 4: t = 4 / (2 x 0.8) = 2.5, the centre's distance along the axis and the
    // radius. Check: the rim (3.2 along, 2.4 across) is sqrt(0.7^2 + 2.4^2) = 2.5 from the centre.
    const glm::vec4 sphere = spotBoundingSphere({0.0f, 1.0f, 0.0f}, {0.0f, -1.0f, 0.0f}, 4.0f, 0.8f);
    EXPECT_FLOAT_EQ(sphere.x, 0.0f);
    EXPECT_FLOAT_EQ(sphere.y, -1.5f);
    EXPECT_FLOAT_EQ(sphere.z, 0.0f);
    EXPECT_FLOAT_EQ(sphere.w, 2.5f);
}

TEST(SpotBoundingSphere, ZeroAngleConeIsTheSegment) {
    // cos = 1: the cone is the segment from the apex to range 6 along the axis; the sphere on it
    // has centre 3 along the axis and radius 3.
    const glm::vec4 sphere = spotBoundingSphere({0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, 6.0f, 1.0f);
    EXPECT_EQ(sphere.y, 3.0f);
    EXPECT_EQ(sphere.w, 3.0f);
}

TEST(SpotBoundingSphere, HalfSpaceConeIsTheRangeSphere) {
    // cos = 0 (90 degrees): the rim circle is the range circle through the apex, centre at the
    // apex, radius the range. cos(pi/2) in float is -4.4e-8: the clamp keeps sin at 1.
    const glm::vec4 sphere = spotBoundingSphere({1.0f, 1.0f, 1.0f}, {0.0f, 0.0f, 1.0f}, 3.0f, 0.0f);
    EXPECT_EQ(sphere, glm::vec4(1.0f, 1.0f, 1.0f, 3.0f));
    const glm::vec4 rounded = spotBoundingSphere({1.0f, 1.0f, 1.0f}, {0.0f, 0.0f, 1.0f}, 3.0f, std::cos(1.5707964f));
    EXPECT_EQ(rounded.w, 3.0f);
    EXPECT_NEAR(rounded.z, 1.0f, 1e-6f);
}

TEST(SpotBoundingSphere, BothCasesMeetAt45Degrees) {
    // At cos = sin = sqrt(2)/2 both give centre and radius r / sqrt(2): r cos = r / (2 cos).
    const float c = 0.70710678f;
    const glm::vec4 narrow = spotBoundingSphere({0.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}, 2.0f, std::nextafter(c, 1.0f));
    const glm::vec4 wide = spotBoundingSphere({0.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}, 2.0f, std::nextafter(c, 0.0f));
    EXPECT_NEAR(narrow.x, std::sqrt(2.0f), 1e-6f);
    EXPECT_NEAR(narrow.w, std::sqrt(2.0f), 1e-6f);
    EXPECT_NEAR(wide.x, std::sqrt(2.0f), 1e-6f);
    EXPECT_NEAR(wide.w, std::sqrt(2.0f), 1e-6f);
}

// ---- light grid: packed light <-> (word, bit) ---------------------------------------------------

TEST(LightGrid, LightLIsBitLMod32OfWordLDiv32) {
    // Spots and points alike, in packed order: 64 spots then 32 points fill words 0-2.
    EXPECT_EQ(lightGridWord(0), 0u);
    EXPECT_EQ(lightGridBit(0), 0u);
    EXPECT_EQ(lightGridWord(31), 0u);
    EXPECT_EQ(lightGridBit(31), 31u);
    EXPECT_EQ(lightGridWord(32), 1u);
    EXPECT_EQ(lightGridBit(32), 0u);
    EXPECT_EQ(lightGridWord(95), 2u);  // the design notes' last light
    EXPECT_EQ(lightGridBit(95), 31u);
    EXPECT_EQ(lightGridWord(8191), 255u);  // 8,192 lights: 256 words
    EXPECT_EQ(lightGridBit(8191), 31u);
    EXPECT_EQ(lightGridFirstLight(0), 0u);
    EXPECT_EQ(lightGridFirstLight(2), 64u);
    EXPECT_EQ(lightGridFirstLight(255), 8160u);
}

TEST(LightGrid, WordsPerCellHoldEveryLightAndNoEmptyWord) {
    // ceil(lights / 32), one word for none (a cell is never empty of words).
    EXPECT_EQ(gridWordsOf(0), 1u);
    EXPECT_EQ(gridWordsOf(1), 1u);
    EXPECT_EQ(gridWordsOf(32), 1u);
    EXPECT_EQ(gridWordsOf(33), 2u);
    EXPECT_EQ(gridWordsOf(PUNCTUAL_DEFAULT_MAX_SPOT_LIGHTS + PUNCTUAL_DEFAULT_MAX_POINT_LIGHTS), 3u);
    EXPECT_EQ(gridWordsOf(8192), 256u);
    EXPECT_EQ(gridWordsOf(2 * PUNCTUAL_MAX_LIGHT_CAPACITY), 1024u);
}

TEST(LightGrid, AllLightsWordSetsExactlyTheFramesLights) {
    // 40 lights: word 0 full, word 1 bits 0-7, word 2 none.
    EXPECT_EQ(allLightsWord(0, 40), 0xFFFFFFFFu);
    EXPECT_EQ(allLightsWord(1, 40), 0xFFu);
    EXPECT_EQ(allLightsWord(2, 40), 0u);
    EXPECT_EQ(allLightsWord(1, 64), 0xFFFFFFFFu);
    EXPECT_EQ(allLightsWord(0, 0), 0u);
}

TEST(LightGrid, WalkingTheWordsVisitsEveryLightOnceInAscendingOrder) {
    // For light counts up to 8,192: set every light's bit, then walk the words and their bits
    // upwards as forward.frag does; the lights come back as 0, 1, 2, ...
    for (const uint32_t lights : {0u, 1u, 40u, 96u, 97u, 1000u, 8192u}) {
        std::vector<uint32_t> words(gridWordsOf(lights), 0u);
        for (uint32_t light = 0; light < lights; ++light) {
            ASSERT_LT(lightGridWord(light), words.size());
            ASSERT_LT(lightGridBit(light), 32u);
            const uint32_t bit = 1u << lightGridBit(light);
            EXPECT_EQ(words[lightGridWord(light)] & bit, 0u) << "two lights share a bit";
            words[lightGridWord(light)] |= bit;
        }
        uint32_t expected = 0;
        for (uint32_t word = 0; word < words.size(); ++word) {
            EXPECT_EQ(words[word], allLightsWord(word, lights)) << lights;
            for (uint32_t bit = 0; bit < 32; ++bit) {
                if (words[word] & (1u << bit)) {
                    EXPECT_EQ(lightGridFirstLight(word) + bit, expected++) << lights;
                }
            }
        }
        EXPECT_EQ(expected, lights);
    }
}

// ---- 2.5D depth mask: 32 equal cells over the tile's extent -------------------------------------

TEST(DepthMask, CellsSplitTheExtentIntoThirtyTwoEqualParts) {
    // Extent 10..42: 32 cells of exactly 1 unit (scale 1), cell k = [10 + k, 11 + k).
    const float scale = gpu::depthMaskScale(10.0f, 42.0f);
    EXPECT_FLOAT_EQ(scale, 1.0f);
    EXPECT_EQ(gpu::depthMaskCell(10.0f, 10.0f, scale), 0u);
    EXPECT_EQ(gpu::depthMaskCell(10.999f, 10.0f, scale), 0u);
    EXPECT_EQ(gpu::depthMaskCell(11.0f, 10.0f, scale), 1u);
    EXPECT_EQ(gpu::depthMaskCell(25.5f, 10.0f, scale), 15u);
    EXPECT_EQ(gpu::depthMaskCell(41.999f, 10.0f, scale), 31u);
    EXPECT_EQ(gpu::depthMaskCell(42.0f, 10.0f, scale), 31u);   // the far end: the last cell, not a 33rd
    EXPECT_EQ(gpu::depthMaskCell(5.0f, 10.0f, scale), 0u);     // before the extent: clamped
    EXPECT_EQ(gpu::depthMaskCell(1000.0f, 10.0f, scale), 31u); // beyond it: clamped
}

TEST(DepthMask, AFlatTileIsOneCell) {
    // Every pixel at one distance: scale 0, everything in cell 0.
    const float scale = gpu::depthMaskScale(7.0f, 7.0f);
    EXPECT_EQ(scale, 0.0f);
    EXPECT_EQ(gpu::depthMaskCell(7.0f, 7.0f, scale), 0u);
    EXPECT_EQ(gpu::depthMaskCell(100.0f, 7.0f, scale), 0u);
}

TEST(DepthMask, BitsOfACellRange) {
    EXPECT_EQ(gpu::depthMaskBits(0, 0), 0x1u);
    EXPECT_EQ(gpu::depthMaskBits(3, 5), 0x38u);
    EXPECT_EQ(gpu::depthMaskBits(31, 31), 0x80000000u);
    EXPECT_EQ(gpu::depthMaskBits(0, 31), 0xFFFFFFFFu);
    EXPECT_EQ(gpu::depthMaskBits(30, 31), 0xC0000000u);
}

TEST(DepthMask, ALightCoversTheCellsOfItsSphereDepthExtent) {
    // Extent 10..42 (scale 1). A sphere centred 20 units ahead (view z = -20), radius 3: view
    // distances 17..23, cells 7..13. Sideways position plays no part.
    gpu::CullLight light{};
    light.cosOuter = -1.0f;  // a point light: its extent is its sphere's
    light.sphereCenter = glm::vec3(5.0f, -2.0f, -20.0f);
    light.sphereRadius = 3.0f;
    EXPECT_EQ(gpu::lightDepthMask(light, 10.0f, 1.0f), gpu::depthMaskBits(7, 13));
    // A pixel at distance 30 (cell 20) is not met; one at 22.5 (cell 12) is.
    EXPECT_EQ(gpu::lightDepthMask(light, 10.0f, 1.0f) & (1u << 20), 0u);
    EXPECT_NE(gpu::lightDepthMask(light, 10.0f, 1.0f) & (1u << 12), 0u);
    // A light wholly behind the extent still lands in the last cell: the kernel tests it against the
    // tile's occupied cells, and the side and depth tests have already dropped it if it misses.
    light.sphereCenter.z = -100.0f;
    EXPECT_EQ(gpu::lightDepthMask(light, 10.0f, 1.0f), gpu::depthMaskBits(31, 31));
}

TEST(DepthMask, EveryDistanceInsideALightsExtentHasItsCell) {
    // The losslessness argument of culling.h, checked on a sweep: for lights of many extents over
    // an awkward tile extent, every distance inside the light's extent has its cell in the mask.
    const float nearD = 0.37f, farD = 913.1f;
    const float scale = gpu::depthMaskScale(nearD, farD);
    size_t checked = 0;
    for (float centre = 0.1f; centre < 1000.0f; centre *= 1.37f) {
        for (float radius = 0.01f; radius < 500.0f; radius *= 2.9f) {
            gpu::CullLight light{};
            light.cosOuter = -1.0f;  // a point light: its extent is its sphere's
            light.sphereCenter = glm::vec3(0.0f, 0.0f, -centre);
            light.sphereRadius = radius;
            const uint32_t mask = gpu::lightDepthMask(light, nearD, scale);
            for (int k = 0; k <= 64; ++k) {
                const float d = std::max(centre - radius, nearD) + (std::min(centre + radius, farD) - std::max(centre - radius, nearD)) * float(k) / 64.0f;
                if (d < nearD || d > farD || d < centre - radius || d > centre + radius) continue;
                EXPECT_NE(mask & (1u << gpu::depthMaskCell(d, nearD, scale)), 0u) << centre << " " << radius << " " << d;
                ++checked;
            }
        }
    }
    EXPECT_GT(checked, 1000u);
}

TEST(DepthMask, ACellsSegmentSpansItsShareOfTheExtent) {
    // Extent 10..42: cell k spans [10 + k, 11 + k], widened by the culling margin (1e-3 relative:
    // culling.h); the last cell ends at the extent's far end. Sideways, the tile's planes.
    const glm::vec4 ndcToView(1.0f, 1.0f, 0.0f, 0.0f);  // a 90-degree square view
    const gpu::TileVolume first = gpu::makeDepthCellVolume(glm::vec2(-0.5f), glm::vec2(0.0f), 0, 10.0f, 42.0f, ndcToView);
    EXPECT_FLOAT_EQ(first.nearDistance, 10.0f * (1.0f - PUNCTUAL_CULL_RELATIVE_MARGIN));
    EXPECT_FLOAT_EQ(first.farDistance, 11.0f * (1.0f + PUNCTUAL_CULL_RELATIVE_MARGIN));
    const gpu::TileVolume middle = gpu::makeDepthCellVolume(glm::vec2(-0.5f), glm::vec2(0.0f), 15, 10.0f, 42.0f, ndcToView);
    EXPECT_FLOAT_EQ(middle.nearDistance, 25.0f * (1.0f - PUNCTUAL_CULL_RELATIVE_MARGIN));
    EXPECT_FLOAT_EQ(middle.farDistance, 26.0f * (1.0f + PUNCTUAL_CULL_RELATIVE_MARGIN));
    const gpu::TileVolume last = gpu::makeDepthCellVolume(glm::vec2(-0.5f), glm::vec2(0.0f), 31, 10.0f, 42.0f, ndcToView);
    EXPECT_FLOAT_EQ(last.nearDistance, 41.0f * (1.0f - PUNCTUAL_CULL_RELATIVE_MARGIN));
    EXPECT_FLOAT_EQ(last.farDistance, 42.0f * (1.0f + PUNCTUAL_CULL_RELATIVE_MARGIN));
    // The tile x in [-0.5, 0] NDC: at distance 25 the segment spans x from -12.5 to 0.
    EXPECT_NEAR(middle.aabbMin.x, -0.5f * 26.0f * (1.0f + PUNCTUAL_CULL_RELATIVE_MARGIN), 1e-4f);
    EXPECT_NEAR(middle.aabbMax.x, 0.0f, 1e-6f);
    // A flat tile (far = near): every cell is the one distance.
    const gpu::TileVolume flat = gpu::makeDepthCellVolume(glm::vec2(-0.5f), glm::vec2(0.0f), 0, 7.0f, 7.0f, ndcToView);
    EXPECT_FLOAT_EQ(flat.nearDistance, 7.0f * (1.0f - PUNCTUAL_CULL_RELATIVE_MARGIN));
    EXPECT_FLOAT_EQ(flat.farDistance, 7.0f * (1.0f + PUNCTUAL_CULL_RELATIVE_MARGIN));
}

TEST(DepthMask, ALightNearAnOccupiedCellsDepthButBesideTheTileMissesItsSegment) {
    // The per-cell test's point: a sphere at the occupied cell's distance but well to the side of
    // the tile spans the cell's depths (the mask keeps it) yet misses the cell's segment.
    const glm::vec4 ndcToView(1.0f, 1.0f, 0.0f, 0.0f);
    const gpu::TileVolume cell = gpu::makeDepthCellVolume(glm::vec2(-0.1f), glm::vec2(0.1f), 15, 10.0f, 42.0f, ndcToView);
    gpu::CullLight light{};
    light.cosOuter = -1.0f;
    light.sphereCenter = glm::vec3(8.0f, 0.0f, -25.5f);  // the cell's distance; the tile spans |x| <= 2.6
    light.sphereRadius = 3.0f;
    EXPECT_NE(gpu::lightDepthMask(light, 10.0f, gpu::depthMaskScale(10.0f, 42.0f)) & (1u << 15), 0u);
    EXPECT_FALSE(gpu::lightMayTouchTile(light, cell));
    light.sphereCenter.x = 4.0f;  // now within 3 of the tile's side
    EXPECT_TRUE(gpu::lightMayTouchTile(light, cell));
}

TEST(TileColumn, SpansNearPlaneToFarPlane) {
    // Camera near 0.1, far 100: a = f n / (f - n), b = n / (f - n) (culling.h), and the column
    // runs from the near plane to the far plane, widened by the margin.
    const float n = 0.1f, f = 100.0f;
    const glm::vec2 depthToView(f * n / (f - n), n / (f - n));
    const gpu::TileVolume column = gpu::makeTileColumn(glm::vec2(-1.0f), glm::vec2(1.0f), depthToView, glm::vec4(1, 1, 0, 0));
    EXPECT_NEAR(column.nearDistance, n * (1.0f - PUNCTUAL_CULL_RELATIVE_MARGIN), 1e-6f);
    EXPECT_NEAR(column.farDistance, f * (1.0f + PUNCTUAL_CULL_RELATIVE_MARGIN), 1e-3f);
    // An infinite far plane (b = 0) gives a huge but finite far distance, not a division by zero.
    const gpu::TileVolume infinite = gpu::makeTileColumn(glm::vec2(-1.0f), glm::vec2(1.0f), glm::vec2(n, 0.0f), glm::vec4(1, 1, 0, 0));
    EXPECT_TRUE(std::isfinite(infinite.farDistance));
    EXPECT_GT(infinite.farDistance, 1e20f);
}

// A spot with apex `apex`, unit axis `axis`, slant `range` and half-angle of cosine `cosOuter`,
// its bounding sphere spotBoundingSphere's (no margins: the answers below are exact but for them).
gpu::CullLight spotLight(glm::vec3 apex, glm::vec3 axis, float range, float cosOuter) {
    gpu::CullLight light{};
    light.position = apex;
    light.axis = axis;
    light.range = range;
    light.cosOuter = cosOuter;
    const glm::vec4 sphere = gpu::spotBoundingSphere(apex, axis, range, cosOuter);
    light.sphereCenter = glm::vec3(sphere);
    light.sphereRadius = sphere.w;
    return light;
}

TEST(SpotExtent, APointingAwaySpotSpansFromItsApexToItsRange) {
    // Apex 10 ahead, pointing away, range 5, 30 deg: the sector reaches 5 along the view direction
    // and 0 back towards the camera (every w has w . (0, 0, 1) < 0): distances 10..15, padded by
    // the margin of the range (0.005). Its bounding sphere (radius 5 / (2 cos 30) = 2.887 around
    // distance 12.887) would reach 15.77.
    const float cos30 = std::sqrt(3.0f) / 2.0f;
    const gpu::CullLight light = spotLight(glm::vec3(0.0f, 0.0f, -10.0f), glm::vec3(0.0f, 0.0f, -1.0f), 5.0f, cos30);
    EXPECT_NEAR(light.sphereRadius, 5.0f / (2.0f * cos30), 1e-5f);
    const glm::vec2 extent = gpu::lightDistanceExtent(light);
    // The near end is the sphere's (it passes through the apex), tighter than the padded sector's.
    EXPECT_NEAR(extent.x, 10.0f, 1e-5f);
    EXPECT_NEAR(-gpu::spotReachAlong(light, glm::vec3(0.0f, 0.0f, 1.0f)), 10.0f - 0.005f, 1e-5f);
    EXPECT_NEAR(extent.y, 15.0f + 0.005f, 1e-5f);
}

TEST(SpotExtent, ASideOnSpotSpansHalfItsRangeEachWayAt30Degrees) {
    // Pointing along +x, 30 deg: the view direction is 90 deg from the axis, 60 deg from the nearest
    // edge of the cone, so the sector reaches 5 cos 60 = 2.5 each way: distances 7.5..12.5 (plus
    // 0.005). The bounding sphere spans 10 -/+ 2.887.
    const gpu::CullLight light = spotLight(glm::vec3(1.0f, 2.0f, -10.0f), glm::vec3(1.0f, 0.0f, 0.0f), 5.0f, std::sqrt(3.0f) / 2.0f);
    const glm::vec2 extent = gpu::lightDistanceExtent(light);
    EXPECT_NEAR(extent.x, 7.5f - 0.005f, 1e-5f);
    EXPECT_NEAR(extent.y, 12.5f + 0.005f, 1e-5f);
    // Along +x it reaches its whole range (the axis), along -x nothing past the apex but the pad.
    EXPECT_NEAR(gpu::spotReachAlong(light, glm::vec3(1.0f, 0.0f, 0.0f)), 1.0f + 5.005f, 1e-5f);
    EXPECT_NEAR(gpu::spotReachAlong(light, glm::vec3(-1.0f, 0.0f, 0.0f)), -1.0f + 0.005f, 1e-5f);
}

TEST(SpotExtent, TheSphereCutsTheSectorAndPointsKeepTheirSphere) {
    // A sector extent wider than the light's sphere (here a sphere set smaller by hand) is cut by
    // it: both bound the light, so their intersection does.
    gpu::CullLight light = spotLight(glm::vec3(0.0f, 0.0f, -10.0f), glm::vec3(0.0f, 0.0f, -1.0f), 5.0f, 0.5f);
    light.sphereCenter = glm::vec3(0.0f, 0.0f, -12.0f);
    light.sphereRadius = 1.0f;
    EXPECT_EQ(gpu::lightDistanceExtent(light), glm::vec2(11.0f, 13.0f));
    gpu::CullLight point{};
    point.cosOuter = -1.0f;
    point.sphereCenter = glm::vec3(3.0f, 0.0f, -20.0f);
    point.sphereRadius = 4.0f;
    EXPECT_EQ(gpu::lightDistanceExtent(point), glm::vec2(16.0f, 24.0f));
}

TEST(SpotExtent, TheSectorTestCullsAWideSpotBesideATileThatItsSpheresPass) {
    // The tile spans |x|, |y| <= 0.1 D between distances 10 and 42. A 60 deg spot at x = 3,
    // distance 20, pointing along +x: every lit point has x >= 3 (each w has w . x >= cos 60 > 0)
    // and distance within 20 -/+ 5 sin 60, where the tile reaches x <= 2.44. Its bounding sphere
    // (centre x = 5.5, radius 4.33) meets the side plane and the AABB, and the cone meets the
    // segment's big bounding sphere: only the sector's own planes see the miss.
    const gpu::TileVolume tile = gpu::makeTileVolume(glm::vec2(-0.1f), glm::vec2(0.1f), 10.0f, 42.0f, glm::vec4(1, 1, 0, 0));
    gpu::CullLight light = spotLight(glm::vec3(3.0f, 0.0f, -20.0f), glm::vec3(1.0f, 0.0f, 0.0f), 5.0f, 0.5f);
    EXPECT_TRUE(gpu::sphereMayTouchTile(light.sphereCenter, light.sphereRadius, tile));
    EXPECT_TRUE(gpu::coneMayTouchSphere(light.position, light.axis, light.range, light.cosOuter, tile.sphereCenter, tile.sphereRadius));
    EXPECT_FALSE(gpu::spotMayTouchTile(light, tile));
    EXPECT_FALSE(gpu::lightMayTouchTile(light, tile));
    // Moved to x = 1.5, inside the tile at distance 20 (|x| <= 2): it touches.
    light = spotLight(glm::vec3(1.5f, 0.0f, -20.0f), glm::vec3(1.0f, 0.0f, 0.0f), 5.0f, 0.5f);
    EXPECT_TRUE(gpu::spotMayTouchTile(light, tile));
    EXPECT_TRUE(gpu::lightMayTouchTile(light, tile));
}

TEST(SpotExtent, DepthAloneSeparatesALightFromASegmentWhoseDistancesItMisses) {
    // A segment between distances 10 and 42, widened by the culling margin (1e-3 of each: 9.99 to
    // 42.042): a light extent overlaps it when it reaches 9.99 and starts by 42.042, touching ends
    // included (lightDepthMeetsSegment, the tile test's first step).
    const gpu::TileVolume segment = gpu::makeTileVolume(glm::vec2(-0.1f), glm::vec2(0.1f), 10.0f, 42.0f, glm::vec4(1, 1, 0, 0));
    EXPECT_FLOAT_EQ(segment.nearDistance, 9.99f);
    EXPECT_FLOAT_EQ(segment.farDistance, 42.042f);
    EXPECT_FALSE(gpu::lightDepthMeetsSegment(glm::vec2(2.0f, 9.98f), segment));
    EXPECT_TRUE(gpu::lightDepthMeetsSegment(glm::vec2(2.0f, segment.nearDistance), segment));
    EXPECT_TRUE(gpu::lightDepthMeetsSegment(glm::vec2(20.0f, 30.0f), segment));
    EXPECT_TRUE(gpu::lightDepthMeetsSegment(glm::vec2(1.0f, 100.0f), segment));
    EXPECT_TRUE(gpu::lightDepthMeetsSegment(glm::vec2(segment.farDistance, 50.0f), segment));
    EXPECT_FALSE(gpu::lightDepthMeetsSegment(glm::vec2(42.05f, 50.0f), segment));
    // A point 5 m wide at distance 50 misses it by depth, so the whole tile test rejects it.
    gpu::CullLight point{};
    point.cosOuter = -1.0f;
    point.position = point.sphereCenter = glm::vec3(0.0f, 0.0f, -50.0f);
    point.range = point.sphereRadius = 5.0f;
    EXPECT_FALSE(gpu::lightDepthMeetsSegment(gpu::lightDistanceExtent(point), segment));
    EXPECT_FALSE(gpu::lightMayTouchTile(point, segment));
    // At distance 45 it reaches 40: both pass (it sits on the axis, inside the side planes).
    point.position = point.sphereCenter = glm::vec3(0.0f, 0.0f, -45.0f);
    EXPECT_TRUE(gpu::lightDepthMeetsSegment(gpu::lightDistanceExtent(point), segment));
    EXPECT_TRUE(gpu::lightMayTouchTile(point, segment));
}

}  // namespace
}  // namespace punctual
