#pragma once
// What `punctual play` writes (issue 34): per-frame statistics of a sequence as CSV and JSON, the
// percentiles of every pass's time over it (p50, p95, p99: a spike matters more than a median
// in motion), a frame-time chart (SVG, drawn here: no runtime dependency) and the index.html
// that shows them.
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/output_folder.h"
#include "render/pass_timings.h"

namespace punctual::report {

// The p-th percentile (0 <= p <= 100) of `values`, interpolated linearly between the closest
// ranks (numpy's default): at rank h = (n - 1) p / 100, v[floor h] + (h - floor h) (v[floor h + 1]
// - v[floor h]) over the sorted values. 0 for no values.
double percentile(std::vector<double> values, double p);

// One frame of a sequence.
struct SequenceFrame {
    uint32_t index = 0;
    double time = 0.0;           // seconds into the scene's animation or path
    render::PassTimings ms;      // GPU times (the median over --frames repetitions)
    nlohmann::json stats;        // frameStatsJson's counters and memory for the frame
};

// The sequence's summary: per pass (in frame order) and for the total, {"p50", "p95", "p99",
// "max", "mean"} in ms; where frames were validated, "validation": {"frames", "mean", "max"} of
// their share misclassified outside the edge band.
nlohmann::json sequenceSummaryJson(const std::vector<SequenceFrame>& frames);

// frames.json: {"scene", "device", "fps", "seconds", "size", "settings", "passes" (in frame order), "summary",
// "frames": [{"frame", "time_s", "gpu_ms": {passes..., "total"}, "stats"}], "files"}. `files`
// is filled by the caller (the output folder's manifest).
nlohmann::json sequenceJson(const std::vector<SequenceFrame>& frames, const nlohmann::json& header);

// frames.csv: frame, time_s, each pass's ms, total_ms, then the counters a frame's cost follows
// (lights kept, shadow views rendered, shadow memory, draws, device memory), then for the frames
// validated against Embree (a "validation" object in their stats) the shadow tests compared and
// the share misclassified outside the edge band (empty cells for the others).
std::string sequenceCsv(const std::vector<SequenceFrame>& frames);

// frame_times.svg: the total GPU time per frame against time, with p50, p95 and p99 as dashed
// lines and labels.
std::string frameTimesSvg(const std::vector<SequenceFrame>& frames);

// index.html: the header, the percentile table, the chart, the video (frames.mp4) where `video`,
// and the frames (frame-NNNN.png) where `frameImages` names them.
std::string sequenceHtml(const nlohmann::json& document, const std::vector<std::string>& frameImages, bool video = false);

// The play command's folder: frames.json (the manifest), frames.csv, frame_times.svg, index.html,
// frame-*.png and frames.mp4.
const OutputFolderLayout& sequenceFolderLayout();

// "frame-0007.png".
std::string frameImageName(uint32_t index);

}  // namespace punctual::report
