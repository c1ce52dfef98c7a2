#pragma once
// Shared by the reference tests: the CPU ones (tests/unit/test_reference.cpp) and the ones that
// compare the reference with the GPU image (tests/gpu/test_reference.cpp).
#include <cstdint>

#include "reference/reference_renderer.h"
#include "scene/scene.h"

namespace punctual::testing {

// A grey dielectric (base colour 0.7, roughness 0.5).
Material greyMaterial();

// Reference settings for a `width` x `height` frame without shadows, which is what the GPU
// images it is compared with draw.
reference::ReferenceSettings unshadowed(uint32_t width, uint32_t height, float exposure = 1.0f);

}  // namespace punctual::testing
