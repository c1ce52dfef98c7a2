#pragma once
// The sun's cascades in the bench's failure study (issue 12; README, "Where methods fail"):
//   shimmering:            shadow flips along a camera path, texel snapping on and off, seen from
//                          the moving camera and on fixed receivers;
//   cascade seams:         error in the split band against inside the cascades, per blend;
//   perspective aliasing:  error against view depth, split ratios against lambda, 1-4 cascades;
//   pancaking:             a caster in front of the first cascade's near plane, depth clamp on, off.
// The measuring functions below are public so that tests can check them on a few small frames.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "bench/failure_study.h"
#include "lights/cascade_settings.h"
#include "lights/shadow_setup.h"
#include "metrics/shadow_factor_image.h"
#include "reference/embree_scene.h"
#include "reference/shadow_validation.h"
#include "render/render_settings.h"
#include "scene/scene.h"

namespace punctual::vk {
class Context;
}

namespace punctual::bench {

// The cascade studies at `width` x `height` (fewer values and variants when `quick`).
std::vector<FailureStudy> cascadeFailureStudies(vk::Context& context, bool quick, uint32_t width, uint32_t height);

// ---- shimmering ----------------------------------------------------------------------------------

// A slow walk with a slight turn from `start`: `frames` cameras, each 5 cm further along the
// ground in the direction the camera faces and turned 0.1 degrees further to the left (1.5 m/s and
// 3 degrees/s at 30 frames a second). Field of view and planes stay those of `start`.
std::vector<Camera> walkingCameraPath(const Camera& start, uint32_t frames);

// Flips of the sun's shadow between consecutive frames, pixel by pixel (a pixel of one frame
// against the same pixel of the next, which sees a slightly different point as the camera moves).
struct ShimmerCounts {
    uint64_t compared = 0;           // pixels the sun reaches in both frames of a pair, over all pairs
    uint64_t gpuFlips = 0;           // of those, where the GPU's lit/dark verdict changes
    uint64_t truthFlips = 0;         // where Embree's ray-cast visibility changes
    uint64_t unexplainedFlips = 0;   // where the GPU's verdict changes and Embree's does not

    void add(const ShimmerCounts& other);
    // unexplainedFlips / compared: the study's metric.
    double unexplainedShare() const { return fraction(unexplainedFlips, compared); }
};

// Counts the flips between two frames' per-pixel verdicts on the sun (SunShadowValidation::
// verdicts of the same size): the GPU's verdict is lit for AgreeLit and FalseLit, the ray's for
// AgreeLit and FalseShadow.
ShimmerCounts countShimmerFlips(const std::vector<reference::PixelVerdict>& before,
                                const std::vector<reference::PixelVerdict>& after);

// What the frames of a shimmering measure show.
enum class ShimmerView {
    // Each frame from its own camera of the path: what a viewer sees. A pixel sees a slightly
    // different point in the next frame, so edges that move with the view flip pixels in the GPU's
    // image and in Embree's alike, and a GPU edge that lies off the true one by part of a texel flips
    // pixels where Embree's does not, snapped or not.
    MovingView,
    // Every frame from the path's first camera, under the cascades fitted to the frame's own camera
    // (RenderSettings::cascadeCamera): the same receivers in every frame, so Embree's truth never
    // flips and every flip is the shadow moving over a still surface, which is shimmering.
    FixedReceivers,
};

// Renders `scene` along `path` (as `view` says) with `settings`, validates each frame's sun against
// `embree` (the scene's geometry) and counts the flips of every consecutive pair. `totalMs`, when
// given, receives the frames' mean GPU time.
ShimmerCounts measureShimmer(vk::Context& context, const Scene& scene, const reference::EmbreeScene& embree,
                             const std::vector<Camera>& path, ShimmerView view, const render::RenderSettings& settings,
                             double* totalMs = nullptr);

// ---- seams and perspective aliasing -------------------------------------------------------------

// The sun's counts in three regions of the cascades, each pixel placed by its position (as the
// forward shader selects cascades, CascadePlan::selection):
//   splitBand: within one texel of a split (nearCascadeSplit), on either side;
//   blendZone: the rest of the outer cascadeFade share of the radius of every cascade but the last,
//              where the soft and dither blends read the next cascade too (hard reads its own);
//   inside:    the rest.
// Pixels where the shadow fades out by design are left out: the last cascade's outer cascadeFade
// share and the last distanceFade of the shadow distance (view depth along `view`'s axis).
struct CascadeSeamCounts {
    reference::ShadowCounts splitBand;
    reference::ShadowCounts blendZone;
    reference::ShadowCounts inside;
};
CascadeSeamCounts cascadeSeamCounts(const ShadowFactorImage& factors, const reference::SunShadowValidation& sun,
                                    const ShadowPlan& plan, const CascadeSettings& settings, const glm::mat4& view);

// The sun's counts per bucket of view depth (metres along the camera's axis of `view`): bucket i
// holds the pixels deeper than bucketEnds[i - 1] (0 for the first) up to bucketEnds[i]; deeper
// pixels are left out.
std::vector<reference::ShadowCounts> sunCountsByViewDepth(const ShadowFactorImage& factors,
                                                          const reference::SunShadowValidation& sun,
                                                          const glm::mat4& view, const std::vector<float>& bucketEnds);

}  // namespace punctual::bench
