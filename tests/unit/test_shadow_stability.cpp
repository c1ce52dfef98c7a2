// Temporal stability (reference/shadow_stability.h): pixels reproject onto themselves between
// identical frames, and a flip is counted exactly where a static point under an unmoved light kept
// its ray-traced truth but changed its GPU state; a changed truth, a moved light or a moved
// receiver is not compared. Synthetic frames: a camera 5 m above the plane z = 0, looking down.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "reference/shadow_stability.h"

namespace punctual::reference {
namespace {

constexpr uint32_t kWidth = 16;
constexpr uint32_t kHeight = 9;

// The frame of a camera at `eye` looking straight down -z at the plane z = 0, every pixel covered
// (its position where its centre's ray meets the plane), one light (scene index 0) whose every
// verdict is `verdict`.
StabilityFrame planeFrame(glm::vec3 eye, PixelVerdict verdict) {
    Scene scene;
    scene.camera.view = glm::lookAtRH(eye, eye - glm::vec3(0.0f, 0.0f, 1.0f), glm::vec3(0.0f, 1.0f, 0.0f));
    scene.camera.yfov = 0.8f;
    scene.camera.znear = 0.1f;
    scene.camera.zfar = 20.0f;
    Light light;
    light.type = LightType::Point;
    light.position = glm::vec3(0.0f, 0.0f, 3.0f);
    light.range = 10.0f;
    scene.lights = {light};
    ShadowFactorImage factors;
    factors.width = kWidth;
    factors.height = kHeight;
    const glm::mat4 inverse = glm::inverse(scene.camera.projection(float(kWidth) / float(kHeight)) * scene.camera.view);
    for (uint32_t y = 0; y < kHeight; ++y) {
        for (uint32_t x = 0; x < kWidth; ++x) {
            const glm::vec2 ndc((float(x) + 0.5f) / kWidth * 2.0f - 1.0f, (float(y) + 0.5f) / kHeight * 2.0f - 1.0f);
            const glm::vec4 nearPoint = inverse * glm::vec4(ndc, 1.0f, 1.0f);  // reversed Z: 1 at the near plane
            const glm::vec3 a = glm::vec3(nearPoint) / nearPoint.w;
            const glm::vec3 direction = glm::normalize(a - eye);
            factors.positions.push_back(eye + direction * (-eye.z / direction.z));
            factors.covered.push_back(1);
        }
    }
    ShadowValidation validation;
    LightShadowValidation lightValidation;
    lightValidation.sceneLight = 0;
    lightValidation.verdicts.assign(size_t(kWidth) * kHeight, verdict);
    validation.lights.push_back(lightValidation);
    return stabilityFrame(scene, factors, validation);
}

TEST(ShadowStability, IdenticalFramesCompareEveryPixelWithNoFlip) {
    const StabilityFrame frame = planeFrame(glm::vec3(0.0f, 0.0f, 5.0f), PixelVerdict::AgreeLit);
    const ShadowFlips flips = countShadowFlips(frame, frame);
    EXPECT_EQ(flips.compared, uint64_t(kWidth) * kHeight);  // every pixel found itself
    EXPECT_EQ(flips.flips, 0u);
}

TEST(ShadowStability, AFlipIsAChangedGpuStateUnderAnUnchangedTruth) {
    const StabilityFrame before = planeFrame(glm::vec3(0.0f, 0.0f, 5.0f), PixelVerdict::AgreeLit);
    StabilityFrame after = before;
    after.verdicts[0][5] = PixelVerdict::FalseShadow;  // truth lit as before, GPU now dark: a flip
    after.verdicts[0][6] = PixelVerdict::AgreeShadow;  // truth changed: not compared
    after.verdicts[0][7] = PixelVerdict::NotCompared;  // the light does not reach: not compared
    const ShadowFlips flips = countShadowFlips(before, after);
    EXPECT_EQ(flips.compared, uint64_t(kWidth) * kHeight - 2);
    EXPECT_EQ(flips.flips, 1u);
    EXPECT_DOUBLE_EQ(flips.rate(), 1.0 / double(kWidth * kHeight - 2));
}

// A pixel beside an edge of the previous frame's shadow (a neighbour dark where it is lit) is not
// compared: the sub-pixel offset between the two samples may cross the edge with nothing changed.
TEST(ShadowStability, PointsOnAnEdgeOfThePreviousFrameAreNotCompared) {
    StabilityFrame before = planeFrame(glm::vec3(0.0f, 0.0f, 5.0f), PixelVerdict::AgreeLit);
    const size_t centre = 4 * kWidth + 8;
    before.verdicts[0][centre + 1] = PixelVerdict::AgreeShadow;  // an edge right of the centre
    StabilityFrame after = before;
    after.verdicts[0][centre] = PixelVerdict::FalseShadow;
    const ShadowFlips flips = countShadowFlips(before, after);
    EXPECT_EQ(flips.flips, 0u);
    // Every pixel of the 3 x 3 around the dark one is on its edge, and the dark one too.
    EXPECT_EQ(flips.compared, uint64_t(kWidth) * kHeight - 9);
}

TEST(ShadowStability, AMovedLightOrReceiverIsNotCompared) {
    const StabilityFrame before = planeFrame(glm::vec3(0.0f, 0.0f, 5.0f), PixelVerdict::AgreeLit);
    StabilityFrame moved = planeFrame(glm::vec3(0.0f, 0.0f, 5.0f), PixelVerdict::FalseShadow);
    moved.lights[0].position.x += 0.5f;
    EXPECT_EQ(countShadowFlips(before, moved).compared, 0u);
    // The receiver moved 1 m towards the camera (many pixels' size): nothing is the same point.
    StabilityFrame lifted = before;
    for (glm::vec3& p : lifted.positions) p.z += 1.0f;
    EXPECT_EQ(countShadowFlips(before, lifted).compared, 0u);
}

// The camera slid half a metre along x: the plane's points are still seen, by other pixels, and
// the ones seen in both frames are compared, none flipped.
TEST(ShadowStability, PixelsReprojectIntoTheOtherCamera) {
    const StabilityFrame before = planeFrame(glm::vec3(0.0f, 0.0f, 5.0f), PixelVerdict::AgreeShadow);
    const StabilityFrame after = planeFrame(glm::vec3(0.5f, 0.0f, 5.0f), PixelVerdict::AgreeShadow);
    const ShadowFlips flips = countShadowFlips(before, after);
    EXPECT_GT(flips.compared, uint64_t(kWidth) * kHeight / 2);
    EXPECT_LT(flips.compared, uint64_t(kWidth) * kHeight);  // the column that slid in was not seen before
    EXPECT_EQ(flips.flips, 0u);
}

// Flips are told apart by whether the light's maps changed resolution between the frames: the
// point light's six faces, one of them a tier finer in the second frame, make both flips "resized";
// with the same faces, neither is. recordMapResolutions reads them from the plan.
TEST(ShadowStability, FlipsUnderAResizedMapAreToldApart) {
    const StabilityFrame before = planeFrame(glm::vec3(0.0f, 0.0f, 5.0f), PixelVerdict::AgreeLit);
    StabilityFrame after = before;
    after.verdicts[0][5] = PixelVerdict::FalseShadow;
    after.verdicts[0][40] = PixelVerdict::FalseShadow;
    ShadowPlan plan;
    for (uint32_t face = 0; face < 6; ++face) {
        ShadowView view;
        view.isPoint = true;
        view.face = face;
        view.packedLight = 0;
        view.resolution = 256;
        plan.views.push_back(view);
    }
    StabilityFrame first = before;
    recordMapResolutions(first, plan, {0u}, std::nullopt);
    EXPECT_EQ(first.mapResolutions.at(0), std::vector<uint32_t>(6, 256u));
    StabilityFrame same = after;
    recordMapResolutions(same, plan, {0u}, std::nullopt);
    ShadowFlips flips = countShadowFlips(first, same);
    EXPECT_EQ(flips.flips, 2u);
    EXPECT_EQ(flips.flipsWhereMapsResized, 0u);
    plan.views[3].resolution = 512;
    StabilityFrame resized = after;
    recordMapResolutions(resized, plan, {0u}, std::nullopt);
    flips = countShadowFlips(first, resized);
    EXPECT_EQ(flips.flips, 2u);
    EXPECT_EQ(flips.flipsWhereMapsResized, 2u);
}

}  // namespace
}  // namespace punctual::reference
