// Known answers for the bilinear compare every atlas lookup makes in the shader (shadows.h:
// bilinearCorner, bilinearFraction, bilinearCompare): the four texels around a sample point, its
// place between their centres, and the weighted compares, as the hardware's sampler2DShadow tap
// computes them (VK_COMPARE_OP_LESS_OR_EQUAL, bilinear).
#include <gtest/gtest.h>

#include "shadows.h"

namespace punctual {
namespace {

using gpu::bilinearCompare;
using gpu::bilinearCorner;
using gpu::bilinearFraction;

// textureGather's order: (u0, v1), (u1, v1), (u1, v0), (u0, v0).
glm::vec4 gathered(float u0v0, float u1v0, float u0v1, float u1v1) { return {u0v1, u1v1, u1v0, u0v0}; }

TEST(BilinearCompare, ATexelCentreReadsThatTexelAlone) {
    // Texel 2's centre is 2.5: the four texels are 2 and 3 on each axis (corner 3), and the sample
    // sits on the first one's centre.
    const glm::vec2 position(2.5f, 2.5f);
    const glm::vec2 corner = bilinearCorner(position, 8.0f);
    EXPECT_EQ(corner, glm::vec2(3.0f, 3.0f));
    EXPECT_EQ(bilinearFraction(position, corner), glm::vec2(0.0f, 0.0f));
    EXPECT_EQ(bilinearCompare(gathered(0.9f, 0.1f, 0.1f, 0.1f), 0.5f, glm::vec2(0.0f)), 1.0f);
    EXPECT_EQ(bilinearCompare(gathered(0.1f, 0.9f, 0.9f, 0.9f), 0.5f, glm::vec2(0.0f)), 0.0f);
}

TEST(BilinearCompare, BetweenCentresTheWeightsAreTheDistances) {
    // (2.75, 3.25): a quarter of the way from texel 2's centre to 3's in u; in v, 3.25 is past
    // texel 2's centre (2.5) by three quarters, so the corner is (3, 3) and f = (1/4, 3/4).
    const glm::vec2 position(2.75f, 3.25f);
    const glm::vec2 corner = bilinearCorner(position, 8.0f);
    EXPECT_EQ(corner, glm::vec2(3.0f, 3.0f));
    const glm::vec2 f = bilinearFraction(position, corner);
    EXPECT_EQ(f, glm::vec2(0.25f, 0.75f));
    // The u0 column lit, the u1 column in shadow: 1 - 1/4.
    EXPECT_FLOAT_EQ(bilinearCompare(gathered(0.9f, 0.1f, 0.9f, 0.1f), 0.5f, f), 0.75f);
    // The v0 row lit, the v1 row in shadow: 1 - 3/4.
    EXPECT_FLOAT_EQ(bilinearCompare(gathered(0.9f, 0.9f, 0.1f, 0.1f), 0.5f, f), 0.25f);
    // Only u1v1 lit: 1/4 x 3/4.
    EXPECT_FLOAT_EQ(bilinearCompare(gathered(0.1f, 0.1f, 0.1f, 0.9f), 0.5f, f), 0.1875f);
}

TEST(BilinearCompare, AReferenceEqualToTheCasterIsLit) {
    // LESS_OR_EQUAL: a receiver at the caster's own depth is lit, as the compare sampler says.
    EXPECT_EQ(bilinearCompare(glm::vec4(0.5f), 0.5f, glm::vec2(0.3f, 0.6f)), 1.0f);
    EXPECT_EQ(bilinearCompare(glm::vec4(0.5f), 0.50001f, glm::vec2(0.3f, 0.6f)), 0.0f);
}

TEST(BilinearCompare, AtTheSquaresEdgeTheFourTexelsStayInside) {
    // Lookups are clamped half a texel inside the square: at (0.5, 7.5) of an 8-texel square the
    // corner would be (1, 8), whose texel 8 lies outside; kept at 7, the sample sits on texel 7's
    // centre (f = 1), and the first texel's on u (f = 0): clamp to edge.
    const glm::vec2 position(0.5f, 7.5f);
    const glm::vec2 corner = bilinearCorner(position, 8.0f);
    EXPECT_EQ(corner, glm::vec2(1.0f, 7.0f));
    EXPECT_EQ(bilinearFraction(position, corner), glm::vec2(0.0f, 1.0f));
}

}  // namespace
}  // namespace punctual
