#include "report/sequence_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace punctual::report {
namespace {

std::string escapeHtml(const std::string& text) {
    std::string out;
    for (char c : text) {
        switch (c) {
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '&': out += "&amp;"; break;
            case '"': out += "&quot;"; break;
            default: out += c;
        }
    }
    return out;
}

std::string fixed(double value, int decimals) {
    char text[64];
    std::snprintf(text, sizeof text, "%.*f", decimals, value);
    return text;
}

std::vector<double> column(const std::vector<SequenceFrame>& frames, const std::string& pass) {
    std::vector<double> values;
    values.reserve(frames.size());
    for (const SequenceFrame& f : frames) values.push_back(pass == "total" ? f.ms.total : f.ms.of(pass));
    return values;
}

nlohmann::json spread(const std::vector<double>& values) {
    double sum = 0.0;
    for (double v : values) sum += v;
    return {{"p50", percentile(values, 50.0)},
            {"p95", percentile(values, 95.0)},
            {"p99", percentile(values, 99.0)},
            {"max", values.empty() ? 0.0 : *std::max_element(values.begin(), values.end())},
            {"mean", values.empty() ? 0.0 : sum / double(values.size())}};
}

// A counter of the frame's stats by JSON pointer, 0 where absent.
double counter(const nlohmann::json& stats, const char* pointer) {
    const nlohmann::json::json_pointer at(pointer);
    return stats.contains(at) && stats[at].is_number() ? stats[at].get<double>() : 0.0;
}

struct CsvCounter {
    const char* column;
    const char* pointer;
};
constexpr CsvCounter kCsvCounters[] = {
    {"spot_lights", "/lights/spot"},
    {"point_lights", "/lights/point"},
    {"lights_outside_view", "/lights/culled_by_frustum"},
    {"objects_in_view", "/geometry/objects_in_view"},
    {"depth_draws", "/geometry/camera_draws/depth"},
    {"shadow_draws", "/geometry/shadow_draws/total"},
    {"shadow_views_rendered", "/shadows/views_rendered"},
    {"shadow_tier_switches", "/shadows/tier_switches"},
    {"shadow_cache_kept_views", "/shadows/cache/kept_views"},  // --shadow-cache on: 0 without
    {"shadow_cache_drawn_views", "/shadows/cache/drawn_views"},
    {"shadow_cache_laid_out", "/shadows/cache/laid_out"},
    {"shadow_cache_over_static_views", "/shadows/cache/over_static_views"},  // --shadow-cache mixed
    {"shadow_cache_dynamic_casters", "/shadows/cache/dynamic_casters"},
    {"shadow_pages_allocated", "/shadows/pages/allocated"},  // --shadow-res virtual
    {"shadow_cache_kept_pages", "/shadows/cache/kept_pages"},  // --shadow-cache on with virtual pages
    {"shadow_cache_drawn_pages", "/shadows/cache/drawn_pages"},
    {"shadow_memory_bytes", "/shadows/memory_bytes"},
    {"device_bytes", "/memory/device_bytes"},
};

}  // namespace

double percentile(std::vector<double> values, double p) {
    if (values.empty()) return 0.0;
    std::sort(values.begin(), values.end());
    const double rank = (double(values.size()) - 1.0) * std::clamp(p, 0.0, 100.0) / 100.0;
    const size_t low = size_t(std::floor(rank));
    if (low + 1 >= values.size()) return values.back();
    return values[low] + (rank - double(low)) * (values[low + 1] - values[low]);
}

nlohmann::json sequenceSummaryJson(const std::vector<SequenceFrame>& frames) {
    nlohmann::json summary = nlohmann::json::object();
    if (!frames.empty()) {
        for (const auto& [pass, ms] : frames.front().ms.passes) summary[pass] = spread(column(frames, pass));
    }
    summary["total"] = spread(column(frames, "total"));
    std::vector<double> misclassified;
    double flipTests = 0.0;
    double flips = 0.0;
    double resizedFlips = 0.0;
    for (const SequenceFrame& f : frames) {
        if (!f.stats.contains("validation")) continue;
        misclassified.push_back(counter(f.stats, "/validation/misclassified_outside_band"));
        flipTests += counter(f.stats, "/validation/flips/compared");
        flips += counter(f.stats, "/validation/flips/flips");
        resizedFlips += counter(f.stats, "/validation/flips/where_maps_resized");
    }
    if (!misclassified.empty()) {
        const nlohmann::json s = spread(misclassified);
        summary["validation"] = {{"frames", misclassified.size()}, {"mean", s["mean"]}, {"max", s["max"]},
                                 {"flip_tests", flipTests}, {"flips", flips}, {"flips_where_maps_resized", resizedFlips},
                                 {"flip_rate", flipTests > 0.0 ? flips / flipTests : 0.0}};
    }
    return summary;
}

nlohmann::json sequenceJson(const std::vector<SequenceFrame>& frames, const nlohmann::json& header) {
    nlohmann::json document = header;
    document["summary"] = sequenceSummaryJson(frames);
    document["passes"] = nlohmann::json::array();  // in frame order (JSON objects sort their keys)
    if (!frames.empty()) {
        for (const auto& [pass, ms] : frames.front().ms.passes) document["passes"].push_back(pass);
    }
    document["frames"] = nlohmann::json::array();
    for (const SequenceFrame& f : frames) {
        nlohmann::json ms = nlohmann::json::object();
        for (const auto& [pass, value] : f.ms.passes) ms[pass] = value;
        ms["total"] = f.ms.total;
        document["frames"].push_back({{"frame", f.index}, {"time_s", f.time}, {"gpu_ms", ms}, {"stats", f.stats}});
    }
    return document;
}

std::string sequenceCsv(const std::vector<SequenceFrame>& frames) {
    std::ostringstream csv;
    csv << "frame,time_s";
    if (!frames.empty()) {
        for (const auto& [pass, ms] : frames.front().ms.passes) csv << "," << pass << "_ms";
    }
    csv << ",total_ms";
    for (const CsvCounter& c : kCsvCounters) csv << "," << c.column;
    csv << ",shadow_reduced_views,shadow_compared,shadow_misclassified,shadow_flip_tests,shadow_flips\n";
    for (const SequenceFrame& f : frames) {
        csv << f.index << "," << fixed(f.time, 4);
        for (const auto& [pass, ms] : f.ms.passes) csv << "," << fixed(ms, 3);
        csv << "," << fixed(f.ms.total, 3);
        for (const CsvCounter& c : kCsvCounters) csv << "," << fixed(counter(f.stats, c.pointer), 0);
        const nlohmann::json::json_pointer reduced("/shadows/reduced");
        csv << "," << (f.stats.contains(reduced) && f.stats[reduced].is_array() ? f.stats[reduced].size() : 0);
        // Validated frames only (play --validate-every): empty cells elsewhere.
        if (f.stats.contains("validation")) {
            csv << "," << fixed(counter(f.stats, "/validation/compared"), 0) << ","
                << fixed(counter(f.stats, "/validation/misclassified_outside_band"), 8);
        } else {
            csv << ",,";
        }
        if (f.stats.contains(nlohmann::json::json_pointer("/validation/flips"))) {
            csv << "," << fixed(counter(f.stats, "/validation/flips/compared"), 0) << ","
                << fixed(counter(f.stats, "/validation/flips/flips"), 0);
        } else {
            csv << ",,";
        }
        csv << "\n";
    }
    return csv.str();
}

std::string frameTimesSvg(const std::vector<SequenceFrame>& frames) {
    constexpr double kWidth = 800, kHeight = 320, kLeft = 60, kRight = 110, kTop = 30, kBottom = 40;
    const std::vector<double> totals = column(frames, "total");
    const double top = std::max(1e-3, totals.empty() ? 1.0 : *std::max_element(totals.begin(), totals.end())) * 1.1;
    const double lastTime = frames.empty() ? 1.0 : std::max(frames.back().time, 1e-3);
    const auto x = [&](double t) { return kLeft + (kWidth - kLeft - kRight) * t / lastTime; };
    const auto y = [&](double ms) { return kHeight - kBottom - (kHeight - kTop - kBottom) * ms / top; };
    std::ostringstream svg;
    svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << kWidth << "\" height=\"" << kHeight
        << "\" font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
        << "<text x=\"" << kLeft << "\" y=\"18\">GPU time per frame (total, ms) against time (s)</text>\n"
        << "<line x1=\"" << kLeft << "\" y1=\"" << y(0) << "\" x2=\"" << kWidth - kRight << "\" y2=\"" << y(0)
        << "\" stroke=\"black\"/>\n<line x1=\"" << kLeft << "\" y1=\"" << y(0) << "\" x2=\"" << kLeft << "\" y2=\""
        << kTop << "\" stroke=\"black\"/>\n";
    for (int tick = 0; tick <= 4; ++tick) {
        const double ms = top * tick / 4.0;
        svg << "<text x=\"" << kLeft - 6 << "\" y=\"" << y(ms) + 4 << "\" text-anchor=\"end\">" << fixed(ms, 1)
            << "</text>\n<text x=\"" << x(lastTime * tick / 4.0) << "\" y=\"" << kHeight - kBottom + 16
            << "\" text-anchor=\"middle\">" << fixed(lastTime * tick / 4.0, 2) << "</text>\n";
    }
    svg << "<polyline fill=\"none\" stroke=\"#1f77b4\" stroke-width=\"1.5\" points=\"";
    for (size_t i = 0; i < frames.size(); ++i) svg << (i ? " " : "") << fixed(x(frames[i].time), 1) << "," << fixed(y(totals[i]), 1);
    svg << "\"/>\n";
    // The percentile lines, their labels pushed at least a line apart where the values are close.
    const std::pair<const char*, const char*> lines[] = {{"p99", "#d62728"}, {"p95", "#ff7f0e"}, {"p50", "#2ca02c"}};
    double labelY = 0.0;
    for (const auto& [name, colour] : lines) {
        const double ms = percentile(totals, std::stod(name + 1));
        labelY = std::max(y(ms) + 4.0, labelY + 14.0);
        svg << "<line x1=\"" << kLeft << "\" y1=\"" << fixed(y(ms), 1) << "\" x2=\"" << kWidth - kRight << "\" y2=\""
            << fixed(y(ms), 1) << "\" stroke=\"" << colour << "\" stroke-dasharray=\"6,4\"/>\n<text x=\""
            << kWidth - kRight + 6 << "\" y=\"" << fixed(labelY, 1) << "\" fill=\"" << colour << "\">" << name << " "
            << fixed(ms, 1) << " ms</text>\n";
    }
    svg << "</svg>\n";
    return svg.str();
}

std::string sequenceHtml(const nlohmann::json& document, const std::vector<std::string>& frameImages, bool video) {
    std::ostringstream html;
    html << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>punctual play</title>\n"
         << "<style>body{font-family:sans-serif} table{border-collapse:collapse} td,th{border:1px solid #aaa;"
         << "padding:2px 8px;text-align:right} .frames img{width:160px;margin:2px}</style></head><body>\n"
         << "<h1>Sequence: " << escapeHtml(document.value("scene", "")) << "</h1>\n<p>"
         << document.value("frame_count", 0) << " frames at " << document.value("fps", 0.0) << " fps over "
         << document.value("seconds", 0.0) << " s, " << escapeHtml(document.value("size", "")) << ", on "
         << escapeHtml(document.value("device", "")) << ". Settings: " << escapeHtml(document.value("settings", nlohmann::json()).dump())
         << ". Per-frame figures: <a href=\"frames.csv\">frames.csv</a>, <a href=\"frames.json\">frames.json</a>.</p>\n"
         << "<p><img src=\"frame_times.svg\" alt=\"GPU time per frame\"></p>\n"
         << (video ? "<p><video src=\"frames.mp4\" controls loop muted></video></p>\n" : "")
         << "<table><tr><th>pass</th><th>p50 ms</th><th>p95 ms</th><th>p99 ms</th><th>max ms</th><th>mean ms</th></tr>\n";
    std::vector<std::string> passes = document.value("passes", std::vector<std::string>{});
    passes.push_back("total");
    for (const std::string& pass : passes) {
        const nlohmann::json& s = document["summary"][pass];
        html << "<tr><td>" << escapeHtml(pass) << "</td>";
        for (const char* key : {"p50", "p95", "p99", "max", "mean"}) html << "<td>" << fixed(s[key].get<double>(), 2) << "</td>";
        html << "</tr>\n";
    }
    html << "</table>\n";
    if (document["summary"].contains("validation")) {
        const nlohmann::json& total = document["summary"]["validation"];
        html << "<h2>Shadows against Embree</h2>\n<p>Flips (a static receiver's shadow state changed from one "
             << "validated frame to the next where the ray-traced truth did not): " << fixed(total["flips"].get<double>(), 0)
             << " of " << fixed(total["flip_tests"].get<double>(), 0) << " tests ("
             << fixed(100.0 * total["flip_rate"].get<double>(), 4) << "%).</p>\n"
             << "<table><tr><th>frame</th><th>time s</th><th>compared</th>"
             << "<th>false shadow</th><th>false lit</th><th>misclassified outside band</th><th>flips</th></tr>\n";
        for (const nlohmann::json& f : document["frames"]) {
            if (!f["stats"].contains("validation")) continue;
            const nlohmann::json& v = f["stats"]["validation"];
            html << "<tr><td>" << f["frame"] << "</td><td>" << fixed(f["time_s"].get<double>(), 2) << "</td><td>"
                 << v["compared"] << "</td><td>" << v["false_shadow"] << "</td><td>" << v["false_lit"] << "</td><td>"
                 << fixed(100.0 * v["misclassified_outside_band"].get<double>(), 4) << "%</td><td>"
                 << (v.contains("flips") ? std::to_string(v["flips"]["flips"].get<uint64_t>()) : std::string(""))
                 << "</td></tr>\n";
        }
        html << "</table>\n";
    }
    if (!frameImages.empty()) {
        html << "<h2>Frames</h2>\n<div class=\"frames\">\n";
        for (const std::string& image : frameImages) html << "<img src=\"" << escapeHtml(image) << "\" alt=\"" << escapeHtml(image) << "\">\n";
        html << "</div>\n";
    }
    html << "</body></html>\n";
    return html.str();
}

const OutputFolderLayout& sequenceFolderLayout() {
    static const OutputFolderLayout layout{"frames.json", {"frames.json", "frames.csv", "frame_times.svg", "index.html", "frame-*.png", "frames.mp4"}, {}};
    return layout;
}

std::string frameImageName(uint32_t index) {
    char name[32];
    std::snprintf(name, sizeof name, "frame-%04u.png", index);
    return name;
}

}  // namespace punctual::report
