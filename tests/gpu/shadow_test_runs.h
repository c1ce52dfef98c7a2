#pragma once
// The one helper every GPU shadow test needs: render a scene's shadow factors on the GPU and
// compare them with Embree's visibility. The scenes themselves are CPU-only
// (tests/support/shadow_test_scenes.h, included here).
#include <cstdint>
#include <string>

#include "core/image.h"
#include "lights/light_setup.h"
#include "lights/shadow_setup.h"
#include "metrics/shadow_factor_image.h"
#include "reference/shadow_validation.h"
#include "render/renderer.h"
#include "scene/scene.h"
#include "shadow_test_scenes.h"
#include "vk/context.h"

namespace punctual::testing {

// Everything one validated frame produced; copies, so the Renderer can be gone.
struct ShadowRun {
    ImageRgba8 image;
    ShadowFactorImage factors;
    FrameLights lights;
    ShadowPlan plan;
    reference::ShadowValidation validation;
};

// Settings of a small frame with the shadow-factor readback on.
render::RenderSettings shadowRenderSettings(uint32_t width, uint32_t height, const ShadowSettings& shadows);

// Builds a Renderer, renders one frame (no warm-up: a single frame is all the factors need),
// reads the shadow factors back and validates them against Embree's ray-cast visibility.
ShadowRun renderAndValidateShadows(vk::Context& context, const Scene& scene, const render::RenderSettings& settings);

// When PUNCTUAL_TEST_OUTPUT_DIR is set: NAME.png (the frame) and NAME-mismatch-SLOT.png per
// shadowed light (the colours of `punctual validate`'s maps); otherwise nothing.
void saveShadowRun(const std::string& name, const ShadowRun& run);

}  // namespace punctual::testing
