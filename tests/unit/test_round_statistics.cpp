// The bench's timing arithmetic (metrics/round_statistics.h), on hand-computed samples.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "metrics/round_statistics.h"

namespace punctual {
namespace {

TEST(RoundStatistics, QuantilesInterpolateBetweenOrderStatistics) {
    // Sorted: 1 2 4 8 16. Position q (n - 1): the quartiles sit at 1 and 3, exactly on samples;
    // q = 0.1 sits at 0.4, 40% of the way from 1 to 2.
    const std::vector<double> samples = {8, 1, 16, 2, 4};
    EXPECT_DOUBLE_EQ(quantile(samples, 0.25), 2.0);
    EXPECT_DOUBLE_EQ(quantile(samples, 0.5), 4.0);
    EXPECT_DOUBLE_EQ(quantile(samples, 0.75), 8.0);
    EXPECT_DOUBLE_EQ(quantile(samples, 0.1), 1.4);
    EXPECT_DOUBLE_EQ(quantile(samples, 1.0), 16.0);
    // Four samples 10 20 30 40: the median at 1.5 is 25, the quartiles at 0.75 and 2.25.
    EXPECT_DOUBLE_EQ(quantile({40, 10, 30, 20}, 0.5), 25.0);
    EXPECT_DOUBLE_EQ(quantile({40, 10, 30, 20}, 0.25), 17.5);
    EXPECT_DOUBLE_EQ(quantile({40, 10, 30, 20}, 0.75), 32.5);
    EXPECT_DOUBLE_EQ(quantile({}, 0.5), 0.0);
}

TEST(RoundStatistics, SummaryOfFiveRounds) {
    // 9 10 10 11 60: median 10, IQR 11 - 10 = 1 (the outlier does not move it). Mean 20; the
    // squared deviations 121 100 100 81 1600 sum to 2002, / 4 = 500.5, sqrt = 22.3719...
    const RoundSummary s = summarizeRounds({10, 60, 9, 11, 10});
    EXPECT_DOUBLE_EQ(s.median, 10.0);
    EXPECT_DOUBLE_EQ(s.iqr, 1.0);
    EXPECT_NEAR(s.cv, 22.371857321 / 20.0, 1e-9);
    EXPECT_DOUBLE_EQ(summarizeRounds({5}).cv, 0.0);  // one sample has no spread
    EXPECT_DOUBLE_EQ(summarizeRounds({0, 0, 0}).cv, 0.0);
}

TEST(RoundStatistics, SpreadLimitFlagsWideConfigurations) {
    EXPECT_FALSE(exceedsSpreadLimit(summarizeRounds({10, 60, 9, 11, 10}), 0.15));  // IQR 1 of 10
    // 10 12 14 16 18: IQR 16 - 12 = 4, 4 / 14 = 0.29 > 0.15.
    EXPECT_TRUE(exceedsSpreadLimit(summarizeRounds({10, 12, 14, 16, 18}), 0.15));
    EXPECT_FALSE(exceedsSpreadLimit(summarizeRounds({10, 12, 14, 16, 18}), 0.3));
    EXPECT_FALSE(exceedsSpreadLimit(summarizeRounds({0, 0, 0}), 0.15));
    EXPECT_TRUE(exceedsSpreadLimit(summarizeRounds({0, 0, 1, 2, 2}), 0.15));  // IQR 2 on a median of 1
    EXPECT_DOUBLE_EQ(medianOf({0.3, 0.1, 0.2}), 0.2);
}

TEST(RoundStatistics, RoundOrdersArePermutationsFixedBySeedGroupAndRound) {
    const std::vector<uint32_t> order = roundOrder(12, 1, 0, 0);
    ASSERT_EQ(order.size(), 12u);
    EXPECT_EQ(std::set<uint32_t>(order.begin(), order.end()).size(), 12u);
    EXPECT_EQ(*std::max_element(order.begin(), order.end()), 11u);
    EXPECT_EQ(order, roundOrder(12, 1, 0, 0));  // reproducible
    // Another round, group or seed draws another order (12! orders: a repeat would be a bug).
    EXPECT_NE(order, roundOrder(12, 1, 0, 1));
    EXPECT_NE(order, roundOrder(12, 1, 1, 0));
    EXPECT_NE(order, roundOrder(12, 2, 0, 0));
    // Every position is visited by every configuration over many rounds: no fixed order.
    std::vector<std::set<uint32_t>> seenAt(12);
    for (uint32_t round = 0; round < 200; ++round) {
        const std::vector<uint32_t> o = roundOrder(12, 7, 3, round);
        for (uint32_t i = 0; i < 12; ++i) seenAt[i].insert(o[i]);
    }
    for (const std::set<uint32_t>& seen : seenAt) EXPECT_EQ(seen.size(), 12u);
    EXPECT_TRUE(roundOrder(0, 1, 0, 0).empty());
    EXPECT_EQ(roundOrder(1, 1, 0, 0), std::vector<uint32_t>{0});
}

}  // namespace
}  // namespace punctual
