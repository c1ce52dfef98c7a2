#pragma once
// Shadow validation: the GPU's shadow factor at every pixel, for every shadowed light, against
// Embree's ray-cast visibility from the same surface point.
//
// A pixel counts for a light only where the light reaches it: attenuation > 0 and the surface
// faces the light (N.L > 0; facing away it receives nothing, shadow or not). The GPU says
// "dark" when its filtered factor is below 0.5. Two kinds of disagreement:
//   false_shadow: GPU dark, ray lit (acne, over-darkening);
//   false_lit:    GPU lit, ray blocked (light leaks, peter-panning).
// Near a shadow's edge a shadow map cannot be exact: its texels are finite and its filters blur.
// A pixel is in the edge band when the ray-traced visibility changes within the band's width of
// the point, probed by four more rays; every count is also given with that band excluded. The
// width is one shadow texel (its world size at the pixel, as the bias computes it) by default. A
// texel band widens as texels grow and so hides the error of low resolutions: EdgeBand's
// screenPixels gives a band of fixed width on screen instead (--edge-band-px N), which compares
// resolutions fairly. misclassified() counts every compared pixel, no band excluded.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "lights/shadow_setup.h"
#include "metrics/shadow_factor_image.h"
#include "reference/embree_scene.h"

namespace punctual::reference {

// Per pixel, what the comparison found for one light.
enum class PixelVerdict : uint8_t { NotCompared, AgreeLit, AgreeShadow, FalseShadow, FalseLit };

struct ShadowCounts {
    uint64_t compared = 0;
    uint64_t falseShadow = 0;
    uint64_t falseLit = 0;
    uint64_t edgeBand = 0;  // compared pixels inside the edge band
    uint64_t comparedOutsideBand = 0;
    uint64_t falseShadowOutsideBand = 0;
    uint64_t falseLitOutsideBand = 0;

    void add(const ShadowCounts& other);
    // Counts one pixel's verdict (NotCompared counts nothing), inside or outside the edge band.
    void count(PixelVerdict verdict, bool inBand);
    // Misclassified share of the compared pixels outside the edge band.
    double misclassifiedOutsideBand() const;
    // Misclassified share of every compared pixel.
    double misclassified() const;
};

struct LightShadowValidation {
    uint32_t slot = 0;         // shadowed-light order: spots, then points
    uint32_t packedLight = 0;  // index into FrameLights::packed
    uint32_t sceneLight = 0;   // index into Scene::lights
    bool isPoint = false;
    ShadowCounts counts;
    std::vector<PixelVerdict> verdicts;  // per pixel
    std::vector<uint8_t> inBand;         // per pixel: 1 in the edge band
};

// The sun's cascaded shadow against rays towards the sun, at every pixel it reaches (N.L > 0,
// inside the shadow distance), per cascade (by the cascade the GPU read) and in the split band:
// pixels within one texel of where the selection changes cascade.
struct SunShadowValidation {
    uint32_t sceneLight = 0;
    ShadowCounts counts;
    std::vector<ShadowCounts> cascades;
    ShadowCounts splitBand;
    std::vector<PixelVerdict> verdicts;  // per pixel
    std::vector<uint8_t> inBand;         // per pixel: 1 in the edge band
};

struct ShadowValidation {
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<LightShadowValidation> lights;
    ShadowCounts spots;
    ShadowCounts points;
    std::optional<SunShadowValidation> sun;  // when the frame's sun has cascades
    ShadowCounts overall;                    // spots, points and the sun
};

// The edge band's width: one shadow texel (screenPixels = 0), or screenPixels screen pixels of the
// camera below, at the pixel's depth. In the surface's plane, a pixel's footprint stretches by
// 1 / cos(view angle) along the view's slant, and so do those probes.
struct EdgeBand {
    float screenPixels = 0.0f;
    glm::mat4 cameraView{1.0f};           // world -> view (looking down -Z)
    float pixelSpanAtUnitDepth = 0.0f;    // 2 tan(yfov / 2) / height (screenPixelWorldSize)

    // A band `pixels` wide on the screen of `camera` at a frame `height` pixels tall.
    static EdgeBand ofScreenPixels(float pixels, const Camera& camera, uint32_t height);
};

// Casts the rays in parallel (TBB); deterministic.
ShadowValidation validateShadows(const EmbreeScene& embree, const ShadowFactorImage& factors,
                                 const FrameLights& lights, const ShadowPlan& plan, const EdgeBand& band = {});

}  // namespace punctual::reference
