#pragma once
// Command-line options shared by the commands: render, compare and validate parse them all,
// reference all but the GPU-only ones, bench the few it passes on.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "lights/shadow_setup.h"
#include "render/renderer.h"
#include "vk/context.h"
#include "render/light_list_method.h"
#include "scene/light_generator.h"

namespace punctual::cli {

struct RenderOptions {
    std::optional<std::string> scenePath;  // a glTF file; none: a built-in scene
    std::optional<std::string> sceneName;  // --scene NAME, a name of kBuiltinScenes; none: the default one
    std::optional<uint64_t> sceneTriangles;  // --scene-triangles N: the size of a sized built-in scene
    std::optional<double> time;            // --time T: seconds into the scene file's animations
    std::optional<double> movingLights;    // --moving-lights F: the share of a built-in path's lights that move
    std::optional<double> movingCasters;   // --moving-casters F: the share of a built-in path's props that move
    std::optional<LightCounts> lights;     // --lights S,P[,SEED]
    std::optional<LightRange> lightRange;  // --light-range R|auto (generated lights only)
    LightCapacity maxLights;               // --max-lights S,P
    uint32_t width = 1280;
    uint32_t height = 720;
    std::optional<std::string> outPath;    // --out FILE.png
    std::optional<std::string> statsPath;  // --stats FILE.json
    int deviceIndex = -1;                  // --device N
    bool validate = false;                 // --validate
    float exposure = 1.0f;                 // --exposure X
    uint32_t frames = 1;                   // --frames N (timed; the median is reported)
    render::LightListMethod culling = render::LightListMethod::Tiled;  // --culling
    render::LightListForm lightLists = render::LightListForm::Masks;  // --light-lists
    uint32_t tileSize = 16;                // --tile-size N
    uint32_t slices = 16;                  // --slices N (clustered)
    bool coarseTiles = true;               // --coarse-tiles on|off (the grid methods)
    bool subgroupTiles = true;             // --subgroup-tiles on|off (tiled, zbin, zbin-2d)
    std::optional<std::string> heatmapPath;  // --heatmap FILE.png
    std::optional<std::string> shadowDensityPath;  // --shadow-density FILE.png
    std::optional<std::string> shadowPagesPath;    // --shadow-pages FILE.png
    ShadowSettings shadows;                // --shadows, --shadow-res, --shadow-filter, ...
};

// Parses the arguments after the command name. Throws punctual::Error naming the option.
RenderOptions parseRenderOptions(const std::vector<std::string>& args);

// "250k" -> 250000: a whole number, in scientific notation (1e6) or with a suffix k (x 10^3) or M
// (x 10^6), from rooms_scene::kMinTriangles to kMaxTriangles. Throws Error("--scene-triangles", ...).
uint64_t parseSceneTriangles(const std::string& text);

// "1280x720" -> (1280, 720). Throws Error("--size", ...).
void parseSize(const std::string& text, uint32_t& width, uint32_t& height);

std::string renderUsage();

// The renderer and device settings the options ask for (statistics and validation variants off).
render::RenderSettings renderSettingsFrom(const RenderOptions& options);
vk::ContextOptions contextOptionsFrom(const RenderOptions& options);

}  // namespace punctual::cli
