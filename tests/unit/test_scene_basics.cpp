#include <gtest/gtest.h>

#include "scene/scene.h"

namespace punctual {
namespace {

TEST(Bounds, TransformedCornersEnclosed) {
    Bounds b;
    b.extend(glm::vec3(-1.0f, 0.0f, 0.0f));
    b.extend(glm::vec3(1.0f, 2.0f, 3.0f));
    glm::mat4 translate(1.0f);
    translate[3] = glm::vec4(10.0f, 0.0f, 0.0f, 1.0f);
    const Bounds t = b.transformed(translate);
    EXPECT_FLOAT_EQ(t.min.x, 9.0f);
    EXPECT_FLOAT_EQ(t.max.x, 11.0f);
    EXPECT_FLOAT_EQ(t.max.z, 3.0f);
}

TEST(DerivedRange, IlluminanceAtRangeIsCutoff) {
    const float range = derivedRange(100.0f, glm::vec3(1.0f));
    EXPECT_NEAR(100.0f / (range * range), kInfiniteRangeCutoffLux, 1e-6f);
}

TEST(FitCamera, BoundsCentreProjectsToImageCentre) {
    Bounds b;
    b.extend(glm::vec3(-5.0f, 0.0f, -5.0f));
    b.extend(glm::vec3(5.0f, 3.0f, 5.0f));
    const Camera camera = fitCameraToBounds(b);
    const glm::vec4 clip = camera.projection(16.0f / 9.0f) * camera.view * glm::vec4(b.center(), 1.0f);
    EXPECT_NEAR(clip.x / clip.w, 0.0f, 1e-5f);
    EXPECT_NEAR(clip.y / clip.w, 0.0f, 1e-5f);
    EXPECT_GT(clip.z / clip.w, 0.0f);
    EXPECT_LT(clip.z / clip.w, 1.0f);
}

}  // namespace
}  // namespace punctual
