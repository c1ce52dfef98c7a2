#pragma once
// The four ways the forward pass finds the lights of a pixel, as users name them on the command
// line (--culling) and in stats.
#include <cstdint>
#include <string>

#include "gpu_types.h"

namespace punctual::render {

enum class LightListMethod : uint32_t {
    Brute = PUNCTUAL_LIGHT_LIST_BRUTE,
    PerObject = PUNCTUAL_LIGHT_LIST_PER_OBJECT,
    Tiled = PUNCTUAL_LIGHT_LIST_TILED,
    Clustered = PUNCTUAL_LIGHT_LIST_CLUSTERED,
};

const char* methodName(LightListMethod method);  // "brute", "per-object", "tiled", "clustered"
// Throws Error("--culling", ...) for an unknown name.
LightListMethod parseMethod(const std::string& name);
inline bool usesLightGrid(LightListMethod m) { return m == LightListMethod::Tiled || m == LightListMethod::Clustered; }

}  // namespace punctual::render
