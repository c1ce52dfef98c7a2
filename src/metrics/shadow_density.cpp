#include "metrics/shadow_density.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "lights/shadow_resolution.h"
#include "metrics/heatmap.h"
#include "shadows.h"

namespace punctual {
namespace {

// The colour scale: log2 density from -3 (1/8) to +3 (8) in steps of 1/100, so the heat map's
// integer scale 0..600 holds it with 1 (log2 = 0) at 300.
constexpr float kScaleStepsPerOctave = 100.0f;
constexpr float kLowestOctave = -3.0f;
constexpr uint32_t kScaleMax = 600;

}  // namespace

ShadowDensityImage computeShadowDensity(const Scene& scene, const FrameLights& lights, const ShadowPlan& plan,
                                        uint32_t width, uint32_t height) {
    ShadowDensityImage image;
    image.width = width;
    image.height = height;
    image.density.assign(size_t(width) * height, 0.0f);
    // The first view of each shadowed light (a point light's six follow it).
    std::vector<uint32_t> firstViews;
    for (uint32_t v = 0; v < plan.views.size(); ++v) {
        if (!plan.views[v].isPoint || plan.views[v].face == 0) firstViews.push_back(v);
    }
    forEachVisibleReceiver(scene, width, height, 1, [&](uint32_t x, uint32_t y, const ReceiverSample& sample) {
        float smallest = 0.0f;
        for (uint32_t first : firstViews) {
            const gpu::GpuPunctualLight& light = lights.packed[plan.views[first].packedLight];
            const glm::vec3 lightPosition(light.positionInvRangeSq);
            const uint32_t view =
                plan.views[first].isPoint ? first + gpu::cubeFaceOfDirection(sample.position - lightPosition) : first;
            if (!plan.views[view].rendered()) continue;
            const float needed = resolutionNeededAt(plan, view, light, sample);
            if (!(needed > 0.0f)) continue;
            // The resolution the receiver reads: the view's, or its virtual level's there.
            const glm::vec3 axis = plan.views[view].isPoint ? gpu::cubeFaceAxis(plan.views[view].face)
                                                            : glm::vec3(light.directionAngleScale);
            const float depth = std::abs(glm::dot(sample.position - lightPosition, axis));
            const float density = shadowResolutionRead(plan, view, depth, sample.position) / needed;
            smallest = smallest > 0.0f ? std::min(smallest, density) : density;
        }
        image.density[size_t(y) * width + x] = smallest;
    });
    return image;
}

ImageRgba8 renderShadowDensity(const ShadowDensityImage& image, const std::string& title) {
    std::vector<uint32_t> scaled(image.density.size(), 0);
    std::vector<uint8_t> background(image.density.size(), 0);
    double logSum = 0.0;
    size_t reached = 0;
    size_t under = 0;  // below half a texel per pixel: visibly blocky
    for (size_t i = 0; i < image.density.size(); ++i) {
        const float density = image.density[i];
        if (!(density > 0.0f)) {
            background[i] = 1;
            continue;
        }
        const float octaves = std::log2(density);
        logSum += double(octaves);
        ++reached;
        under += density < 0.5f;
        const float step = std::round((octaves - kLowestOctave) * kScaleStepsPerOctave);
        scaled[i] = uint32_t(std::clamp(step, 0.0f, float(kScaleMax)));
    }
    HeatmapOptions options;
    options.maxValue = kScaleMax;
    options.title = title;
    options.ticks = {{0, "1/8"}, {100, "1/4"}, {200, "1/2"}, {300, "1"}, {400, "2"}, {500, "4"}, {600, "8"}};
    char stats[128];
    if (reached == 0) {
        std::snprintf(stats, sizeof(stats), "no pixel reached by a shadowed light");
    } else {
        std::snprintf(stats, sizeof(stats), "geometric mean %.2f, %.1f%% of pixels below 1/2", std::exp2(logSum / double(reached)),
                      100.0 * double(under) / double(reached));
    }
    options.statsText = stats;
    return renderHeatmap(scaled, background, image.width, image.height, options);
}

}  // namespace punctual
