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
};

struct LightListMethodInfo {
    LightListMethod value;
    const char* name;
    GpuConstant gpu;
    bool usesLightGrid;  // a culling pass fills a light grid (per tile or per cluster) for the forward pass
    bool depthSlices;    // the grid's tiles are split into --slices depth slices (clusters)
    bool objectLists;    // the CPU builds per-object light lists (at most 8 per object) for it
    bool isReference;    // the exact sum every other method is compared against
    bool quickBench;     // swept by `bench --quick` (the full bench sweeps every method)
    const char* description;
};

inline constexpr std::array<LightListMethodInfo, 4> kLightListMethods = {{
    // value, name, GPU value, light grid, depth slices, object lists, reference, quick bench, help
    {LightListMethod::Brute, "brute", PUNCTUAL_GPU_CONSTANT(PUNCTUAL_LIGHT_LIST_BRUTE), false, false, false, true,
     true, "every light"},
    {LightListMethod::PerObject, "per-object", PUNCTUAL_GPU_CONSTANT(PUNCTUAL_LIGHT_LIST_PER_OBJECT), false, false,
     true, false, true, "the object's lights, at most 8, ranked on the CPU"},
    {LightListMethod::Tiled, "tiled", PUNCTUAL_GPU_CONSTANT(PUNCTUAL_LIGHT_LIST_TILED), true, false, false, false,
     true, "the lights culled to its screen tile"},
    {LightListMethod::Clustered, "clustered", PUNCTUAL_GPU_CONSTANT(PUNCTUAL_LIGHT_LIST_CLUSTERED), true, true,
     false, false, true, "the lights culled to its depth slice of the tile"},
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

// The exact method every other is compared against (brute force).
inline LightListMethod referenceMethod() {
    for (const LightListMethodInfo& info : kLightListMethods) {
        if (info.isReference) return info.value;
    }
    return kLightListMethods.front().value;
}

}  // namespace punctual::render
