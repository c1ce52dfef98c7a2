// `punctual bench --quick` as CI runs it: a smoke test of the files and their columns, never of
// the timings (lavapipe timings are CPU timings and vary from run to run).
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "gpu_test_support.h"
#include "lights/shadow_drawing_tiles.h"
#include "lights/shadow_filters.h"
#include "lights/shadow_setup.h"
#include "render/light_list_method.h"

namespace punctual {
namespace {

// The names a table marks for `bench --quick` (never restated here: a new variant needs no edit).
template <typename Table>
std::set<std::string> quickNames(const Table& table) {
    std::set<std::string> names;
    for (const auto& entry : table) {
        if (entry.quickBench) names.insert(entry.name);
    }
    return names;
}

using testing::readText;
using testing::RunResult;
using testing::runPunctual;

TEST(BenchCli, QuickModeWritesResultsWithEveryColumn) {
    testing::TempFolder folder;
    const std::string dir = folder.file("bench");
    // An earlier run's folder: its listed image that this run does not write goes, the user's stays.
    std::filesystem::create_directories(dir + "/images");
    std::ofstream(dir + "/results.json") << R"({"files": ["results.json", "images/mismatch-gone.png"]})";
    std::ofstream(dir + "/images/mismatch-gone.png") << "an earlier run's";
    std::ofstream(dir + "/images/mine.png") << "the user's";
    const RunResult run = runPunctual(folder, "bench --quick --validate --out-dir '" + dir + "'");
    ASSERT_EQ(run.exitCode, 0) << run.err;
    EXPECT_EQ(run.err, "");  // no validation messages, no progress bar (not a terminal)

    std::istringstream csv(readText(dir + "/results.csv"));
    std::string header;
    std::getline(csv, header);
    // Every pass any configuration ran has its columns (virtual pages' marking passes included).
    EXPECT_EQ(header,
              "config,series,method,spot,point,light_range,width,height,pixels,scene,scene_triangles,objects,shadows,"
              "shadow_res,shadow_budget_mib,shadow_format,shadow_filter,point_layout,cascades,shadowed_spots,"
              "shadowed_points,coarse_tiles,tile_kernel,tile_threads,light_lists,rounds,best_of,depth_ms,"
              "transparent_depth_ms,culling_ms,shadow_marks_ms,shadow_marks_transparent_ms,shadows_ms,forward_ms,"
              "transparent_ms,tonemap_ms,total_ms,depth_iqr_ms,transparent_depth_iqr_ms,culling_iqr_ms,"
              "shadow_marks_iqr_ms,shadow_marks_transparent_iqr_ms,shadows_iqr_ms,forward_iqr_ms,transparent_iqr_ms,"
              "tonemap_iqr_ms,total_iqr_ms,depth_cv,transparent_depth_cv,culling_cv,shadow_marks_cv,"
              "shadow_marks_transparent_cv,shadows_cv,forward_cv,transparent_cv,tonemap_cv,total_cv,flagged,flag_reason,"
              "tested_per_pixel,affecting_per_pixel,shadow_lookups_per_pixel,filter_taps_per_pixel,shadow_views,"
              "shadow_texels_rendered,shadow_filter_taps,objects_in_view,camera_triangles,depth_triangles,"
              "forward_triangles,transparent_triangles,shadow_triangles,depth_draws,forward_draws,transparent_draws,"
              "shadow_draws,shadow_draws_max,shadow_memory_bytes,shadow_floor_bytes,shadow_pages,shadow_pages_coarsened,"
              "shadow_allocate_ms,light_grid_bytes,light_list_bytes,light_grid_floor_bytes,scene_bytes,frame_bytes,"
              "device_bytes,peak_rss_bytes,efficiency,floor_efficiency,missed_energy,image_error,pixels_off,"
              "shadow_reduced_views,shadow_misclassified,shadow_misclassified_all,shadow_misclassified_1px,"
              "shadow_false_shadow,shadow_false_lit,sun_misclassified,sun_misclassified_1px,"
              "sun_cascade0_misclassified_1px,sun_cascade1_misclassified_1px,sun_cascade2_misclassified_1px,"
              "sun_cascade3_misclassified_1px");
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
    // --quick: the mix alone for the light counts (the full run adds spots and points alone), and
    // thousands of lights at constant density alone (the full run adds the fixed range).
    EXPECT_EQ(series, (std::set<std::string>{"mix", "scale", "range", "pixels", "shadows",
                                             "shadow-quality", "shadow-budget", "shadow-filters", "shadow-memory",
                                             "cascades", "triangles", "methods"}));
    EXPECT_EQ(methods, quickNames(render::kLightListMethods));

    const nlohmann::json json = nlohmann::json::parse(readText(dir + "/results.json"));
    EXPECT_EQ(json["configurations"].size(), rows);
    EXPECT_TRUE(json["quick"].get<bool>());
    // Where the numbers come from, and how noisy the run was (docs/BENCH_RESULTS.md).
    const nlohmann::json& provenance = json["provenance"];
    for (const char* key : {"name", "type", "driver_name", "driver_info", "api_version"}) {
        EXPECT_FALSE(provenance["device"][key].dump().empty()) << key;
    }
    EXPECT_EQ(provenance["device"]["name"], json["device"]);
    EXPECT_GE(provenance["cpu"]["logical_cores"].get<int>(), 1);
    EXPECT_EQ(provenance["git_commit"].get<std::string>().size(), 40u);  // built from a clone
    EXPECT_NE(provenance["command_line"].get<std::string>().find("punctual bench --quick --validate --out-dir"),
              std::string::npos);
    EXPECT_EQ(provenance["date"].get<std::string>().size(), 20u);  // 2026-12-02T11:29:12Z
    EXPECT_EQ(provenance["scene"]["triangles"], 348);
    EXPECT_EQ(json["noise"]["rounds"], 3);
    EXPECT_EQ(json["noise"]["best_of"], 1);  // --quick: one frame a round
    EXPECT_GE(json["noise"]["frame_median_cv"].get<double>(), 0.0);
    EXPECT_EQ(json["noise"]["flag_limit"], 0.15);
    EXPECT_GE(json["noise"]["median_cv"].get<double>(), 0.0);
    uint32_t flaggedRows = 0;
    std::string gridKernel;  // the first grid row's
    for (const auto& row : json["configurations"]) {
        const std::string config = row["config"];
        EXPECT_EQ(row["rounds"], "3") << config;
        EXPECT_EQ(row["best_of"], "1") << config;
        EXPECT_EQ(row["frame_total_ms"].size(), 3u) << config;  // 3 rounds of 1 frame
        EXPECT_TRUE(row["flagged"] == "0" || row["flagged"] == "1") << config;
        EXPECT_EQ(row["flag_reason"].get<std::string>().empty(), row["flagged"] == "0") << config;
        flaggedRows += row["flagged"] == "1" ? 1u : 0u;
        // The counters every configuration has, whatever the device.
        for (const char* column : {"tested_per_pixel", "affecting_per_pixel", "shadow_lookups_per_pixel",
                                   "filter_taps_per_pixel", "depth_triangles", "forward_draws", "device_bytes",
                                   "scene_bytes", "frame_bytes", "total_iqr_ms", "total_cv"}) {
            EXPECT_NE(row[column].get<std::string>(), "") << config << ": " << column;
        }
        // The coarse pass: 4 fine tiles a side for the grid methods (64 / 16 pixels), none otherwise.
        const bool grid = row["method"] == "tiled" || row["method"] == "clustered";
        EXPECT_EQ(row["coarse_tiles"], grid ? "4" : "0") << config;
        // Which culling kernel ran: for tiled and clustered alike, the subgroup ones where the
        // device has subgroup arithmetic, else the shared-memory one; none without a grid.
        EXPECT_EQ(row["tile_kernel"] != "", grid) << config;
        if (grid) {
            const std::string kernel = row["tile_kernel"];
            EXPECT_TRUE(kernel == "subgroup" || kernel == "shared-memory") << config;
            if (gridKernel.empty()) gridKernel = kernel;
            EXPECT_EQ(kernel, gridKernel) << config;
        }
        EXPECT_EQ(row["tile_threads"] != "", grid) << config;
        const bool shadows = row["shadows"] == "1";
        EXPECT_EQ(std::stod(row["shadow_lookups_per_pixel"].get<std::string>()) > 0.0, shadows) << config;
        // Brute force tests every light at every pixel: the nested generated sets' counts.
        if (row["method"] == "brute" && row["series"] != "cascades" && row["series"] != "triangles") {
            EXPECT_DOUBLE_EQ(std::stod(row["tested_per_pixel"].get<std::string>()),
                             std::stod(row["spot"].get<std::string>()) + std::stod(row["point"].get<std::string>()))
                << config;
        }
    }
    EXPECT_EQ(json["noise"]["flagged"], flaggedRows);
    // The shadow sweep: auto against fixed resolutions at 16 and 32 bits, and the former default;
    // every row with its memory, texels and accuracy, and per-light counts for the target's
    // comparison on the lights two settings both shadow.
    std::set<std::string> shadowSettings;
    for (const auto& row : json["configurations"]) {
        if (row["series"] != "shadow-quality") continue;
        shadowSettings.insert(row["shadow_res"].get<std::string>() + "-" + row["shadow_format"].get<std::string>() + "-" +
                              row["shadowed_spots"].get<std::string>() + "+" + row["shadowed_points"].get<std::string>());
        for (const char* column : {"shadow_memory_bytes", "shadow_texels_rendered", "shadow_misclassified_all",
                                   "shadow_misclassified_1px"}) {
            EXPECT_NE(row[column].get<std::string>(), "") << row["config"] << ": " << column;
        }
        ASSERT_TRUE(row.contains("shadow_lights")) << row["config"];
        EXPECT_EQ(row["shadow_lights"].size(),
                  std::stoul(row["shadowed_spots"].get<std::string>()) + std::stoul(row["shadowed_points"].get<std::string>()));
    }
    EXPECT_EQ(shadowSettings, (std::set<std::string>{"auto-d16-64+32", "auto-d32-64+32", "256-d16-64+32", "256-d32-64+32",
                                                     "1024-d32-32+8"}));
    // The sun's cascades on the outdoor scene: 1 and 4 cascades at 512 with hw and tent5, each with
    // the sun's error overall and per cascade (empty beyond its count), its lamps unshadowed.
    std::set<std::string> cascadeSettings;
    for (const auto& row : json["configurations"]) {
        if (row["series"] != "cascades") continue;
        const std::string count = row["cascades"].get<std::string>();
        cascadeSettings.insert(count + "-" + row["shadow_res"].get<std::string>() + "-" + row["shadow_filter"].get<std::string>());
        EXPECT_EQ(row["spot"], "16") << row["config"];
        EXPECT_EQ(row["shadowed_spots"], "0") << row["config"];
        for (const char* column : {"shadows_ms", "forward_ms", "shadow_memory_bytes", "shadow_texels_rendered",
                                   "sun_misclassified", "sun_misclassified_1px"}) {
            EXPECT_NE(row[column].get<std::string>(), "") << row["config"] << ": " << column;
        }
        for (uint32_t i = 0; i < 4; ++i) {
            const std::string column = "sun_cascade" + std::to_string(i) + "_misclassified_1px";
            EXPECT_EQ(row[column].get<std::string>().empty(), i >= std::stoul(count)) << row["config"] << ": " << column;
        }
        ASSERT_TRUE(row.contains("sun_cascades")) << row["config"];
        EXPECT_EQ(row["sun_cascades"].size(), std::stoul(count));
        EXPECT_EQ(row["sun_cascades"].back()["resolution"], 512);
    }
    std::set<std::string> expectedCascades;
    for (const std::string& filter : quickNames(kShadowFilters)) {
        for (const char* count : {"1", "4"}) expectedCascades.insert(std::string(count) + "-512-" + filter);
    }
    EXPECT_EQ(cascadeSettings, expectedCascades);
    // The names the chart scripts read instead of lists of their own: every pass has its columns.
    EXPECT_EQ(json["passes"], nlohmann::json({"depth", "transparent_depth", "culling", "shadow_marks",
                                              "shadow_marks_transparent", "shadows", "forward", "transparent", "tonemap"}));
    EXPECT_EQ(json["methods"], nlohmann::json(render::methodNames()));
    EXPECT_EQ(json["shadow_filters"], nlohmann::json(shadowFilterNames()));
    EXPECT_EQ(json["point_layouts"], nlohmann::json(pointShadowLayoutNames()));
    for (const auto& pass : json["passes"]) {
        EXPECT_NE(header.find(pass.get<std::string>() + "_ms,"), std::string::npos) << pass;
        EXPECT_NE(header.find(pass.get<std::string>() + "_iqr_ms,"), std::string::npos) << pass;
        EXPECT_NE(header.find(pass.get<std::string>() + "_cv,"), std::string::npos) << pass;
    }
    EXPECT_TRUE(std::filesystem::exists(dir + "/images/heatmap-tiled.png"));
    // The bench drew its own report (CI has python3-matplotlib).
    EXPECT_TRUE(std::filesystem::exists(dir + "/index.html"));
    EXPECT_TRUE(std::filesystem::exists(dir + "/failures.html"));
    EXPECT_TRUE(std::filesystem::exists(dir + "/charts/forward_time.png"));
    // The budget series: the auto resolution fitted to 8 and 64 MiB, the smaller never larger. The
    // budget is the atlas's (--help); the shadow memory holds beside it the drawing square
    // (lights/shadow_drawing_tiles.h, at most 1024^2 16-bit texels) and the placeholder cube array.
    std::map<std::string, uint64_t> budgetMemory;
    for (const auto& row : json["configurations"]) {
        if (row["series"] != "shadow-budget") continue;
        budgetMemory[row["shadow_budget_mib"]] = std::stoull(row["shadow_memory_bytes"].get<std::string>());
        EXPECT_NE(row["shadow_misclassified_1px"].get<std::string>(), "") << row["config"];
    }
    ASSERT_EQ(budgetMemory.size(), 2u);
    EXPECT_LE(budgetMemory["8"], (8ull << 20) + uint64_t(kDrawingSquareSide) * kDrawingSquareSide * 2 + (64 << 10));
    EXPECT_LE(budgetMemory["8"], budgetMemory["64"]);
    // results.json lists every file of the run (and only those), so the next run can tell its own.
    ASSERT_TRUE(json.contains("files"));
    std::set<std::string> listed;
    for (const auto& name : json["files"]) listed.insert(name.get<std::string>());
    EXPECT_TRUE(listed.count("results.json") && listed.count("results.csv") && listed.count("failures.csv"));
    EXPECT_TRUE(listed.count("images/heatmap-tiled.png"));
    for (const std::string& name : listed) EXPECT_TRUE(std::filesystem::is_regular_file(dir + "/" + name)) << name;
    EXPECT_FALSE(std::filesystem::exists(dir + "/images/mismatch-gone.png"));
    EXPECT_EQ(readText(dir + "/images/mine.png"), "the user's");

    // The failure study: every known failure measured against its parameter.
    std::istringstream failures(readText(dir + "/failures.csv"));
    std::string failureHeader;
    std::getline(failures, failureHeader);
    EXPECT_EQ(failureHeader, "study,parameter,value,variant,metric,error,total_ms");
    std::set<std::string> studies;
    for (std::string line; std::getline(failures, line);) studies.insert(line.substr(0, line.find(',')));
    EXPECT_EQ(studies, (std::set<std::string>{"acne-vs-bias", "peter-panning-vs-bias", "cube-seams", "pancaking-leak",
                                              "wide-spot", "tile-depth-discontinuities", "per-object-large-objects",
                                              "beyond-the-caps", "cascade-shimmering", "cascade-shimmering-moving-view",
                                              "cascade-seams", "perspective-aliasing-splits", "perspective-aliasing-counts",
                                              "cascade-pancaking", "transparency-tiled-depth-bounds"}));
}

// --compare hands two folders to bench/compare_runs.py: ratios per configuration both runs have,
// a counter that differs marked.
TEST(BenchCli, CompareWritesTheSideBySidePage) {
    testing::TempFolder folder;
    auto writeRun = [&](const std::string& name, const std::string& forwardMs, const std::string& tested) {
        const std::string dir = folder.file(name);
        std::filesystem::create_directories(dir);
        std::ofstream(dir + "/results.csv") << "config,series,method,forward_ms,total_ms,tested_per_pixel\n"
                                            << "mix-tiled-64s32p,mix,tiled," << forwardMs << ",20," << tested << "\n";
        std::ofstream(dir + "/results.json")
            << R"({"passes": ["forward"], "configurations": [], "provenance": {"device": {"name": ")" << name << R"("}}})";
        return dir;
    };
    const std::string a = writeRun("lavapipe", "10", "7.5");
    const std::string b = writeRun("gpu", "2.5", "7.5");
    const std::string out = folder.file("compared");
    std::filesystem::create_directories(out);
    const RunResult run = runPunctual(folder, "bench --compare '" + a + "' '" + b + "' --out-dir '" + out + "'");
    ASSERT_EQ(run.exitCode, 0) << run.err;
    const std::string csv = readText(out + "/compare.csv");
    EXPECT_NE(csv.find("mix-tiled-64s32p"), std::string::npos) << csv;
    EXPECT_NE(csv.find("0.25"), std::string::npos) << csv;  // forward: 2.5 / 10
    EXPECT_TRUE(std::filesystem::exists(out + "/compare.html"));

    // A FIFO or a folder in place of a results file is refused in one line, never opened (issue 30:
    // the C++ side checked results.json while the script blocked forever opening results.csv).
    std::filesystem::remove(a + "/results.csv");
    ASSERT_EQ(::mkfifo((a + "/results.csv").c_str(), 0600), 0);
    std::filesystem::remove(b + "/results.json");
    std::filesystem::create_directories(b + "/results.json");
    for (const auto& [args, mention] :
         {std::pair<std::string, std::string>{"bench --compare '" + a + "' '" + a + "' --out-dir '" + out + "'",
                                              "results.csv: cannot be read (a named pipe (FIFO), not a regular file)"},
          {"bench --compare '" + b + "' '" + b + "' --out-dir '" + out + "'",
           "results.json: cannot be read (a directory, not a regular file)"}}) {
        const auto started = std::chrono::steady_clock::now();
        const RunResult bounded = runPunctual(folder, args);
        EXPECT_LT(std::chrono::steady_clock::now() - started, std::chrono::seconds(30)) << args;
        testing::expectOneClearError(bounded, args, mention);
    }
}

TEST(BenchCli, BadOptionsFailCleanly) {
    testing::TempFolder folder;
    for (const std::string& args : std::vector<std::string>{
             "bench", "bench --out-dir", "bench --out-dir '" + folder.file("a/b") + "'",
             "bench --culling tiled --out-dir '" + folder.file("x") + "'",
             "bench --frames 3 --out-dir '" + folder.file("x") + "'",
             "bench --rounds 0 --out-dir '" + folder.file("x") + "'",
             "bench --rounds many --out-dir '" + folder.file("x") + "'",
             "bench --best-of 0 --out-dir '" + folder.file("x") + "'",
             "bench --best-of 101 --out-dir '" + folder.file("x") + "'",
             "bench --seed -1 --out-dir '" + folder.file("x") + "'",
             "bench --series mix,nothing --out-dir '" + folder.file("x") + "'",
             "bench --compare '" + folder.file("none-a") + "' '" + folder.file("none-b") + "' --out-dir '" +
                 folder.file("x") + "'"}) {
        const RunResult run = runPunctual(folder, args);
        EXPECT_NE(run.exitCode, 0) << args;
        EXPECT_EQ(testing::lineCount(run.err), 1u) << args << ": " << run.err;
        EXPECT_NE(run.err.find("punctual: error: "), std::string::npos) << run.err;
    }
    EXPECT_FALSE(std::filesystem::exists(folder.file("x")));
}

}  // namespace
}  // namespace punctual
