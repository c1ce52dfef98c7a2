// The built-in scenes' paths (scene/scene_path.h): at time 0 the still scene bit for bit, the
// keyframes where the path says (and halfway between, halfway), the swaying lamps offset by their
// track and the others still, the end held past the path's length, and an eye that never passes
// through anything. Measured on the scenes' own cameras, lights and objects.
#include <gtest/gtest.h>

#include "scene/builtin_scenes.h"
#include "scene/scene_path.h"
#include "scene_test_support.h"

namespace punctual {
namespace {

Scene posed(const char* name, double time) { return makeBuiltinScene(parseBuiltinScene(name), std::nullopt, time); }

void expectNear(const glm::vec3& actual, const glm::vec3& expected) {
    EXPECT_NEAR(actual.x, expected.x, 1e-4f);
    EXPECT_NEAR(actual.y, expected.y, 1e-4f);
    EXPECT_NEAR(actual.z, expected.z, 1e-4f);
}

TEST(ScenePath, AtTimeZeroEveryPathIsItsStillScene) {
    size_t withPaths = 0;
    for (const BuiltinScene& scene : kBuiltinScenes) {
        if (!scene.hasPath()) continue;
        EXPECT_EQ(testing::firstSceneDifference(makeBuiltinScene(scene), makeBuiltinScene(scene, std::nullopt, 0.0)), "")
            << scene.name;
        EXPECT_GT(scene.pathSeconds, 0.0f) << scene.name;
        ++withPaths;
    }
    EXPECT_EQ(withPaths, 2u);  // the hall's walk and the street's drive
}

// The walk's second keyframe is the eye at (-6, 6, 14) at 3 s; at 1.5 s it is halfway from the
// still eye (0, 9, 18.5): (-3, 7.5, 16.25).
TEST(ScenePath, TheHallsEyePassesItsKeyframes) {
    expectNear(posed("hall", 3.0).camera.position(), glm::vec3(-6.0f, 6.0f, 14.0f));
    expectNear(posed("hall", 1.5).camera.position(), glm::vec3(-3.0f, 7.5f, 16.25f));
    EXPECT_EQ(posed("hall", 100.0).camera.view, posed("hall", default_scene::kWalkSeconds).camera.view);
}

// Every sixth lamp is 1 m to +x at 3 s, 0.5 m at 1.5 s, back at 6 s and 1 m to -x at 9 s; the
// others never move.
TEST(ScenePath, EverySixthLampSwaysAndTheOthersStandStill) {
    const Scene still = makeDefaultScene();
    for (const auto& [time, sway] : {std::pair{3.0, 1.0f}, {1.5, 0.5f}, {6.0, 0.0f}, {9.0, -1.0f}}) {
        const Scene at = posed("hall", time);
        size_t swaying = 0;
        for (size_t i = 0; i < still.lights.size(); ++i) {
            const glm::vec3 expected = still.lights[i].position + glm::vec3(i % 6 == 0 ? sway : 0.0f, 0.0f, 0.0f);
            EXPECT_EQ(at.lights[i].position, expected) << i << " at " << time;
            EXPECT_EQ(at.lights[i].direction, still.lights[i].direction);
            swaying += i % 6 == 0;
        }
        EXPECT_EQ(swaying, 16u);
    }
}

// movingLights: light floor(k / F), worked by hand: a sixth is 0, 6, ..., 90 (16 of 96); a
// quarter 0, 4, ..., 92 (24); a tenth, held a little above 0.1 by a double, still 0, 10, 20; all
// and none.
TEST(ScenePath, AShareOfTheLightsMovesEveryOneOverItsLight) {
    EXPECT_EQ(movingLights(13, 1.0 / 6.0), (std::vector<uint32_t>{0, 6, 12}));
    EXPECT_EQ(movingLights(96, 1.0 / 6.0).size(), 16u);
    EXPECT_EQ(movingLights(9, 0.25), (std::vector<uint32_t>{0, 4, 8}));
    EXPECT_EQ(movingLights(96, 0.25).size(), 24u);
    EXPECT_EQ(movingLights(25, 0.1), (std::vector<uint32_t>{0, 10, 20}));
    EXPECT_EQ(movingLights(3, 1.0), (std::vector<uint32_t>{0, 1, 2}));
    EXPECT_TRUE(movingLights(96, 0.0).empty());
    EXPECT_TRUE(movingLights(0, 0.5).empty());
    // 1/3: 3 k a hair below 3 k in a double's division would floor to 3 k - 1 without the hair.
    EXPECT_EQ(movingLights(10, 1.0 / 3.0), (std::vector<uint32_t>{0, 3, 6, 9}));
}

// --moving-lights: a quarter of the hall's lamps sway at 3 s, the others stand; none, and the
// hall's own sixth when not given; the street's lamps stand unless a share is given.
TEST(ScenePath, TheMovingShareChoosesWhichLampsSway) {
    const Scene still = makeDefaultScene();
    auto swaying = [&](const Scene& at, const Scene& from) {
        std::vector<uint32_t> moved;
        for (uint32_t i = 0; i < from.lights.size(); ++i) {
            if (at.lights[i].position != from.lights[i].position) moved.push_back(i);
        }
        return moved;
    };
    const BuiltinScene& hall = parseBuiltinScene("hall");
    EXPECT_EQ(swaying(makeBuiltinScene(hall, std::nullopt, 3.0, {0.25}), still), movingLights(96, 0.25));
    EXPECT_TRUE(swaying(makeBuiltinScene(hall, std::nullopt, 3.0, {0.0}), still).empty());
    EXPECT_EQ(swaying(posed("hall", 3.0), still), movingLights(96, 1.0 / 6.0));
    const BuiltinScene& street = parseBuiltinScene("outdoor");
    const Scene streetStill = makeBuiltinScene(street);
    EXPECT_TRUE(swaying(posed("outdoor", 2.5), streetStill).empty());
    const std::vector<uint32_t> half = swaying(makeBuiltinScene(street, std::nullopt, 2.5, {0.5}), streetStill);
    EXPECT_EQ(half, movingLights(uint32_t(streetStill.lights.size()), 0.5));
    EXPECT_FALSE(half.empty());
}

// The hall's props are its 14 crates, blocks and posts (objects 15 to 28, after the floor, six
// walls and eight 6 m pillars; the 6 m partition and the walls are longer than 4 m). Half of them,
// props 0, 2, ..., 12 (objects 15, 17, ..., 27), lift 1 m at 3 s (a quarter of the walk), 0.5 m at
// 1.5 s, and are back at 6 s; the rest and the lamps' own share do not change.
TEST(ScenePath, AShareOfThePropsLiftsAndSinks) {
    const Scene still = makeDefaultScene();
    std::vector<uint32_t> expectedProps;
    for (uint32_t i = 15; i <= 28; ++i) expectedProps.push_back(i);
    ASSERT_EQ(sceneProps(still), expectedProps);
    EXPECT_EQ(still.objects[14].name, "pillar");
    EXPECT_EQ(still.objects[15].name, "crate");
    EXPECT_EQ(still.objects[28].name, "slab");
    const BuiltinScene& hall = parseBuiltinScene("hall");
    for (const auto& [time, lift] : {std::pair{3.0, 1.0f}, {1.5, 0.5f}, {6.0, 0.0f}, {9.0, 1.0f}}) {
        const Scene at = makeBuiltinScene(hall, std::nullopt, time, {0.0, 0.5});
        size_t lifted = 0;
        for (uint32_t i = 0; i < still.objects.size(); ++i) {
            const bool moves = i >= 15 && i <= 27 && (i - 15) % 2 == 0;
            glm::mat4 expected = still.objects[i].model;
            expected[3].y += moves ? lift : 0.0f;
            EXPECT_EQ(at.objects[i].model, expected) << i << " at " << time;
            EXPECT_NEAR(at.objects[i].worldBounds.min.y, still.objects[i].worldBounds.min.y + (moves ? lift : 0.0f), 1e-5f);
            lifted += moves;
        }
        EXPECT_EQ(lifted, 7u);
        for (size_t l = 0; l < still.lights.size(); ++l) EXPECT_EQ(at.lights[l].position, still.lights[l].position);
    }
    // None by default: the walk's own lamps move, no object does.
    const Scene walk = makeBuiltinScene(hall, std::nullopt, 3.0);
    for (uint32_t i = 0; i < still.objects.size(); ++i) EXPECT_EQ(walk.objects[i].model, still.objects[i].model) << i;
}

// The drive covers 60 m in 10 s down -z at eye height: at 5 s, 30 m.
TEST(ScenePath, TheStreetsEyeDrivesDownTheStreet) {
    expectNear(posed("outdoor", 5.0).camera.position(), glm::vec3(0.0f, 1.7f, -30.0f));
    expectNear(posed("outdoor", outdoor_scene::kDriveSeconds).camera.position(), glm::vec3(0.0f, 1.7f, -60.0f));
    const Scene still = makeOutdoorScene();
    const Scene at = posed("outdoor", 5.0);
    for (size_t i = 0; i < still.lights.size(); ++i) EXPECT_EQ(at.lights[i].position, still.lights[i].position);
}

// Sampled every 0.05 s, the eye stays 0.3 m clear of every object's bounds and above the ground.
TEST(ScenePath, NoEyePassesThroughAnything) {
    for (const BuiltinScene& entry : kBuiltinScenes) {
        if (!entry.hasPath()) continue;
        const Scene scene = makeBuiltinScene(entry);
        size_t samples = 0;
        for (double t = 0.0; t <= double(entry.pathSeconds); t += 0.05) {
            const glm::vec3 eye = makeBuiltinScene(entry, std::nullopt, t).camera.position();
            for (const Object& object : scene.objects) {
                const Bounds& b = object.worldBounds;
                const bool inside = glm::all(glm::greaterThan(eye, b.min - 0.3f)) && glm::all(glm::lessThan(eye, b.max + 0.3f));
                EXPECT_FALSE(inside) << entry.name << " at " << t << " s: in " << object.name;
            }
            ++samples;
        }
        EXPECT_GT(samples, 190u) << entry.name;
    }
}

}  // namespace
}  // namespace punctual
