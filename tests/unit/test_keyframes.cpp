// Keyframe interpolation (scene/keyframes.h) against answers computed by hand from glTF 2.0's
// Appendix C: STEP holds, LINEAR blends, rotations take the shorter arc at constant speed,
// CUBICSPLINE follows the Hermite basis with tangents scaled by the interval; before the first
// keyframe and after the last the track holds its end values.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "scene/keyframes.h"

namespace punctual {
namespace {

KeyframeTrack track(Interpolation interpolation, uint32_t components, std::vector<float> times, std::vector<float> values,
                    bool rotation = false) {
    KeyframeTrack t;
    t.interpolation = interpolation;
    t.components = components;
    t.rotation = rotation;
    t.times = std::move(times);
    t.values = std::move(values);
    EXPECT_EQ(trackProblem(t), "");
    return t;
}

TEST(Keyframes, LinearBlendsBetweenTheKeyframesAroundTheTime) {
    const KeyframeTrack t = track(Interpolation::Linear, 3, {1.0f, 3.0f, 4.0f}, {0, 0, 0, 2, 4, -8, 3, 4, -8});
    // At 1.5: a quarter of the way from (0, 0, 0) to (2, 4, -8).
    EXPECT_EQ(sampleTrack(t, 1.5), (std::vector<float>{0.5f, 1.0f, -2.0f}));
    // At 3.5: halfway through the second interval.
    EXPECT_EQ(sampleTrack(t, 3.5), (std::vector<float>{2.5f, 4.0f, -8.0f}));
    // At a keyframe, its value exactly.
    EXPECT_EQ(sampleTrack(t, 3.0), (std::vector<float>{2.0f, 4.0f, -8.0f}));
}

TEST(Keyframes, BeforeTheFirstAndAfterTheLastTheEndValuesHold) {
    const KeyframeTrack t = track(Interpolation::Linear, 1, {1.0f, 2.0f}, {10.0f, 20.0f});
    EXPECT_EQ(sampleTrack(t, 0.0), std::vector<float>{10.0f});
    EXPECT_EQ(sampleTrack(t, 2.0), std::vector<float>{20.0f});
    EXPECT_EQ(sampleTrack(t, 1e6), std::vector<float>{20.0f});
    const KeyframeTrack single = track(Interpolation::CubicSpline, 1, {0.5f}, {9.0f, 7.0f, 9.0f});
    EXPECT_EQ(sampleTrack(single, 0.0), std::vector<float>{7.0f});
    EXPECT_EQ(sampleTrack(single, 3.0), std::vector<float>{7.0f});
}

TEST(Keyframes, StepHoldsTheLastKeyframeReached) {
    const KeyframeTrack t = track(Interpolation::Step, 1, {0.0f, 1.0f, 2.0f}, {5.0f, 6.0f, 7.0f});
    EXPECT_EQ(sampleTrack(t, 0.999), std::vector<float>{5.0f});
    EXPECT_EQ(sampleTrack(t, 1.0), std::vector<float>{6.0f});
    EXPECT_EQ(sampleTrack(t, 1.999), std::vector<float>{6.0f});
}

// Hermite basis at s = 1/2: h00 = 1/2, h10 = 1/8, h01 = 1/2, h11 = -1/8. Keyframes at 0 and 2
// (td = 2), v0 = 0, v1 = 1: with zero tangents 0.5; with an out-tangent 1 per second at the
// first, 0.5 + 2 x 1/8 = 0.75; with an in-tangent 1 at the second instead, 0.5 - 2 x 1/8 = 0.25.
// At s = 1/4: h00 = 27/32, h10 = 9/64, h01 = 5/32, h11 = -3/64, so with both tangents 1:
// 5/32 + 2 (9/64 - 3/64) = 11/32.
TEST(Keyframes, CubicSplineFollowsTheHermiteBasisWithTangentsScaledByTheInterval) {
    // Per keyframe: in-tangent, value, out-tangent.
    EXPECT_EQ(sampleTrack(track(Interpolation::CubicSpline, 1, {0.0f, 2.0f}, {0, 0, 0, 0, 1, 0}), 1.0),
              std::vector<float>{0.5f});
    EXPECT_EQ(sampleTrack(track(Interpolation::CubicSpline, 1, {0.0f, 2.0f}, {0, 0, 1, 0, 1, 0}), 1.0),
              std::vector<float>{0.75f});
    EXPECT_EQ(sampleTrack(track(Interpolation::CubicSpline, 1, {0.0f, 2.0f}, {0, 0, 0, 1, 1, 0}), 1.0),
              std::vector<float>{0.25f});
    EXPECT_EQ(sampleTrack(track(Interpolation::CubicSpline, 1, {0.0f, 2.0f}, {0, 0, 1, 1, 1, 0}), 0.5),
              std::vector<float>{11.0f / 32.0f});
}

// From no rotation to a quarter turn about y, halfway: an eighth turn, (0, sin(pi/8), 0,
// cos(pi/8)); a quarter of the way: a sixteenth turn (constant angular speed, not the chord's).
TEST(Keyframes, LinearRotationsSlerpAtConstantSpeed) {
    const float h = float(std::sqrt(0.5));
    const KeyframeTrack t = track(Interpolation::Linear, 4, {0.0f, 1.0f}, {0, 0, 0, 1, 0, h, 0, h}, true);
    const std::vector<float> half = sampleTrack(t, 0.5);
    EXPECT_EQ(half, (std::vector<float>{0.0f, float(std::sin(std::numbers::pi / 8)), 0.0f, float(std::cos(std::numbers::pi / 8))}));
    const std::vector<float> quarter = sampleTrack(t, 0.25);
    EXPECT_NEAR(quarter[1], std::sin(std::numbers::pi / 16), 1e-7);
    EXPECT_NEAR(quarter[3], std::cos(std::numbers::pi / 16), 1e-7);
}

// q and -q are one rotation: slerp towards -q goes the short way, to the same eighth turn.
TEST(Keyframes, RotationsTakeTheShorterArc) {
    const float h = float(std::sqrt(0.5));
    const KeyframeTrack t = track(Interpolation::Linear, 4, {0.0f, 1.0f}, {0, 0, 0, 1, 0, -h, 0, -h}, true);
    const std::vector<float> half = sampleTrack(t, 0.5);
    EXPECT_NEAR(half[1], std::sin(std::numbers::pi / 8), 1e-7);
    EXPECT_NEAR(half[3], std::cos(std::numbers::pi / 8), 1e-7);
}

// A spline through rotations is normalised: from (0, 0, 0, 1) to (0, 1, 0, 0) with zero tangents,
// halfway the basis gives (0, 1/2, 0, 1/2), normalised (0, sqrt(1/2), 0, sqrt(1/2)).
TEST(Keyframes, CubicSplineRotationsAreNormalised) {
    const std::vector<float> zero(4, 0.0f);
    std::vector<float> values = zero;
    for (float x : {0.0f, 0.0f, 0.0f, 1.0f}) values.push_back(x);
    values.insert(values.end(), zero.begin(), zero.end());
    values.insert(values.end(), zero.begin(), zero.end());
    for (float x : {0.0f, 1.0f, 0.0f, 0.0f}) values.push_back(x);
    values.insert(values.end(), zero.begin(), zero.end());
    const std::vector<float> half = sampleTrack(track(Interpolation::CubicSpline, 4, {0.0f, 1.0f}, values, true), 0.5);
    const float h = float(std::sqrt(0.5));
    EXPECT_EQ(half, (std::vector<float>{0.0f, h, 0.0f, h}));
}

TEST(Keyframes, MalformedTracksAreNamed) {
    KeyframeTrack t;
    t.components = 3;
    EXPECT_EQ(trackProblem(t), "has no keyframes");
    t.times = {0.0f, 1.0f, 1.0f};
    t.values.assign(9, 0.0f);
    EXPECT_EQ(trackProblem(t), "has keyframe times that are not strictly increasing");
    t.times = {-1.0f, 1.0f, 2.0f};
    EXPECT_EQ(trackProblem(t), "has a negative keyframe time");
    t.times = {0.0f, 1.0f, 2.0f};
    t.values.assign(8, 0.0f);
    EXPECT_EQ(trackProblem(t), "has 8 output numbers where 3 LINEAR keyframes need 9");
    t.interpolation = Interpolation::CubicSpline;
    EXPECT_EQ(trackProblem(t), "has 8 output numbers where 3 CUBICSPLINE keyframes need 27");
    t.interpolation = Interpolation::Linear;
    t.values.assign(9, 0.0f);
    t.values[4] = std::nanf("");
    EXPECT_EQ(trackProblem(t), "has an output value that is not finite");
    KeyframeTrack r;
    r.components = 4;
    r.rotation = true;
    r.times = {0.0f};
    r.values = {0.0f, 0.0f, 0.0f, 0.0f};
    EXPECT_EQ(trackProblem(r), "has a zero rotation quaternion at keyframe 0");
}

}  // namespace
}  // namespace punctual
