// What `punctual play` writes (report/sequence_report.h; CPU only, but in the GPU binary, which
// links the report code): percentiles by linear interpolation between ranks (known answers), the
// summary per pass and for the total, the CSV's rows and columns, the chart's percentile lines,
// and an HTML page that escapes what it quotes.
#include <gtest/gtest.h>

#include <string>

#include "report/sequence_report.h"

namespace punctual::report {
namespace {

// Sorted 1, 2, 3, 4: p50 at rank 1.5 is 2.5; p95 at rank 2.85 is 3 + 0.85 = 3.85; p0 the least,
// p100 the most; one value is every percentile.
TEST(SequenceReport, PercentilesInterpolateBetweenTheClosestRanks) {
    EXPECT_DOUBLE_EQ(percentile({4.0, 1.0, 3.0, 2.0}, 50.0), 2.5);
    EXPECT_DOUBLE_EQ(percentile({4.0, 1.0, 3.0, 2.0}, 95.0), 3.85);
    EXPECT_DOUBLE_EQ(percentile({4.0, 1.0, 3.0, 2.0}, 0.0), 1.0);
    EXPECT_DOUBLE_EQ(percentile({4.0, 1.0, 3.0, 2.0}, 100.0), 4.0);
    EXPECT_DOUBLE_EQ(percentile({7.0}, 99.0), 7.0);
    EXPECT_DOUBLE_EQ(percentile({}, 50.0), 0.0);
    // 100 frames at 10 ms and one spike of 100: the median does not see it; p99.5 falls halfway
    // between the last 10 (rank 99) and the spike (rank 100): 10 + 0.5 x 90.
    std::vector<double> frames(100, 10.0);
    frames.push_back(100.0);
    EXPECT_DOUBLE_EQ(percentile(frames, 50.0), 10.0);
    EXPECT_DOUBLE_EQ(percentile(frames, 99.5), 55.0);
}

std::vector<SequenceFrame> threeFrames() {
    std::vector<SequenceFrame> frames;
    for (uint32_t i = 0; i < 3; ++i) {
        SequenceFrame f;
        f.index = i;
        f.time = 0.5 * i;
        f.ms.passes = {{"depth", 1.0 + i}, {"forward", 10.0 * (i + 1)}};
        f.ms.total = f.ms.passes[0].second + f.ms.passes[1].second;
        f.stats = {{"lights", {{"spot", 4 + i}, {"point", 2}}}, {"shadows", {{"memory_bytes", 1024 * (i + 1)}}}};
        frames.push_back(f);
    }
    return frames;
}

TEST(SequenceReport, TheSummaryGivesEveryPassAndTheTotalTheirPercentiles) {
    const nlohmann::json summary = sequenceSummaryJson(threeFrames());
    EXPECT_DOUBLE_EQ(summary["forward"]["p50"].get<double>(), 20.0);
    EXPECT_DOUBLE_EQ(summary["forward"]["max"].get<double>(), 30.0);
    EXPECT_DOUBLE_EQ(summary["depth"]["mean"].get<double>(), 2.0);
    EXPECT_DOUBLE_EQ(summary["total"]["p50"].get<double>(), 22.0);     // 11, 22, 33
    EXPECT_DOUBLE_EQ(summary["total"]["p95"].get<double>(), 31.9);     // rank 1.9: 22 + 0.9 x 11
    const nlohmann::json document = sequenceJson(threeFrames(), {{"scene", "s"}});
    EXPECT_EQ(document["passes"], nlohmann::json({"depth", "forward"}));
    ASSERT_EQ(document["frames"].size(), 3u);
    EXPECT_DOUBLE_EQ(document["frames"][2]["time_s"].get<double>(), 1.0);
    EXPECT_DOUBLE_EQ(document["frames"][2]["gpu_ms"]["total"].get<double>(), 33.0);
}

TEST(SequenceReport, TheCsvHasARowAFrameWithItsPassesAndCounters) {
    const std::string csv = sequenceCsv(threeFrames());
    const std::string header = csv.substr(0, csv.find('\n'));
    EXPECT_EQ(header.rfind("frame,time_s,depth_ms,forward_ms,total_ms,spot_lights,point_lights,", 0), 0u) << header;
    EXPECT_NE(header.find("shadow_memory_bytes"), std::string::npos);
    EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 4);
    EXPECT_NE(csv.find("\n2,1.0000,3.000,30.000,33.000,6,2,"), std::string::npos) << csv;
    EXPECT_NE(csv.find(",3072,"), std::string::npos) << csv;  // the third frame's shadow memory
}

TEST(SequenceReport, TheChartDrawsTheFramesAndThreePercentileLines) {
    const std::string svg = frameTimesSvg(threeFrames());
    EXPECT_EQ(svg.rfind("<svg", 0), 0u);
    EXPECT_NE(svg.find("<polyline"), std::string::npos);
    for (const char* label : {">p50 22.0 ms<", ">p95 31.9 ms<", ">p99 32.8 ms<"}) {
        EXPECT_NE(svg.find(label), std::string::npos) << label;
    }
}

TEST(SequenceReport, ThePageEscapesWhatItQuotesAndShowsTheFrames) {
    nlohmann::json document = sequenceJson(threeFrames(), {{"scene", "<b>&scene"}, {"device", "gpu"}});
    const std::string html = sequenceHtml(document, {frameImageName(0), frameImageName(12)});
    EXPECT_NE(html.find("&lt;b&gt;&amp;scene"), std::string::npos);
    EXPECT_EQ(html.find("<b>&scene"), std::string::npos);
    EXPECT_NE(html.find("src=\"frame-0012.png\""), std::string::npos);
    EXPECT_NE(html.find("src=\"frame_times.svg\""), std::string::npos);
    EXPECT_LT(html.find("<td>depth</td>"), html.find("<td>forward</td>"));  // frame order
    EXPECT_LT(html.find("<td>forward</td>"), html.find("<td>total</td>"));
}

}  // namespace
}  // namespace punctual::report
