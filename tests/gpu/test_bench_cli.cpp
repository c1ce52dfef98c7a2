// `punctual bench --quick` as CI runs it: a smoke test of the files and their columns, never of
// the timings (lavapipe timings are CPU timings and vary from run to run).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <set>
#include <vector>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "gpu_test_support.h"

namespace punctual {
namespace {

std::string readAll(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

TEST(BenchCli, QuickModeWritesResultsWithEveryColumn) {
    testing::TempFolder folder;
    const std::string dir = folder.file("bench");
    const std::string command = std::string("'") + PUNCTUAL_BINARY + "' bench --quick --validate --out-dir '" + dir +
                                "' > '" + folder.file("out.txt") + "' 2> '" + folder.file("err.txt") + "'";
    ASSERT_EQ(std::system(command.c_str()), 0) << readAll(folder.file("err.txt"));
    EXPECT_EQ(readAll(folder.file("err.txt")), "");  // no validation messages, no progress bar (not a terminal)

    std::istringstream csv(readAll(dir + "/results.csv"));
    std::string header;
    std::getline(csv, header);
    EXPECT_EQ(header,
              "config,series,method,spot,point,shadows,shadow_res,shadow_filter,point_layout,frames,depth_ms,culling_ms,"
              "shadows_ms,forward_ms,total_ms,forward_spread_ms,total_spread_ms,tested_per_pixel,affecting_per_pixel,"
              "efficiency,missed_energy,image_error,pixels_off,shadow_misclassified,shadow_false_shadow,shadow_false_lit");
    const size_t columns = size_t(std::count(header.begin(), header.end(), ',')) + 1;
    size_t rows = 0;
    std::set<std::string> series, methods;
    for (std::string line; std::getline(csv, line);) {
        ++rows;
        EXPECT_EQ(size_t(std::count(line.begin(), line.end(), ',')) + 1, columns) << line;
        std::istringstream fields(line);
        std::string config, s, method;
        std::getline(fields, config, ',');
        std::getline(fields, s, ',');
        std::getline(fields, method, ',');
        series.insert(s);
        methods.insert(method);
    }
    EXPECT_GE(rows, 30u);
    EXPECT_EQ(series, (std::set<std::string>{"mix", "spot-only", "point-only", "shadows", "shadow-quality"}));
    EXPECT_EQ(methods, (std::set<std::string>{"brute", "per-object", "tiled", "clustered"}));

    const nlohmann::json json = nlohmann::json::parse(readAll(dir + "/results.json"));
    EXPECT_EQ(json["configurations"].size(), rows);
    EXPECT_TRUE(json["quick"].get<bool>());
    EXPECT_TRUE(std::filesystem::exists(dir + "/images/heatmap-tiled.png"));

    // The failure study: every known failure measured against its parameter.
    std::istringstream failures(readAll(dir + "/failures.csv"));
    std::string failureHeader;
    std::getline(failures, failureHeader);
    EXPECT_EQ(failureHeader, "study,parameter,value,variant,metric,error,total_ms");
    std::set<std::string> studies;
    for (std::string line; std::getline(failures, line);) studies.insert(line.substr(0, line.find(',')));
    EXPECT_EQ(studies, (std::set<std::string>{"acne-vs-bias", "peter-panning-vs-bias", "cube-seams", "pancaking-leak",
                                              "wide-spot", "tile-depth-discontinuities", "per-object-large-objects",
                                              "beyond-the-caps"}));
}

TEST(BenchCli, BadOptionsFailCleanly) {
    testing::TempFolder folder;
    for (const std::string& args : std::vector<std::string>{"bench", "bench --out-dir", "bench --out-dir '" + folder.file("a/b") + "'",
                                   "bench --culling tiled --out-dir '" + folder.file("x") + "'"}) {
        const std::string command = std::string("'") + PUNCTUAL_BINARY + "' " + args + " > /dev/null 2> '" +
                                    folder.file("err.txt") + "'";
        const int status = std::system(command.c_str());
        EXPECT_NE(status, 0) << args;
        const std::string err = readAll(folder.file("err.txt"));
        EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << args << ": " << err;
        EXPECT_NE(err.find("punctual: error: "), std::string::npos) << err;
    }
    EXPECT_FALSE(std::filesystem::exists(folder.file("x")));
}

}  // namespace
}  // namespace punctual
