#include "app/options.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <filesystem>
#include <cmath>
#include <vector>

#include "core/error.h"
#include "scene/builtin_scenes.h"

namespace punctual::app {
namespace {

template <typename T>
bool parseNumber(const std::string& text, T& value) {
    const char* first = text.data();
    const char* last = text.data() + text.size();
    const auto [end, ec] = std::from_chars(first, last, value);
    return ec == std::errc() && end == last && !text.empty();
}

// A whole number. Options that are render settings take any: their ranges are checked in one place,
// validateRenderSettings (render/render_settings.h), once every option is read.
uint32_t parseWhole(const std::string& option, const std::string& text) {
    uint32_t value = 0;
    if (!parseNumber(text, value)) throw Error(option, "expected a whole number, got '" + text + "'");
    return value;
}

// A switch: "on" or "off".
bool parseOnOff(const std::string& option, const std::string& text) {
    if (text != "on" && text != "off") throw Error(option, "expected on or off, got '" + text + "'");
    return text == "on";
}

// A whole number of an option that is not a render setting (--device, --frames), in its range.
uint32_t parseCount(const std::string& option, const std::string& text, uint32_t min, uint32_t max) {
    uint32_t value = 0;
    if (!parseNumber(text, value) || value < min || value > max) {
        throw Error(option, "expected a whole number from " + std::to_string(min) + " to " + std::to_string(max) +
                                ", got '" + text + "'");
    }
    return value;
}

float parseFloat(const std::string& option, const std::string& text) {
    float value = 0.0f;
    if (!parseNumber(text, value) || !std::isfinite(value)) {
        throw Error(option, "expected a number, got '" + text + "'");
    }
    return value;
}

// "1,1,1,0" -> exactly `count` comma-separated numbers; `expected` says what they are.
std::vector<float> parseNumberList(const std::string& option, const std::string& text, size_t count,
                                   const std::string& expected) {
    std::vector<float> numbers;
    size_t start = 0;
    for (size_t i = 0; i < count; ++i) {
        const size_t comma = text.find(',', start);
        if ((i + 1 < count) != (comma != std::string::npos)) {
            throw Error(option, "expected " + expected + ", got '" + text + "'");
        }
        numbers.push_back(parseFloat(option, text.substr(start, comma - start)));
        start = comma + 1;
    }
    return numbers;
}

// "S,P" -> the most spot and point lights that cast a shadow (ranges: validateShadowSettings).
void parseShadowedCounts(const std::string& text, ShadowSettings& shadows) {
    const size_t comma = text.find(',');
    if (comma == std::string::npos || text.find(',', comma + 1) != std::string::npos) {
        throw Error("--shadowed", "expected S,P (spot and point lights), got '" + text + "'");
    }
    shadows.maxShadowedSpots = parseWhole("--shadowed", text.substr(0, comma));
    shadows.maxShadowedPoints = parseWhole("--shadowed", text.substr(comma + 1));
}

// Extensions that name a file format, and the format's name. An output named for one format
// but written in another (`--out x.jpg` getting PNG bytes) is refused: viewers refuse or misread
// such files. A name with no extension or one naming no format (/dev/stdout, a FIFO, "frame",
// "x.v2") is taken as it is.
struct NamedFormat {
    const char* extension;
    const char* format;
};
constexpr NamedFormat kNamedFormats[] = {
    {".png", "PNG"},   {".jpg", "JPEG"},  {".jpeg", "JPEG"}, {".webp", "WebP"}, {".exr", "OpenEXR"},
    {".hdr", "Radiance HDR"}, {".bmp", "BMP"}, {".tga", "TGA"}, {".gif", "GIF"}, {".tif", "TIFF"},
    {".tiff", "TIFF"}, {".ppm", "PPM"}, {".json", "JSON"}, {".gltf", "glTF"}, {".glb", "glTF"},
    {".svg", "SVG"}, {".html", "HTML"}, {".csv", "CSV"}, {".txt", "text"},
};

void checkOutputExtension(const char* option, const std::optional<std::string>& path, const char* extension,
                          const char* format) {
    if (!path) return;
    std::string found = std::filesystem::path(*path).extension().string();
    std::transform(found.begin(), found.end(), found.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    if (found == extension) return;
    for (const NamedFormat& named : kNamedFormats) {
        if (found != named.extension) continue;
        throw Error(option, std::string("'") + *path + "' is named for " + named.format + " (" + found +
                                ") but punctual writes " + format + " there; name it " + extension);
    }
}

}  // namespace

uint64_t parseSceneTriangles(const std::string& text) {
    const std::string expected = "expected a triangle count from 10k to 10M (e.g. 250k, 2M, 1e6), got '" + text + "'";
    double scale = 1.0;
    std::string digits = text;
    if (!digits.empty() && (digits.back() == 'k' || digits.back() == 'M')) {
        scale = digits.back() == 'k' ? 1e3 : 1e6;
        digits.pop_back();
    }
    double value = 0.0;
    if (digits.empty() || !(digits[0] >= '0' && digits[0] <= '9') || !parseNumber(digits, value)) {
        throw Error("--scene-triangles", expected);
    }
    value *= scale;
    if (!(value >= double(rooms_scene::kMinTriangles) && value <= double(rooms_scene::kMaxTriangles)) ||
        value != std::floor(value)) {
        throw Error("--scene-triangles", expected);
    }
    return uint64_t(value);
}

void parseSize(const std::string& text, uint32_t& width, uint32_t& height) {
    const auto x = text.find('x');
    const std::string expected = "expected WxH (e.g. 1280x720), got '" + text + "'";
    if (x == std::string::npos || !parseNumber(text.substr(0, x), width) || !parseNumber(text.substr(x + 1), height)) {
        throw Error("--size", expected);
    }
}

// What no single option can check: options that contradict each other, outputs named for another
// format.
void checkOptionCombinations(const RenderOptions& options, bool splitsAndLambda) {
    if (splitsAndLambda) {
        throw Error("--cascade-lambda", "conflicts with --cascade-splits: the splits are either given or computed by "
                                        "the practical scheme from lambda; give one of the two");
    }
    checkOutputExtension("--out", options.outPath, ".png", "PNG");
    checkOutputExtension("--heatmap", options.heatmapPath, ".png", "PNG");
    checkOutputExtension("--shadow-density", options.shadowDensityPath, ".png", "PNG");
    checkOutputExtension("--stats", options.statsPath, ".json", "JSON");
    if (options.scenePath && options.sceneName) {
        throw Error("--scene", "a built-in scene and a scene file ('" + *options.scenePath +
                                   "') cannot both be given: choose one");
    }
    if (options.sceneTriangles && !(options.sceneName && parseBuiltinScene(*options.sceneName).sized())) {
        std::string sized;
        for (const BuiltinScene& scene : kBuiltinScenes) {
            if (scene.sized()) sized += std::string(sized.empty() ? "" : " or ") + "--scene " + scene.name;
        }
        throw Error("--scene-triangles", "sizes only " + sized + ", not " +
                                             (options.scenePath ? "a scene file"
                                                                : "--scene " + options.sceneName.value_or(
                                                                                   kDefaultBuiltinScene.name)));
    }
}

RenderOptions parseRenderOptions(const std::vector<std::string>& args) {
    RenderOptions options;
    bool splitsGiven = false;  // --cascade-splits and --cascade-lambda are two ways to say one thing
    bool lambdaGiven = false;
    for (size_t i = 0; i < args.size(); ++i) {
        const std::string& arg = args[i];
        // An option's value never starts with "--": `--heatmap --out x.png` is a missing value,
        // not a heat map written to a file called "--out".
        auto value = [&]() -> const std::string& {
            if (i + 1 >= args.size() || args[i + 1].rfind("--", 0) == 0) throw Error(arg, "needs a value");
            return args[++i];
        };
        if (arg == "--scene") {
            options.sceneName = parseBuiltinScene(value()).name;
        } else if (arg == "--scene-triangles") {
            options.sceneTriangles = parseSceneTriangles(value());
        } else if (arg == "--lights") {
            options.lights = parseLightCounts(value());
        } else if (arg == "--size") {
            parseSize(value(), options.width, options.height);
        } else if (arg == "--out") {
            options.outPath = value();
        } else if (arg == "--stats") {
            options.statsPath = value();
        } else if (arg == "--device") {
            options.deviceIndex = int(parseCount(arg, value(), 0, 64));
        } else if (arg == "--validate") {
            options.validate = true;
        } else if (arg == "--frames") {
            options.frames = parseCount(arg, value(), 1, 1000);
        } else if (arg == "--culling") {
            options.culling = render::parseMethod(value());
        } else if (arg == "--tile-size") {
            options.tileSize = parseWhole(arg, value());
        } else if (arg == "--slices") {
            options.slices = parseWhole(arg, value());
        } else if (arg == "--heatmap") {
            options.heatmapPath = value();
        } else if (arg == "--shadow-density") {
            options.shadowDensityPath = value();
        } else if (arg == "--coarse-tiles") {
            options.coarseTiles = parseOnOff(arg, value());
        } else if (arg == "--subgroup-tiles") {
            options.subgroupTiles = parseOnOff(arg, value());
        } else if (arg == "--shadows") {
            options.shadows.enabled = parseOnOff(arg, value());
        } else if (arg == "--shadow-res") {
            const std::string& text = value();
            options.shadows.resolution = text == "auto" ? ShadowSettings::kAutoResolution : parseWhole(arg, text);
            if (text != "auto" && options.shadows.resolution == ShadowSettings::kAutoResolution) {
                throw Error(arg, "must be auto or a power of two from 16 to 8192, got 0");
            }
        } else if (arg == "--shadowed") {
            parseShadowedCounts(value(), options.shadows);
        } else if (arg == "--shadow-texels-per-pixel") {
            options.shadows.texelsPerPixel = parseFloat(arg, value());
        } else if (arg == "--shadow-budget") {
            options.shadows.budgetBytes = uint64_t(parseWhole(arg, value())) << 20;
        } else if (arg == "--shadow-format") {
            const std::string& text = value();
            if (text != "d16" && text != "d32") throw Error(arg, "expected d16 or d32, got '" + text + "'");
            options.shadows.format = text == "d16" ? ShadowFormat::D16 : ShadowFormat::D32;
        } else if (arg == "--shadow-filter") {
            options.shadows.filter = parseShadowFilter(value());
        } else if (arg == "--shadow-samples") {
            options.shadows.diskSamples = parseWhole(arg, value());
        } else if (arg == "--shadow-bias") {
            const std::vector<float> bias =
                parseNumberList(arg, value(), 4, "four numbers DEPTH,SLOPE,NORMAL,SIN_NORMAL");
            options.shadows.bias = glm::vec4(bias[0], bias[1], bias[2], bias[3]);
        } else if (arg == "--cascades") {
            options.shadows.cascades.count = parseWhole(arg, value());
        } else if (arg == "--cascade-splits") {
            const std::vector<float> splits =
                parseNumberList(arg, value(), 3, "three fractions of the shadow distance, e.g. 0.1,0.25,0.5");
            options.shadows.cascades.splits = {splits[0], splits[1], splits[2]};
            options.shadows.cascades.lambda = -1.0f;
            splitsGiven = true;
        } else if (arg == "--cascade-lambda") {
            lambdaGiven = true;
            options.shadows.cascades.lambda = parseFloat(arg, value());
            if (options.shadows.cascades.lambda < 0.0f) throw Error(arg, "must be from 0 to 1");
        } else if (arg == "--shadow-distance") {
            const std::string& text = value();
            options.shadows.cascades.shadowDistance = text == "auto" ? 0.0f : parseFloat(arg, text);
            if (text != "auto" && !(options.shadows.cascades.shadowDistance > 0.0f)) {
                throw Error(arg, "must be auto or a distance in metres above 0");
            }
        } else if (arg == "--cascade-blend") {
            options.shadows.cascades.blend = parseCascadeBlend(value());
        } else if (arg == "--transparent-shadows") {
            options.shadows.transparent = parseTransparentShadows(value());
        } else if (arg == "--shadow-receiver-plane") {
            options.shadows.receiverPlane = parseOnOff(arg, value());
        } else if (arg == "--shadow-penumbra") {
            options.shadows.diskRadius = parseFloat(arg, value());
        } else if (arg == "--shadow-strength") {
            options.shadows.strength = parseFloat(arg, value());
        } else if (arg == "--point-shadow-layout") {
            options.shadows.pointLayout = parsePointShadowLayout(value());
        } else if (arg == "--exposure") {
            options.exposure = parseFloat(arg, value());
        } else if (!arg.empty() && arg[0] == '-') {
            throw Error(arg, "unknown option (see punctual render --help)");
        } else if (!options.scenePath) {
            options.scenePath = arg;
        } else {
            throw Error(arg, "unexpected argument: only one scene file can be given");
        }
    }
    checkOptionCombinations(options, splitsGiven && lambdaGiven);
    render::validateRenderSettings(renderSettingsFrom(options));
    return options;
}

render::RenderSettings renderSettingsFrom(const RenderOptions& options) {
    render::RenderSettings settings;
    settings.width = options.width;
    settings.height = options.height;
    settings.exposure = options.exposure;
    settings.method = options.culling;
    settings.tileSize = options.tileSize;
    settings.clusterSlices = options.slices;
    settings.coarseTiles = options.coarseTiles;
    settings.subgroupTiles = options.subgroupTiles;
    settings.shadows = options.shadows;
    return settings;
}

vk::ContextOptions contextOptionsFrom(const RenderOptions& options) {
    vk::ContextOptions context;
    context.validation = options.validate;
    context.deviceIndex = options.deviceIndex;
    return context;
}

std::string renderUsage() {
    // The variant lists come from their tables (render/light_list_method.h, lights/shadow_filters.h),
    // indented under their option; the defaults are those of RenderOptions.
    const RenderOptions defaults;
    constexpr size_t kListIndent = 25;
    return R"(usage: punctual render [SCENE.gltf|SCENE.glb|--scene NAME] [options]

Renders SCENE (or a built-in scene) on the GPU and prints per-pass GPU times.

options:
  --scene NAME         a built-in scene instead of a file:
)" + variantHelp(kBuiltinScenes, kDefaultBuiltinScene.value, kListIndent) +
           R"(  --scene-triangles N  the size of --scene rooms, 10k to 10M triangles (e.g. 250k, 2M, 1e6;
                       default 100k)
  --lights S,P[,SEED]  replace the scene's lights with S spot (<= 64) and P point (<= 32)
                       lights generated inside its bounds (same seed, same lights; seed 1)
  --size WxH           output size in pixels (default 1280x720)
  --out FILE.png       write the tone-mapped image
  --stats FILE.json    write per-pass GPU times, light counts and culling statistics
  --culling METHOD     how each pixel finds its lights:
)" + variantHelp(render::kLightListMethods, defaults.culling, kListIndent) +
           R"(  --tile-size N        tile size in pixels for tiled and clustered culling (default 16)
  --slices N           depth slices for clustered culling, 1 to 32 (default 16)
  --coarse-tiles on|off  on (default): the grid methods cull the lights to 64x64-pixel big
                       tiles first, and the tile (or cluster) tests start from those
  --subgroup-tiles on|off  on (default): the grid methods cull each tile with one subgroup (no
                       shared-memory atomics, no barriers) where the device has subgroup
                       arithmetic; off: with the shared-memory kernel (same lists)
  --heatmap FILE.png   draw the lights tested per pixel as a colour map with a legend
  --shadow-density FILE.png  draw the shadow texels per screen pixel (1 is the target of auto
                       resolution) where shadowed lights reach, with a legend
  --shadows on|off     spot and point shadows (default on: every spot and point light)
  --shadowed S,P       shadow at most S spot and P point lights, the most important
                       (default 64,32: all of them)
  --shadow-res auto|N  auto (default): each shadow view the power-of-two resolution at which
                       one texel covers about one screen pixel where it is seen, within
                       --shadow-budget; N: every view N x N texels (a power of two, 16-8192)
  --shadow-texels-per-pixel X  auto: the shadow texels a screen pixel should span where a
                       view's receivers are seen, 0.25 to 16 (default 1)
  --shadow-budget MiB  the most memory auto resolution may give the shadow atlas (default 64)
  --shadow-format F    d16 (default) or d32: the shadow maps' depth format
  --shadow-filter F    the shadow filter:
)" + variantHelp(kShadowFilters, defaults.shadows.filter, kListIndent) +
           R"(  --shadow-samples N   disk filter samples, 1 to 64 (default 16)
  --shadow-penumbra W  disk radius in shadow-map UV units (default 0.00244 = 2.5/1024)
  --shadow-bias D,S,N,SN  depth, slope-scaled, normal and sin-scaled normal bias, in texels
                       at the receiver (default 1,1,0,0), widened by the filter's reach
                       where receiver-plane compares are off
  --cascades N         the sun's shadow cascades, 1 to 4 (default 4)
  --cascade-splits A,B,C  where cascades 1-3 end, as fractions of the shadow distance
                       (default 0.1,0.25,0.5, the design notes')
  --cascade-lambda L   instead: the practical split scheme, 0 (linear) to 1 (logarithmic)
  --shadow-distance D  how far the sun's shadow reaches, in metres; auto (default): the
                       farthest surface the frame shows, at most 200
  --cascade-blend B    between cascades:
)" + variantHelp(kCascadeBlends, defaults.shadows.cascades.blend, kListIndent) +
           R"(  --shadow-receiver-plane on|off  on (default): hw and tent filters compare each texel with
                       the receiver's plane under it, so the bias need not cover the filter's
                       reach; off: the design notes' compares (disk and cube maps always)
  --transparent-shadows M  how alphaMode BLEND surfaces cast shadows:
)" + variantHelp(kTransparentShadowModes, defaults.shadows.transparent, kListIndent) +
           R"(  --shadow-strength S  0 (no shadow) to 1 (default 1), times each light's own strength
  --point-shadow-layout L  how point lights' shadow maps are stored:
)" + variantHelp(kPointShadowLayouts, defaults.shadows.pointLayout, kListIndent) +
           R"(  --exposure X         linear exposure before tone mapping (default 1)
  --frames N           render N frames and report the median GPU times (default 1)
  --device N           use Vulkan device N (see `punctual devices`); default: the best one
  --validate           enable the Vulkan validation layers; any message fails the run
)";
}

}  // namespace punctual::app
