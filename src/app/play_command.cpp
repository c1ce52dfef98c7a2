#include "app/play_command.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <optional>
#include <system_error>

#include "cli/options.h"
#include "cli/scene_source.h"
#include "core/error.h"
#include "core/image.h"
#include "core/output_files.h"
#include "core/output_folder.h"
#include "report/frame_stats.h"
#include "report/sequence_report.h"
#include "render/renderer.h"
#include "vk/context.h"

namespace punctual::app {

using namespace cli;
using namespace report;
namespace {

constexpr const char* kUsage = R"(usage: punctual play [SCENE] [render options] --out-dir DIR [--fps F] [--seconds S]
                     [--save-frames]

Renders a sequence: the scene posed every 1/F s from 0 to S (a glTF file's animations, or a
built-in scene's path: the hall's walk, the street's drive), each frame rendered and timed as
`punctual render` times one, and writes:
  DIR/frames.csv       per frame: its time, every pass's GPU ms and the total, the lights kept,
                       shadow views rendered, shadow memory, draws and device memory
  DIR/frames.json      the same with each frame's whole statistics (render --stats), and per
                       pass the p50, p95, p99, max and mean over the frames
  DIR/frame_times.svg  the total GPU time per frame, with its p50, p95 and p99
  DIR/index.html       all of it on one page
  DIR/frame-NNNN.png   with --save-frames: every frame
--fps F is 0.1 to 240 frames a second (default 10); --seconds S defaults to the length of the
file's animations or the scene's path. At most 10,000 frames. DIR is created if missing (its
parent must exist); frames.json lists the files written, and a later run into DIR removes the
listed files it does not write again (and nothing else). All render options apply but --time
(play sets each frame's) and the single-frame outputs (--out, --stats, --heatmap, ...).
)";

constexpr uint32_t kMaxFrames = 10'000;

struct PlayArgs {
    std::vector<std::string> renderArgs;
    std::optional<std::string> outDir;
    double fps = 10.0;
    std::optional<double> seconds;
    bool saveFrames = false;
    bool help = false;
};

double parseNumberIn(const std::string& option, const std::string& text, double low, double high, const char* unit) {
    double value = 0.0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error != std::errc() || end != text.data() + text.size() || !(value >= low && value <= high)) {
        char range[96];
        std::snprintf(range, sizeof range, "%g to %g", low, high);
        throw Error(option, std::string("expected ") + unit + " from " + range + ", got '" + text + "'");
    }
    return value;
}

PlayArgs parsePlayArgs(const std::vector<std::string>& args) {
    PlayArgs parsed;
    const auto value = [&](size_t& i) -> const std::string& {
        if (i + 1 >= args.size() || args[i + 1].rfind("--", 0) == 0) throw Error(args[i], "needs a value");
        return args[++i];
    };
    for (size_t i = 0; i < args.size(); ++i) {
        const std::string& arg = args[i];
        if (arg == "--help" || arg == "-h") {
            parsed.help = true;
            return parsed;
        } else if (arg == "--out-dir") {
            parsed.outDir = value(i);
        } else if (arg == "--fps") {
            parsed.fps = parseNumberIn("--fps", value(i), 0.1, 240.0, "frames a second");
        } else if (arg == "--seconds") {
            parsed.seconds = parseNumberIn("--seconds", value(i), 0.0, 1e6, "seconds");
        } else if (arg == "--save-frames") {
            parsed.saveFrames = true;
        } else if (arg == "--time") {
            throw Error("--time", "play sets each frame's time itself (--fps F, --seconds S)");
        } else if (arg == "--out" || arg == "--stats" || arg == "--heatmap" || arg == "--shadow-density" ||
                   arg == "--shadow-pages") {
            throw Error(arg, "not an option of play (it writes into --out-dir)");
        } else {
            parsed.renderArgs.push_back(arg);
        }
    }
    if (!parsed.outDir) throw Error("--out-dir", "play needs an output folder (--out-dir DIR)");
    return parsed;
}

// The frames of a sequence of `seconds` at `fps`: one at each multiple of 1/fps up to `seconds`.
uint32_t frameCount(double seconds, double fps) {
    const double last = std::floor(seconds * fps + 1e-9);  // a frame exactly at the end counts
    if (last + 1.0 > double(kMaxFrames)) {
        throw Error("--seconds", "the sequence would have " + std::to_string(uint64_t(last + 1.0)) + " frames (--fps x --seconds + 1); " +
                                     "play renders at most " + std::to_string(kMaxFrames));
    }
    return uint32_t(last) + 1;
}

}  // namespace

int runPlayCommand(const std::vector<std::string>& args) {
    const PlayArgs parsed = parsePlayArgs(args);
    if (parsed.help) {
        std::fputs(kUsage, stdout);
        return 0;
    }
    const std::string dir = *parsed.outDir;
    const OutputFolderLayout& layout = sequenceFolderLayout();
    checkOutputFolder(dir, layout);
    RenderOptions options = parseRenderOptions(parsed.renderArgs);
    // As stored first: the length of its animations or path says whether it moves at all. A still
    // scene (a file without animations, a built-in scene without a path) is one scene for every
    // frame; a moving one is posed at each frame's time.
    const Scene still = loadSceneForOptions(options);
    checkOutputFolder(dir, layout);  // again, now that the files the scene reads are known
    const bool moves = still.animationSeconds > 0.0;
    const double seconds = parsed.seconds.value_or(still.animationSeconds);
    if (!parsed.seconds && !moves) {
        throw Error("--seconds", still.source + " has no animation or path to take a length from: give --seconds S");
    }
    const uint32_t count = frameCount(seconds, parsed.fps);

    vk::Context context(contextOptionsFrom(options));
    const render::RenderSettings settings = renderSettingsFrom(options);
    std::vector<SequenceFrame> frames;
    OutputFiles outputs;
    std::vector<std::string> frameImages;
    for (uint32_t i = 0; i < count; ++i) {
        const double time = double(i) / parsed.fps;
        options.time = moves ? std::optional<double>(time) : std::nullopt;
        const Scene scene = moves ? loadSceneForOptions(options) : still;
        render::Renderer renderer(context, scene, settings);
        const render::FrameResult result = renderer.render(options.frames);
        nlohmann::json stats = frameStatsJson(result, renderer, scene, context.deviceName(), options.frames);
        stats["shadows"] = shadowStatsJson(renderer);
        frames.push_back({i, time, result.medianMs, std::move(stats)});
        if (parsed.saveFrames) {
            frameImages.push_back(frameImageName(i));
            outputs.add(dir + "/" + frameImages.back(), encodePng(result.image));
        }
    }
    if (context.validationMessageCount() > 0) {
        throw Error("vulkan", std::to_string(context.validationMessageCount()) +
                                  " validation message(s) (printed above); no output written");
    }

    nlohmann::json header = {{"scene", still.source},
                             {"device", context.deviceName()},
                             {"fps", parsed.fps},
                             {"seconds", seconds},
                             {"frame_count", count},
                             {"size", std::to_string(options.width) + "x" + std::to_string(options.height)},
                             {"settings",
                              {{"culling", render::methodName(settings.method)},
                               {"shadows", settings.shadows.enabled ? shadowResolutionName(settings.shadows) : "off"},
                               {"shadow_filter", shadowFilterName(settings.shadows.filter)},
                               {"timed_frames_each", options.frames}}}};
    nlohmann::json document = sequenceJson(frames, header);
    outputs.add(dir + "/frames.csv", sequenceCsv(frames));
    outputs.add(dir + "/frame_times.svg", frameTimesSvg(frames));
    outputs.add(dir + "/index.html", sequenceHtml(document, frameImages));
    const std::vector<std::string> files = outputFolderFiles(outputs, dir, layout);
    document["files"] = files;
    outputs.add(dir + "/frames.json", document.dump(2) + "\n");
    prepareOutputFolder(outputs, dir, layout, files);
    outputs.commit();

    const nlohmann::json& total = document["summary"]["total"];
    std::printf("play: %s, %u frames at %g fps over %g s; GPU ms per frame p50 %.2f, p95 %.2f, p99 %.2f, max %.2f\n",
                still.source.c_str(), count, parsed.fps, seconds, total["p50"].get<double>(), total["p95"].get<double>(),
                total["p99"].get<double>(), total["max"].get<double>());
    std::printf("wrote %s/index.html, frames.csv and frames.json\n", dir.c_str());
    return 0;
}

}  // namespace punctual::app
