// Depth precision at any near plane (glTF allows any znear > 0): the camera uses reversed Z (depth
// 1 at the near plane, 0 at the far one) into a 32-bit float depth buffer, whose relative precision
// then holds at every distance. With the usual mapping (0 at near) a near plane of 1e-6 m pushed
// the depth of everything beyond ~17 m to exactly 1.0, the clear value: those pixels failed the
// depth test and stayed black, and the culling kernels took them for background.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "culling.h"
#include "gpu_test_support.h"
#include "render/renderer.h"
#include "scene/default_scene.h"

namespace punctual {
namespace {

using render::LightListMethod;

struct Frame {
    ImageRgba8 image;
    std::vector<float> depth;
    glm::vec2 depthToView;
};

Frame renderFrame(vk::Context& context, const Scene& scene, LightListMethod method) {
    render::RenderSettings settings = testing::renderSettings(320, 180);
    settings.method = method;
    render::Renderer renderer(context, scene, settings);
    Frame frame;
    frame.image = renderer.render(1, 0).image;
    frame.depth = renderer.readDepth();
    frame.depthToView = glm::vec2(renderer.projection()[3][2], renderer.projection()[2][2]);
    return frame;
}

// Pixels whose 3x3 neighbourhood holds background or a view-distance jump above 3%: where two
// surfaces meet, which one a pixel shows may differ between depth mappings (they round the two
// surfaces' depths differently).
std::vector<uint8_t> edgePixels(const Frame& frame) {
    const int width = int(frame.image.width);
    const int height = int(frame.image.height);
    std::vector<uint8_t> edge(size_t(width) * size_t(height), 0);
    auto distance = [&](size_t i) { return gpu::viewDistanceFromDepth(frame.depth[i], frame.depthToView); };
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const size_t centre = size_t(y) * size_t(width) + size_t(x);
            for (int dy = -1; dy <= 1 && !edge[centre]; ++dy) {
                for (int dx = -1; dx <= 1; ++dx) {
                    const size_t i = size_t(std::clamp(y + dy, 0, height - 1)) * size_t(width) +
                                     size_t(std::clamp(x + dx, 0, width - 1));
                    if (gpu::isBackgroundDepth(frame.depth[i]) || gpu::isBackgroundDepth(frame.depth[centre]) ||
                        std::abs(distance(i) - distance(centre)) > 0.03f * distance(centre)) {
                        edge[centre] = 1;
                        break;
                    }
                }
            }
        }
    }
    return edge;
}

TEST(DepthPrecision, TinyNearPlaneRendersLikeTheUsualOne) {
    auto context = testing::makeValidatedContext();
    Scene scene = makeDefaultScene();
    ASSERT_FLOAT_EQ(scene.camera.znear, 0.1f) << "the default camera's near plane; nothing in view is nearer";
    const Frame usual = renderFrame(*context, scene, LightListMethod::Tiled);
    testing::saveTestImage("depth-precision-znear-0.1", usual.image);
    const std::vector<uint8_t> edge = edgePixels(usual);
    const size_t pixels = size_t(usual.image.width) * usual.image.height;
    size_t usualLit = 0;
    size_t usualBackground = 0;
    for (size_t p = 0; p < pixels; ++p) {
        const uint8_t* u = &usual.image.pixels[4 * p];
        usualLit += u[0] > 0 || u[1] > 0 || u[2] > 0;
        usualBackground += gpu::isBackgroundDepth(usual.depth[p]);
    }
    ASSERT_GT(usualLit, pixels / 2) << "the default view should be mostly lit";

    for (const float znear : {1e-4f, 1e-6f}) {
        scene.camera.znear = znear;
        const std::string what = "znear " + std::to_string(znear);
        const Frame tiny = renderFrame(*context, scene, LightListMethod::Tiled);
        testing::saveTestImage("depth-precision-znear-" + std::to_string(znear), tiny.image);
        size_t edgeCount = 0;
        size_t differing = 0;       // off the edges, some channel more than 1/255 apart
        size_t wentBlack = 0;       // lit with the usual near plane, black with the tiny one
        size_t background = 0;
        for (size_t p = 0; p < pixels; ++p) {
            const uint8_t* u = &usual.image.pixels[4 * p];
            const uint8_t* t = &tiny.image.pixels[4 * p];
            const bool lit = u[0] > 0 || u[1] > 0 || u[2] > 0;
            wentBlack += lit && t[0] == 0 && t[1] == 0 && t[2] == 0;
            background += gpu::isBackgroundDepth(tiny.depth[p]);
            edgeCount += edge[p];
            if (edge[p]) continue;
            int worst = 0;
            for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(int(u[c]) - int(t[c])));
            differing += worst > 1;
        }
        EXPECT_EQ(wentBlack, 0u) << what << ": lit pixels gone black, of " << usualLit;
        EXPECT_EQ(differing, 0u) << what << ": pixels off the edges more than 1/255 apart, of " << pixels - edgeCount;
        EXPECT_EQ(background, usualBackground) << what << ": background pixels (depth at the clear value)";
        EXPECT_LT(edgeCount, pixels / 5) << "the edge band should be a small part of the frame";
        std::printf("[ depth    ] %s: %zu of %zu pixels differ off the edges (%zu edge pixels), %zu lit pixels black\n",
                    what.c_str(), differing, pixels - edgeCount, edgeCount, wentBlack);

        // The light lists stay exact at that near plane: every light-grid method equals brute
        // force bit for bit.
        const Frame brute = renderFrame(*context, scene, LightListMethod::Brute);
        EXPECT_TRUE(tiny.image.pixels == brute.image.pixels) << what << ": tiled differs from brute force";
        for (LightListMethod method : render::gridMethods()) {
            if (method == LightListMethod::Tiled) continue;  // `tiny`, just compared
            EXPECT_TRUE(renderFrame(*context, scene, method).image.pixels == brute.image.pixels)
                << what << ": " << render::methodName(method) << " differs from brute force";
        }
    }
    testing::expectNoValidationMessages(*context);
}

}  // namespace
}  // namespace punctual
