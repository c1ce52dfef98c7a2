#pragma once
// Per-object light lists, the CPU side of Unity's classic forward path: every drawn object gets at
// most PUNCTUAL_MAX_LIGHTS_PER_OBJECT of the frame's spot/point lights, the ones estimated to
// contribute most to it, and the forward shader loops over that short list instead of all lights.
//
// Candidates: a light is a candidate for an object when its lit region may meet the object's world
// AABB (lightMayReachBox, conservative: it never rejects a light that lights any point of the box).
// Ranking: estimatedContribution (see below). An object with at most 8 candidates gets all of them,
// in ascending packed order, so its shading sum is bit-identical to the brute-force loop (the
// lights left out contribute exactly 0 there). An object with more loses the weakest ones.
#include <cstdint>
#include <vector>

#include "gpu_types.h"
#include "lights/light_setup.h"
#include "scene/scene.h"

namespace punctual {

// The value of a list slot past counts[o].
constexpr uint32_t kUnusedLightSlot = 0xFFFFFFFFu;

struct PerObjectLightLists {
    // For object o: lights[o * PUNCTUAL_MAX_LIGHTS_PER_OBJECT + k], k < counts[o], are indices into
    // FrameLights::packed, sorted ASCENDING (so the forward shader sums them in the same order as
    // the brute-force loop, and an object reached by <= 8 lights gets a bit-identical result).
    std::vector<uint32_t> lights;   // objectCount * 8 entries; unused slots hold kUnusedLightSlot
    std::vector<uint32_t> counts;   // objectCount
    uint32_t objectsOverCap = 0;    // objects reached by more than 8 lights (their lists lose light)
    uint32_t maxCandidates = 0;     // the most lights that reached any one object before the cap
};

// Builds the lists for every scene object from its Object::worldBounds (Scene::computeBounds must
// have run). Deterministic: the same input gives the same output bit for bit.
PerObjectLightLists buildPerObjectLightLists(const Scene& scene, const FrameLights& frameLights);

// Conservative reach test of a packed light against an axis-aligned box: false only when the
// light's attenuation (gpu::punctualAttenuation) is 0 at every point of the box. Tests, all exact
// up to a float-rounding slack of about 1e-5 relative: the range sphere against the box; for
// spots also the bounding sphere of the cone (as lightBoundingSphere) and a plane tangent to the
// cone through its apex (rejects boxes beside or behind the cone). An empty box is never reached.
bool lightMayReachBox(const gpu::GpuPunctualLight& light, const Bounds& box);

// The bounding sphere of a packed light's lit region, recovered from the packed fields: the same
// sphere as lightBoundingSphere(Light) up to float rounding (range from 1/sqrt(invRangeSq), cos of
// the outer angle from -angleOffsetShadow.x / directionAngleScale.w).
BoundingSphere packedLightBoundingSphere(const gpu::GpuPunctualLight& light);

// Estimated contribution of a packed light to an axis-aligned box, used for ranking; 0 when the
// light cannot reach the box at all (lightMayReachBox false), > 0 otherwise unless the light is
// black or only grazes the box within the rounding slack of the range. With x the point of the box
// closest to the light and c the box centre:
//   contribution = peak radiant intensity (max channel of radiantColor.rgb)
//                x distanceAttenuation(max(|x - light|^2, 1e-4), invRangeSq)
//                x angular factor (spots only; 1 for points):
//                  max(spotAttenuation towards x, spotAttenuation towards c), and 0.05 when both
//                  are 0 although the cone reaches the box (a grazing spot ranks after aimed ones);
//                  1 when the light is inside the box.
// The 1 cm distance clamp (the shader's own) makes lights inside the box rank by intensity.
float estimatedContribution(const gpu::GpuPunctualLight& light, const Bounds& box);

}  // namespace punctual
