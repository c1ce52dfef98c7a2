// Triangle strips and fans as triangle lists, checked against index lists written out by hand
// from the glTF 2.0 spec's rules (scene/triangle_topology.h).
#include <gtest/gtest.h>

#include "scene/triangle_topology.h"

namespace punctual {
namespace {

using Indices = std::vector<uint32_t>;

TEST(StripAndFan, TooShortGivesNothing) {
    EXPECT_TRUE(triangleListFromStrip(Indices{}).empty());
    EXPECT_TRUE(triangleListFromStrip(Indices{0, 1}).empty());
    EXPECT_TRUE(triangleListFromFan(Indices{}).empty());
    EXPECT_TRUE(triangleListFromFan(Indices{4, 5}).empty());
}

TEST(StripAndFan, StripOfOneTriangleIsThatTriangle) {
    EXPECT_EQ(triangleListFromStrip(Indices{7, 3, 9}), (Indices{7, 3, 9}));
}

TEST(StripAndFan, StripAlternatesWindingOnOddTriangles) {
    // p_i = {v_i, v_{i+(1+i%2)}, v_{i+(2-i%2)}}: odd triangles take v_{i+2} before v_{i+1}.
    const Indices strip = {10, 11, 12, 13, 14, 15};
    const Indices expected = {
        10, 11, 12,  // i = 0
        11, 13, 12,  // i = 1 (odd)
        12, 13, 14,  // i = 2
        13, 15, 14,  // i = 3 (odd)
    };
    EXPECT_EQ(triangleListFromStrip(strip), expected);
}

TEST(StripAndFan, StripKeepsTheWindingOfAFlatQuadCounterClockwise) {
    // Corners of a unit quad in the z = 0 plane, counter-clockwise seen from +Z: 0 (0,0), 1 (1,0),
    // 2 (1,1), 3 (0,1). Strip order 0 1 3 2 must give two counter-clockwise triangles.
    const Indices list = triangleListFromStrip(Indices{0, 1, 3, 2});
    EXPECT_EQ(list, (Indices{0, 1, 3, 1, 2, 3}));
    const float x[4] = {0, 1, 1, 0};
    const float y[4] = {0, 0, 1, 1};
    for (size_t t = 0; t < list.size(); t += 3) {
        const uint32_t a = list[t], b = list[t + 1], c = list[t + 2];
        const float signedArea = (x[b] - x[a]) * (y[c] - y[a]) - (x[c] - x[a]) * (y[b] - y[a]);
        EXPECT_GT(signedArea, 0.0f) << "triangle " << t / 3;
    }
}

TEST(StripAndFan, StripDropsDegenerateJoinsAndKeepsTheParityOfTheNextRun) {
    // Two quads joined by repeating the last index of the first and the first of the second:
    // triangles 2 to 5 repeat an index and are dropped; the second run starts at an even
    // position again, so its triangles keep their winding.
    const Indices strip = {0, 1, 3, 2, 2, 4, 4, 5, 7, 6};
    const Indices expected = {
        0, 1, 3,  // i = 0
        1, 2, 3,  // i = 1 (odd)
        // i = 2..5: (3 2 2), (2 4 2), (2 4 4), (4 5 4): dropped
        4, 5, 7,  // i = 6
        5, 6, 7,  // i = 7 (odd)
    };
    EXPECT_EQ(triangleListFromStrip(strip), expected);
}

TEST(StripAndFan, StripOfOnlyDegenerateTrianglesIsEmpty) {
    EXPECT_TRUE(triangleListFromStrip(Indices{3, 3, 3, 3}).empty());
    EXPECT_TRUE(triangleListFromStrip(Indices{1, 2, 1, 2}).empty());
}

TEST(StripAndFan, FanSharesTheFirstVertexAndStartsEachTriangleAfterIt) {
    // p_i = {v_{i+1}, v_{i+2}, v_0}.
    const Indices fan = {20, 21, 22, 23, 24};
    const Indices expected = {
        21, 22, 20,
        22, 23, 20,
        23, 24, 20,
    };
    EXPECT_EQ(triangleListFromFan(fan), expected);
}

TEST(StripAndFan, FanDropsTrianglesThatRepeatAnIndex) {
    const Indices fan = {0, 1, 1, 2, 0, 3};
    // (1 1 0), (1 2 0) kept, (2 0 0), (0 3 0).
    EXPECT_EQ(triangleListFromFan(fan), (Indices{1, 2, 0}));
}

TEST(StripAndFan, FanOverARotatedQuadEqualsTheStripOfThatQuad) {
    // The two topologies can describe the very same triangles, vertex order included: the test
    // scenes (tests/support/gltf_geometry_variants.cpp) rely on it to compare renders bit for bit.
    EXPECT_EQ(triangleListFromFan(Indices{3, 0, 1, 2}), triangleListFromStrip(Indices{0, 1, 3, 2}));
}

}  // namespace
}  // namespace punctual
