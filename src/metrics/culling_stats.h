#pragma once
// Culling statistics from the forward shader's per-pixel light counts: how many lights each pixel
// walks, how many really reach it, and how much light a method loses.
#include <cstdint>
#include <vector>

namespace punctual {

// Per pixel, from the forward shader's statistics variant (rows top to bottom).
struct LightStatsImage {
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<uint32_t> tested;        // lights the method made this pixel evaluate
    std::vector<uint32_t> affecting;     // lights with attenuation x cone > 0 at this pixel
    std::vector<uint32_t> shadowLookups; // filtered shadow-map reads the method's lights took here
    std::vector<uint32_t> shadowTaps;    // texture instructions those reads issued
    std::vector<uint8_t> covered;        // 1 where geometry is, 0 for background
    std::vector<float> methodLuminance;  // luminance of the method's radiance
    std::vector<float> bruteLuminance;   // luminance of the brute-force radiance
    // Per pixel, sums over the transparent (alphaMode BLEND) fragments drawn there.
    std::vector<uint32_t> transparentTested;
    std::vector<uint32_t> transparentAffecting;
    std::vector<uint32_t> transparentFragments;
    std::vector<uint32_t> transparentMissingLight;  // fragments whose method radiance fell short of brute force's
    // Per opaque pixel, its list cell: the key its method's list is a function of (forward.frag,
    // pixelListCell: the tile, the cluster, the tile and z-bin, the object).
    std::vector<uint32_t> listCells;
    // Per list cell, the lights that reach at least one of its opaque pixels (the union of their
    // masks, gathered on the GPU): the cell's exact list.
    std::vector<uint32_t> cellReachingLights;
};

struct CullingStats {
    double testedPerPixel = 0.0;     // mean over covered pixels of the light-list length walked
    double affectingPerPixel = 0.0;  // mean over covered pixels of the lights that reach them
    double shadowLookupsPerPixel = 0.0;  // mean over covered pixels
    double shadowTapsPerPixel = 0.0;     // mean over covered pixels
    uint32_t maxTested = 0;
    uint32_t maxAffecting = 0;
    // tested / affecting: 1 is a perfect list; brute force is lights / affecting.
    double efficiency = 0.0;
    // The efficiency of exact lists at the method's granularity: each list cell's list the lights
    // that reach at least one of its covered pixels, so a pixel tests its cell's union. No
    // conservative method of that granularity tests fewer; efficiency / floorEfficiency is how far
    // a method's shapes and depth tests are from it, floorEfficiency - 1 what the cells' size costs.
    // 0 where the image has no masks.
    double floorEfficiency = 0.0;
    // 1 - (sum of the method's luminance) / (sum of brute force's): the share of radiance the
    // method's lists lose (0 for every conservative method, > 0 for per-object over its cap).
    double missedEnergy = 0.0;
    // Covered pixels where the method's luminance is below brute force's by more than 1e-6
    // relative: where light went missing.
    uint64_t pixelsMissingLight = 0;
    uint64_t coveredPixels = 0;
    // The transparent fragments: shaded like pixels, and as able to miss lights (tiled depth
    // bounds come from the opaque depth unless the transparent depth span widens them).
    uint64_t transparentFragments = 0;
    double transparentTestedPerFragment = 0.0;
    double transparentAffectingPerFragment = 0.0;
    uint64_t transparentFragmentsMissingLight = 0;
};

CullingStats computeCullingStats(const LightStatsImage& image);

}  // namespace punctual
