#include "cli/options.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <filesystem>
#include <cmath>
#include <vector>

#include "cli/option_values.h"
#include "cli/render_option_table.h"
#include "core/error.h"
#include "scene/builtin_scenes.h"

namespace punctual::cli {
namespace {

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

namespace {

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
    if (options.lights && (options.lights->spot > options.maxLights.spots || options.lights->point > options.maxLights.points)) {
        throw Error("--lights", std::to_string(options.lights->spot) + "," + std::to_string(options.lights->point) +
                                    " is over the capacity, --max-lights " + std::to_string(options.maxLights.spots) +
                                    "," + std::to_string(options.maxLights.points) + ": raise it too");
    }
    if (options.lightRange && !options.lights) {
        throw Error("--light-range", "sets the range of generated lights: give --lights S,P too");
    }
    if (options.scenePath && options.sceneName) {
        throw Error("--scene", "a built-in scene and a scene file ('" + *options.scenePath +
                                   "') cannot both be given: choose one");
    }
    std::string withPaths;
    for (const BuiltinScene& s : kBuiltinScenes) {
        if (s.hasPath()) withPaths += std::string(withPaths.empty() ? "" : " and ") + s.name;
    }
    const BuiltinScene& builtin = options.sceneName ? parseBuiltinScene(*options.sceneName) : kDefaultBuiltinScene;
    if (options.time && !options.scenePath && !builtin.hasPath()) {
        throw Error("--time", std::string("poses a scene file's animations or a built-in scene's path; ") + builtin.name +
                                  " has none (" + withPaths + " have)");
    }
    for (const auto& [option, given] : {std::pair{"--moving-lights", options.movingLights.has_value()},
                                        std::pair{"--moving-casters", options.movingCasters.has_value()}}) {
        if (given && (options.scenePath || !builtin.hasPath())) {
            throw Error(option, std::string("moves lights or props along a built-in scene's path (") + withPaths + "); " +
                                    (options.scenePath ? "a scene file's animations decide what moves"
                                                       : std::string(builtin.name) + " has no path"));
        }
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

}  // namespace

RenderOptions parseRenderOptions(const std::vector<std::string>& args) {
    RenderOptions options;
    RenderOptionNotes notes;
    for (size_t i = 0; i < args.size(); ++i) {
        const std::string& arg = args[i];
        if (const RenderOptionSpec* spec = findRenderOption(arg)) {
            std::string value;
            if (spec->valueName) value = optionValue(args, i);
            spec->apply(options, value, notes);
        } else if (!arg.empty() && arg[0] == '-') {
            throw Error(arg, "unknown option (see punctual render --help)");
        } else if (!options.scenePath) {
            options.scenePath = arg;
        } else {
            throw Error(arg, "unexpected argument: only one scene file can be given");
        }
    }
    checkOptionCombinations(options, notes.cascadeSplits && notes.cascadeLambda);
    render::validateRenderSettings(renderSettingsFrom(options));
    return options;
}

render::RenderSettings renderSettingsFrom(const RenderOptions& options) {
    render::RenderSettings settings;
    settings.width = options.width;
    settings.height = options.height;
    settings.exposure = options.exposure;
    settings.method = options.culling;
    settings.lightLists = options.lightLists;
    settings.tileSize = options.tileSize;
    settings.clusterSlices = options.slices;
    settings.coarseTiles = options.coarseTiles;
    settings.subgroupTiles = options.subgroupTiles;
    settings.shadows = options.shadows;
    settings.maxLights = options.maxLights;
    return settings;
}

vk::ContextOptions contextOptionsFrom(const RenderOptions& options) {
    vk::ContextOptions context;
    context.validation = options.validate;
    context.deviceIndex = options.deviceIndex;
    return context;
}

std::string renderUsage() {
    return "usage: punctual render [SCENE.gltf|SCENE.glb|--scene NAME] [options]\n\n"
           "Renders SCENE (or a built-in scene) on the GPU and prints per-pass GPU times.\n\n"
           "options:\n" +
           renderOptionsHelp();
}

}  // namespace punctual::cli
