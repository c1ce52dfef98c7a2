#pragma once
// How alphaMode BLEND surfaces cast shadows (--transparent-shadows), after the seed's four shadow
// modes (catlike-directional-cascaded-shadows.md, section 5): a shadow map stores depth, so a
// caster is either there or not, per texel. The CPU reference follows the same rule per ray
// (reference/embree_scene.h), and alphaMode MASK casters always clip at their cutoff.
#include <array>
#include <cstdint>
#include <string>

#include "core/variant_table.h"

namespace punctual {

enum class TransparentShadows : uint32_t { On, Clip, Dither, Off };

// The cutoff of clip mode (glTF's BLEND materials have no alphaCutoff; the MASK default).
inline constexpr float kTransparentShadowCutoff = 0.5f;

struct TransparentShadowsInfo {
    TransparentShadows value;
    const char* name;
    const char* description;
};

inline constexpr std::array<TransparentShadowsInfo, 4> kTransparentShadowModes = {{
    {TransparentShadows::On, "on", "as solid casters"},
    {TransparentShadows::Clip, "clip",
     "where alpha >= 0.5, like a mask (the default: stable, the seed's advice for most transparent casters)"},
    {TransparentShadows::Dither, "dither",
     "where alpha beats a per-texel noise (the seed's preset for fades: coverage ~ alpha, flickers as views move)"},
    {TransparentShadows::Off, "off", "no shadow at all"},
}};
static_assert(namesAreUnique(kTransparentShadowModes));

inline const char* transparentShadowsName(TransparentShadows mode) {
    return variantName(kTransparentShadowModes, mode);
}

// Throws Error("--transparent-shadows", "expected on, clip, dither or off, got 'x'").
inline TransparentShadows parseTransparentShadows(const std::string& name) {
    return parseVariant(kTransparentShadowModes, name, "--transparent-shadows").value;
}

}  // namespace punctual
