#include "metrics/culling_stats.h"

#include <algorithm>

#include "gpu_types.h"

namespace punctual {
namespace {

// Lights tested over the covered pixels if each list cell's list held exactly the lights that reach
// one of its pixels: each covered pixel tests its cell's union.
double exactListTested(const LightStatsImage& image) {
    if (image.listCells.size() != image.covered.size()) return 0.0;
    double tested = 0.0;
    for (size_t i = 0; i < image.covered.size(); ++i) {
        if (!image.covered[i]) continue;
        const uint32_t cell = image.listCells[i];
        if (cell < image.cellReachingLights.size()) tested += double(image.cellReachingLights[cell]);
    }
    return tested;
}

}  // namespace

CullingStats computeCullingStats(const LightStatsImage& image) {
    CullingStats stats;
    double tested = 0.0;
    double affecting = 0.0;
    double methodSum = 0.0;
    double bruteSum = 0.0;
    double lookups = 0.0;
    double taps = 0.0;
    for (size_t i = 0; i < image.covered.size(); ++i) {
        if (!image.covered[i]) continue;
        ++stats.coveredPixels;
        tested += image.tested[i];
        affecting += image.affecting[i];
        if (i < image.shadowLookups.size()) lookups += image.shadowLookups[i];
        if (i < image.shadowTaps.size()) taps += image.shadowTaps[i];
        stats.maxTested = std::max(stats.maxTested, image.tested[i]);
        stats.maxAffecting = std::max(stats.maxAffecting, image.affecting[i]);
        methodSum += double(image.methodLuminance[i]);
        bruteSum += double(image.bruteLuminance[i]);
        if (image.methodLuminance[i] < image.bruteLuminance[i] * (1.0f - 1e-6f)) ++stats.pixelsMissingLight;
    }
    if (stats.coveredPixels > 0) {
        stats.testedPerPixel = tested / double(stats.coveredPixels);
        stats.affectingPerPixel = affecting / double(stats.coveredPixels);
        stats.shadowLookupsPerPixel = lookups / double(stats.coveredPixels);
        stats.shadowTapsPerPixel = taps / double(stats.coveredPixels);
    }
    double transparentTested = 0.0;
    double transparentAffecting = 0.0;
    for (size_t i = 0; i < image.transparentFragments.size(); ++i) {
        stats.transparentFragments += image.transparentFragments[i];
        transparentTested += image.transparentTested[i];
        transparentAffecting += image.transparentAffecting[i];
        stats.transparentFragmentsMissingLight += image.transparentMissingLight[i];
    }
    if (stats.transparentFragments > 0) {
        stats.transparentTestedPerFragment = transparentTested / double(stats.transparentFragments);
        stats.transparentAffectingPerFragment = transparentAffecting / double(stats.transparentFragments);
    }
    stats.efficiency = affecting > 0.0 ? tested / affecting : 0.0;
    stats.floorEfficiency = affecting > 0.0 ? exactListTested(image) / affecting : 0.0;
    stats.missedEnergy = bruteSum > 0.0 ? std::max(0.0, 1.0 - methodSum / bruteSum) : 0.0;
    return stats;
}

}  // namespace punctual
