#pragma once
// What every study of the bench's failure study shares (bench_failures.cpp for the lights and
// culling, bench_cascade_failures.cpp for the sun's cascades): a study's description with its
// measuring function, and one frame rendered and validated against Embree.
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "metrics/shadow_factor_image.h"
#include "reference/embree_scene.h"
#include "reference/shadow_validation.h"
#include "render/renderer.h"
#include "scene/scene.h"

namespace punctual::vk {
class Context;
}

namespace punctual::bench {

// One known failure: the error `metric` against the `parameter` that provokes it, at each of
// `values`, for each of `variants` (a line each in bench/plot_failures.py's chart).
struct FailureStudy {
    std::string name;
    std::string parameter;
    std::string metric;
    std::vector<double> values;
    std::vector<std::string> variants;
    // Renders and measures one (value, variant); returns (error, total ms).
    std::function<std::pair<double, double>(double value, const std::string& variant)> measure;
};

// One frame with its shadow factors and their validation.
struct ValidatedFrame {
    render::FrameResult result;
    ShadowFactorImage factors;
    ShadowPlan plan;  // the views and the sun's cascades the frame was rendered with
    reference::ShadowValidation validation;
};

// Renders `scene` once (one warm-up frame, one timed) with the shadow-factor readback and
// validates the factors against `embree`, built from the same geometry, with edge band `band`.
ValidatedFrame renderAndValidate(vk::Context& context, const Scene& scene, const reference::EmbreeScene& embree,
                                 render::RenderSettings settings, const reference::EdgeBand& band = {});
// The same, building the Embree scene from `scene`.
ValidatedFrame renderAndValidate(vk::Context& context, const Scene& scene, const render::RenderSettings& settings,
                                 const reference::EdgeBand& band = {});

// part / whole, 0 when whole is 0.
inline double fraction(uint64_t part, uint64_t whole) { return whole > 0 ? double(part) / double(whole) : 0.0; }

}  // namespace punctual::bench
