#pragma once
// What a frame is rendered with, and the one place that checks it: the command line parses
// values, then hands them to validateRenderSettings, which the renderer calls again for callers
// that build settings in code.
#include <cstdint>
#include <optional>

#include "lights/light_setup.h"
#include "lights/shadow_setup.h"
#include "render/light_list_form.h"
#include "render/light_list_method.h"
#include "scene/scene.h"

namespace punctual::render {

// Limits of the settings (the error messages name them).
inline constexpr uint32_t kMaxImageSide = 8192;
inline constexpr uint32_t kMinTileSize = 4;
inline constexpr uint32_t kMaxTileSize = 128;
// The coarse pass's big tiles: as many fine tiles a side as fit in this many pixels (4 of 16);
// none where fewer than two fit (HDRP's big tiles are 64 pixels too).
inline constexpr uint32_t kCoarseTilePixels = 64;

struct RenderSettings {
    uint32_t width = 1280;
    uint32_t height = 720;
    float exposure = 1.0f;  // linear multiplier before tone mapping
    LightListMethod method = LightListMethod::Tiled;
    LightListForm lightLists = LightListForm::Masks;  // how the grid methods' cells hold their lights
    uint32_t tileSize = 16;       // pixels, tiled and clustered
    uint32_t clusterSlices = 16;  // depth slices, clustered only
    // The coarse pass (--coarse-tiles): big tiles of about kCoarseTilePixels a side cull the
    // lights first, and the fine culling kernel tests only those. The grid methods only.
    bool coarseTiles = true;
    // Tiled, zbin and zbin-2d cull with one subgroup per tile (tile_culling.comp) where the device
    // has compute subgroup arithmetic. False: with light_culling.comp's shared-memory workgroups,
    // as a device without it does (the tests compare the two; the grids are the same).
    bool subgroupTiles = true;
    // For tests: the culling kernels' invocations per tile instead of the device's subgroup size (a
    // power of two up to PUNCTUAL_MAX_TILE_THREADS; 0: the subgroup size). More than a subgroup
    // runs tile_culling.comp's several-subgroup path, which a device may take with its own sizes.
    uint32_t tileThreads = 0;
    bool collectLightStats = false;  // allocate what readLightStats() needs
    bool collectShadowFactors = false;  // allocate what readShadowFactors() needs
    ShadowSettings shadows;
    LightCapacity maxLights;  // --max-lights: the spots and points a frame keeps (lights/light_setup.h)
    // For the failure study only (bench), never needed to render correctly: the camera the sun's
    // cascades are fitted to, when not the scene's. The shimmering study renders one camera's
    // pixels under the cascades of a moving one, so that every frame shows the same receivers.
    std::optional<Camera> cascadeCamera;
    // For the failure study only: cull tiles and clusters by the opaque depth alone, as before the
    // transparent depth span existed, to show the lights a transparent surface then misses.
    bool opaqueCullingDepth = false;
    // For tests and studies only: false draws every object in the camera's passes (depth,
    // forward, transparent) instead of only those whose bounds meet the camera's frustum. The
    // image is the same either way; only the work differs.
    bool cullObjectsToView = true;
    // Whether the renderer warns when the shadow budget gave views less resolution than their
    // receivers need. The bench turns it off: it sweeps small budgets on purpose and records the
    // reduced views in its own column (shadow_reduced_views).
    bool warnReducedShadows = true;
};


// Throws Error naming the option (--size, --exposure, --tile-size, --slices, the shadow options)
// for a setting out of range.
void validateRenderSettings(const RenderSettings& settings);

}  // namespace punctual::render
