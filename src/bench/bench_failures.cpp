#include "bench/bench_failures.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "bench/bench_cascade_failures.h"
#include "bench/failure_study.h"
#include "scene/study_scenes.h"
#include "shading.h"
#include "shadows.h"

namespace punctual::bench {
namespace {

constexpr float kDegree = 0.0174532925f;

// Misclassification among the point light's compared pixels whose direction from the light lies
// within two texels of a cube-face edge (`seams`) or not (interior).
double seamError(const ValidatedFrame& frame, const Scene& scene, uint32_t resolution, bool seams) {
    uint64_t compared = 0, wrong = 0;
    const glm::vec3 light = scene.lights.front().position;
    for (const reference::LightShadowValidation& v : frame.validation.lights) {
        for (size_t i = 0; i < v.verdicts.size(); ++i) {
            if (v.verdicts[i] == reference::PixelVerdict::NotCompared) continue;
            glm::vec3 d = glm::abs(frame.factors.positions[i] - light);
            std::sort(&d.x, &d.x + 3);  // ascending: d.z is the major axis
            const bool nearSeam = (d.z - d.y) / d.z < 4.0f / float(resolution);
            if (nearSeam != seams) continue;
            ++compared;
            wrong += v.verdicts[i] == reference::PixelVerdict::FalseLit || v.verdicts[i] == reference::PixelVerdict::FalseShadow;
        }
    }
    return fraction(wrong, compared);
}

// Light lost to the caps: at the GPU's surface points, the unshadowed light (attenuation x N.L x
// peak intensity) of the kept lights against that of every light of the scene.
double lightBeyondCaps(const ValidatedFrame& frame, const Scene& scene, const FrameLights& kept) {
    double keptSum = 0.0, allSum = 0.0;
    std::vector<gpu::GpuPunctualLight> all;
    for (const Light& light : scene.lights) all.push_back(packPunctualLight(light));
    auto received = [](const gpu::GpuPunctualLight& light, const glm::vec3& p, const glm::vec3& n) {
        const gpu::LightSample s = gpu::sampleLight(light, p);
        const float peak = std::max({light.radiantColor.r, light.radiantColor.g, light.radiantColor.b});
        return double(s.attenuation * std::max(glm::dot(n, s.toLight), 0.0f) * peak);
    };
    for (size_t i = 0; i < frame.factors.covered.size(); ++i) {
        if (!frame.factors.covered[i]) continue;
        for (const auto& light : kept.packed) keptSum += received(light, frame.factors.positions[i], frame.factors.normals[i]);
        for (const auto& light : all) allSum += received(light, frame.factors.positions[i], frame.factors.normals[i]);
    }
    return allSum > 0.0 ? 1.0 - keptSum / allSum : 0.0;
}

// The light-grid methods, those --quick sweeps where `quick` (it stays under 3 minutes).
std::vector<std::string> gridMethodNames(bool quick) {
    std::vector<std::string> names;
    for (render::LightListMethod method : render::gridMethods()) {
        if (!quick || render::methodInfo(method).quickBench) names.emplace_back(render::methodName(method));
    }
    return names;
}

// The frame every study starts from: brute force (or `method`), shadows at 512.
struct StudyFrame {
    uint32_t width = 0;
    uint32_t height = 0;
    render::RenderSettings operator()(render::LightListMethod method = render::LightListMethod::Brute) const {
        render::RenderSettings settings;
        settings.width = width;
        settings.height = height;
        settings.method = method;
        settings.shadows.resolution = 512;
        return settings;
    }
};

// Where spot and point shadows fail: bias (acne, peter-panning), cube seams, pancaking, wide spots.
void appendShadowStudies(std::vector<FailureStudy>& list, vk::Context& context, bool quick, StudyFrame base) {
    // Acne and peter-panning: one scene rendered with every bias scaled by `value`, measuring
    // false shadows (acne) or false lights (peter-panning) outside the edge band.
    auto biasStudy = [&context, base](Scene (*makeScene)(), bool countFalseShadow) {
        return [&context, base, makeScene, countFalseShadow](double value, const std::string& variant) {
            render::RenderSettings s = base();
            s.shadows.filter = parseShadowFilter(variant);
            s.shadows.bias = float(value) * ShadowSettings{}.bias;
            const ValidatedFrame f = renderAndValidate(context, makeScene(), s);
            const reference::ShadowCounts& c = f.validation.overall;
            const uint64_t wrong = countFalseShadow ? c.falseShadowOutsideBand : c.falseLitOutsideBand;
            return std::pair{fraction(wrong, c.comparedOutsideBand), f.result.medianMs.total};
        };
    };
    list.push_back({"acne-vs-bias", "bias scale (x the default 1,1,0,0)", "false_shadow fraction outside the edge band",
                    quick ? std::vector<double>{0.0, 0.5, 1.0} : std::vector<double>{0.0, 0.25, 0.5, 1.0, 2.0},
                    quick ? std::vector<std::string>{"hw"} : std::vector<std::string>{"hw", "tent5"},
                    biasStudy(&study::grazingLightScene, true)});
    list.push_back({"peter-panning-vs-bias", "bias scale (x the default 1,1,0,0)", "false_lit fraction outside the edge band",
                    quick ? std::vector<double>{1.0, 4.0} : std::vector<double>{0.5, 1.0, 2.0, 4.0, 8.0},
                    quick ? std::vector<std::string>{"tent5"} : std::vector<std::string>{"hw", "tent5"},
                    biasStudy(&study::contactCasterScene, false)});
    list.push_back({"cube-seams", "shadow resolution", "misclassified fraction",
                    quick ? std::vector<double>{256.0} : std::vector<double>{256.0, 512.0, 1024.0},
                    {"cube seams", "cube interior", "slices seams", "slices interior"},
                    [&context, base](double value, const std::string& variant) {
                        render::RenderSettings s = base();
                        s.shadows.resolution = uint32_t(value);
                        s.shadows.pointLayout = variant.rfind("cube", 0) == 0 ? PointShadowLayout::Cube : PointShadowLayout::Slices;
                        const Scene scene = study::seamScene();
                        const ValidatedFrame f = renderAndValidate(context, scene, s);
                        return std::pair{seamError(f, scene, s.shadows.resolution, variant.find("seams") != std::string::npos),
                                         f.result.medianMs.total};
                    }});
    list.push_back({"pancaking-leak", "spot near plane (fraction of range; 0 = fitted to casters)",
                    "false_lit fraction outside the edge band",
                    quick ? std::vector<double>{0.0, 0.3} : std::vector<double>{0.0, 0.1, 0.2, 0.3, 0.4},
                    {"clipped (no pancaking)", "pancaking"},
                    [&context, base](double value, const std::string& variant) {
                        render::RenderSettings s = base();
                        s.shadows.spotNearFraction = float(value);
                        s.shadows.pancaking = variant == "pancaking";
                        const ValidatedFrame f = renderAndValidate(context, study::pancakingScene(), s);
                        return std::pair{fraction(f.validation.overall.falseLitOutsideBand, f.validation.overall.comparedOutsideBand),
                                         f.result.medianMs.total};
                    }});
    list.push_back({"wide-spot", "outer cone angle (degrees)", "misclassified fraction outside the edge band",
                    quick ? std::vector<double>{45.0, 85.0} : std::vector<double>{30.0, 60.0, 75.0, 80.0, 85.0, 89.0},
                    {"spot"},
                    [&context, base](double value, const std::string&) {
                        const ValidatedFrame f = renderAndValidate(context, study::wideSpotScene(float(value) * kDegree), base());
                        return std::pair{f.validation.overall.misclassifiedOutsideBand(), f.result.medianMs.total};
                    }});
}

// Where light lists fail: tile depth discontinuities, per-object lists on large objects, the
// caps, transparent surfaces in tiles bounded by opaque depth.
void appendCullingStudies(std::vector<FailureStudy>& list, vk::Context& context, bool quick, StudyFrame base) {
    list.push_back({"tile-depth-discontinuities", "tile size (pixels)", "lights tested / lights reaching (efficiency)",
                    quick ? std::vector<double>{16.0, 64.0} : std::vector<double>{8.0, 16.0, 32.0, 64.0},
                    gridMethodNames(quick),
                    [&context, base](double value, const std::string& variant) {
                        render::RenderSettings s = base(render::parseMethod(variant));
                        s.tileSize = uint32_t(value);
                        s.shadows.enabled = false;
                        s.collectLightStats = true;
                        render::Renderer renderer(context, study::postsScene(), s);
                        const double ms = renderer.render(1, 1).medianMs.total;
                        return std::pair{computeCullingStats(renderer.readLightStats()).efficiency, ms};
                    }});
    list.push_back({"per-object-large-objects", "lights on the floor", "missed energy (share of brute-force light)",
                    quick ? std::vector<double>{8.0, 16.0} : std::vector<double>{4.0, 8.0, 12.0, 16.0, 24.0, 32.0},
                    {"per-object"},
                    [&context, base](double value, const std::string&) {
                        render::RenderSettings s = base(render::LightListMethod::PerObject);
                        s.shadows.enabled = false;
                        s.collectLightStats = true;
                        render::Renderer renderer(context, study::largeFloorScene(int(value)), s);
                        const double ms = renderer.render(1, 1).medianMs.total;
                        return std::pair{computeCullingStats(renderer.readLightStats()).missedEnergy, ms};
                    }});
    list.push_back({"beyond-the-caps", "spot lights in the scene (half as many points)",
                    "light lost to the caps (share of all lights' unshadowed light)",
                    quick ? std::vector<double>{64.0, 128.0} : std::vector<double>{32.0, 64.0, 96.0, 128.0},
                    {"tiled"},
                    [&context, base](double value, const std::string&) {
                        const Scene scene = study::manyLightsScene(int(value), int(value) / 2);
                        render::RenderSettings s = base(render::LightListMethod::Tiled);
                        s.collectShadowFactors = true;
                        render::Renderer renderer(context, scene, s);
                        ValidatedFrame frame;
                        frame.result = renderer.render(1, 1);
                        frame.factors = renderer.readShadowFactors();
                        return std::pair{lightBeyondCaps(frame, scene, renderer.lights()), frame.result.medianMs.total};
                    }});
    list.push_back({"transparency-tiled-depth-bounds", "wall distance behind the glass (m)",
                    "share of transparent fragments missing light",
                    quick ? std::vector<double>{1.0, 8.0} : std::vector<double>{0.5, 1.0, 2.0, 4.0, 8.0},
                    {"tiled: opaque depth", "tiled", "clustered: opaque depth", "clustered"},
                    [&context, base](double value, const std::string& variant) {
                        // "opaque depth": tiles and clusters bounded by the depth prepass alone,
                        // as before the transparent depth span (render/transparent_depth_pass.h).
                        const bool opaqueOnly = variant.find("opaque depth") != std::string::npos;
                        render::RenderSettings s = base(render::parseMethod(variant.substr(0, variant.find(':'))));
                        s.shadows.enabled = false;
                        s.collectLightStats = true;
                        s.opaqueCullingDepth = opaqueOnly;
                        render::Renderer renderer(context, study::glassPanesScene(float(value)), s);
                        const double ms = renderer.render(1, 1).medianMs.total;
                        const CullingStats stats = computeCullingStats(renderer.readLightStats());
                        return std::pair{fraction(stats.transparentFragmentsMissingLight, stats.transparentFragments), ms};
                    }});
}

std::vector<FailureStudy> studies(vk::Context& context, bool quick, uint32_t width, uint32_t height) {
    std::vector<FailureStudy> list;
    appendShadowStudies(list, context, quick, StudyFrame{width, height});
    appendCullingStudies(list, context, quick, StudyFrame{width, height});
    // The sun's cascades: shimmering, seams, perspective aliasing and pancaking.
    for (FailureStudy& study : cascadeFailureStudies(context, quick, width, height)) list.push_back(std::move(study));
    return list;
}

}  // namespace

size_t failureStudySize(vk::Context& context, bool quick) {
    size_t count = 0;
    for (const FailureStudy& s : studies(context, quick, 1, 1)) count += s.values.size() * s.variants.size();
    return count;
}

std::vector<FailureRow> runFailureStudy(vk::Context& context, bool quick, uint32_t width, uint32_t height,
                                        const std::function<void(const std::string&)>& onStep) {
    std::vector<FailureRow> rows;
    for (const FailureStudy& s : studies(context, quick, width, height)) {
        for (const std::string& variant : s.variants) {
            for (double value : s.values) {
                const auto [error, ms] = s.measure(value, variant);
                rows.push_back({s.name, s.parameter, value, variant, s.metric, error, ms});
                onStep(s.name + " " + variant);
            }
        }
    }
    return rows;
}

std::string failuresCsv(const std::vector<FailureRow>& rows) {
    auto quoted = [](const std::string& text) { return "\"" + text + "\""; };
    std::ostringstream csv;
    csv.precision(6);
    csv << "study,parameter,value,variant,metric,error,total_ms\n";
    for (const FailureRow& r : rows) {
        csv << r.study << "," << quoted(r.parameter) << "," << r.value << "," << quoted(r.variant) << ","
            << quoted(r.metric) << "," << r.error << "," << r.totalMs << "\n";
    }
    return csv.str();
}

}  // namespace punctual::bench
