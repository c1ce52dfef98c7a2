#pragma once
// The ways the forward pass finds the lights of a pixel, one table entry each: the name users give
// on the command line (--culling) and see in stats, the shader's value, and what --help and the
// bench say about it. Adding a method is an entry here plus its case in forward.frag (see
// core/variant_table.h).
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/check.h"
#include "core/variant_table.h"
#include "gpu_types.h"

namespace punctual::render {

enum class LightListMethod : uint32_t {
    Brute = PUNCTUAL_LIGHT_LIST_BRUTE,
    PerObject = PUNCTUAL_LIGHT_LIST_PER_OBJECT,
    Tiled = PUNCTUAL_LIGHT_LIST_TILED,
    Clustered = PUNCTUAL_LIGHT_LIST_CLUSTERED,
    Tiled25D = PUNCTUAL_LIGHT_LIST_TILED_25D,
    ZBin = PUNCTUAL_LIGHT_LIST_ZBIN,
    ZBin2D = PUNCTUAL_LIGHT_LIST_ZBIN_2D,
};

struct LightListMethodInfo {
    LightListMethod value;
    const char* name;
    GpuConstant gpu;
    bool usesLightGrid = false;  // a culling pass fills a light grid (per tile or per cluster) for the forward pass
    bool depthSlices = false;    // the grid's tiles are split into --slices depth slices (clusters)
    bool depthMask = false;      // the culling kernel keeps a light only where it meets the tile's 2.5D depth mask
    bool zBins = false;          // tile masks ANDed with CPU-built z-bins (lights/z_bins.h)
    bool depthlessTiles = false; // the tile masks read no depth: every light in the tile's column, near to far plane
    bool objectLists = false;    // the CPU builds per-object light lists (at most 8 per object) for it
    bool isReference = false;    // the exact sum every other method is compared against
    bool quickBench = false;     // swept by `bench --quick` (the full bench sweeps every method)
    const char* description = "";
};

inline constexpr std::array<LightListMethodInfo, 7> kLightListMethods = {{
    {.value = LightListMethod::Brute,
     .name = "brute",
     .gpu = PUNCTUAL_GPU_CONSTANT(PUNCTUAL_LIGHT_LIST_BRUTE),
     .isReference = true,
     .quickBench = true,
     .description = "every light"},
    {.value = LightListMethod::PerObject,
     .name = "per-object",
     .gpu = PUNCTUAL_GPU_CONSTANT(PUNCTUAL_LIGHT_LIST_PER_OBJECT),
     .objectLists = true,
     .quickBench = true,
     .description = "the object's lights, at most 8, ranked on the CPU"},
    {.value = LightListMethod::Tiled,
     .name = "tiled",
     .gpu = PUNCTUAL_GPU_CONSTANT(PUNCTUAL_LIGHT_LIST_TILED),
     .usesLightGrid = true,
     .quickBench = true,
     .description = "the lights culled to its screen tile"},
    {.value = LightListMethod::Clustered,
     .name = "clustered",
     .gpu = PUNCTUAL_GPU_CONSTANT(PUNCTUAL_LIGHT_LIST_CLUSTERED),
     .usesLightGrid = true,
     .depthSlices = true,
     .quickBench = true,
     .description = "the lights culled to its depth slice of the tile"},
    {.value = LightListMethod::Tiled25D,
     .name = "tiled-2.5d",
     .gpu = PUNCTUAL_GPU_CONSTANT(PUNCTUAL_LIGHT_LIST_TILED_25D),
     .usesLightGrid = true,
     .depthMask = true,
     .description = "the lights culled to its screen tile and its tile's occupied depth cells (Harada's 2.5D mask)"},
    {.value = LightListMethod::ZBin,
     .name = "zbin",
     .gpu = PUNCTUAL_GPU_CONSTANT(PUNCTUAL_LIGHT_LIST_ZBIN),
     .usesLightGrid = true,
     .zBins = true,
     .description = "its screen tile's lights (within the tile's depth extent) AND its depth bin's range of depth-sorted lights (URP Forward+'s bins, Drobot's depth-tested tiles)"},
    {.value = LightListMethod::ZBin2D,
     .name = "zbin-2d",
     .gpu = PUNCTUAL_GPU_CONSTANT(PUNCTUAL_LIGHT_LIST_ZBIN_2D),
     .usesLightGrid = true,
     .zBins = true,
     .depthlessTiles = true,
     .description = "its screen tile's lights (at every depth) AND its depth bin's range (URP Forward+ as shipped: tiles built without depth)"},
}};
static_assert(kLightListMethods.size() == PUNCTUAL_LIGHT_LIST_COUNT, "one entry per PUNCTUAL_LIGHT_LIST_* value");
static_assert(gpuValuesAreIndices(kLightListMethods), "entry i is the method of GPU value i");
static_assert(namesAreUnique(kLightListMethods));
static_assert(kLightListMethods[0].isReference, "compare and the bench render the reference method first");

// "brute", "per-object", ...; "unknown" for a value outside the table.
inline const char* methodName(LightListMethod method) {
    const LightListMethodInfo* info = findVariant(kLightListMethods, method);
    return info ? info->name : "unknown";
}

// Every method's name, in table order.
inline std::vector<std::string> methodNames() { return variantNames(kLightListMethods); }

// Throws Error("--culling", "expected brute, per-object, tiled or clustered, got 'x'").
inline LightListMethod parseMethod(const std::string& name) {
    return parseVariant(kLightListMethods, name, "--culling").value;
}

// The method's entry; an internal error for a value outside the table (a cast from a bad integer).
inline const LightListMethodInfo& methodInfo(LightListMethod method) {
    const LightListMethodInfo* info = findVariant(kLightListMethods, method);
    PUNCTUAL_CHECK(info != nullptr, "light-list method outside kLightListMethods");
    return *info;
}

inline bool usesLightGrid(LightListMethod method) { return methodInfo(method).usesLightGrid; }

// The methods that cull to a light grid (tiled, clustered, tiled-2.5d, ...), in table order: the
// lossless ones every test and study compares with brute force, so a new entry joins them.
inline std::vector<LightListMethod> gridMethods() {
    std::vector<LightListMethod> methods;
    for (const LightListMethodInfo& info : kLightListMethods) {
        if (info.usesLightGrid) methods.push_back(info.value);
    }
    return methods;
}

// The exact method every other is compared against (brute force).
inline LightListMethod referenceMethod() {
    for (const LightListMethodInfo& info : kLightListMethods) {
        if (info.isReference) return info.value;
    }
    return kLightListMethods.front().value;
}

}  // namespace punctual::render
