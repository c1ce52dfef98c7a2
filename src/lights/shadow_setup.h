#pragma once
// Which lights cast shadows this frame, and the views the shadow stage renders for them.
//
// Spots take one view each (a perspective frustum of field of view 2 x outer angle); points take
// six views (+X -X +Y -Y +Z -Z). By default every spot and point light in the frame is shadowed
// (up to 64 + 32); --shadowed S,P caps them, chosen by rank. Every view lists the objects whose
// bounds meet its frustum; a view with none is not rendered.
//
// Each view gets its own resolution: in fixed mode (--shadow-res N) N, in auto mode the tier its
// visible receivers need (lights/shadow_resolution.h) within the budget (lights/shadow_budget.h).
// Spot views and point faces stored as slices live in one atlas (lights/shadow_atlas.h); the cube
// layout keeps a cube array and needs a fixed resolution.
#include <array>
#include <cstdint>
#include <map>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "core/variant_table.h"
#include "gpu_types.h"
#include "lights/cascade_settings.h"
#include "lights/cascade_setup.h"
#include "lights/light_setup.h"
#include "lights/shadow_atlas.h"
#include "lights/shadow_budget.h"
#include "lights/shadow_filters.h"
#include "lights/transparent_shadows.h"
#include "scene/scene.h"

namespace punctual {

enum class ShadowFormat : uint32_t { D16, D32 };

struct ShadowSettings {
    bool enabled = true;
    // Texels a side of every view (fixed mode, --shadow-res N), or kAutoResolution: each view the
    // tier its visible receivers need (--shadow-res auto, the default).
    uint32_t resolution = kAutoResolution;
    static constexpr uint32_t kAutoResolution = 0;
    // Each spot view and point slice a virtual map whose pages visible receivers mark
    // (--shadow-res virtual; shaders/shared/shadow_pages.h); the sun's cascades as in auto.
    static constexpr uint32_t kVirtualResolution = 1;
    // auto: the shadow texels one screen pixel should span where a view's receivers are seen (the
    // tier rule's target density; see shadow_resolution.h).
    float texelsPerPixel = 1.0f;
    uint32_t minTier = 16;     // auto: the smallest and largest tiers a view may get
    uint32_t maxTier = 2048;
    // auto in a sequence (punctual play): octaves of hysteresis on each view's tier
    // (--shadow-hysteresis; shadowTierWithHysteresis), and the tiers the previous frame gave,
    // by (scene light index, face). Empty for a still frame.
    float tierHysteresis = 0.0f;
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> previousTiers;
    // virtual in a sequence: the previous frame's page marks by (scene light index, face), each
    // ShadowPageMarkLayout::kWordsPerView words, which the same --shadow-hysteresis holds levels
    // by (VirtualPageReads). Empty for a still frame.
    std::map<std::pair<uint32_t, uint32_t>, std::vector<uint32_t>> previousPageMarks;
    uint64_t budgetBytes = 64ull << 20;  // auto: the atlas's largest size (--shadow-budget MiB)
    uint32_t maxShadowedSpots = PUNCTUAL_MAX_SHADOWED_SPOT_LIGHTS;  // --shadowed S,P
    uint32_t maxShadowedPoints = PUNCTUAL_MAX_SHADOWED_POINT_LIGHTS;
    ShadowFormat format = ShadowFormat::D16;
    ShadowFilter filter = ShadowFilter::Tent5;
    uint32_t diskSamples = 16;
    // Disk radius in shadow-map UV units: a fixed share of the map, so the penumbra does not
    // change with the resolution (the design notes' "penumbra independent of map size").
    float diskRadius = 2.5f / 1024.0f;
    glm::vec4 bias{1.0f, 1.0f, 0.0f, 0.0f};  // depth, slope-scaled, normal, sin-scaled normal
    PointShadowLayout pointLayout = PointShadowLayout::Slices;
    // Compare each texel of the footprint filters (hw, tents) on the atlas with the receiver's plane
    // under it (shadows.h, receiverPlaneDepthSlope) instead of with the sample point's depth: the
    // bias then no longer widens with the filter's reach (biasPenumbraTexels).
    bool receiverPlane = true;
    float strength = 1.0f;  // multiplies every light's own shadow strength
    CascadeSettings cascades;  // the sun's (lights/cascade_setup.h)
    TransparentShadows transparent = TransparentShadows::Clip;  // alphaMode BLEND casters
    // For the failure study only (bench), never needed to render correctly:
    bool pancaking = false;         // clamp caster vertices' depth onto the near plane (Unity's pancaking)
    float spotNearFraction = 0.0f;  // > 0: spot near plane at this fraction of the range, not fitted

    // Auto sizing of whole views: --shadow-res auto, and the sun's cascades with virtual pages.
    bool autoResolution() const { return resolution == kAutoResolution || resolution == kVirtualResolution; }
    bool virtualPages() const { return resolution == kVirtualResolution; }
    // The filter's reach in texels, for a view of `viewResolution` texels a side, which widens the
    // bias (the design notes' penumbra) and the slices' guard band, and its lookups per shadow
    // test: the filter table's footprint, or the disk's settings.
    float penumbraTexels(uint32_t viewResolution) const;
    // The penumbra that widens the receiver bias of a view (applyShadowBias): the filter's reach with
    // the notes' per-tap compares; 0 where receiver-plane compares read every texel at the
    // receiver's own depth (the atlas with a footprint filter), as shadow_sampling.glsl decides.
    float biasPenumbraTexels(uint32_t viewResolution, bool onAtlas) const;
    uint32_t filterTaps() const;
    uint32_t texelBytes() const { return format == ShadowFormat::D16 ? 2u : 4u; }
};

// The named values of --shadow-res (any other value is a fixed resolution N): a table, so parsing,
// --help and the bench's series derive from it.
struct ShadowResolutionModeInfo {
    uint32_t value;     // ShadowSettings::resolution
    const char* name;
    GpuConstant pages;  // how the forward shader reads spot and point shadows (PUNCTUAL_SHADOW_PAGES_*)
    const char* description;
};
inline constexpr std::array<ShadowResolutionModeInfo, 2> kShadowResolutionModes = {{
    {ShadowSettings::kAutoResolution, "auto", PUNCTUAL_GPU_CONSTANT(PUNCTUAL_SHADOW_PAGES_OFF),
     "each view the power of two at which a texel spans about a pixel"},
    {ShadowSettings::kVirtualResolution, "virtual", PUNCTUAL_GPU_CONSTANT(PUNCTUAL_SHADOW_PAGES_LOOKUP),
     "32-texel pages of 16384-texel maps, where visible pixels read them"},
}};
static_assert(namesAreUnique(kShadowResolutionModes));

const char* shadowFormatName(ShadowFormat format);
// What receiver-plane compares subtract from the plane's depth (frame.shadowDepthQuantum): the format's
// rounding, in depth units. D16 stores round(depth x 65535), off by up to half a step, and the
// rasterizer's interpolated depth may be off by about as much again: two steps. D32 floats hold
// depth near 1 to 2^-24; 2^-20 covers the interpolation (measured: bench/RESULTS.md).
float shadowDepthQuantum(ShadowFormat format);
// "auto" or the fixed resolution, as --shadow-res takes it.
std::string shadowResolutionName(const ShadowSettings& settings);

// Throws Error naming the option for out-of-range settings.
void validateShadowSettings(const ShadowSettings& settings);

struct ShadowView {
    gpu::GpuShadowView gpu{};
    std::vector<uint32_t> casters;  // object indices whose bounds meet the view's frustum
    uint32_t packedLight = 0;       // index into FrameLights::packed
    uint32_t face = 0;              // 0 for spots; the cube face for points; the cascade for the sun
    uint32_t cubeLayer = 0;         // cube layout: the face's layer in the cube array
    bool isPoint = false;
    bool isCascade = false;         // one of the sun's cascades (packedLight unused)
    float nearPlane = 0.0f;         // metres along the view's axis
    float farPlane = 0.0f;
    float tanSpan = 0.0f;           // 2 tan(half field of view): the view's width at unit depth
    float demand = 0.0f;            // auto: texels a side its visible receivers need (0: none seen)
    uint32_t demandedTier = 0;      // auto: the tier of the demand, before the budget
    uint32_t resolution = 0;        // texels a side it is rendered at; 0: no storage, always lit
                                    // (virtual pages: PUNCTUAL_VIRTUAL_SHADOW_SIZE, its level 0)
    uint32_t coarserLevels = 0;     // virtual pages: levels coarser than its receivers ask (the budget's)
    AtlasRect rect;                 // where it lives in the atlas (not for the cube layout)
    bool rendered() const { return resolution > 0 && !casters.empty(); }
};

// Virtual pages (--shadow-res virtual): what sets the level a receiver reads, beside its view
// (shaders/shared/shadow_pages.glsl, virtualReadLevel): the camera, for the world size of a
// screen pixel at the receiver, and the target density.
struct VirtualPageReads {
    bool enabled = false;
    glm::vec3 eye{0.0f};
    glm::vec3 forward{0.0f, 0.0f, -1.0f};  // the camera's axis
    float pixelSpan = 0.0f;                 // a screen pixel's world size at unit depth along it
    float texelsPerPixel = 1.0f;
    // Hysteresis in a sequence (--shadow-hysteresis H; shadow_pages.h, virtualShadowMayKeepFiner):
    // 2^H, and the previous frame's marks in this frame's layout (ShadowPageMarkLayout), with per
    // plan view the first word of its light's and face's previous marks (PUNCTUAL_NO_SHADOW_PAGE
    // where there are none: the nearest level). Empty without hysteresis.
    float keep = 1.0f;
    std::vector<uint32_t> previousMarks;
    std::vector<uint32_t> previousFirstWord;
};

struct ShadowPlan {
    std::vector<ShadowView> views;  // spots first (one each), then points (six each), then cascades
    uint32_t shadowedSpots = 0;     // spot lights with a view
    uint32_t shadowedPoints = 0;    // point lights with six
    uint32_t droppedByCap = 0;      // shadow-casting lights over --shadowed (they stay unshadowed)

    // Of a frame's `punctualLights` spot and point lights, those without a shadow map: the ones
    // over the caps (droppedByCap) and the ones that cast none (their scene light says so, or
    // shadows are off). Validation compares only the shadowed ones, so its figures say nothing
    // of these.
    uint32_t unshadowedLights(uint32_t punctualLights) const {
        return punctualLights - shadowedSpots - shadowedPoints;
    }
    uint32_t viewsRendered = 0;     // views with storage and at least one caster
    uint32_t viewsSkipped = 0;      // the others (no caster, or no visible receiver in auto mode)
    AtlasLayout atlas;              // spot views and point slices
    uint32_t cubeResolution = 0;    // cube layout: the cube array's side (fixed mode only)
    uint64_t budgetBytes = 0;       // auto: the budget the views were fitted to
    std::vector<ShadowReduction> reductions;  // auto: views given less than their tier asked
    std::string reducedBy;          // what forced the reductions
    uint32_t receiverSamples = 0;   // auto: visible receiver samples the demand came from
    uint32_t sampleStep = 0;        // auto: pixels between them
    CascadePlan cascades;           // the sun's (planCascades)
    VirtualPageReads virtualReads;
    // How alphaMode BLEND casters shadow (ShadowSettings::transparent), for whoever checks the
    // views against rays (reference/shadow_validation.h).
    TransparentShadows transparentShadows = TransparentShadows::Clip;
};

// Chooses the shadowed lights (by lightImportance, see light_setup.h), builds their views (casters,
// near and far planes) and writes each shadowed light's first view index and strength into
// `lights.packed` (angleOffsetShadow.y and .w). Lights without a shadow keep y = -1. The views
// have no resolution yet: sizeShadowViews (lights/shadow_sizing.h) gives them one.
ShadowPlan planShadows(const Scene& scene, FrameLights& lights, const glm::vec3& cameraPosition,
                       const ShadowSettings& settings);

// The resolution receiver `position`, `linearDepth` along view `view`'s axis, reads of the view:
// its own, or with virtual pages its level's (virtualShadowReadLevel, as the forward shader
// chooses it); 0 for a view without storage.
float shadowResolutionRead(const ShadowPlan& plan, uint32_t view, float linearDepth, const glm::vec3& position);

// The matrix of cube face `face` of a light at `position`: clip.x = dot(r, U) / scale,
// clip.y = dot(r, V) / scale, clip.w = dot(r, axis) for r = p - position (see shadows.h), and a
// depth of 0 at `nearPlane`, 1 at `farPlane` along the axis. scale = 1 for a cube face, > 1 for a
// widened slice.
glm::mat4 cubeFaceViewProjection(const glm::vec3& position, uint32_t face, float nearPlane, float farPlane,
                                 float scale = 1.0f);

}  // namespace punctual
