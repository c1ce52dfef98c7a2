// Known answers for the tent shadow filters (shaders/shared/shadow_tent.h): the bilinear compare
// fetches it places, emulated on the CPU, must weigh every texel exactly as the continuous tent
// integrated over that texel does, for any sub-texel position of the sample point.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "shadow_tent.h"

namespace punctual {
namespace {

using gpu::tentAxisFetch;
using gpu::tentAxisTexelPair;
using gpu::tentFetch;
using gpu::tentFetchCount;
using gpu::tentFetchesPerAxis;
using gpu::tentTexelWeight;

constexpr uint32_t kSizes[] = {3u, 5u, 7u};

// ---- hand-computed values --------------------------------------------------------------------

TEST(ShadowTent, FetchCounts) {
    // (N + 1) / 2 fetches per axis: 2, 3 and 4; squared: 4, 9 and 16 (not (N - 1)^2).
    EXPECT_EQ(tentFetchCount(3u), 4u);
    EXPECT_EQ(tentFetchCount(5u), 9u);
    EXPECT_EQ(tentFetchCount(7u), 16u);
}

TEST(ShadowTent, Tent3AtATexelCorner) {
    // 3x3, sample point exactly on a texel corner (o = 0): h = 1.5, area scale 1 / h^2 = 4/9. The
    // four texels' centres lie at -1.5, -0.5, 0.5, 1.5 from the sample point.
    //   end texels: the tent covers half of each ((0.5 - o) = 0.5 of base), a triangle of area
    //     0.5 x 0.5 x 0.5 = 0.125 (height 0.5 before scaling), so 0.125 x 4/9 = 1/18;
    //   middle texels: the apex on their shared edge, mean |x - t| over each = 0.5, so
    //     (1.5 - 0.5) x 4/9 = 4/9.
    //   1/18 + 4/9 + 4/9 + 1/18 = 1.
    EXPECT_NEAR(tentTexelWeight(-1.5f, 1.5f), 1.0f / 18.0f, 1e-7f);
    EXPECT_NEAR(tentTexelWeight(-0.5f, 1.5f), 4.0f / 9.0f, 1e-7f);
    EXPECT_NEAR(tentTexelWeight(0.5f, 1.5f), 4.0f / 9.0f, 1e-7f);
    EXPECT_NEAR(tentTexelWeight(1.5f, 1.5f), 1.0f / 18.0f, 1e-7f);
    // Fetch 0 reads texels 0 and 1: weight 1/18 + 4/9 = 1/2, at texel 0's centre plus
    // (4/9) / (1/2) = 8/9 of a texel: -1.5 + 8/9 = -11/18. Fetch 1 mirrors it: 1/2 at +11/18.
    const glm::vec2 first = tentAxisFetch(0.0f, 3u, 0u);
    const glm::vec2 second = tentAxisFetch(0.0f, 3u, 1u);
    EXPECT_NEAR(first.x, 0.5f, 1e-7f);
    EXPECT_NEAR(first.y, -11.0f / 18.0f, 1e-6f);
    EXPECT_NEAR(second.x, 0.5f, 1e-7f);
    EXPECT_NEAR(second.y, 11.0f / 18.0f, 1e-6f);
    // In 2D, four fetches of weight 1/4 at (+-11/18, +-11/18), row by row.
    const glm::vec3 expected[] = {{-11.0f / 18.0f, -11.0f / 18.0f, 0.25f},
                                  {11.0f / 18.0f, -11.0f / 18.0f, 0.25f},
                                  {-11.0f / 18.0f, 11.0f / 18.0f, 0.25f},
                                  {11.0f / 18.0f, 11.0f / 18.0f, 0.25f}};
    for (uint32_t i = 0; i < 4u; ++i) {
        const glm::vec3 fetch = tentFetch(glm::vec2(7.0f, 3.0f), 3u, i);  // on a corner: o = 0
        EXPECT_NEAR(fetch.x, expected[i].x, 1e-6f) << i;
        EXPECT_NEAR(fetch.y, expected[i].y, 1e-6f) << i;
        EXPECT_NEAR(fetch.z, expected[i].z, 1e-7f) << i;
    }
}

TEST(ShadowTent, Tent3AtATexelCentre) {
    // 3x3, sample point at a texel's centre: t = c - 0.5, o = -0.5. Texel centres at -1, 0, 1, 2.
    //   texel 0: tent covers (0.5 - o) = 1 of it, triangle 1 x 1 / 2 = 0.5 -> 0.5 x 4/9 = 2/9;
    //   texel 1: the apex at its centre, mean |x - t| = 0.25, (1.5 - 0.25) x 4/9 = 5/9;
    //   texel 2: like texel 0, 2/9;  texel 3: outside the tent, 0.
    // The classic [2 5 2] / 9 of a 3-texel tent. Fetch 0: 7/9 at -1 + (5/9)/(7/9) = -2/7;
    // fetch 1: 2/9 exactly at texel 2's centre (+1), so the bilinear fetch reads texel 2 alone.
    EXPECT_NEAR(tentTexelWeight(-1.0f, 1.5f), 2.0f / 9.0f, 1e-7f);
    EXPECT_NEAR(tentTexelWeight(0.0f, 1.5f), 5.0f / 9.0f, 1e-7f);
    EXPECT_NEAR(tentTexelWeight(1.0f, 1.5f), 2.0f / 9.0f, 1e-7f);
    EXPECT_EQ(tentTexelWeight(2.0f, 1.5f), 0.0f);
    const glm::vec2 first = tentAxisFetch(-0.5f, 3u, 0u);
    const glm::vec2 second = tentAxisFetch(-0.5f, 3u, 1u);
    EXPECT_NEAR(first.x, 7.0f / 9.0f, 1e-7f);
    EXPECT_NEAR(first.y, -2.0f / 7.0f, 1e-6f);
    EXPECT_NEAR(second.x, 2.0f / 9.0f, 1e-7f);
    EXPECT_NEAR(second.y, 1.0f, 1e-6f);
}

TEST(ShadowTent, Tent5AtATexelCorner) {
    // 5x5, o = 0: h = 2.5, scale 1 / 6.25 = 0.16; texel centres at -2.5 ... 2.5.
    //   |x| = 2.5: end triangle 0.125 -> 0.02;  |x| = 1.5: midpoint h - 1.5 = 1 -> 0.16;
    //   |x| = 0.5: apex on the edge, h - 0.5 = 2 -> 0.32.  Sum 2 x (0.02 + 0.16 + 0.32) = 1.
    // Fetches: 0.18 at -2.5 + 0.16/0.18 = -1.6111; 0.64 at -0.5 + 0.32/0.64 = 0; 0.18 at +1.6111.
    const float expectedWeight[] = {0.18f, 0.64f, 0.18f};
    const float expectedPosition[] = {-2.5f + 0.16f / 0.18f, 0.0f, 1.5f + 0.02f / 0.18f};
    for (uint32_t m = 0; m < 3u; ++m) {
        const glm::vec2 fetch = tentAxisFetch(0.0f, 5u, m);
        EXPECT_NEAR(fetch.x, expectedWeight[m], 1e-6f) << m;
        EXPECT_NEAR(fetch.y, expectedPosition[m], 1e-6f) << m;
    }
}

// ---- against brute force ----------------------------------------------------------------------

// The exact integral of the unit-area tent of half-width h centred at 0 from -infinity to x (its
// cumulative distribution): 0 before -h, (x + h)^2 / (2 h^2) up to the apex, 1 - (h - x)^2 /
// (2 h^2) after it, 1 beyond h. A texel's weight is the difference at its two edges. Worked out
// here independently of the header's per-texel formula.
double tentCdf(double x, double h) {
    if (x <= -h) return 0.0;
    if (x >= h) return 1.0;
    if (x <= 0.0) return (x + h) * (x + h) / (2.0 * h * h);
    return 1.0 - (h - x) * (h - x) / (2.0 * h * h);
}

struct CompareMap {
    int size = 0;
    std::vector<double> lit;  // compare result per texel: 0 (shadowed) or 1 (lit)
    double at(int x, int y) const { return lit[size_t(y) * size_t(size) + size_t(x)]; }
};

// A hardware bilinear compare fetch at texel coordinate q (Vulkan: i0 = floor(q - 0.5), weights
// 1 - frac and frac), in double.
double bilinearFetch(const CompareMap& map, double qx, double qy) {
    const double sx = qx - 0.5, sy = qy - 0.5;
    const int x0 = int(std::floor(sx)), y0 = int(std::floor(sy));
    const double fx = sx - x0, fy = sy - y0;
    return (1 - fx) * (1 - fy) * map.at(x0, y0) + fx * (1 - fy) * map.at(x0 + 1, y0) +
           (1 - fx) * fy * map.at(x0, y0 + 1) + fx * fy * map.at(x0 + 1, y0 + 1);
}

// The filter as the shader runs it: the header's fetches, emulated.
double filteredByFetches(const CompareMap& map, glm::vec2 t, uint32_t n, double* weightSum) {
    double sum = 0.0;
    *weightSum = 0.0;
    for (uint32_t i = 0; i < tentFetchCount(n); ++i) {
        const glm::vec3 fetch = tentFetch(t, n, i);
        sum += double(fetch.z) * bilinearFetch(map, double(t.x) + double(fetch.x), double(t.y) + double(fetch.y));
        *weightSum += double(fetch.z);
    }
    return sum;
}

// Brute force: every texel the tent may touch, weighted by the tent's exact integral over it.
double filteredByTexels(const CompareMap& map, glm::vec2 t, uint32_t n) {
    const double h = 0.5 * n;
    double sum = 0.0;
    for (int y = 0; y < map.size; ++y) {
        const double wy = tentCdf(y + 1 - double(t.y), h) - tentCdf(y - double(t.y), h);
        if (wy == 0.0) continue;
        for (int x = 0; x < map.size; ++x) {
            const double wx = tentCdf(x + 1 - double(t.x), h) - tentCdf(x - double(t.x), h);
            sum += wx * wy * map.at(x, y);
        }
    }
    return sum;
}

TEST(ShadowTent, FetchesWeighEveryTexelAsTheContinuousTent) {
    std::mt19937 random(11);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    CompareMap map;
    map.size = 16;
    size_t checked = 0;
    for (int round = 0; round < 40; ++round) {
        map.lit.assign(size_t(map.size * map.size), 0.0);
        for (double& value : map.lit) value = random() & 1u ? 1.0 : 0.0;
        // Sub-texel positions: a regular sweep including the corner (o = 0), the texel centre
        // (o = -0.5) and just below the next centre, then random ones; the tent (reach < 4
        // texels) stays inside the 16 x 16 map around texel 7 or 8.
        std::vector<glm::vec2> points;
        for (float f : {0.0f, 0.25f, 0.5f, 0.75f, 0.4999f, 0.5001f, 0.9999f})
            for (float g : {0.0f, 0.5f, 0.125f, 0.99f}) points.emplace_back(8.0f + f, 7.0f + g);
        for (int k = 0; k < 20; ++k) points.emplace_back(7.5f + unit(random), 7.5f + unit(random));
        for (const glm::vec2 t : points) {
            for (const uint32_t n : kSizes) {
                double weights = 0.0;
                const double fetched = filteredByFetches(map, t, n, &weights);
                const double brute = filteredByTexels(map, t, n);
                ASSERT_NEAR(weights, 1.0, 1e-6) << "N " << n << " at " << t.x << ", " << t.y;
                ASSERT_NEAR(fetched, brute, 1e-6) << "N " << n << " at " << t.x << ", " << t.y;
                ++checked;
            }
        }
    }
    EXPECT_EQ(checked, 40u * (28u + 20u) * 3u);
}

// The receiver-plane path (shadow_sampling.glsl, filterAtlasReceiverPlane) reads the same texels
// as 2 x 2 gathers of raw depths and weighs each texel itself: texel pair m along an axis starts at
// the texel whose centre lies u.x from the sample point (index round(t + u.x - 0.5)), with
// weights u.y and u.z. Emulated here with the compare results of a map, it must give the brute-force
// tent too; N = 1 must give the hardware's bilinear fetch at the sample point.
double filteredByTexelPairs(const CompareMap& map, glm::vec2 t, uint32_t n, double* weightSum) {
    const glm::vec2 o = t - glm::floor(t + 0.5f);
    double sum = 0.0;
    *weightSum = 0.0;
    for (uint32_t i = 0; i < tentFetchCount(n); ++i) {
        const glm::vec3 u = tentAxisTexelPair(o.x, n, i % tentFetchesPerAxis(n));
        const glm::vec3 v = tentAxisTexelPair(o.y, n, i / tentFetchesPerAxis(n));
        const int x0 = int(std::lround(double(t.x) + double(u.x) - 0.5));
        const int y0 = int(std::lround(double(t.y) + double(v.x) - 0.5));
        const double wx[2] = {double(u.y), double(u.z)};
        const double wy[2] = {double(v.y), double(v.z)};
        for (int dy = 0; dy < 2; ++dy) {
            for (int dx = 0; dx < 2; ++dx) {
                sum += wx[dx] * wy[dy] * map.at(x0 + dx, y0 + dy);
                *weightSum += wx[dx] * wy[dy];
            }
        }
    }
    return sum;
}

TEST(ShadowTent, TexelPairsWeighEveryTexelAsTheTentAndTheHardware) {
    std::mt19937 random(12);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    CompareMap map;
    map.size = 16;
    size_t checked = 0;
    for (int round = 0; round < 20; ++round) {
        map.lit.assign(size_t(map.size * map.size), 0.0);
        for (double& value : map.lit) value = random() & 1u ? 1.0 : 0.0;
        std::vector<glm::vec2> points = {{8.0f, 7.0f}, {8.5f, 7.5f}, {8.4999f, 7.0001f}, {8.9999f, 7.25f}};
        for (int k = 0; k < 20; ++k) points.emplace_back(7.5f + unit(random), 7.5f + unit(random));
        for (const glm::vec2 t : points) {
            for (const uint32_t n : kSizes) {
                double weights = 0.0;
                const double paired = filteredByTexelPairs(map, t, n, &weights);
                ASSERT_NEAR(weights, 1.0, 1e-6) << "N " << n;
                ASSERT_NEAR(paired, filteredByTexels(map, t, n), 1e-6) << "N " << n << " at " << t.x << ", " << t.y;
                ++checked;
            }
            double weights = 0.0;
            const double hardware = filteredByTexelPairs(map, t, 1u, &weights);
            ASSERT_NEAR(weights, 1.0, 1e-6);
            ASSERT_NEAR(hardware, bilinearFetch(map, double(t.x), double(t.y)), 1e-6) << t.x << ", " << t.y;
            ++checked;
        }
    }
    EXPECT_EQ(checked, 20u * 24u * 4u);
}

TEST(ShadowTent, HardwarePairIsTheBilinearFootprint) {
    // N = 1, sample point a quarter texel past a corner (o = 0.25): texel centres at -0.75 and
    // +0.25, bilinear weights 1 - 0.75 = 0.25 and 1 - 0.25 = 0.75; one fetch of weight 1 at 0.
    const glm::vec3 pair = tentAxisTexelPair(0.25f, 1u, 0u);
    EXPECT_NEAR(pair.x, -0.75f, 1e-7f);
    EXPECT_NEAR(pair.y, 0.25f, 1e-7f);
    EXPECT_NEAR(pair.z, 0.75f, 1e-7f);
    const glm::vec2 fetch = tentAxisFetch(0.25f, 1u, 0u);
    EXPECT_NEAR(fetch.x, 1.0f, 1e-7f);
    EXPECT_NEAR(fetch.y, 0.0f, 1e-7f);
}

TEST(ShadowTent, TexelWeightsMatchTheExactIntegralAndSumToOne) {
    // One axis, many offsets: each texel j = 0 .. N (centre at j - h - o from the sample point)
    // against the integral of the tent over it; together they cover the tent.
    for (const uint32_t n : kSizes) {
        const float h = 0.5f * float(n);
        for (int step = 0; step <= 1000; ++step) {
            const float o = -0.5f + float(step) / 1000.0f * 0.99999f;
            double sum = 0.0;
            for (uint32_t j = 0; j <= n; ++j) {
                const float x = float(j) - h - o;
                const double exact = tentCdf(double(x) + 0.5, h) - tentCdf(double(x) - 0.5, h);
                const float weight = tentTexelWeight(x, h);
                ASSERT_NEAR(weight, exact, 1e-6) << "N " << n << " o " << o << " texel " << j;
                ASSERT_GE(weight, 0.0f);
                sum += double(weight);
            }
            ASSERT_NEAR(sum, 1.0, 1e-6) << "N " << n << " o " << o;
        }
    }
}

}  // namespace
}  // namespace punctual
