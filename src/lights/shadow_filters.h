#pragma once
// The shadow filters and point-shadow layouts, one table entry each: the name users give on the
// command line (--shadow-filter, --point-shadow-layout) and see in stats, what the shaders get, and
// what --help and the bench say about it. A filter is a kernel and a size
// (shaders/shared/shadow_kernels.h): a new filter of a kernel the shaders know (a tent9, say) is a
// row here and its test; a new kernel adds its cases in shadow_kernels.h (docs/EXTENDING.md).
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/check.h"
#include "core/variant_table.h"
#include "gpu_types.h"
#include "shadow_kernels.h"

namespace punctual {

// The table's index of each filter.
enum class ShadowFilter : uint32_t { Hardware, Tent3, Tent5, Tent7, Disk };

struct ShadowFilterInfo {
    ShadowFilter value;
    const char* name;
    GpuConstant kernel;  // a PUNCTUAL_SHADOW_KERNEL_* of shadow_kernels.h
    uint32_t size;       // the kernel's size: the tent's N (the bilinear kernel's 1; unused by the disk)
    bool quickBench;     // swept by `bench --quick` (the full bench sweeps every filter)
    const char* description;

    // The N x N texel footprint that receiver-plane compares weigh texel by texel; 0 for a kernel
    // without one (the disk).
    constexpr uint32_t footprint() const { return gpu::shadowKernelFootprint(kernel.value, size); }
    // Hardware compare lookups per shadow test (the disk's: `diskSamples`).
    constexpr uint32_t taps(uint32_t diskSamples) const { return gpu::shadowKernelTaps(kernel.value, size, diskSamples); }
    // How far from the centre the filter reads, in texels (the disk's: its radius in texels), which
    // widens the bias (the design notes' penumbra) and the slices layout's guard band.
    float reachTexels(float diskRadiusTexels) const {
        return gpu::shadowKernelReachTexels(kernel.value, size, diskRadiusTexels);
    }
};

inline constexpr std::array<ShadowFilterInfo, 5> kShadowFilters = {{
    {ShadowFilter::Hardware, "hw", PUNCTUAL_GPU_CONSTANT(PUNCTUAL_SHADOW_KERNEL_BILINEAR), 1, true,
     "one hardware bilinear compare of 2x2 texels"},
    {ShadowFilter::Tent3, "tent3", PUNCTUAL_GPU_CONSTANT(PUNCTUAL_SHADOW_KERNEL_TENT), 3, false,
     "tent over 3x3 texels, 4 bilinear taps placed per pixel"},
    {ShadowFilter::Tent5, "tent5", PUNCTUAL_GPU_CONSTANT(PUNCTUAL_SHADOW_KERNEL_TENT), 5, true,
     "tent over 5x5 texels, 9 bilinear taps placed per pixel"},
    {ShadowFilter::Tent7, "tent7", PUNCTUAL_GPU_CONSTANT(PUNCTUAL_SHADOW_KERNEL_TENT), 7, false,
     "tent over 7x7 texels, 16 bilinear taps placed per pixel"},
    {ShadowFilter::Disk, "disk", PUNCTUAL_GPU_CONSTANT(PUNCTUAL_SHADOW_KERNEL_DISK), 0, false,
     "--shadow-samples taps on a disk of radius --shadow-penumbra"},
}};
static_assert(valuesAreIndices(kShadowFilters), "entry i is the filter of enum value i");
static_assert(namesAreUnique(kShadowFilters));

// Every filter's kernel is one the shaders know, and a tent's size is odd (its taps pair texels
// about the sample point's nearest corner, shadow_tent.h).
constexpr bool filterKernelsAreKnown() {
    for (const ShadowFilterInfo& filter : kShadowFilters) {
        if (filter.kernel.value >= PUNCTUAL_SHADOW_KERNEL_COUNT || filter.taps(1) == 0) return false;
        if (filter.kernel.value == PUNCTUAL_SHADOW_KERNEL_TENT && (filter.size < 3 || filter.size % 2 == 0)) return false;
    }
    return true;
}
static_assert(filterKernelsAreKnown());

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

// The filter's entry; an internal error for a value outside the table (a cast from a bad integer).
inline const ShadowFilterInfo& shadowFilterInfo(ShadowFilter filter) {
    const ShadowFilterInfo* info = findVariant(kShadowFilters, filter);
    PUNCTUAL_CHECK(info != nullptr, "shadow filter outside kShadowFilters");
    return *info;
}

// "hw", "tent3", ...; "unknown" for a value outside the table.
inline const char* shadowFilterName(ShadowFilter filter) {
    return variantName(kShadowFilters, filter);
}
inline std::vector<std::string> shadowFilterNames() { return variantNames(kShadowFilters); }
// Throws Error("--shadow-filter", "expected hw, ... or disk, got 'x'").
inline ShadowFilter parseShadowFilter(const std::string& name) {
    return parseVariant(kShadowFilters, name, "--shadow-filter").value;
}

// "cube", "slices"; "unknown" for a value outside the table.
inline const char* pointShadowLayoutName(PointShadowLayout layout) {
    return variantName(kPointShadowLayouts, layout);
}
inline std::vector<std::string> pointShadowLayoutNames() { return variantNames(kPointShadowLayouts); }
// Throws Error("--point-shadow-layout", "expected cube or slices, got 'x'").
inline PointShadowLayout parsePointShadowLayout(const std::string& name) {
    return parseVariant(kPointShadowLayouts, name, "--point-shadow-layout").value;
}

}  // namespace punctual
