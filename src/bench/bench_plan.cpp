#include "bench/bench_plan.h"

#include <algorithm>
#include <sstream>
#include <tuple>

#include "core/error.h"
#include "core/variant_table.h"
#include "lights/shadow_filters.h"

namespace punctual::bench {
namespace {

// Methods in table order; --quick keeps the entries marked for it.
std::vector<render::LightListMethod> benchMethods(bool quick) {
    std::vector<render::LightListMethod> methods;
    for (const render::LightListMethodInfo& method : render::kLightListMethods) {
        if (!quick || method.quickBench) methods.push_back(method.value);
    }
    return methods;
}

// The series whose frames cost seconds (96 shadowed lights, 10^5 triangles): --quick keeps brute
// force, the reference, and tiled, the default, to stay within its few minutes.
std::vector<render::LightListMethod> heavyBenchMethods(bool quick) {
    if (quick) return {render::LightListMethod::Brute, render::LightListMethod::Tiled};
    return benchMethods(false);
}

// The list forms a grid method is measured with, in table order (--quick: those marked for it);
// the methods without a grid have none to vary, and are measured once (with the default).
std::vector<render::LightListForm> benchListForms(render::LightListMethod method, bool quick) {
    if (!render::usesLightGrid(method)) return {render::LightListForm::Masks};
    std::vector<render::LightListForm> forms;
    for (const render::LightListFormInfo& form : render::kLightListForms) {
        if (!quick || form.quickBench) forms.push_back(form.value);
    }
    return forms;
}

ShadowSettings shadowsOff() {
    ShadowSettings off;
    off.enabled = false;
    return off;
}

// Light counts, with a fixed range per light: the mix (2 spots to a point), spots alone, points
// alone. Each count's lights are the first of the largest set, so a larger count only adds
// lights.
void addLightCountSeries(std::vector<BenchConfig>& configs, bool quick) {
    const std::vector<uint32_t> counts = quick ? std::vector<uint32_t>{0, 16, 64} : std::vector<uint32_t>{0, 8, 16, 32, 48, 64};
    for (const auto& [series, spotShare, pointShare] :
         {std::tuple<const char*, uint32_t, uint32_t>{"mix", 2, 1}, {"spot-only", 2, 0}, {"point-only", 0, 1}}) {
        for (uint32_t count : counts) {
            if (std::string(series) != "mix" && count == 0) continue;  // the same empty frame as mix
            if (std::string(series) != "mix" && quick) continue;        // --quick: the mix alone
            for (render::LightListMethod method : benchMethods(quick)) {
                BenchConfig config;
                config.series = series;
                config.method = method;
                config.spot = spotShare ? count : 0;
                config.point = pointShare ? count / 2 : 0;
                config.shadows = shadowsOff();
                configs.push_back(config);
            }
        }
    }
}

// Thousands of lights (issue 32): 16 to 8,192, half spots and half points, each count's own set,
// at constant density (scale: --light-range auto, the lights reaching a pixel about as 96 put
// them) and at the fixed range (scale-fixed: every pixel under more lights as they multiply).
// --quick: 16 and 128 at constant density.
void addScaleSeries(std::vector<BenchConfig>& configs, bool quick) {
    std::vector<uint32_t> counts;
    for (uint32_t count = 16; count <= (quick ? 128 : kBenchScaleLights); count *= quick ? 8 : 2) counts.push_back(count);
    for (const bool constantDensity : {true, false}) {
        if (quick && !constantDensity) continue;
        for (uint32_t count : counts) {
            for (render::LightListMethod method : benchMethods(quick)) {
                for (render::LightListForm form : benchListForms(method, quick)) {
                    BenchConfig config;
                    config.series = constantDensity ? "scale" : "scale-fixed";
                    config.method = method;
                    config.lightLists = form;
                    config.spot = count / 2;
                    config.point = count / 2;
                    config.ownLights = true;
                    config.constantDensity = constantDensity;
                    config.shadows = shadowsOff();
                    configs.push_back(config);
                }
            }
        }
    }
}

BenchConfig fullLightSet(const char* series, render::LightListMethod method) {
    BenchConfig config;
    config.series = series;
    config.method = method;
    config.spot = kBenchSpots;
    config.point = kBenchPoints;
    config.shadows = shadowsOff();
    return config;
}

// Overlap alone: 64 + 32 lights, every range the same share of the diagonal.
void addRangeSeries(std::vector<BenchConfig>& configs, bool quick) {
    const std::vector<float> ranges = quick ? std::vector<float>{0.1f, 0.35f} : std::vector<float>{0.1f, 0.2f, 0.35f, 0.5f, 0.7f};
    for (float range : ranges) {
        for (render::LightListMethod method : benchMethods(quick)) {
            BenchConfig config = fullLightSet("range", method);
            config.lightRange = range;
            configs.push_back(config);
        }
    }
}

// Pixels alone: the same lights and scene from 320x180 to 2560x1440.
void addPixelSeries(std::vector<BenchConfig>& configs, bool quick) {
    const std::vector<std::pair<uint32_t, uint32_t>> sizes =
        quick ? std::vector<std::pair<uint32_t, uint32_t>>{{320, 180}, {640, 360}}
              : std::vector<std::pair<uint32_t, uint32_t>>{{320, 180}, {640, 360}, {1280, 720}, {1920, 1080}, {2560, 1440}};
    for (const auto& [width, height] : sizes) {
        for (render::LightListMethod method : benchMethods(quick)) {
            BenchConfig config = fullLightSet("pixels", method);
            config.width = width;
            config.height = height;
            configs.push_back(config);
        }
    }
}

void addShadowSeries(std::vector<BenchConfig>& configs, bool quick) {
    for (render::LightListMethod method : heavyBenchMethods(quick)) {
        configs.push_back(fullLightSet("shadows", method));
        BenchConfig on = fullLightSet("shadows", method);
        on.shadows = ShadowSettings{};
        configs.push_back(on);
    }
    // Shadow quality against memory: auto (every light, each view at its tier) and fixed
    // resolutions, at 16 and 32 bits, validated against Embree; and the former default, 1024 at
    // 32 bits for the 32 spots and 8 points that matter most (issue 11's "A").
    const std::vector<uint32_t> resolutions = quick ? std::vector<uint32_t>{ShadowSettings::kAutoResolution, 256}
                                                    : std::vector<uint32_t>{ShadowSettings::kAutoResolution, 256, 512,
                                                                            1024, 2048};
    for (uint32_t resolution : resolutions) {
        for (ShadowFormat format : {ShadowFormat::D16, ShadowFormat::D32}) {
            BenchConfig config = fullLightSet("shadow-quality", render::LightListMethod::Tiled);
            config.shadows.enabled = true;
            config.shadows.resolution = resolution;
            config.shadows.format = format;
            // A 16384^2 atlas holds 64 views of 2048^2: not 256, nor the 80 of 32 spots and 8
            // points (each point six slices); the fixed 2048 sweep shadows the 32 spots and 5
            // points that matter most (62 views).
            if (resolution == 2048) {
                config.shadows.maxShadowedSpots = 32;
                config.shadows.maxShadowedPoints = 5;
            }
            config.validateShadows = true;
            configs.push_back(config);
        }
    }
    BenchConfig former = fullLightSet("shadow-quality", render::LightListMethod::Tiled);
    former.shadows = ShadowSettings{};
    former.shadows.resolution = 1024;
    former.shadows.format = ShadowFormat::D32;
    former.shadows.maxShadowedSpots = 32;
    former.shadows.maxShadowedPoints = 8;
    former.validateShadows = true;
    configs.push_back(former);
    // The auto resolution's budget: the storage the views are fitted to, against their accuracy.
    const std::vector<uint64_t> budgetsMib = quick ? std::vector<uint64_t>{8, 64} : std::vector<uint64_t>{8, 16, 32, 64, 128};
    for (uint64_t mib : budgetsMib) {
        BenchConfig config = fullLightSet("shadow-budget", render::LightListMethod::Tiled);
        config.shadows = ShadowSettings{};
        config.shadows.budgetBytes = mib << 20;
        config.validateShadows = true;
        configs.push_back(config);
    }
    // The filters at the default (auto) resolution.
    for (const ShadowFilterInfo& filter : kShadowFilters) {
        if (quick && !filter.quickBench) continue;
        BenchConfig config = fullLightSet("shadow-filters", render::LightListMethod::Tiled);
        config.shadows = ShadowSettings{};
        config.shadows.filter = filter.value;
        config.validateShadows = true;
        configs.push_back(config);
    }
}

// Virtual shadow pages against whole views (issue 33): auto and virtual on the hall (the default
// scene), the outdoor street, the engine (thin parts) and the rooms, each with its own lights, at
// 1280x720 and validated; the rooms at 10^4..10^6 triangles, whose memory must follow the pairs the
// frame shades, not the views; then the bench's scene with 12 to 96 of its generated lights (2
// spots to a point, as the mix series), the same growth against the light count. --quick: the
// hall alone, at the run's size.
void addShadowMemorySeries(std::vector<BenchConfig>& configs, bool quick) {
    std::vector<std::pair<const BuiltinScene*, uint64_t>> scenes = {{&kDefaultBuiltinScene, 0}};
    std::vector<std::pair<uint32_t, uint32_t>> lightCounts;
    if (!quick) {
        scenes.emplace_back(&parseBuiltinScene("outdoor"), 0);
        scenes.emplace_back(&parseBuiltinScene("engine"), 0);
        for (uint64_t triangles : {10'000ull, 100'000ull, 1'000'000ull}) scenes.emplace_back(&parseBuiltinScene("rooms"), triangles);
        lightCounts = {{8, 4}, {16, 8}, {32, 16}, {kBenchSpots, kBenchPoints}};
    }
    const auto add = [&](BenchConfig config) {
        for (const ShadowResolutionModeInfo& mode : kShadowResolutionModes) {
            config.series = "shadow-memory";
            config.shadows.resolution = mode.value;
            config.validateShadows = true;
            if (!quick) {
                config.width = 1280;
                config.height = 720;
            }
            configs.push_back(config);
        }
    };
    for (const auto& [scene, triangles] : scenes) {
        BenchConfig config;
        config.scene = scene;
        config.triangles = triangles;
        add(config);
    }
    for (const auto& [spots, points] : lightCounts) {
        BenchConfig config;
        config.spot = spots;
        config.point = points;
        add(config);
    }
}

// The sun's cascades on the outdoor scene: count x fixed resolution x filter. Its lamps keep
// lighting the street but cast no shadow, so that the shadow stage and its memory are the
// cascades' alone. The filters are those whose reach is counted in texels (the disk's radius is a
// share of the map, the same for every cascade: the filters without a texel footprint); --quick keeps the ones marked for it.
void addCascadeSeries(std::vector<BenchConfig>& configs, bool quick) {
    const BuiltinScene& outdoor = parseBuiltinScene("outdoor");
    const std::vector<uint32_t> counts = quick ? std::vector<uint32_t>{1, 4} : std::vector<uint32_t>{1, 2, 3, 4};
    const std::vector<uint32_t> resolutions = quick ? std::vector<uint32_t>{512} : std::vector<uint32_t>{512, 1024, 2048};
    for (uint32_t count : counts) {
        for (uint32_t resolution : resolutions) {
            for (const ShadowFilterInfo& filter : kShadowFilters) {
                if (filter.footprint() == 0 || (quick && !filter.quickBench)) continue;
                BenchConfig config;
                config.series = "cascades";
                config.scene = &outdoor;
                config.shadows.resolution = resolution;
                config.shadows.filter = filter.value;
                config.shadows.maxShadowedSpots = 0;
                config.shadows.maxShadowedPoints = 0;
                config.shadows.cascades.count = count;
                config.validateShadows = true;
                configs.push_back(config);
            }
        }
    }
}

// Cost against triangles: the rooms scene (its own 64 spots, 32 points and sun, every one
// shadowed at auto resolution) at each size, every method. Sizes ascending, so each size's peak
// memory is its own (the bench frees a size's scene before building the next).
void addTriangleSeries(std::vector<BenchConfig>& configs, bool quick) {
    const BuiltinScene& rooms = parseBuiltinScene("rooms");
    const std::vector<uint64_t> sizes = quick ? std::vector<uint64_t>{10'000, 100'000}
                                              : std::vector<uint64_t>{10'000, 100'000, 1'000'000, 10'000'000};
    for (uint64_t triangles : sizes) {
        for (render::LightListMethod method : heavyBenchMethods(quick)) {
            BenchConfig config;
            config.series = "triangles";
            config.scene = &rooms;
            config.triangles = triangles;
            config.method = method;
            configs.push_back(config);
        }
    }
}

// The peers' comparison on the default scene with its own lights, at 1280x720 with shadows off
// (issue 15's targets): every method, and each grid method again without its coarse pass.
// --quick: the quick methods at the run's size, coarse pass on.
void addMethodSeries(std::vector<BenchConfig>& configs, bool quick) {
    for (render::LightListMethod method : benchMethods(quick)) {
        for (render::LightListForm form : benchListForms(method, quick)) {
            for (bool coarse : {true, false}) {
                if (!coarse && (quick || !render::usesLightGrid(method))) continue;
                BenchConfig config;
                config.series = "methods";
                config.scene = &kDefaultBuiltinScene;
                config.method = method;
                config.lightLists = form;
                config.shadows = shadowsOff();
                config.coarseTiles = coarse;
                if (!quick) {
                    config.width = 1280;
                    config.height = 720;
                }
                configs.push_back(config);
            }
        }
    }
}

}  // namespace

const std::vector<BenchSeries>& benchSeries() {
    static const std::vector<BenchSeries> series = {
        {"mix", "lights 0-96, 2 spots to a point, at a fixed range per light, x the methods " +
                    joinNames(render::methodNames(), ", ") + " (shadows off)"},
        {"spot-only", "spot lights 8-64 alone, as mix"},
        {"point-only", "point lights 4-32 alone, as mix"},
        {"scale", "lights 16-8192, half spots, at constant density (--light-range auto), x every method and "
                  "list form (" + joinNames(render::lightListFormNames()) + ", shadows off)"},
        {"scale-fixed", "lights 16-8192, half spots, at the fixed range, x every method and list form (shadows off)"},
        {"range", "64 + 32 lights at ranges 0.1-0.7 x the scene's diagonal (overlap alone), x every method"},
        {"pixels", "64 + 32 lights at 320x180 to 2560x1440 (pixels alone), x every method"},
        {"shadows", "64 + 32 lights, shadows off and on, per method"},
        {"shadow-quality", "auto and fixed 256..2048 shadow resolutions x 16 and 32 bits, validated against Embree"},
        {"shadow-budget", "the auto resolution's budget, 8..128 MiB, validated against Embree"},
        {"shadow-filters", "the filters " + joinNames(shadowFilterNames(), ", ") +
                               " at auto resolution, validated against Embree"},
        {"shadow-memory", "auto against virtual shadow pages on the default scene, the outdoor street, the engine, the "
                          "rooms (10^4..10^6 triangles) and 12-96 generated lights, 1280x720, validated against Embree"},
        {"cascades", "the outdoor scene's sun: 1-4 cascades x 512, 1024, 2048 x the texel filters, validated"},
        {"triangles", "the rooms scene at 10^4..10^7 triangles x every method, with peak memory"},
        {"methods", "the default scene's own lights at 1280x720, shadows off, x every method and list form, the "
                    "grid methods also without their coarse pass"},
        {"failures", "the failure study (failures.csv)"},
    };
    return series;
}

std::vector<BenchConfig> benchPlan(bool quick) {
    // In benchSeries() order, each series (and each group) consecutive.
    std::vector<BenchConfig> configs;
    addLightCountSeries(configs, quick);
    addScaleSeries(configs, quick);
    addRangeSeries(configs, quick);
    addPixelSeries(configs, quick);
    addShadowSeries(configs, quick);
    addShadowMemorySeries(configs, quick);
    addCascadeSeries(configs, quick);
    addTriangleSeries(configs, quick);
    addMethodSeries(configs, quick);
    return configs;
}

std::string benchGroupKey(const BenchConfig& config) {
    std::string key = config.series;
    if (config.scene) key += std::string("/") + config.scene->name + "/" + std::to_string(config.triangles);
    // The scale series: a group per count, so that a round holds one count's renderers.
    if (config.ownLights) key += "/" + std::to_string(config.spot + config.point);
    return key;
}

std::string benchConfigName(const BenchConfig& c) {
    std::ostringstream s;
    s << c.series << "-" << render::methodName(c.method) << "-";
    if (c.scene) {
        s << c.scene->name;
        if (c.triangles) s << "-" << c.triangles << "t";
    } else {
        s << c.spot << "s" << c.point << "p";
        if (c.lightRange != kBenchLightRange) s << "-range" << c.lightRange;
    }
    if (c.width) s << "-" << c.width << "x" << c.height;
    if (!c.coarseTiles) s << "-no-coarse";
    if (c.lightLists != render::LightListForm::Masks) s << "-" << render::lightListFormName(c.lightLists);
    if (c.shadows.enabled) {
        s << "-shadows-" << shadowResolutionName(c.shadows) << "-" << shadowFormatName(c.shadows.format) << "-"
          << shadowFilterName(c.shadows.filter) << "-" << pointShadowLayoutName(c.shadows.pointLayout);
        const ShadowSettings defaults;
        if (c.shadows.maxShadowedSpots != defaults.maxShadowedSpots ||
            c.shadows.maxShadowedPoints != defaults.maxShadowedPoints) {
            s << "-shadowed-" << c.shadows.maxShadowedSpots << "s" << c.shadows.maxShadowedPoints << "p";
        }
        if (c.shadows.budgetBytes != defaults.budgetBytes) s << "-budget" << (c.shadows.budgetBytes >> 20) << "m";
        if (c.scene) s << "-" << c.shadows.cascades.count << "c";
    }
    return s.str();
}

std::vector<std::string> parseBenchSeries(const std::string& text) {
    std::vector<std::string> series;
    size_t start = 0;
    while (start <= text.size()) {
        const size_t comma = std::min(text.find(',', start), text.size());
        const std::string name = text.substr(start, comma - start);
        const auto& known = benchSeries();
        if (std::none_of(known.begin(), known.end(), [&](const BenchSeries& s) { return name == s.name; })) {
            std::string list;
            for (const BenchSeries& k : known) list += (list.empty() ? "" : ", ") + std::string(k.name);
            throw Error("--series", "expected names from " + list + ", got '" + name + "'");
        }
        series.push_back(name);
        start = comma + 1;
    }
    return series;
}

}  // namespace punctual::bench
