#include "cli/render_option_table.h"


#include "cli/option_values.h"
#include "core/error.h"
#include "core/variant_table.h"
#include "scene/builtin_scenes.h"
#include "scene/light_generator.h"

namespace punctual::cli {
namespace {

// Help text starts in this column; a longer name and value take two spaces instead.
constexpr size_t kHelpColumn = 23;
// Variant lists are indented under their option by this much.
constexpr size_t kListIndent = 25;

using Notes = RenderOptionNotes;

// --shadow-res: a named mode (kShadowResolutionModes), or a whole number (the modes' stored values,
// 0 and 1, are refused as numbers: validateShadowSettings takes 16 to 8192).
void applyShadowResolution(RenderOptions& o, const std::string& v, Notes&) {
    for (const ShadowResolutionModeInfo& mode : kShadowResolutionModes) {
        if (v == mode.name) {
            o.shadows.resolution = mode.value;
            return;
        }
    }
    const uint32_t resolution = parseWhole("--shadow-res", v);
    if (resolution < 16) {
        throw Error("--shadow-res", "must be auto, virtual or a power of two from 16 to 8192, got " + v);
    }
    o.shadows.resolution = resolution;
}

// --moving-lights, --moving-casters: a share from 0 to 1 (a double, as movingLights divides by it).
double parseMovingShare(const char* option, const std::string& v) {
    double share = 0.0;
    if (!parseNumber(v, share) || !(share >= 0.0 && share <= 1.0)) {
        throw Error(option, "must be a share from 0 to 1, got '" + v + "'");
    }
    return share;
}

// --time: seconds, from 0 to 10^6 (a day is 86,400; a keyframe time past 2^24 s is not even a
// whole second in float).
double parseTime(const std::string& v) {
    const float seconds = parseFloat("--time", v);
    if (!(seconds >= 0.0f) || seconds > 1e6f) throw Error("--time", "must be seconds from 0 to 10^6, got '" + v + "'");
    return double(seconds);
}

// --light-range: auto, or metres above 0 and at most 10^6.
LightRange parseLightRangeValue(const std::string& v) {
    if (v == "auto") return {LightRange::Kind::ConstantDensity, 0.0f};
    const float metres = parseFloat("--light-range", v);
    if (!(metres > 0.0f) || metres > 1e6f) {
        throw Error("--light-range", "must be auto or a range in metres above 0 and at most 10^6, got '" + v + "'");
    }
    return {LightRange::Kind::Metres, metres};
}

void applyShadowFormat(RenderOptions& o, const std::string& v, Notes&) {
    if (v != "d16" && v != "d32") throw Error("--shadow-format", "expected d16 or d32, got '" + v + "'");
    o.shadows.format = v == "d16" ? ShadowFormat::D16 : ShadowFormat::D32;
}

void applyShadowBias(RenderOptions& o, const std::string& v, Notes&) {
    const std::vector<float> bias = parseNumberList("--shadow-bias", v, 4, "four numbers DEPTH,SLOPE,NORMAL,SIN_NORMAL");
    o.shadows.bias = glm::vec4(bias[0], bias[1], bias[2], bias[3]);
}

void applyCascadeSplits(RenderOptions& o, const std::string& v, Notes& notes) {
    const std::vector<float> splits =
        parseNumberList("--cascade-splits", v, 3, "three fractions of the shadow distance, e.g. 0.1,0.25,0.5");
    o.shadows.cascades.splits = {splits[0], splits[1], splits[2]};
    o.shadows.cascades.lambda = -1.0f;
    notes.cascadeSplits = true;
}

void applyCascadeLambda(RenderOptions& o, const std::string& v, Notes& notes) {
    o.shadows.cascades.lambda = parseFloat("--cascade-lambda", v);
    if (o.shadows.cascades.lambda < 0.0f) throw Error("--cascade-lambda", "must be from 0 to 1");
    notes.cascadeLambda = true;
}

void applyShadowDistance(RenderOptions& o, const std::string& v, Notes&) {
    o.shadows.cascades.shadowDistance = v == "auto" ? 0.0f : parseFloat("--shadow-distance", v);
    if (v != "auto" && !(o.shadows.cascades.shadowDistance > 0.0f)) {
        throw Error("--shadow-distance", "must be auto or a distance in metres above 0");
    }
}

const RenderOptionSpec kRenderOptions[] = {
    {"--scene", "NAME", "a built-in scene instead of a file (every command that takes a SCENE\ntakes --scene, and not both):",
     [](RenderOptions& o, const std::string& v, Notes&) { o.sceneName = parseBuiltinScene(v).name; },
     [](const RenderOptions&, size_t indent) { return variantHelp(kBuiltinScenes, kDefaultBuiltinScene.value, indent); }},
    {"--scene-triangles", "N", "the size of --scene rooms, 10k to 10M triangles (e.g. 250k, 2M, 1e6;\ndefault 100k)",
     [](RenderOptions& o, const std::string& v, Notes&) { o.sceneTriangles = parseSceneTriangles(v); }},
    {"--time", "T",
     "pose the scene at T seconds: a file's glTF animations (node\ntranslation, rotation, scale, morph weights; "
     "cameras, lights and\nmeshes alike; every animation from 0 at once) or a built-in scene's\npath (--scene: the walk, the drive); "
     "default: as stored",
     [](RenderOptions& o, const std::string& v, Notes&) { o.time = parseTime(v); }},
    {"--moving-lights", "F",
     "along a built-in scene's path, the share of its lamps that sway 1 m\nto either side (0 to 1: light floor(k / F) for k = 0, 1, ...; default\nthe path's own: the hall's 1/6, the street's none)",
     [](RenderOptions& o, const std::string& v, Notes&) { o.movingLights = parseMovingShare("--moving-lights", v); }},
    {"--moving-casters", "F",
     "along a built-in scene's path, the share of its props (objects within\na 4 m cube: crates, blocks, bollards) "
     "that lift 1 m and sink back\ntwice (0 to 1, chosen as --moving-lights chooses lamps; default 0)",
     [](RenderOptions& o, const std::string& v, Notes&) { o.movingCasters = parseMovingShare("--moving-casters", v); }},
    {"--max-lights", "S,P",
     "the light capacity: each frame keeps at most S spot and P point\nlights, the most important (default 64,32, "
     "the design notes'; up to\n16384,16384). The light lists hold one bit per light kept",
     [](RenderOptions& o, const std::string& v, Notes&) { o.maxLights = parseLightCapacity(v); }},
    {"--lights", "S,P[,SEED]",
     "replace the scene's lights with S spot and P point lights (at most\n--max-lights) generated inside its bounds, "
     "each reaching something\nthe camera sees (same seed, same lights; seed 1)",
     [](RenderOptions& o, const std::string& v, Notes&) { o.lights = parseLightCounts(v); }},
    {"--light-range", "R|auto",
     "with --lights, the generated lights' range: R metres, or auto: their\ndrawn ranges all scaled by "
     "the one factor that lets about as many\nlights reach what the camera sees as 96 do (constant density; "
     "no\nredraws towards the view); default: drawn, 0.25-0.45 x the scene's\ndiagonal",
     [](RenderOptions& o, const std::string& v, Notes&) { o.lightRange = parseLightRangeValue(v); }},
    {"--size", "WxH", "output size in pixels (default 1280x720)",
     [](RenderOptions& o, const std::string& v, Notes&) { parseSize(v, o.width, o.height); }},
    {"--out", "FILE.png", "write the tone-mapped image",
     [](RenderOptions& o, const std::string& v, Notes&) { o.outPath = v; }},
    {"--stats", "FILE.json", "write per-pass GPU times, light counts and culling statistics",
     [](RenderOptions& o, const std::string& v, Notes&) { o.statsPath = v; }},
    {"--culling", "METHOD", "how each pixel finds its lights:",
     [](RenderOptions& o, const std::string& v, Notes&) { o.culling = render::parseMethod(v); },
     [](const RenderOptions& d, size_t indent) { return variantHelp(render::kLightListMethods, d.culling, indent); }},
    {"--light-lists", "FORM", "how the grid methods' cells hold their lights:",
     [](RenderOptions& o, const std::string& v, Notes&) { o.lightLists = render::parseLightListForm(v); },
     [](const RenderOptions& d, size_t indent) { return variantHelp(render::kLightListForms, d.lightLists, indent); }},
    {"--tile-size", "N", "tile size in pixels for tiled and clustered culling (default 16)",
     [](RenderOptions& o, const std::string& v, Notes&) { o.tileSize = parseWhole("--tile-size", v); }},
    {"--slices", "N", "depth slices for clustered culling, 1 to 32 (default 16)",
     [](RenderOptions& o, const std::string& v, Notes&) { o.slices = parseWhole("--slices", v); }},
    {"--coarse-tiles", "on|off",
     "on (default): the grid methods cull the lights to 64x64-pixel big\ntiles first, and the tile (or cluster) tests "
     "start from those",
     [](RenderOptions& o, const std::string& v, Notes&) { o.coarseTiles = parseOnOff("--coarse-tiles", v); }},
    {"--subgroup-tiles", "on|off",
     "on (default): the grid methods cull each tile with one subgroup (no\nshared-memory atomics, no barriers) where "
     "the device has subgroup\narithmetic; off: with the shared-memory kernel (same lists)",
     [](RenderOptions& o, const std::string& v, Notes&) { o.subgroupTiles = parseOnOff("--subgroup-tiles", v); }},
    {"--heatmap", "FILE.png", "draw the lights tested per pixel as a colour map with a legend",
     [](RenderOptions& o, const std::string& v, Notes&) { o.heatmapPath = v; }},
    {"--shadow-density", "FILE.png",
     "draw the shadow texels per screen pixel (1 is the target of auto\nresolution) where shadowed lights reach, with "
     "a legend",
     [](RenderOptions& o, const std::string& v, Notes&) { o.shadowDensityPath = v; }},
    {"--shadow-pages", "FILE.png",
     "with --shadow-res virtual: tint each pixel by the finest level of\nthe virtual shadow maps its lights read, with a legend",
     [](RenderOptions& o, const std::string& v, Notes&) { o.shadowPagesPath = v; }},
    {"--shadows", "on|off", "spot and point shadows (default on: every spot and point light)",
     [](RenderOptions& o, const std::string& v, Notes&) { o.shadows.enabled = parseOnOff("--shadows", v); }},
    {"--shadowed", "S,P", "shadow at most S spot and P point lights, the most important\n(default 64,32: all of them)",
     [](RenderOptions& o, const std::string& v, Notes&) { parseShadowedCounts(v, o.shadows); }},
    {"--shadow-res", "MODE|N",
     "N: every shadow view N x N texels (a power of two, 16-8192); or,\nwithin --shadow-budget:",
     &applyShadowResolution,
     [](const RenderOptions& d, size_t indent) {
         return variantHelp(kShadowResolutionModes, d.shadows.resolution, indent);
     }},
    {"--shadow-texels-per-pixel", "X",
     "auto: the shadow texels a screen pixel should span where a\nview's receivers are seen, 0.25 to 16 (default 1)",
     [](RenderOptions& o, const std::string& v, Notes&) {
         o.shadows.texelsPerPixel = parseFloat("--shadow-texels-per-pixel", v);
     }},
    {"--shadow-hysteresis", "H",
     "auto, in a sequence (play): a view goes up to a finer tier at once\nbut keeps its finer tier from the previous "
     "frame until its demand\nfalls below it / 2^(1/2 + H); virtual: a receiver keeps the level\none finer than the "
     "nearest where the previous frame marked its\npage, as long; H octaves, 0 to 2 (default 0: the nearest every frame)",
     [](RenderOptions& o, const std::string& v, Notes&) {
         const float octaves = parseFloat("--shadow-hysteresis", v);
         if (!(octaves >= 0.0f && octaves <= 2.0f)) {
             throw Error("--shadow-hysteresis", "expected octaves from 0 to 2, got '" + v + "'");
         }
         o.shadows.tierHysteresis = octaves;
     }},
    {"--shadow-budget", "MiB", "the most memory auto or virtual resolution may give the shadow\natlas (default 64)",
     [](RenderOptions& o, const std::string& v, Notes&) {
         o.shadows.budgetBytes = uint64_t(parseWhole("--shadow-budget", v)) << 20;
     }},
    {"--shadow-format", "F", "d16 (default) or d32: the shadow maps' depth format", &applyShadowFormat},
    {"--shadow-filter", "F", "the shadow filter:",
     [](RenderOptions& o, const std::string& v, Notes&) { o.shadows.filter = parseShadowFilter(v); },
     [](const RenderOptions& d, size_t indent) { return variantHelp(kShadowFilters, d.shadows.filter, indent); }},
    {"--shadow-samples", "N", "disk filter samples, 1 to 64 (default 16)",
     [](RenderOptions& o, const std::string& v, Notes&) { o.shadows.diskSamples = parseWhole("--shadow-samples", v); }},
    {"--shadow-penumbra", "W", "disk radius in shadow-map UV units (default 0.00244 = 2.5/1024)",
     [](RenderOptions& o, const std::string& v, Notes&) { o.shadows.diskRadius = parseFloat("--shadow-penumbra", v); }},
    {"--shadow-bias", "D,S,N,SN",
     "depth, slope-scaled, normal and sin-scaled normal bias, in texels\nat the receiver (default 1,1,0,0), widened by "
     "the filter's reach\nwhere receiver-plane compares are off",
     &applyShadowBias},
    {"--cascades", "N", "the sun's shadow cascades, 1 to 4 (default 4)",
     [](RenderOptions& o, const std::string& v, Notes&) { o.shadows.cascades.count = parseWhole("--cascades", v); }},
    {"--cascade-splits", "A,B,C",
     "where cascades 1-3 end, as fractions of the shadow distance\n(default 0.1,0.25,0.5, the design notes')",
     &applyCascadeSplits},
    {"--cascade-lambda", "L", "instead: the practical split scheme, 0 (linear) to 1 (logarithmic)", &applyCascadeLambda},
    {"--shadow-distance", "D",
     "how far the sun's shadow reaches, in metres; auto (default): the\nfarthest surface the frame shows, at most 200",
     &applyShadowDistance},
    {"--cascade-blend", "B", "between cascades:",
     [](RenderOptions& o, const std::string& v, Notes&) { o.shadows.cascades.blend = parseCascadeBlend(v); },
     [](const RenderOptions& d, size_t indent) { return variantHelp(kCascadeBlends, d.shadows.cascades.blend, indent); }},
    {"--shadow-receiver-plane", "on|off",
     "on (default): hw and tent filters compare each texel with\nthe receiver's plane under it, so the bias need not "
     "cover the filter's\nreach; off: the design notes' compares (disk and cube maps always)",
     [](RenderOptions& o, const std::string& v, Notes&) {
         o.shadows.receiverPlane = parseOnOff("--shadow-receiver-plane", v);
     }},
    {"--transparent-shadows", "M", "how alphaMode BLEND surfaces cast shadows:",
     [](RenderOptions& o, const std::string& v, Notes&) { o.shadows.transparent = parseTransparentShadows(v); },
     [](const RenderOptions& d, size_t indent) {
         return variantHelp(kTransparentShadowModes, d.shadows.transparent, indent);
     }},
    {"--shadow-strength", "S", "0 (no shadow) to 1 (default 1), times each light's own strength",
     [](RenderOptions& o, const std::string& v, Notes&) { o.shadows.strength = parseFloat("--shadow-strength", v); }},
    {"--point-shadow-layout", "L", "how point lights' shadow maps are stored:",
     [](RenderOptions& o, const std::string& v, Notes&) { o.shadows.pointLayout = parsePointShadowLayout(v); },
     [](const RenderOptions& d, size_t indent) { return variantHelp(kPointShadowLayouts, d.shadows.pointLayout, indent); }},
    {"--exposure", "X", "linear exposure before tone mapping (default 1)",
     [](RenderOptions& o, const std::string& v, Notes&) { o.exposure = parseFloat("--exposure", v); }},
    {"--frames", "N", "render N frames and report the median GPU times (default 1, after\none warm-up frame)",
     [](RenderOptions& o, const std::string& v, Notes&) { o.frames = parseCount("--frames", v, 1, 1000); }},
    {"--device", "N", "use Vulkan device N (see `punctual devices`); default: the best one",
     [](RenderOptions& o, const std::string& v, Notes&) { o.deviceIndex = int(parseCount("--device", v, 0, 64)); }},
    {"--validate", nullptr, "enable the Vulkan validation layers; any message fails the run",
     [](RenderOptions& o, const std::string&, Notes&) { o.validate = true; }},
};

}  // namespace

std::span<const RenderOptionSpec> renderOptionTable() { return kRenderOptions; }

const RenderOptionSpec* findRenderOption(const std::string& name) {
    for (const RenderOptionSpec& spec : kRenderOptions) {
        if (name == spec.name) return &spec;
    }
    return nullptr;
}

std::string renderOptionsHelp() {
    const RenderOptions defaults;
    std::string help;
    for (const RenderOptionSpec& spec : kRenderOptions) {
        std::string line = std::string("  ") + spec.name + (spec.valueName ? std::string(" ") + spec.valueName : "");
        line += line.size() < kHelpColumn ? std::string(kHelpColumn - line.size(), ' ') : "  ";
        const std::string text = spec.help;
        size_t start = 0;
        while (true) {
            const size_t end = text.find('\n', start);
            help += line + text.substr(start, end == std::string::npos ? std::string::npos : end - start) + "\n";
            if (end == std::string::npos) break;
            line = std::string(kHelpColumn, ' ');
            start = end + 1;
        }
        if (spec.variants) help += spec.variants(defaults, kListIndent);
    }
    return help;
}

}  // namespace punctual::cli
