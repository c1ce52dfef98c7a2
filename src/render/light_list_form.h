#pragma once
// How a light-grid cell holds its lights, one table entry each (--light-lists): the grid methods'
// masks (one bit per light the frame keeps), or the papers' index lists (Olsson et al. 2012,
// Harada et al. 2012: per cell an offset into one compacted array of 16-bit indices, whose first
// entry is the count). Both give the forward pass the same lights in the same order, so the same
// image bit for bit; they differ in memory (a mask is a bit per light in the frame, a list 2 bytes
// per light in the cell) and in the walk. The shaders get the entry's `gpu` value as the
// specialization constant LIGHT_LIST_FORM (culling.h, "Index lists").
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/variant_table.h"
#include "gpu_types.h"

namespace punctual::render {

enum class LightListForm : uint32_t { Masks = PUNCTUAL_LIGHT_LIST_MASKS, Indices = PUNCTUAL_LIGHT_LIST_INDICES };

struct LightListFormInfo {
    LightListForm value;
    const char* name;
    GpuConstant gpu;
    bool quickBench = false;  // swept by `bench --quick` (the full bench sweeps every form)
    const char* description = "";
};

inline constexpr std::array<LightListFormInfo, 2> kLightListForms = {{
    {.value = LightListForm::Masks,
     .name = "masks",
     .gpu = PUNCTUAL_GPU_CONSTANT(PUNCTUAL_LIGHT_LIST_MASKS),
     .quickBench = true,
     .description = "one bit per light the frame keeps, in every cell"},
    {.value = LightListForm::Indices,
     .name = "indices",
     .gpu = PUNCTUAL_GPU_CONSTANT(PUNCTUAL_LIGHT_LIST_INDICES),
     .description = "per cell, a list of 16-bit light indices in one array (Olsson's)"},
}};
static_assert(kLightListForms.size() == PUNCTUAL_LIGHT_LIST_FORM_COUNT, "one entry per PUNCTUAL_LIGHT_LIST_* value");
static_assert(gpuValuesAreIndices(kLightListForms), "entry i is the form of GPU value i");
static_assert(namesAreUnique(kLightListForms));

// "masks", "indices"; "unknown" for a value outside the table.
inline const char* lightListFormName(LightListForm form) {
    return variantName(kLightListForms, form);
}
inline std::vector<std::string> lightListFormNames() { return variantNames(kLightListForms); }
// Throws Error("--light-lists", "expected masks or indices, got 'x'").
inline LightListForm parseLightListForm(const std::string& name) {
    return parseVariant(kLightListForms, name, "--light-lists").value;
}

}  // namespace punctual::render
