#pragma once
// Adaptive shadow resolution (--shadow-res auto): how many texels a side each shadow view needs so
// that one of its texels covers about one screen pixel where its light reaches visible receivers.
//
// The estimator works on the CPU, from the surfaces the frame shows, as sample-distribution
// shadow maps do on the GPU from the depth buffer:
//  - A grid of primary rays, one per `step` x `step` pixels of the frame (step = the smallest
//    that keeps the grid within kMaxSampleColumns x kMaxSampleRows), finds the visible surfaces
//    (scene/triangle_bvh.h). Each hit is a receiver sample: its point, its normal turned towards
//    the camera (faces are two-sided), and the world size of one screen pixel there
//    (screenPixelWorldSize in shaders/shared/shadows.h).
//  - A view shades a sample when the sample is within its light's range, in front of the light
//    along the view's axis, inside the view (a spot's frustum and outer cone; for a point light,
//    the cube face its direction falls on) and facing the light (N.L > 0: elsewhere the BRDF is
//    zero and the forward pass skips the shadow lookup). Shadowed samples count: their shadow is
//    what the map must resolve.
//  - At each sample it shades, the view needs resolutionForOneTexelPerPixel(depth along the view's
//    axis, the view's span, the pixel's size) texels a side (shadows.h); the view's demand is the
//    largest. A view that shades no sample has demand 0 and gets no storage.
//
// Error of the estimate:
//  - Receivers smaller than the sample spacing (`step` pixels) can be missed. Their view then
//    gets the demand of the other samples, or nothing at all when it has no other sample: a
//    missed receiver is shaded unshadowed. The spacing is 4 pixels at 1280x720.
//  - The pixel size is measured across the line of sight and the texel size across the light's
//    axis. A surface seen at a slant from the camera, or lit at a slant, covers more world per
//    pixel or per texel along the slant; neither factor is modelled, so the density there is off
//    by up to 1 / cos of the angle (the estimate stays right for surfaces facing both).
//  - Occlusion between the light and the sample is ignored (shadowed samples need the map too).
#include <cstdint>
#include <functional>
#include <vector>

#include <glm/glm.hpp>

#include "lights/light_setup.h"
#include "scene/scene.h"
#include "scene/triangle_bvh.h"

namespace punctual {

struct ShadowPlan;

struct ReceiverSample {
    glm::vec3 position{0.0f};
    glm::vec3 normal{0.0f};        // unit, towards the camera
    float pixelWorldSize = 0.0f;   // world size of one screen pixel at the sample
};

struct VisibleReceivers {
    std::vector<ReceiverSample> samples;
    uint32_t step = 1;  // pixels between samples, in each direction
};

inline constexpr uint32_t kMaxSampleColumns = 320;
inline constexpr uint32_t kMaxSampleRows = 180;

// Casts the sample grid for a width x height frame seen by the scene's camera. `geometry`: the
// scene's tree, shared with the frame's other planners; null builds one for this call.
VisibleReceivers sampleVisibleReceivers(const Scene& scene, uint32_t width, uint32_t height,
                                        const LazyTriangleBvh* geometry = nullptr);

// Casts one primary ray through the centre of every `step`-th pixel of each `step`-th row of a
// width x height frame (starting at step / 2) and calls visit(x, y, sample) for each that meets a
// surface. The grid of sampleVisibleReceivers, at any step (1: every pixel). `geometry` as there.
void forEachVisibleReceiver(const Scene& scene, uint32_t width, uint32_t height, uint32_t step,
                            const std::function<void(uint32_t x, uint32_t y, const ReceiverSample& sample)>& visit,
                            const LazyTriangleBvh* geometry = nullptr);

// Whether `view` (of `plan`, lit by packed light `light`) shades `sample`, and the resolution it
// needs there (texels a side, see the top of this file); 0 when it does not shade it.
float resolutionNeededAt(const ShadowPlan& plan, uint32_t view, const gpu::GpuPunctualLight& light,
                         const ReceiverSample& sample);

// The demand of every view of `plan`, in plan order: the largest resolutionNeededAt over the
// samples, 0 for a view that shades none.
std::vector<float> shadowViewDemand(const ShadowPlan& plan, const FrameLights& lights,
                                    const VisibleReceivers& receivers);

// The power-of-two tier of a demand: the nearest power of two in log scale (so the density at the
// most demanding receiver is within sqrt 2 of one texel per pixel), clamped to [minTier, maxTier];
// 0 for a demand of 0.
uint32_t shadowTierFor(float demand, uint32_t minTier, uint32_t maxTier);

// The tier of a demand in a sequence whose previous frame gave the view `previousTier` (0: none),
// with `octaves` of hysteresis (--shadow-hysteresis): a view goes up to a finer tier as soon as the
// nearest tier is finer, but keeps its finer previous tier while the demand stays above
// previous / 2^(1/2 + octaves), so that a demand that wanders about a tier's boundary (a camera
// walking past the distance where the nearest tier changes) does not switch the view's
// resolution back and forth. It never gives a view less than its nearest tier (measured: a
// hysteresis that also held coarser tiers cost accuracy and flipped more, bench/RESULTS.md); it
// costs memory instead. Without hysteresis or a previous tier, shadowTierFor.
uint32_t shadowTierWithHysteresis(float demand, uint32_t previousTier, float octaves, uint32_t minTier, uint32_t maxTier);

}  // namespace punctual
