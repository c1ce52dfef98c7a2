// Generated lights (--lights S,P[,SEED]): determinism, placement, scaling, argument parsing.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include <glm/gtc/matrix_transform.hpp>

#include "core/error.h"
#include "light_test_scenes.h"
#include "scene/light_generator.h"
#include "scene/light_reach.h"
#include "scene/study_scenes.h"

namespace punctual {
namespace {

using unit_testing::kDegree;

// Only the bounds matter to the generator.
Scene sceneWithBounds(glm::vec3 min, glm::vec3 max) {
    Scene scene;
    scene.bounds.extend(min);
    scene.bounds.extend(max);
    return scene;
}

Scene hall() { return sceneWithBounds({-10.0f, 0.0f, -5.0f}, {10.0f, 6.0f, 5.0f}); }

template <typename T>
bool sameBits(const T& a, const T& b) {
    return std::memcmp(&a, &b, sizeof(T)) == 0;
}

bool identical(const Light& a, const Light& b) {
    return a.name == b.name && a.type == b.type && sameBits(a.position, b.position) &&
           sameBits(a.direction, b.direction) && sameBits(a.color, b.color) && sameBits(a.intensity, b.intensity) &&
           sameBits(a.range, b.range) && sameBits(a.innerConeAngle, b.innerConeAngle) &&
           sameBits(a.outerConeAngle, b.outerConeAngle) && a.castsShadow == b.castsShadow;
}

TEST(LightGen, PortableRandomIsInUnitIntervalOn24BitGrid) {
    PortableRandom random(123);
    for (int i = 0; i < 10000; ++i) {
        const float u = random.uniform();
        ASSERT_GE(u, 0.0f);
        ASSERT_LT(u, 1.0f);
        const float scaled = u * 16777216.0f;
        ASSERT_EQ(scaled, std::floor(scaled));
    }
}

TEST(LightGen, PortableRandomGoldenValues) {
    // mt19937 and seed_seq are specified bit for bit by the C++ standard, and the float mapping is
    // ours, so these values hold on every conforming platform. A change here changes every
    // generated scene (and the default scene's lights).
    PortableRandom random(1);
    const uint32_t first = static_cast<uint32_t>(random.uniform() * 16777216.0f);
    const uint32_t second = static_cast<uint32_t>(random.uniform() * 16777216.0f);
    PortableRandom again(1);
    EXPECT_EQ(static_cast<uint32_t>(again.uniform() * 16777216.0f), first);
    EXPECT_EQ(static_cast<uint32_t>(again.uniform() * 16777216.0f), second);
    EXPECT_EQ(first, 11127857u);  // the top 24 bits of the first two outputs
    EXPECT_EQ(second, 11168143u);
}

TEST(LightGen, SameSeedGivesIdenticalLights) {
    Scene a = hall(), b = hall();
    replaceLights(a, 20, 10, 7);
    replaceLights(b, 20, 10, 7);
    ASSERT_EQ(a.lights.size(), b.lights.size());
    for (size_t i = 0; i < a.lights.size(); ++i) EXPECT_TRUE(identical(a.lights[i], b.lights[i])) << i;
}

TEST(LightGen, DifferentSeedGivesDifferentLights) {
    Scene a = hall(), b = hall();
    replaceLights(a, 20, 10, 7);
    replaceLights(b, 20, 10, 8);
    size_t differing = 0;
    for (size_t i = 0; i < a.lights.size(); ++i) differing += identical(a.lights[i], b.lights[i]) ? 0 : 1;
    EXPECT_EQ(differing, a.lights.size());
}

// The bench's fixed-range sets: every range the same share of the diagonal, the intensity scaled
// by the square of the change (so illuminance at half the range is unchanged), and nested subsets.
TEST(LightGen, FixedRangesKeepIlluminanceAtAShareOfTheRange) {
    Scene scene = hall();
    replaceLights(scene, 6, 3, 1);
    Light sun;
    sun.type = LightType::Directional;
    sun.intensity = 3.0f;
    scene.lights.push_back(sun);
    const Scene before = scene;
    const float diagonal = glm::length(scene.bounds.max - scene.bounds.min);
    setLightRanges(scene, 0.5f);
    for (size_t i = 0; i < scene.lights.size(); ++i) {
        const Light& old = before.lights[i];
        const Light& now = scene.lights[i];
        if (now.type == LightType::Directional) {
            EXPECT_TRUE(identical(now, old));  // a sun has no range
            continue;
        }
        EXPECT_FLOAT_EQ(now.range, 0.5f * diagonal) << i;
        // I / r^2 is what replaceLights drew (the brightness factor): unchanged.
        EXPECT_NEAR(now.intensity / (now.range * now.range), old.intensity / (old.range * old.range),
                    1e-6f * old.intensity / (old.range * old.range)) << i;
        EXPECT_EQ(now.position, old.position) << i;
    }
    EXPECT_THROW(setLightRanges(scene, 0.0f), Error);
}

TEST(LightGen, FirstLightsAreNestedSubsets) {
    Scene all = hall();
    replaceLights(all, 10, 5, 3);
    Light sun;
    sun.type = LightType::Directional;
    all.lights.push_back(sun);
    Scene some = all;
    keepFirstLights(some, 4, 2);
    ASSERT_EQ(some.lights.size(), 7u);  // 4 spots, 2 points, the sun
    for (size_t i = 0; i < 4; ++i) EXPECT_TRUE(identical(some.lights[i], all.lights[i])) << i;
    for (size_t i = 0; i < 2; ++i) EXPECT_TRUE(identical(some.lights[4 + i], all.lights[10 + i])) << i;
    EXPECT_EQ(some.lights[6].type, LightType::Directional);
    keepFirstLights(some, 0, 0);
    ASSERT_EQ(some.lights.size(), 1u);
}

TEST(LightGen, CountsAndTypes) {
    Scene scene = hall();
    Light sun;
    sun.type = LightType::Directional;
    scene.lights = {sun, sun};
    replaceLights(scene, 10, 5, 1);
    ASSERT_EQ(scene.lights.size(), 15u);  // the directional lights are gone too
    for (size_t i = 0; i < scene.lights.size(); ++i) {
        EXPECT_EQ(scene.lights[i].type, i < 10 ? LightType::Spot : LightType::Point) << i;
        EXPECT_TRUE(scene.lights[i].castsShadow);
    }
    EXPECT_NO_THROW(validateLights(scene.lights, "generated"));

    replaceLights(scene, 0, 0, 1);
    EXPECT_TRUE(scene.lights.empty());
    replaceLights(scene, 64, 32, 99);
    EXPECT_EQ(scene.lights.size(), 96u);
    EXPECT_NO_THROW(validateLights(scene.lights, "generated"));
}

TEST(LightGen, PositionsInsideBoundsAndAboveTheFloor) {
    Scene scene = hall();
    replaceLights(scene, 64, 32, 3);
    for (const Light& light : scene.lights) {
        EXPECT_TRUE(glm::all(glm::greaterThanEqual(light.position, scene.bounds.min))) << light.name;
        EXPECT_TRUE(glm::all(glm::lessThanEqual(light.position, scene.bounds.max))) << light.name;
        EXPECT_GE(light.position.y, 0.6f) << light.name;  // min.y + 10% of the 6 m height
    }
}

TEST(LightGen, SpotsPointDownWithValidCones) {
    Scene scene = hall();
    replaceLights(scene, 64, 0, 11);
    for (const Light& light : scene.lights) {
        EXPECT_NEAR(glm::length(light.direction), 1.0f, 1e-5f);
        EXPECT_LT(light.direction.y, -0.8f) << light.name;  // within ~36 degrees of straight down
        EXPECT_GE(light.outerConeAngle, 25.0f * kDegree * 0.9999f);
        EXPECT_LE(light.outerConeAngle, 50.0f * kDegree * 1.0001f);
        EXPECT_GE(light.innerConeAngle, 0.5f * light.outerConeAngle * 0.9999f);
        EXPECT_LE(light.innerConeAngle, 0.9f * light.outerConeAngle * 1.0001f);
        EXPECT_LE(std::max({light.color.r, light.color.g, light.color.b}), 1.0f);
        EXPECT_EQ(std::max({light.color.r, light.color.g, light.color.b}), 1.0f);
    }
}

TEST(LightGen, RangesOverlapAndScaleWithTheScene) {
    Scene small = hall();
    Scene large = sceneWithBounds(small.bounds.min * 10.0f, small.bounds.max * 10.0f);
    replaceLights(small, 30, 20, 5);
    replaceLights(large, 30, 20, 5);
    const float diagonal = glm::length(small.bounds.size());
    for (size_t i = 0; i < small.lights.size(); ++i) {
        const Light& s = small.lights[i];
        const Light& l = large.lights[i];
        EXPECT_GE(s.range, 0.25f * diagonal * 0.9999f);
        EXPECT_LE(s.range, 0.45f * diagonal * 1.0001f);
        EXPECT_NEAR(l.range / s.range, 10.0f, 1e-4f);
        EXPECT_NEAR(l.intensity / s.intensity, 100.0f, 1e-3f);  // same illuminance at the same range fraction
        EXPECT_LT(glm::distance(l.position, s.position * 10.0f), 1e-3f * glm::length(l.position) + 1e-3f);
        EXPECT_EQ(l.direction, s.direction);
        EXPECT_EQ(l.outerConeAngle, s.outerConeAngle);
    }
}

TEST(LightGen, FlatSceneGetsLightsAboveIt) {
    Scene flat = sceneWithBounds({-20.0f, 0.0f, -20.0f}, {20.0f, 0.0f, 20.0f});
    replaceLights(flat, 8, 8, 1);
    for (const Light& light : flat.lights) {
        EXPECT_GE(light.position.y, 0.05f * 40.0f * 0.9999f);
        EXPECT_LE(light.position.y, 0.2f * 40.0f * 1.0001f);
    }
}

TEST(LightGen, RejectsOverTheLargestCapacityAndEmptyScenes) {
    Scene scene = hall();
    try {
        replaceLights(scene, 16385, 0, 1);
        FAIL() << "expected an Error";
    } catch (const Error& e) {
        EXPECT_EQ(e.subject(), "--lights");
        EXPECT_STREQ(e.what(), "--lights: at most 16384 spot and 16384 point lights (got 16385,0)");
    }
    EXPECT_THROW(replaceLights(scene, 0, 16385, 1), Error);
    Scene empty;
    EXPECT_THROW(replaceLights(empty, 1, 1, 1), Error);
}

// ---- placement that reaches what the camera sees ----------------------------------------------

// A closed 1 m cube standing on y = 0, alone, seen by the fitted camera: the first draws all fall
// inside it (its bounds are the scene's), where they light nothing the camera sees.
Scene closedCube() {
    Scene scene;
    study::addBox(scene, {0.0f, 0.5f, 0.0f}, {1.0f, 1.0f, 1.0f});
    scene.materials.push_back(Material{});
    scene.computeBounds();
    scene.camera = fitCameraToBounds(scene.bounds);
    return scene;
}

// A 10 x 4 x 10 m room modelled as one closed box, seen from inside: its lights must stay
// inside, where the camera is (rejecting candidates inside any object's bounds would put
// them all outside the walls).
Scene closedRoom() {
    Scene scene;
    study::addBox(scene, {0.0f, 2.0f, 0.0f}, {10.0f, 4.0f, 10.0f});
    study::addBox(scene, {1.0f, 0.5f, -1.0f}, {1.0f, 1.0f, 1.0f});  // a crate on the floor
    scene.materials.push_back(Material{});
    scene.computeBounds();
    scene.camera.view = glm::lookAt(glm::vec3(0.0f, 1.7f, 4.5f), glm::vec3(0.0f, 1.0f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f));
    scene.camera.yfov = 1.0f;
    scene.camera.znear = 0.05f;
    scene.camera.zfar = 30.0f;
    return scene;
}

bool strictlyInside(const glm::vec3& p, const Bounds& b) {
    return glm::all(glm::greaterThan(p, b.min)) && glm::all(glm::lessThan(p, b.max));
}

TEST(LightGen, ClosedModelGetsLightsAroundItThatReachWhatTheCameraSees) {
    Scene scene = closedCube();
    replaceLights(scene, 16, 16, 1);
    ASSERT_EQ(scene.lights.size(), 32u);
    const LightReach reach(scene);
    ASSERT_FALSE(reach.empty());
    for (const Light& light : scene.lights) {
        EXPECT_FALSE(strictlyInside(light.position, scene.bounds)) << light.name;
        EXPECT_TRUE(reach.reaches(light)) << light.name;
        EXPECT_GE(light.position.y, scene.bounds.min.y) << light.name;  // never below the model
    }
    EXPECT_NO_THROW(validateLights(scene.lights, "generated"));
    Scene again = closedCube();
    replaceLights(again, 16, 16, 1);
    for (size_t i = 0; i < scene.lights.size(); ++i) EXPECT_TRUE(identical(scene.lights[i], again.lights[i])) << i;
}

TEST(LightGen, RoomSeenFromInsideKeepsItsLightsInside) {
    Scene scene = closedRoom();
    replaceLights(scene, 16, 16, 2);
    const LightReach reach(scene);
    ASSERT_FALSE(reach.empty());
    for (const Light& light : scene.lights) {
        EXPECT_TRUE(strictlyInside(light.position, scene.bounds)) << light.name;
        EXPECT_TRUE(reach.reaches(light)) << light.name;
    }
}

// Lights that reach what the camera sees at their first draw are exactly the lights generated
// before placement was checked: a scene whose lights all reach keeps its images.
TEST(LightGen, LightsThatReachAtTheirFirstDrawAreUnchanged) {
    Scene checked = closedRoom();
    Scene unchecked = closedRoom();
    unchecked.objects.clear();  // nothing to test against: every first draw stands
    replaceLights(checked, 8, 8, 3);
    replaceLights(unchecked, 8, 8, 3);
    const LightReach reach(checked);
    size_t firstDrawsKept = 0;
    for (size_t i = 0; i < checked.lights.size() && reach.reaches(unchecked.lights[i]); ++i) {
        EXPECT_TRUE(identical(checked.lights[i], unchecked.lights[i])) << i;
        ++firstDrawsKept;
    }
    EXPECT_GT(firstDrawsKept, 0u);
}

// ---- parseLightCounts --------------------------------------------------------------------------

TEST(LightGen, ParseAcceptsCountsAndSeed) {
    const LightCounts a = parseLightCounts("64,32");
    EXPECT_EQ(a.spot, 64u);
    EXPECT_EQ(a.point, 32u);
    EXPECT_EQ(a.seed, 1u);  // the default
    const LightCounts b = parseLightCounts("10,5,7");
    EXPECT_EQ(b.spot, 10u);
    EXPECT_EQ(b.point, 5u);
    EXPECT_EQ(b.seed, 7u);
    const LightCounts c = parseLightCounts("0,0,18446744073709551615");
    EXPECT_EQ(c.seed, 18446744073709551615ull);
}

TEST(LightGen, ParseRejectsJunk) {
    for (const char* bad : {"", "a,b", "-1,2", "16385,0", "0,16385", "1", "1,2,3,4", "1,,2", ",1", "1,2,", " 1,2",
                            "1.5,2", "+1,2", "1,2,18446744073709551616", "99999999999999999999999,1"}) {
        try {
            parseLightCounts(bad);
            ADD_FAILURE() << "accepted \"" << bad << "\"";
        } catch (const Error& e) {
            EXPECT_EQ(e.subject(), "--lights") << bad;
            EXPECT_FALSE(e.problem().empty());
        }
    }
}

TEST(LightGen, ParseOverCapMessage) {
    try {
        parseLightCounts("0,16385");
        FAIL();
    } catch (const Error& e) {
        EXPECT_EQ(e.problem(), "at most 16384 spot and 16384 point lights (got 0,16385)");
    }
    // Up to the largest capacity parses (the command line holds it to --max-lights).
    EXPECT_EQ(parseLightCounts("16384,16384").spot, 16384u);
}

// ---- --light-range ----------------------------------------------------------------------------

TEST(LightGen, ConstantDensityScaleKnownAnswers) {
    // The fallback, for free space: r scales by cbrt(96 / N): the reference count keeps its ranges
    // exactly, 1/8 of it doubles them, 8 times it halves them (a point lies in N lights' reach
    // about N r^3 / V times).
    EXPECT_EQ(constantDensityRangeScale(kDensityReferenceLights), 1.0f);
    EXPECT_EQ(constantDensityRangeScale(12), 2.0f);
    EXPECT_FLOAT_EQ(constantDensityRangeScale(768), 0.5f);
    EXPECT_FLOAT_EQ(constantDensityRangeScale(8192), std::cbrt(96.0f / 8192.0f));
    EXPECT_EQ(constantDensityRangeScale(0), 1.0f);
    EXPECT_EQ(generatedLightRange(3.0f, {}), 3.0f);
    EXPECT_EQ(generatedLightRange(3.0f, {LightRange::Kind::Metres, 7.5f}), 7.5f);
    // Auto draws as drawn; the fit scales them all afterwards.
    EXPECT_EQ(generatedLightRange(3.0f, {LightRange::Kind::ConstantDensity, 0.0f}), 3.0f);
}

Light pointAt(glm::vec3 position, float range) {
    Light light;
    light.type = LightType::Point;
    light.position = position;
    light.range = range;
    return light;
}

TEST(LightGen, FittedDensityScaleKnownAnswers) {
    // One probe at the origin; 192 points of range 1000 at distances 1, 2, ..., 192: every pair
    // counts at scale 1 (least scales k / 1000). Twice the reference count: half as many pairs
    // should count, 96, so s lies between the 96th and 97th least scales: 0.0965.
    const std::vector<glm::vec3> origin = {glm::vec3(0.0f)};
    std::vector<Light> lights;
    for (int k = 1; k <= 192; ++k) lights.push_back(pointAt(glm::vec3(float(k), 0.0f, 0.0f), 1000.0f));
    EXPECT_FLOAT_EQ(fittedDensityScale(lights, origin), 0.0965f);
    // A spot shining away from the probe never counts, at any scale: it changes nothing (but the
    // count ratio: 193 lights want 192 x 96 / 193 = 95.5 -> 96 pairs, the same s).
    Light away = pointAt(glm::vec3(0.5f, 0.0f, 0.0f), 1000.0f);
    away.type = LightType::Spot;
    away.direction = glm::vec3(1.0f, 0.0f, 0.0f);
    away.outerConeAngle = 0.5f;
    lights.push_back(away);
    EXPECT_FLOAT_EQ(fittedDensityScale(lights, origin), 0.0965f);
    // The reference count keeps its ranges exactly; no probe falls back to the cube root.
    lights.resize(kDensityReferenceLights);
    EXPECT_EQ(fittedDensityScale(lights, origin), 1.0f);
    lights.resize(12);
    EXPECT_EQ(fittedDensityScale(lights, {}), 2.0f);
    // Fewer lights than the reference grow: 12 lights of range 1000 at 1..12 all count already;
    // 8 x 12 pairs are wanted, more than exist, so s passes the farthest (12 / 1000).
    EXPECT_GT(fittedDensityScale(lights, origin), 0.012f);
}

TEST(LightGen, AutoRangeScalesEveryLightByOneFactorAndKeepsItsIlluminanceShare) {
    // A scene without geometry in view redraws nothing and gives no probes, so the same seed draws
    // the same lights, and auto scales every range by the fallback's one factor (intensities as
    // range^2): cbrt(96 / 12) = 2 exactly, cbrt(96 / 600) below 1.
    for (const auto& [spots, points] : {std::pair<uint32_t, uint32_t>{8, 4}, {400, 200}}) {
        Scene drawn = hall();
        Scene automatic = hall();
        replaceLights(drawn, spots, points, 3);
        replaceLights(automatic, spots, points, 3, {LightRange::Kind::ConstantDensity, 0.0f});
        ASSERT_EQ(automatic.lights.size(), size_t(spots + points));
        const float scale = constantDensityRangeScale(spots + points);
        for (size_t i = 0; i < drawn.lights.size(); ++i) {
            const Light& d = drawn.lights[i];
            const Light& a = automatic.lights[i];
            EXPECT_EQ(a.range, d.range * scale) << i;
            EXPECT_NEAR(a.intensity / d.intensity, scale * scale, 1e-5f) << i;
            EXPECT_TRUE(sameBits(a.position, d.position)) << i;
        }
    }
}

TEST(LightGen, FixedRangeGivesEveryLightThatRange) {
    Scene scene = hall();
    replaceLights(scene, 6, 6, 9, {LightRange::Kind::Metres, 4.0f});
    ASSERT_EQ(scene.lights.size(), 12u);
    for (const Light& light : scene.lights) {
        EXPECT_EQ(light.range, 4.0f);
        // Intensity still range^2 times the drawn factor (spots 0.075-0.15, points 0.025-0.05).
        const float factor = light.intensity / 16.0f;
        EXPECT_GE(factor, light.type == LightType::Spot ? 0.075f * 0.9999f : 0.025f * 0.9999f);
        EXPECT_LE(factor, light.type == LightType::Spot ? 0.15f * 1.0001f : 0.05f * 1.0001f);
    }
}

}  // namespace
}  // namespace punctual
