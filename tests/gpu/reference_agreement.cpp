#include "reference_agreement.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "culling.h"
#include "gpu_test_support.h"
#include "render/renderer.h"

namespace punctual::testing {

using reference::SurfaceHit;

Agreement compare(const ImageRgba8& gpu, const std::vector<float>& depth, const glm::mat4& projection,
                  const ImageRgba8& ref, const std::vector<SurfaceHit>& hits, const std::string& name, int tolerance) {
    const int width = int(gpu.width), height = int(gpu.height);
    // View distance from depth (culling.h): a / (depth + b) with a = P[3][2], b = P[2][2].
    auto viewDistance = [&](size_t i) { return projection[3][2] / (depth[i] + projection[2][2]); };
    auto onSilhouette = [&](int x, int y) {
        const size_t centre = size_t(y) * size_t(width) + size_t(x);
        for (int dy = -1; dy <= 1; ++dy) {
            for (int dx = -1; dx <= 1; ++dx) {
                const int nx = std::clamp(x + dx, 0, width - 1), ny = std::clamp(y + dy, 0, height - 1);
                const size_t i = size_t(ny) * size_t(width) + size_t(nx);
                if (gpu::isBackgroundDepth(depth[i]) || gpu::isBackgroundDepth(depth[centre]) || !hits[i].hit || !hits[centre].hit) return true;
                if (std::abs(viewDistance(i) - viewDistance(centre)) > 0.03f * viewDistance(centre)) return true;
                if (hits[i].object != hits[centre].object) return true;
                if (glm::dot(hits[i].geometricNormal, hits[centre].geometricNormal) < 0.99f) return true;
            }
        }
        return false;
    };
    Agreement result;
    ImageRgba8 diff = gpu;
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const uint8_t* g = gpu.at(uint32_t(x), uint32_t(y));
            const uint8_t* r = ref.at(uint32_t(x), uint32_t(y));
            int worst = 0;
            for (int c = 0; c < 4; ++c) worst = std::max(worst, std::abs(int(g[c]) - int(r[c])));
            ++result.pixels;
            uint8_t* d = diff.at(uint32_t(x), uint32_t(y));
            const uint8_t shade = uint8_t(std::min(255, worst * 32));
            d[0] = d[1] = d[2] = shade;  // grey: the difference x 32
            if (worst <= tolerance) {
                ++result.within;
            } else if (onSilhouette(x, y)) {
                d[0] = 0, d[1] = 0, d[2] = 255;  // blue: differs on a silhouette (allowed)
            } else {
                ++result.offSilhouette;
                d[0] = 255, d[1] = 0, d[2] = 0;  // red: differs where it must not
            }
        }
    }
    saveTestImage(name + "-gpu", gpu);
    saveTestImage(name + "-reference", ref);
    saveTestImage(name + "-diff", diff);
    return result;
}

GpuFrame renderGpu(vk::Context& context, const Scene& scene, uint32_t width, uint32_t height) {
    render::RenderSettings settings = renderSettings(width, height);
    settings.method = render::LightListMethod::Brute;
    settings.shadows.enabled = false;  // compared with the unshadowed reference
    render::Renderer renderer(context, scene, settings);
    GpuFrame frame{renderer.render(1, 0).image, {}, renderer.projection()};
    frame.depth = renderer.readDepth();
    return frame;
}

void expectAgreement(const Agreement& agreement, const std::string& what) {
    EXPECT_GE(agreement.withinFraction(), 0.999) << what << ": " << agreement.pixels - agreement.within << " of "
                                                 << agreement.pixels << " pixels differ by more than 2/255";
    EXPECT_EQ(agreement.offSilhouette, 0u) << what << ": differing pixels away from silhouettes";
}

}  // namespace punctual::testing
