#pragma once
// The shadow filters and point-shadow layouts, one table entry each: the name users give on the
// command line (--shadow-filter, --point-shadow-layout) and see in stats, the shader's value, the
// filter's footprint, and what --help and the bench say about it. Adding a filter is an entry here
// plus its cases in shaders/shared/shadow_sampling.glsl (see core/variant_table.h).
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/variant_table.h"
#include "gpu_types.h"
#include "shadow_tent.h"

namespace punctual {

enum class ShadowFilter : uint32_t {
    Hardware = PUNCTUAL_SHADOW_FILTER_HW,
    Tent3 = PUNCTUAL_SHADOW_FILTER_TENT3,
    Tent5 = PUNCTUAL_SHADOW_FILTER_TENT5,
    Tent7 = PUNCTUAL_SHADOW_FILTER_TENT7,
    Disk = PUNCTUAL_SHADOW_FILTER_DISK,
};

// How far around the shadow test's point a filter reads, which widens the bias (the design
// notes' penumbra) and the slices layout's guard band, and how many lookups it takes.
struct ShadowFilterFootprint {
    float penumbraTexels;   // reach from the centre, in texels
    uint32_t taps;          // hardware compare lookups per shadow test
    bool fromDiskSettings;  // the disk's: reach = disk radius x resolution, taps = disk samples
                            // (ShadowSettings); the two fields above are then unused
};

// An N x N tent (N odd) reaches N / 2 texels from the centre. Its ((N + 1) / 2)^2 bilinear taps,
// placed from the sample point's position inside its texel, cover the (N + 1) x (N + 1) texels
// it may touch (Unity's SampleShadow_ComputeSamples_Tent_NxN): gpu::tentFetchCount, the count
// the shader's loop runs (shaders/shared/shadow_tent.h).
constexpr ShadowFilterFootprint tentFootprint(uint32_t n) {
    return {float(n) * 0.5f, gpu::tentFetchCount(n), false};
}

struct ShadowFilterInfo {
    ShadowFilter value;
    const char* name;
    GpuConstant gpu;
    ShadowFilterFootprint footprint;
    bool quickBench;  // swept by `bench --quick` (the full bench sweeps every filter)
    const char* description;
};

inline constexpr std::array<ShadowFilterInfo, 5> kShadowFilters = {{
    // One bilinear compare: 2 x 2 texels, half a texel from the centre.
    {ShadowFilter::Hardware, "hw", PUNCTUAL_GPU_CONSTANT(PUNCTUAL_SHADOW_FILTER_HW), {0.5f, 1, false}, true,
     "one hardware bilinear compare of 2x2 texels"},
    {ShadowFilter::Tent3, "tent3", PUNCTUAL_GPU_CONSTANT(PUNCTUAL_SHADOW_FILTER_TENT3), tentFootprint(3), false,
     "tent over 3x3 texels, 4 bilinear taps placed per pixel"},
    {ShadowFilter::Tent5, "tent5", PUNCTUAL_GPU_CONSTANT(PUNCTUAL_SHADOW_FILTER_TENT5), tentFootprint(5), true,
     "tent over 5x5 texels, 9 bilinear taps placed per pixel"},
    {ShadowFilter::Tent7, "tent7", PUNCTUAL_GPU_CONSTANT(PUNCTUAL_SHADOW_FILTER_TENT7), tentFootprint(7), false,
     "tent over 7x7 texels, 16 bilinear taps placed per pixel"},
    {ShadowFilter::Disk, "disk", PUNCTUAL_GPU_CONSTANT(PUNCTUAL_SHADOW_FILTER_DISK), {0.0f, 0, true}, false,
     "--shadow-samples taps on a disk of radius --shadow-penumbra"},
}};
static_assert(kShadowFilters.size() == PUNCTUAL_SHADOW_FILTER_COUNT, "one entry per PUNCTUAL_SHADOW_FILTER_* value");
static_assert(gpuValuesAreIndices(kShadowFilters), "entry i is the filter of GPU value i");
static_assert(namesAreUnique(kShadowFilters));

enum class PointShadowLayout : uint32_t { Cube = PUNCTUAL_POINT_SHADOW_CUBE, Slices = PUNCTUAL_POINT_SHADOW_SLICES };

struct PointShadowLayoutInfo {
    PointShadowLayout value;
    const char* name;
    GpuConstant gpu;
    const char* description;
};

inline constexpr std::array<PointShadowLayoutInfo, 2> kPointShadowLayouts = {{
    {PointShadowLayout::Cube, "cube", PUNCTUAL_GPU_CONSTANT(PUNCTUAL_POINT_SHADOW_CUBE),
     "a cube map array, hardware face selection"},
    {PointShadowLayout::Slices, "slices", PUNCTUAL_GPU_CONSTANT(PUNCTUAL_POINT_SHADOW_SLICES),
     "six 2D slices per light with a widened field of view"},
}};
static_assert(kPointShadowLayouts.size() == PUNCTUAL_POINT_SHADOW_LAYOUT_COUNT,
              "one entry per PUNCTUAL_POINT_SHADOW_* layout value");
static_assert(gpuValuesAreIndices(kPointShadowLayouts), "entry i is the layout of GPU value i");
static_assert(namesAreUnique(kPointShadowLayouts));

// "hw", "tent3", ...; "unknown" for a value outside the table.
inline const char* shadowFilterName(ShadowFilter filter) {
    const ShadowFilterInfo* info = findVariant(kShadowFilters, filter);
    return info ? info->name : "unknown";
}
inline std::vector<std::string> shadowFilterNames() { return variantNames(kShadowFilters); }
// Throws Error("--shadow-filter", "expected hw, ... or disk, got 'x'").
inline ShadowFilter parseShadowFilter(const std::string& name) {
    return parseVariant(kShadowFilters, name, "--shadow-filter").value;
}

// "cube", "slices"; "unknown" for a value outside the table.
inline const char* pointShadowLayoutName(PointShadowLayout layout) {
    const PointShadowLayoutInfo* info = findVariant(kPointShadowLayouts, layout);
    return info ? info->name : "unknown";
}
inline std::vector<std::string> pointShadowLayoutNames() { return variantNames(kPointShadowLayouts); }
// Throws Error("--point-shadow-layout", "expected cube or slices, got 'x'").
inline PointShadowLayout parsePointShadowLayout(const std::string& name) {
    return parseVariant(kPointShadowLayouts, name, "--point-shadow-layout").value;
}

}  // namespace punctual
