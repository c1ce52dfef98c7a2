#include "app/play_command.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <system_error>

#include "cli/option_values.h"
#include "cli/options.h"
#include "cli/scene_source.h"
#include "core/error.h"
#include "core/image.h"
#include "core/log.h"
#include "core/output_files.h"
#include "core/output_folder.h"
#include "lights/shadow_page_allocation.h"
#include "reference/embree_scene.h"
#include "reference/shadow_stability.h"
#include "reference/shadow_validation.h"
#include "report/frame_stats.h"
#include "report/sequence_report.h"
#include "report/sequence_video.h"
#include "render/renderer.h"
#include "render/shadow_cache.h"
#include "vk/context.h"

namespace punctual::app {

using namespace cli;
using namespace report;
namespace {

constexpr const char* kUsage = R"(usage: punctual play [SCENE] [render options] --out-dir DIR [--fps F] [--seconds S]
                     [--save-frames] [--video] [--validate-every K] [--shadow-cache MODE]

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
  DIR/frames.mp4       with --video: the frames as an H.264 video at F frames a second (needs
                       ffmpeg on PATH: Debian's ffmpeg package), shown on the page
With --validate-every K, every K-th frame (the first included) also has its shadows compared with
Embree's ray-cast visibility, as `punctual validate` compares them: each such frame's compared
pixels, false shadow, false lit and misclassified share outside the edge band join its row; and
from the second such frame on, the flips since the last: shadow tests on a static receiver, lit
by a light that did not move, whose ray-traced truth is the same in both frames but whose GPU
state changed (temporal instability: shimmer and popping).
--shadow-cache MODE keeps shadow views from frame to frame (render/shadow_cache.h):
{shadow-cache modes}With on, a view keeps the last frame's depth where its square, its light and its casters (their
transforms, geometry and alpha test) are unchanged; only the others are cleared and drawn. Each
row then counts the views kept and drawn (shadow_cache_kept_views, shadow_cache_drawn_views) and
whether the cache laid its atlas out afresh; shadow memory is the cache's atlas. With mixed, an
object whose transform or geometry changed is a dynamic caster from then on; a view with one
keeps its static casters' depth apart, in a second atlas counted in the shadow memory, and while
that holds draws only its dynamic casters over a copy of it (shadow_cache_over_static_views,
shadow_cache_dynamic_casters; whole views only, not virtual). With --shadow-res virtual, on keeps
each marked page in its slot of a pool that outlives the frames, and its depth while its light
and the casters that meet it are unchanged (shadow_cache_kept_pages, shadow_cache_drawn_pages).
The cube layout's faces are drawn every frame. Every mode gives off's frames bit for bit.
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
    uint32_t validateEvery = 0;  // 0: no frame validated
    bool saveFrames = false;
    bool video = false;
    render::ShadowCacheMode shadowCache = render::ShadowCacheMode::Off;
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
    const auto value = [&](size_t& i) -> const std::string& { return optionValue(args, i); };
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
        } else if (arg == "--validate-every") {
            parsed.validateEvery = uint32_t(parseNumberIn("--validate-every", value(i), 1.0, 1e6, "a whole number of frames"));
            if (double(parsed.validateEvery) != std::stod(args[i])) {
                throw Error("--validate-every", "expected a whole number of frames from 1 to 1e+06, got '" + args[i] + "'");
            }
        } else if (arg == "--shadow-cache") {
            parsed.shadowCache = parseVariant(render::kShadowCacheModes, value(i), "--shadow-cache").value;
        } else if (arg == "--save-frames") {
            parsed.saveFrames = true;
        } else if (arg == "--video") {
            parsed.video = true;
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

// A validated frame's shadows against Embree (as `punctual validate` compares them, edge band one
// shadow texel): {"compared", "false_shadow", "false_lit", "edge_band", "misclassified_outside_band"},
// and where an earlier frame was validated, "flips": the tests whose state flipped since it where
// nothing that decides them changed (reference/shadow_stability.h). `previous` becomes this frame.
nlohmann::json frameValidationJson(const Scene& scene, render::Renderer& renderer,
                                   std::optional<reference::StabilityFrame>& previous) {
    const ShadowFactorImage factors = renderer.readShadowFactors();
    const reference::EmbreeScene embree(scene);
    const reference::ShadowValidation validation =
        reference::validateShadows(embree, factors, renderer.lights(), renderer.shadowPlan());
    const reference::ShadowCounts& c = validation.overall;
    nlohmann::json json = {{"compared", c.compared},
                           {"false_shadow", c.falseShadow},
                           {"false_lit", c.falseLit},
                           {"edge_band", c.edgeBand},
                           {"misclassified_outside_band", c.misclassifiedOutsideBand()}};
    reference::StabilityFrame frame = reference::stabilityFrame(scene, factors, validation);
    std::optional<uint32_t> sun;
    if (validation.sun) sun = validation.sun->sceneLight;
    reference::recordMapResolutions(frame, renderer.shadowPlan(), renderer.lights().sceneLightIndex, sun);
    if (previous) {
        const reference::ShadowFlips flips = reference::countShadowFlips(*previous, frame);
        json["flips"] = {{"compared", flips.compared},
                         {"flips", flips.flips},
                         {"rate", flips.rate()},
                         {"where_maps_resized", flips.flipsWhereMapsResized}};
    }
    previous = std::move(frame);
    return json;
}

// The views whose tier (before the budget) differs from the previous frame's for the same light and
// face, and `tiers` replaced by this frame's: what --shadow-hysteresis holds back.
uint64_t countTierSwitches(const render::Renderer& renderer, std::map<std::pair<uint32_t, uint32_t>, uint32_t>& tiers) {
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> now;
    uint64_t switches = 0;
    for (const ShadowView& view : renderer.shadowPlan().views) {
        if (view.isCascade) continue;
        const std::pair<uint32_t, uint32_t> key{renderer.lights().sceneLightIndex[view.packedLight], view.face};
        now[key] = view.demandedTier;
        const auto before = tiers.find(key);
        switches += before != tiers.end() && before->second != view.demandedTier;
    }
    tiers = std::move(now);
    return switches;
}

// One line for the whole sequence where the shadow budget reduced some frame's views (render warns
// per frame; a sequence would repeat it frame after frame).
void warnAboutReducedFrames(const std::vector<SequenceFrame>& frames) {
    size_t reducedFrames = 0;
    size_t most = 0;
    for (const SequenceFrame& f : frames) {
        const size_t reduced = f.stats["shadows"].value("reduced", nlohmann::json::array()).size();
        reducedFrames += reduced > 0;
        most = std::max(most, reduced);
    }
    if (reducedFrames == 0) return;
    log::warn("shadows: in " + std::to_string(reducedFrames) + " of " + std::to_string(frames.size()) +
              " frames, up to " + std::to_string(most) + " view(s) got less resolution than their receivers need, to fit " +
              "--shadow-budget (frames.csv's shadow_reduced_views counts them)");
}

// The frames of a sequence, one after another: the scene posed at the frame's time (a still
// scene, the same every frame), rendered and timed, its statistics, and what the next frame needs
// (the last validated frame, for the flips; auto's tiers, for the hysteresis).
class SequencePlayer {
public:
    SequencePlayer(vk::Context& context, const RenderOptions& options, const render::RenderSettings& settings,
                   const Scene& still, uint32_t validateEvery, render::ShadowCacheMode shadowCache)
        : context_(context), options_(options), settings_(settings), still_(still), validateEvery_(validateEvery) {
        if (shadowCache != render::ShadowCacheMode::Off && settings.shadows.enabled) {
            shadowCache_.emplace(context, settings.shadows, shadowCache);
        }
    }

    // Frame `index` at `time` seconds; its image into `image`.
    SequenceFrame play(uint32_t index, double time, ImageRgba8& image) {
        const bool moves = still_.animationSeconds > 0.0;
        options_.time = moves ? std::optional<double>(time) : std::nullopt;
        const Scene scene = moves ? loadSceneForOptions(options_) : still_;
        const bool validated = validateEvery_ > 0 && index % validateEvery_ == 0;
        render::RenderSettings settings = settings_;
        settings.collectShadowFactors = validated;
        settings.shadows.previousTiers = previousTiers_;
        settings.shadows.previousPageMarks = std::move(previousPageMarks_);
        render::Renderer renderer(context_, scene, settings, shadowCache_ ? &*shadowCache_ : nullptr);
        render::FrameResult result = renderer.render(options_.frames);
        nlohmann::json stats = frameStatsJson(result, renderer, scene, context_.deviceName(), options_.frames);
        stats["shadows"] = shadowStatsJson(renderer);
        // Each view's entry (render --stats lists them, 30 KB a frame on the hall) would make a
        // long sequence's frames.json megabytes; the counts above it stay.
        stats["shadows"].erase("views");
        stats["shadows"]["tier_switches"] = countTierSwitches(renderer, previousTiers_);
        if (settings.shadows.virtualPages() && settings.shadows.tierHysteresis > 0.0f && settings.shadows.enabled) {
            // The levels this frame read, which hysteresis holds in the next (VirtualPageReads).
            previousPageMarks_ = pageMarksByView(renderer.shadowPlan(), renderer.lights(), renderer.readShadowPageMarks());
        }
        if (settings.shadows.virtualPages() && settings.shadows.enabled) {
            // (render --stats gives the whole record, virtual_pages; a sequence keeps the counts)
            stats["shadows"]["pages"] = {{"allocated", renderer.shadowPages().pages.size()},
                                         {"drawn_with_casters", renderer.shadowPageDraws().pagesDrawn}};
        }
        if (const render::ShadowCacheFrame* cache = renderer.shadowCacheFrame()) {
            stats["shadows"]["cache"] = {{"kept_views", cache->keptViews},
                                         {"drawn_views", cache->drawnViews},
                                         {"keepable_views", cache->keepableViews},
                                         {"moved_views", cache->movedViews},
                                         {"laid_out", cache->laidOut ? 1 : 0},  // a number: frames.csv's counters read numbers
                                         {"atlas_texels", cache->atlasTexels},
                                         {"packed_texels", cache->packedTexels},
                                         {"check_ms", cache->checkMs},
                                         {"over_static_views", cache->overStaticViews},
                                         {"static_stored_views", cache->staticStoredViews},
                                         {"dynamic_casters", cache->dynamicCasters},
                                         {"static_texels", cache->staticTexels},
                                         {"kept_pages", cache->keptPages},
                                         {"drawn_pages", cache->drawnPages},
                                         {"keepable_pages", cache->keepablePages},
                                         {"page_slots", cache->pageSlots}};
        }
        if (validated) stats["validation"] = frameValidationJson(scene, renderer, lastValidated_);
        image = std::move(result.image);
        return {index, time, result.medianMs, std::move(stats)};
    }

private:
    vk::Context& context_;
    RenderOptions options_;
    const render::RenderSettings& settings_;
    const Scene& still_;
    uint32_t validateEvery_;
    std::optional<reference::StabilityFrame> lastValidated_;
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> previousTiers_;
    std::map<std::pair<uint32_t, uint32_t>, std::vector<uint32_t>> previousPageMarks_;  // virtual, hysteresis
    std::optional<render::ShadowCache> shadowCache_;  // --shadow-cache on: kept from frame to frame
};

// frames.json's header: what was played, where, and how.
nlohmann::json sequenceHeader(const Scene& scene, const vk::Context& context, const PlayArgs& parsed, double seconds,
                              uint32_t count, const RenderOptions& options, const render::RenderSettings& settings) {
    return {{"scene", scene.source},
            {"device", context.deviceName()},
            {"fps", parsed.fps},
            {"seconds", seconds},
            {"frame_count", count},
            {"size", std::to_string(options.width) + "x" + std::to_string(options.height)},
            {"settings",
             {{"culling", render::methodName(settings.method)},
              {"shadows", settings.shadows.enabled ? shadowResolutionName(settings.shadows) : "off"},
              {"shadow_filter", shadowFilterName(settings.shadows.filter)},
              {"shadow_hysteresis", settings.shadows.tierHysteresis},
              {"shadow_cache", render::kShadowCacheModes[size_t(parsed.shadowCache)].name},
              {"timed_frames_each", options.frames}}}};
}

// Every file of the run, frames.json last: it lists them all, so the next run into DIR removes the
// frames it does not write again.
nlohmann::json commitSequence(const std::string& dir, OutputFiles& outputs, const std::vector<SequenceFrame>& frames,
                              const nlohmann::json& header, const std::vector<std::string>& frameImages, bool video) {
    const OutputFolderLayout& layout = sequenceFolderLayout();
    nlohmann::json document = sequenceJson(frames, header);
    outputs.add(dir + "/frames.csv", sequenceCsv(frames));
    outputs.add(dir + "/frame_times.svg", frameTimesSvg(frames));
    outputs.add(dir + "/index.html", sequenceHtml(document, frameImages, video));
    const std::vector<std::string> files = outputFolderFiles(outputs, dir, layout);
    document["files"] = files;
    // Compact: a frame's statistics indented run to some 130 lines, a sequence's to tens of
    // thousands (frames.csv is the file to read by eye).
    outputs.add(dir + "/frames.json", document.dump() + "\n");
    prepareOutputFolder(outputs, dir, layout, files);
    outputs.commit();
    return document;
}

}  // namespace

int runPlayCommand(const std::vector<std::string>& args) {
    const PlayArgs parsed = parsePlayArgs(args);
    if (parsed.help) {
        std::string usage = kUsage;
        const std::string marker = "{shadow-cache modes}";
        usage.replace(usage.find(marker), marker.size(),
                      variantHelp(render::kShadowCacheModes, render::ShadowCacheMode::Off, 2));
        std::fputs(usage.c_str(), stdout);
        return 0;
    }
    const std::string dir = *parsed.outDir;
    checkOutputFolder(dir, sequenceFolderLayout());
    const RenderOptions options = parseRenderOptions(parsed.renderArgs);
    // As stored first: the length of its animations or path says whether it moves at all. A still
    // scene (a file without animations, a built-in scene without a path) is one scene for every
    // frame; a moving one is posed at each frame's time.
    const Scene still = loadSceneForOptions(options);
    checkOutputFolder(dir, sequenceFolderLayout());  // again, now that the files the scene reads are known
    const double seconds = parsed.seconds.value_or(still.animationSeconds);
    if (!parsed.seconds && !(still.animationSeconds > 0.0)) {
        throw Error("--seconds", still.source + " has no animation or path to take a length from: give --seconds S");
    }
    const uint32_t count = frameCount(seconds, parsed.fps);

    vk::Context context(contextOptionsFrom(options));
    render::RenderSettings settings = renderSettingsFrom(options);
    settings.warnReducedShadows = false;  // counted per frame (shadow_reduced_views), and warned once below
    if (parsed.validateEvery > 0 && !settings.shadows.enabled) {
        throw Error("--validate-every", "compares shadows with Embree: shadows must be on");
    }
    SequencePlayer player(context, options, settings, still, parsed.validateEvery, parsed.shadowCache);
    std::vector<SequenceFrame> frames;
    OutputFiles outputs;
    std::vector<std::string> frameImages;
    std::optional<SequenceVideo> video;  // checked for ffmpeg before the first frame
    if (parsed.video) video.emplace();
    for (uint32_t i = 0; i < count; ++i) {
        ImageRgba8 image;
        frames.push_back(player.play(i, double(i) / parsed.fps, image));
        if (!parsed.saveFrames && !video) continue;
        std::string png = encodePng(image);
        if (video) video->addFrame(png);
        if (parsed.saveFrames) {
            frameImages.push_back(frameImageName(i));
            outputs.add(dir + "/" + frameImages.back(), std::move(png));
        }
    }
    if (video) outputs.add(dir + "/frames.mp4", video->encode(parsed.fps));
    warnAboutReducedFrames(frames);
    if (context.validationMessageCount() > 0) {
        throw Error("vulkan", std::to_string(context.validationMessageCount()) +
                                  " validation message(s) (printed above); no output written");
    }
    const nlohmann::json document =
        commitSequence(dir, outputs, frames, sequenceHeader(still, context, parsed, seconds, count, options, settings), frameImages,
                       parsed.video);
    const nlohmann::json& total = document["summary"]["total"];
    std::printf("play: %s, %u frames at %g fps over %g s; GPU ms per frame p50 %.2f, p95 %.2f, p99 %.2f, max %.2f\n",
                still.source.c_str(), count, parsed.fps, seconds, total["p50"].get<double>(), total["p95"].get<double>(),
                total["p99"].get<double>(), total["max"].get<double>());
    std::printf("wrote %s/index.html, frames.csv%s and frames.json\n", dir.c_str(), parsed.video ? ", frames.mp4" : "");
    return 0;
}

}  // namespace punctual::app
