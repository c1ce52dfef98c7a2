#include "bench/bench_run.h"

#include <algorithm>
#include <optional>

#include "core/memory_usage.h"
#include "metrics/heatmap.h"
#include "metrics/image_diff.h"
#include "metrics/round_statistics.h"
#include "render/renderer.h"
#include "scene/light_generator.h"

namespace punctual::bench {

void mergePassNames(std::vector<std::string>& known, const std::vector<std::string>& names) {
    size_t at = 0;  // where the next new name goes: after the last known name seen
    for (const std::string& name : names) {
        const auto it = std::find(known.begin(), known.end(), name);
        if (it != known.end()) {
            at = size_t(it - known.begin()) + 1;
        } else {
            known.insert(known.begin() + std::ptrdiff_t(at++), name);
        }
    }
}

// One configuration while its group is measured: its scene, renderer and rounds.
struct BenchRun::Measurement {
    BenchConfig config;
    std::unique_ptr<Scene> ownScene;  // generated lights: a copy of the bench's scene
    const Scene* scene = nullptr;
    const reference::EmbreeScene* geometry = nullptr;
    std::unique_ptr<render::Renderer> renderer;
    std::vector<render::PassTimings> rounds;  // one sample a round: the fastest of its frames
    std::vector<double> frameTotals;          // every timed frame, for the run's frame noise
    ImageRgba8 image;
};

// A series with a built-in scene of its own (the cascades' outdoor scene, the rooms at each size):
// built once, on first use, its Embree scene only when a configuration validates against it.
struct BenchRun::OwnScene {
    Scene scene;
    std::unique_ptr<reference::EmbreeScene> embree;
};

BenchRun::BenchRun(vk::Context& context, const Scene& baseScene, const BenchRunSettings& settings, OutputFiles& outputs)
    : context_(context), settings_(settings), outputs_(outputs), embree_(baseScene), fullSet_(baseScene) {
    // The generated lights: the largest set once; each configuration takes its first lights at its
    // range (nested sets, docs/BENCH_RESULTS.md).
    replaceLights(fullSet_, kBenchSpots, kBenchPoints, 1);
}

BenchRun::~BenchRun() = default;

BenchRun::Measurement BenchRun::prepare(const BenchConfig& config) {
    Measurement m;
    m.config = config;
    if (config.scene) {
        const std::pair key{config.scene, config.triangles};
        auto own = ownScenes_.find(key);
        if (own == ownScenes_.end()) {
            if (config.triangles) {  // a sized scene replaces the previous size's: memory holds one size
                std::erase_if(ownScenes_, [&](const auto& entry) { return entry.first.first == config.scene; });
                resetPeakResident();
            }
            auto made = std::make_unique<OwnScene>();
            made->scene = makeBuiltinScene(*config.scene,
                                           config.triangles ? std::optional(config.triangles) : std::nullopt);
            own = ownScenes_.emplace(key, std::move(made)).first;
        }
        OwnScene& made = *own->second;
        if (config.validateShadows && !made.embree) made.embree = std::make_unique<reference::EmbreeScene>(made.scene);
        m.scene = &made.scene;
        m.geometry = made.embree.get();
    } else if (config.ownLights) {
        m.ownScene = std::make_unique<Scene>(fullSet_);
        const LightRange rule{config.constantDensity ? LightRange::Kind::ConstantDensity : LightRange::Kind::Drawn, 0.0f};
        replaceLights(*m.ownScene, config.spot, config.point, 1, rule);
        if (!config.constantDensity) setLightRanges(*m.ownScene, config.lightRange);
        m.scene = m.ownScene.get();
        m.geometry = &embree_;
    } else {
        m.ownScene = std::make_unique<Scene>(fullSet_);
        setLightRanges(*m.ownScene, config.lightRange);
        keepFirstLights(*m.ownScene, config.spot, config.point);
        m.scene = m.ownScene.get();
        m.geometry = &embree_;
    }
    render::RenderSettings settings = cli::renderSettingsFrom(settings_.options);
    if (config.width) {
        settings.width = config.width;
        settings.height = config.height;
    }
    settings.method = config.method;
    settings.coarseTiles = config.coarseTiles;
    settings.lightLists = config.lightLists;
    // Every light the configuration has (at least the design notes' 64 + 32).
    settings.maxLights = {std::max<uint32_t>(settings.maxLights.spots, config.spot),
                          std::max<uint32_t>(settings.maxLights.points, config.point)};
    settings.shadows = config.shadows;
    settings.collectLightStats = true;  // rendered apart, untimed (addCounters)
    settings.collectShadowFactors = config.validateShadows;
    settings.warnReducedShadows = false;  // recorded in shadow_reduced_views
    m.renderer = std::make_unique<render::Renderer>(context_, *m.scene, settings);
    m.renderer->render(1, 0);  // warm-up: pipelines compiled, memory touched
    return m;
}

void BenchRun::runRounds(std::vector<Measurement>& group, uint32_t groupIndex) {
    for (uint32_t round = 0; round < settings_.rounds; ++round) {
        for (uint32_t i : roundOrder(uint32_t(group.size()), settings_.seed, groupIndex, round)) {
            // The round's visit: bestOf frames back to back, the fastest per pass kept.
            std::vector<render::PassTimings> frames;
            for (uint32_t frame = 0; frame < settings_.bestOf; ++frame) {
                render::FrameResult result = group[i].renderer->render(1, 0);
                frames.push_back(result.framesMs.front());
                group[i].frameTotals.push_back(result.framesMs.front().total);
                group[i].image = std::move(result.image);
            }
            group[i].rounds.push_back(fastestPerPass(frames));
        }
    }
}

// The sample heat map (every method at the largest mixed count) and the image error against
// brute force's image of the same frame.
void BenchRun::addImageRows(BenchRow& row, const Measurement& m, const LightStatsImage& pixelWork) {
    const BenchConfig& config = m.config;
    const render::Renderer& renderer = *m.renderer;
    if (config.series == "mix" && config.spot == kBenchSpots) {
        std::vector<uint8_t> background(pixelWork.covered.size());
        for (size_t i = 0; i < background.size(); ++i) background[i] = pixelWork.covered[i] ? 0 : 1;
        HeatmapOptions heatmap;
        heatmap.title = std::string("lights tested per pixel: ") + render::methodName(config.method);
        heatmap.maxValue = 32;
        outputs_.add(settings_.outDir + "/images/heatmap-" + render::methodName(config.method) + ".png",
                     encodePng(renderHeatmap(pixelWork.tested, background, renderer.settings().width,
                                             renderer.settings().height, heatmap)));
    }
    const std::string bruteKey = config.series + "/" + std::to_string(config.spot) + "," + std::to_string(config.point) +
                                 "/" + benchNumber(config.lightRange) + "/" + row["width"] + "x" + row["height"] +
                                 (config.shadows.enabled ? "/s" : "") + "/" + std::to_string(config.triangles);
    if (config.validateShadows) return;
    if (config.method == render::referenceMethod()) {
        bruteImages_[bruteKey] = m.image;
    } else if (bruteImages_.count(bruteKey)) {
        const ImageDifference difference = compareImages(m.image, bruteImages_[bruteKey]);
        row["image_error"] = benchNumber(difference.meanAbsolute);
        row["pixels_off"] = benchNumber(difference.pixelsOff);
    }
}

void BenchRun::recordMeasurement(Measurement& m) {
    const BenchConfig& config = m.config;
    render::Renderer& renderer = *m.renderer;
    // Every pass any configuration has, in frame order (virtual pages add the marking passes).
    mergePassNames(record_.passes, renderer.passNames());
    BenchRow row;
    addConfiguration(row, config, *m.scene, renderer, settings_.rounds, settings_.bestOf);
    const RoundSummary frame = addTimings(row, m.rounds);
    record_.frameCvs.push_back(frame.cv);
    record_.singleFrameCvs.push_back(summarizeRounds(m.frameTotals).cv);
    record_.flagged += row["flagged"] == "1" ? 1u : 0u;
    const LightStatsImage pixelWork = renderer.readLightStats();
    addCounters(row, renderer, &pixelWork);
    const std::string name = row["config"];
    // The raw samples, in the order they were taken (round by round, bestOf frames each), so that
    // a reader can look at the spread behind a flag.
    record_.frameSamples[name] = m.frameTotals;
    addImageRows(row, m, pixelWork);
    if (config.validateShadows && m.geometry) {
        ShadowValidationRows validation = addShadowValidation(row, renderer, *m.geometry, *m.scene);
        record_.shadowLights[name] = validation.perLight;
        if (!validation.perCascade.is_null()) record_.sunCascades[name] = validation.perCascade;
        if (validation.mismatch) {
            outputs_.add(settings_.outDir + "/images/mismatch-" + name + "-light0.png", encodePng(*validation.mismatch));
        }
    }
    m.renderer.reset();  // the group's memory goes as its rows are written
    record_.rows.push_back(std::move(row));
}

void BenchRun::measure(const std::vector<BenchConfig>& configs, ProgressBar& progress) {
    uint32_t groupIndex = 0;
    for (size_t first = 0; first < configs.size(); ++groupIndex) {
        size_t end = first;
        while (end < configs.size() && benchGroupKey(configs[end]) == benchGroupKey(configs[first])) ++end;
        // The group's renderers, all alive while its rounds run.
        std::vector<Measurement> group;
        for (size_t c = first; c < end; ++c) group.push_back(prepare(configs[c]));
        runRounds(group, groupIndex);
        for (Measurement& m : group) {
            recordMeasurement(m);
            progress.step(record_.rows.back().at("config"));
        }
        first = end;
    }
}

std::string resultsCsv(const BenchRecord& record, const std::vector<std::string>& columns) {
    std::string csv;
    for (size_t i = 0; i < columns.size(); ++i) csv += (i ? "," : "") + columns[i];
    csv += "\n";
    for (const BenchRow& row : record.rows) {
        for (size_t i = 0; i < columns.size(); ++i) {
            const auto it = row.find(columns[i]);
            // Only flag_reason holds free text; it never has a comma or a quote.
            csv += (i ? "," : "") + (it == row.end() ? std::string() : it->second);
        }
        csv += "\n";
    }
    return csv;
}

nlohmann::json resultsConfigurations(const BenchRecord& record, const std::vector<std::string>& columns) {
    nlohmann::json json = nlohmann::json::array();
    for (const BenchRow& row : record.rows) {
        nlohmann::json entry;
        for (const std::string& column : columns) {
            const auto it = row.find(column);
            entry[column] = it == row.end() ? "" : it->second;
        }
        const std::string& name = row.at("config");
        if (const auto lights = record.shadowLights.find(name); lights != record.shadowLights.end())
            entry["shadow_lights"] = lights->second;
        if (const auto cascades = record.sunCascades.find(name); cascades != record.sunCascades.end())
            entry["sun_cascades"] = cascades->second;
        entry["frame_total_ms"] = record.frameSamples.at(name);
        json.push_back(entry);
    }
    return json;
}

}  // namespace punctual::bench
