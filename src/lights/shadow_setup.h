#pragma once
// Which lights cast shadows this frame, and the views the shadow stage renders for them.
//
// Spots take one view each (a perspective frustum of field of view 2 x outer angle) and one
// layer of a 2D depth array; points take six views (+X -X +Y -Y +Z -Z) and one cube of a cube
// depth array, or six layers of a 2D array with a widened field of view (URP's "slices"). At
// most 32 spots and 8 points are shadowed, chosen by rank. Every view lists the objects whose
// bounds meet its frustum; a view with none is not rendered.
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "gpu_types.h"
#include "lights/light_setup.h"
#include "lights/shadow_filters.h"
#include "scene/scene.h"

namespace punctual {

struct ShadowSettings {
    bool enabled = true;
    uint32_t resolution = 1024;  // texels a side, every layer
    ShadowFilter filter = ShadowFilter::Tent5;
    uint32_t diskSamples = 16;
    // Disk radius in shadow-map UV units: a fixed share of the map, so the penumbra does not
    // change with the resolution (the design notes' "penumbra independent of map size").
    float diskRadius = 2.5f / 1024.0f;
    glm::vec4 bias{1.0f, 1.0f, 1.0f, 0.0f};  // depth, slope-scaled, normal, sin-scaled normal
    PointShadowLayout pointLayout = PointShadowLayout::Cube;
    float strength = 1.0f;  // multiplies every light's own shadow strength
    // For the failure study only (bench), never needed to render correctly:
    bool pancaking = false;         // clamp caster vertices' depth onto the near plane (Unity's pancaking)
    float spotNearFraction = 0.0f;  // > 0: spot near plane at this fraction of the range, not fitted

    // The filter's reach in texels, which widens the bias (the design notes' penumbra), and its
    // lookups per shadow test: the filter table's footprint, or the disk's settings.
    float penumbraTexels() const;
    uint32_t filterTaps() const;
};

// Throws Error naming the option for out-of-range settings.
void validateShadowSettings(const ShadowSettings& settings);

struct ShadowView {
    gpu::GpuShadowView gpu;
    std::vector<uint32_t> casters;  // object indices whose bounds meet the view's frustum
    uint32_t packedLight = 0;       // index into FrameLights::packed
    uint32_t face = 0;              // 0 for spots; the cube face for points
    uint32_t layer = 0;             // in the spot array, or in the point cube / slice array
    bool isPoint = false;
};

struct ShadowPlan {
    std::vector<ShadowView> views;  // spots first (one each), then points (six each)
    uint32_t shadowedSpots = 0;     // layers of the spot array
    uint32_t shadowedPoints = 0;    // cubes of the point array (or groups of six slices)
    uint32_t droppedByCap = 0;      // shadow-casting lights over the caps (they stay unshadowed)
    uint32_t viewsRendered = 0;     // views with at least one caster
    uint32_t viewsSkipped = 0;      // views with none (spots: not even cleared; points: cleared)
    float sliceScale = 1.0f;        // slices layout: tan of half the widened field of view
};

// Chooses the shadowed lights (by lightImportance, see light_setup.h), builds their views and
// writes each shadowed light's first view index and strength into `lights.packed`
// (angleOffsetShadow.y and .w). Lights without a shadow keep y = -1.
ShadowPlan planShadows(const Scene& scene, FrameLights& lights, const glm::vec3& cameraPosition,
                       const ShadowSettings& settings);

// Bytes of one shadow-map texel (ShadowMaps::kFormat, VK_FORMAT_D32_SFLOAT).
constexpr uint64_t kShadowTexelBytes = 4;

// Bytes the shadow maps of `plan` take at `resolution` texels a side: a layer per shadowed spot,
// six per shadowed point (the placeholders of empty arrays, a few bytes, are left out). A lower
// bound of what the device allocates (it may pad).
uint64_t shadowMapBytes(const ShadowPlan& plan, uint32_t resolution);

// What the device can hold of the shadow maps: all arrays together (`total`, named by
// `totalName`, e.g. "the device's largest heap"), and each array alone (one image; Vulkan's
// maxResourceSize for its format and usage).
struct ShadowMemoryLimits {
    uint64_t total = std::numeric_limits<uint64_t>::max();
    std::string totalName = "the device's largest heap";
    uint64_t spotArray = std::numeric_limits<uint64_t>::max();
    uint64_t pointArray = std::numeric_limits<uint64_t>::max();  // the cube array, or the slice array
};

// Throws Error("--shadow-res N", ...) when the shadow maps of `plan` do not fit `limits`, saying
// what they need, what the device has and the largest resolution that would fit. Called before
// allocating, so that an oversized request fails with that line rather than with the driver's
// out-of-memory code (or a validation error for an image over maxResourceSize).
void checkShadowMapsFit(const ShadowPlan& plan, const ShadowSettings& settings, const ShadowMemoryLimits& limits);

// The matrix of cube face `face` of a light at `position`: clip.x = dot(r, U) / scale,
// clip.y = dot(r, V) / scale, clip.w = dot(r, axis) for r = p - position (see shadows.h), and a
// depth of 0 at `nearPlane`, 1 at `farPlane` along the axis. scale = 1 for a cube face, > 1 for a
// widened slice.
glm::mat4 cubeFaceViewProjection(const glm::vec3& position, uint32_t face, float nearPlane, float farPlane,
                                 float scale = 1.0f);

}  // namespace punctual
