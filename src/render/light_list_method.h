#pragma once
// The ways the forward pass finds the lights of a pixel, one table entry each: the name users give
// on the command line (--culling) and see in stats, what the shaders get (the list's source, the
// grid's depth slices, the culling kernels' flags), and what --help and the bench say about it. A
// method that reuses a light source and culling flags the shaders know is a row here alone; a new
// culling flag adds its define and math in shaders/shared/culling.h and its case in
// light_culling.comp (docs/EXTENDING.md, "A light-list method").
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/check.h"
#include "core/variant_table.h"
#include "culling.h"
#include "gpu_types.h"

namespace punctual::render {

// The table's index of each method.
enum class LightListMethod : uint32_t { Brute, PerObject, Tiled, Clustered, Tiled25D, ZBin, ZBin2D };

struct LightListMethodInfo {
    LightListMethod value;
    const char* name;
    // Where the forward pass finds the pixel's lights (a PUNCTUAL_LIGHT_SOURCE_* of gpu_types.h):
    // every light, the object's list (built on the CPU, at most 8 an object), the set bits of the
    // pixel's light-grid cell (a culling pass fills the grid), or those AND its z-bin's (CPU-built
    // bins, lights/z_bins.h).
    GpuConstant source;
    bool depthSlices = false;  // the grid's tiles are split into --slices depth slices (clusters)
    uint32_t cullFlags = 0;    // the culling kernels' PUNCTUAL_CULL_* flags (shaders/shared/culling.h)
    bool isReference = false;  // the exact sum every other method is compared against
    bool quickBench = false;   // swept by `bench --quick` (the full bench sweeps every method)
    const char* description = "";

    // A culling pass fills a light grid (per tile or per cluster) for the forward pass.
    constexpr bool usesLightGrid() const {
        return source.value == PUNCTUAL_LIGHT_SOURCE_GRID || source.value == PUNCTUAL_LIGHT_SOURCE_GRID_ZBINS;
    }
    constexpr bool objectLists() const { return source.value == PUNCTUAL_LIGHT_SOURCE_OBJECT; }
    constexpr bool zBins() const { return source.value == PUNCTUAL_LIGHT_SOURCE_GRID_ZBINS; }
    constexpr bool hasCullFlag(uint32_t flag) const { return (cullFlags & flag) != 0; }
};

inline constexpr std::array<LightListMethodInfo, 7> kLightListMethods = {{
    {.value = LightListMethod::Brute,
     .name = "brute",
     .source = PUNCTUAL_GPU_CONSTANT(PUNCTUAL_LIGHT_SOURCE_ALL),
     .isReference = true,
     .quickBench = true,
     .description = "every light"},
    {.value = LightListMethod::PerObject,
     .name = "per-object",
     .source = PUNCTUAL_GPU_CONSTANT(PUNCTUAL_LIGHT_SOURCE_OBJECT),
     .quickBench = true,
     .description = "the object's lights, at most 8, ranked on the CPU"},
    {.value = LightListMethod::Tiled,
     .name = "tiled",
     .source = PUNCTUAL_GPU_CONSTANT(PUNCTUAL_LIGHT_SOURCE_GRID),
     .quickBench = true,
     .description = "the lights culled to its screen tile"},
    {.value = LightListMethod::Clustered,
     .name = "clustered",
     .source = PUNCTUAL_GPU_CONSTANT(PUNCTUAL_LIGHT_SOURCE_GRID),
     .depthSlices = true,
     .quickBench = true,
     .description = "the lights culled to its depth slice of the tile"},
    {.value = LightListMethod::Tiled25D,
     .name = "tiled-2.5d",
     .source = PUNCTUAL_GPU_CONSTANT(PUNCTUAL_LIGHT_SOURCE_GRID),
     .cullFlags = PUNCTUAL_CULL_DEPTH_MASK,
     .description = "the lights culled to its screen tile and its tile's occupied depth cells (Harada's 2.5D mask)"},
    {.value = LightListMethod::ZBin,
     .name = "zbin",
     .source = PUNCTUAL_GPU_CONSTANT(PUNCTUAL_LIGHT_SOURCE_GRID_ZBINS),
     .description = "its screen tile's lights (within the tile's depth extent) AND its depth bin's range of depth-sorted lights (URP Forward+'s bins, Drobot's depth-tested tiles)"},
    {.value = LightListMethod::ZBin2D,
     .name = "zbin-2d",
     .source = PUNCTUAL_GPU_CONSTANT(PUNCTUAL_LIGHT_SOURCE_GRID_ZBINS),
     .cullFlags = PUNCTUAL_CULL_DEPTHLESS_TILES,
     .description = "its screen tile's lights (at every depth) AND its depth bin's range (URP Forward+ as shipped: tiles built without depth)"},
}};
static_assert(valuesAreIndices(kLightListMethods), "entry i is the method of enum value i");
static_assert(namesAreUnique(kLightListMethods));
static_assert(kLightListMethods[0].isReference, "compare and the bench render the reference method first");

// "brute", "per-object", ...; "unknown" for a value outside the table.
inline const char* methodName(LightListMethod method) {
    return variantName(kLightListMethods, method);
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

inline bool usesLightGrid(LightListMethod method) { return methodInfo(method).usesLightGrid(); }

// The methods that cull to a light grid (tiled, clustered, tiled-2.5d, ...), in table order: the
// lossless ones every test and study compares with brute force, so a new entry joins them.
inline std::vector<LightListMethod> gridMethods() {
    std::vector<LightListMethod> methods;
    for (const LightListMethodInfo& info : kLightListMethods) {
        if (info.usesLightGrid()) methods.push_back(info.value);
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
