// The bench's per-round sample (src/bench/bench_rows.h): no device needed, but the row helpers live
// in the GPU library with the renderer's types.
#include <gtest/gtest.h>

#include <algorithm>

#include "bench/bench_rows.h"
#include "bench/bench_run.h"

namespace punctual::bench {
namespace {

render::PassTimings frame(double depth, double forward, double total) {
    render::PassTimings t;
    t.passes = {{"depth", depth}, {"forward", forward}};
    t.total = total;
    return t;
}

// The columns hold every pass any configuration ran, in frame order: virtual pages' marking passes
// come between culling and shadows whichever configuration ran first.
TEST(BenchRows, PassNamesOfEveryConfigurationMergeInFrameOrder) {
    std::vector<std::string> known = {"depth", "culling", "shadows", "forward"};
    bench::mergePassNames(known, {"depth", "culling", "shadow_marks", "shadow_marks_transparent", "shadows", "forward"});
    EXPECT_EQ(known, (std::vector<std::string>{"depth", "culling", "shadow_marks", "shadow_marks_transparent", "shadows",
                                               "forward"}));
    bench::mergePassNames(known, {"depth", "shadows", "forward", "tonemap"});
    EXPECT_EQ(known.back(), "tonemap");
    std::vector<std::string> empty;
    bench::mergePassNames(empty, {"depth", "forward"});
    EXPECT_EQ(empty, (std::vector<std::string>{"depth", "forward"}));
}

TEST(BenchRows, FastestPerPassTakesEachPassAndTheTotalApart) {
    // Frame 2 has the fastest depth pass, frame 3 the fastest forward pass, frame 1 the fastest
    // total (its passes overlap less with idle gaps): each is kept on its own.
    const render::PassTimings fastest = fastestPerPass({frame(2.0, 30.0, 33.5), frame(1.5, 31.0, 34.0), frame(2.5, 29.0, 33.9)});
    ASSERT_EQ(fastest.passes.size(), 2u);
    EXPECT_EQ(fastest.passes[0].first, "depth");  // frame order kept
    EXPECT_EQ(fastest.passes[1].first, "forward");
    EXPECT_DOUBLE_EQ(fastest.of("depth"), 1.5);
    EXPECT_DOUBLE_EQ(fastest.of("forward"), 29.0);
    EXPECT_DOUBLE_EQ(fastest.total, 33.5);
}

TEST(BenchRows, FastestOfOneFrameIsThatFrame) {
    const render::PassTimings one = fastestPerPass({frame(1.25, 7.5, 9.0)});
    EXPECT_DOUBLE_EQ(one.of("depth"), 1.25);
    EXPECT_DOUBLE_EQ(one.of("forward"), 7.5);
    EXPECT_DOUBLE_EQ(one.total, 9.0);
    EXPECT_TRUE(fastestPerPass({}).passes.empty());
}

TEST(BenchRows, EveryRowSaysHowManyFramesEachRoundKept) {
    const std::vector<std::string> columns = benchColumns({"depth", "forward"});
    const auto rounds = std::find(columns.begin(), columns.end(), "rounds");
    ASSERT_NE(rounds, columns.end());
    EXPECT_EQ(*(rounds + 1), "best_of");
}

}  // namespace
}  // namespace punctual::bench
