#pragma once
// The sun's cascade settings (--cascades, --cascade-splits, --cascade-lambda, --shadow-distance,
// --cascade-blend) and the blend modes' table. The cascades themselves: lights/cascade_setup.h and
// shaders/shared/cascades.h (seed: catlike-directional-cascaded-shadows.md).
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/variant_table.h"
#include "gpu_types.h"

namespace punctual {

enum class CascadeBlend : uint32_t {
    Hard = PUNCTUAL_CASCADE_BLEND_HARD,
    Soft = PUNCTUAL_CASCADE_BLEND_SOFT,
    Dither = PUNCTUAL_CASCADE_BLEND_DITHER,
};

struct CascadeBlendInfo {
    CascadeBlend value;
    const char* name;
    GpuConstant gpu;
    const char* description;
};

inline constexpr std::array<CascadeBlendInfo, 3> kCascadeBlends = {{
    {CascadeBlend::Hard, "hard", PUNCTUAL_GPU_CONSTANT(PUNCTUAL_CASCADE_BLEND_HARD),
     "each receiver reads one cascade (the seed's default)"},
    {CascadeBlend::Soft, "soft", PUNCTUAL_GPU_CONSTANT(PUNCTUAL_CASCADE_BLEND_SOFT),
     "a cascade's outer share mixes it with the next"},
    {CascadeBlend::Dither, "dither", PUNCTUAL_GPU_CONSTANT(PUNCTUAL_CASCADE_BLEND_DITHER),
     "a cascade's outer share picks it or the next per pixel"},
}};
static_assert(kCascadeBlends.size() == PUNCTUAL_CASCADE_BLEND_COUNT, "one entry per PUNCTUAL_CASCADE_BLEND_* value");
static_assert(gpuValuesAreIndices(kCascadeBlends), "entry i is the blend of GPU value i");
static_assert(namesAreUnique(kCascadeBlends));

inline const char* cascadeBlendName(CascadeBlend blend) {
    return variantName(kCascadeBlends, blend);
}
// Throws Error("--cascade-blend", "expected hard, soft or dither, got 'x'").
inline CascadeBlend parseCascadeBlend(const std::string& name) {
    return parseVariant(kCascadeBlends, name, "--cascade-blend").value;
}

// The fitted shadow distance's ceiling: the seed's default maximum distance is 100 m; twice that
// keeps the built-in outdoor scene's farthest casters (150 m) shadowed.
inline constexpr float kMaxFittedShadowDistance = 200.0f;

struct CascadeSettings {
    uint32_t count = 4;  // --cascades N, 1 to PUNCTUAL_MAX_CASCADES
    // --cascade-splits a,b,c: where cascades 1 .. count - 1 end, as fractions of the shadow
    // distance (the last ends at it). The seed's ratios.
    std::array<float, 3> splits{0.1f, 0.25f, 0.5f};
    // --cascade-lambda L (0 to 1): the practical split scheme (cascades.h, practicalSplit) instead
    // of `splits`; negative: not used.
    float lambda = -1.0f;
    float shadowDistance = 0.0f;  // --shadow-distance D (metres); 0: fitted to the frame
    CascadeBlend blend = CascadeBlend::Hard;
    float cascadeFade = 0.1f;   // the seed's cascade fade: the outer share of each radius that fades
    float distanceFade = 0.1f;  // the seed's distance fade: the share of the shadow distance that fades
    // For the failure study only (bench), never needed to render correctly:
    bool snapToTexels = true;  // texel snapping of each cascade's projection
    bool depthClamp = true;    // pancake the casters in front of a cascade's near plane

    // The seed's culling factor: casters wholly inside this share of the previous cascade's
    // sphere are culled from the next (Unity's shadowCascadeBlendCullingFactor), max(0, 0.8 - fade).
    float cullingFactor() const { return cascadeFade < 0.8f ? 0.8f - cascadeFade : 0.0f; }
};

// Throws Error naming the option for out-of-range settings.
void validateCascadeSettings(const CascadeSettings& settings);

}  // namespace punctual
