// The built-in engine: deterministic, the thin parts it exists for (fins a few pixels thick at
// 1280x720 with gaps between them, grille bars), 64 + 32 generated lamps, and lamps that light
// what the camera sees. Measured on the scene's own objects and lights.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "scene/engine_scene.h"
#include "scene/light_reach.h"
#include "scene_test_support.h"

namespace punctual {
namespace {

using namespace engine_scene;

const Scene& engine() {
    static const Scene scene = makeEngineScene();
    return scene;
}

std::vector<Bounds> boundsOf(const Scene& scene, const std::string& name) {
    std::vector<Bounds> found;
    for (const Object& object : scene.objects) {
        if (object.name.find(name) != std::string::npos) found.push_back(object.worldBounds);
    }
    return found;
}

TEST(EngineScene, Deterministic) {
    EXPECT_EQ(testing::firstSceneDifference(makeEngineScene(), makeEngineScene()), "");
}

// Each cylinder's fins are 6 mm thick with gaps of 14 mm between them: thin casters over thin
// gaps, the case a whole view's one resolution cannot serve everywhere.
TEST(EngineScene, FinsAreThinWithGapsBetweenThem) {
    std::vector<Bounds> fins = boundsOf(engine(), "cooling fin");
    ASSERT_EQ(fins.size(), size_t(kCylinders) * kFinsPerCylinder);
    std::sort(fins.begin(), fins.end(), [](const Bounds& a, const Bounds& b) {
        return a.min.x != b.min.x ? a.min.x < b.min.x : a.min.y < b.min.y;
    });
    for (size_t i = 0; i < fins.size(); ++i) {
        EXPECT_NEAR(fins[i].max.y - fins[i].min.y, 0.006f, 1e-5f) << i;
        if (i % kFinsPerCylinder == 0) continue;  // the next cylinder's first fin
        EXPECT_NEAR(fins[i].min.y - fins[i - 1].max.y, 0.014f, 1e-5f) << i;
        EXPECT_GT(fins[i].max.x - fins[i].min.x, 30.0f * (fins[i].max.y - fins[i].min.y)) << i;  // a plate, not a bar
    }
    const std::vector<Bounds> bars = boundsOf(engine(), "grille bar");
    ASSERT_EQ(bars.size(), size_t(kGrilleBars));
    for (const Bounds& bar : bars) EXPECT_NEAR(bar.max.z - bar.min.z, kGrilleBarWidth, 1e-5f);
}

// In view, and thin there: every fin's centre projects inside the frame, at 1.5 to 4 pixels of
// thickness at 1280x720 (the fin's 6 mm over the pixel's size at its distance).
TEST(EngineScene, TheCameraSeesTheFinsAFewPixelsThick) {
    const Scene& scene = engine();
    const glm::mat4 viewProjection = scene.camera.projection(16.0f / 9.0f) * scene.camera.view;
    const float pixelPerMetreAtOne = 720.0f / (2.0f * std::tan(0.5f * scene.camera.yfov));
    size_t seen = 0;
    for (const Bounds& fin : boundsOf(scene, "cooling fin")) {
        const glm::vec3 centre = 0.5f * (fin.min + fin.max);
        const glm::vec4 clip = viewProjection * glm::vec4(centre, 1.0f);
        ASSERT_GT(clip.w, 0.0f);
        EXPECT_LE(std::abs(clip.x / clip.w), 1.0f);
        EXPECT_LE(std::abs(clip.y / clip.w), 1.0f);
        const float distance = -(scene.camera.view * glm::vec4(centre, 1.0f)).z;
        const float pixels = kFinThickness * pixelPerMetreAtOne / distance;
        EXPECT_GE(pixels, 1.5f);
        EXPECT_LE(pixels, 4.0f);
        ++seen;
    }
    EXPECT_EQ(seen, size_t(kCylinders) * kFinsPerCylinder);
}

TEST(EngineScene, SixtyFourSpotsAndThirtyTwoPointsLightWhatTheCameraSees) {
    const Scene& scene = engine();
    EXPECT_EQ(scene.source, kSource);
    size_t spots = 0;
    size_t points = 0;
    for (const Light& light : scene.lights) {
        spots += light.type == LightType::Spot;
        points += light.type == LightType::Point;
        EXPECT_TRUE(light.castsShadow) << light.name;
    }
    EXPECT_EQ(spots, kSpots);
    EXPECT_EQ(points, kPoints);
    const LightReach reach(scene);
    ASSERT_FALSE(reach.empty());
    size_t reaching = 0;
    for (const Light& light : scene.lights) reaching += reach.reaches(light);
    EXPECT_GE(double(reaching), 0.95 * double(scene.lights.size())) << reaching;
}

}  // namespace
}  // namespace punctual
