// glTF animations posed at a time (GltfLoadOptions::time, scene/gltf_animation.h): the posed
// scene equals, bit for bit, the still file whose nodes hold the values interpolated by hand
// (camera, light and mesh alike), children follow an animated parent, animated weights pick the
// morph pose, and a malformed animation fails with one line naming the file and the part.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>

#include "animated_gltf.h"
#include "core/error.h"
#include "gltf_test_files.h"
#include "scene/gltf_loader.h"
#include "warning_capture.h"

namespace punctual {
namespace {

using testing::AnimatedGltf;
using testing::WarningCapture;
using unit_testing::TempDir;

Scene loadAt(const AnimatedGltf& file, const TempDir& dir, std::optional<double> time, const char* name = "a.gltf") {
    GltfLoadOptions options;
    options.time = time;
    return loadGltf(file.write((dir.path() / name).string()), options);
}

// The pose both files must give: the camera, the spot and the square's model matrix.
void expectSamePose(const Scene& a, const Scene& b) {
    EXPECT_EQ(a.camera.view, b.camera.view);
    ASSERT_EQ(a.lights.size(), 1u);
    ASSERT_EQ(b.lights.size(), 1u);
    EXPECT_EQ(a.lights[0].position, b.lights[0].position);
    EXPECT_EQ(a.lights[0].direction, b.lights[0].direction);
    ASSERT_EQ(a.objects.size(), 1u);
    EXPECT_EQ(a.objects[0].model, b.objects[0].model);
    EXPECT_EQ(a.vertices.size(), b.vertices.size());
    for (size_t i = 0; i < a.vertices.size() && i < b.vertices.size(); ++i) {
        EXPECT_EQ(a.vertices[i].position, b.vertices[i].position) << i;
    }
}

// Camera: LINEAR translation from (0, 0, 3) to (2, 0, 5) over 0..2 s; at 0.5 s a quarter of the
// way, (0.5, 0, 3.5). Spot: LINEAR rotation from none to a quarter turn about x over 0..1 s; at
// 0.5 s an eighth turn, (sin(pi/8), 0, 0, cos(pi/8)). Square: CUBICSPLINE scale from 1 to 2 over
// 0..1 s with zero tangents; at 0.5 s, 1.5 (the Hermite basis at s = 1/2 weighs both ends 1/2).
// Weights: STEP, 0 until 0.25 s and 0.25 after; at 0.5 s, 0.25 (the square moved 0.5 m along z).
TEST(GltfAnimation, ThePoseAtATimeIsTheStillFileWithTheValuesInterpolatedByHand) {
    TempDir dir;
    AnimatedGltf animated;
    const float h = float(std::sqrt(0.5));
    animated.addChannel(0, AnimatedGltf::kCamera, "translation", "LINEAR", {0.0f, 2.0f}, {0, 0, 3, 2, 0, 5});
    animated.addChannel(0, AnimatedGltf::kSpot, "rotation", "LINEAR", {0.0f, 1.0f}, {0, 0, 0, 1, h, 0, 0, h});
    animated.addChannel(0, AnimatedGltf::kSquare, "scale", "CUBICSPLINE", {0.0f, 1.0f},
                        {0, 0, 0, 1, 1, 1, 0, 0, 0, 0, 0, 0, 2, 2, 2, 0, 0, 0});
    animated.addChannel(0, AnimatedGltf::kSquare, "weights", "STEP", {0.0f, 0.25f}, {0.0f, 0.25f});
    const Scene posed = loadAt(animated, dir, 0.5);

    AnimatedGltf still;
    still.doc["nodes"][AnimatedGltf::kCamera]["translation"] = {0.5, 0.0, 3.5};
    still.doc["nodes"][AnimatedGltf::kSpot]["rotation"] = {double(float(std::sin(std::numbers::pi / 8))), 0.0, 0.0,
                                                           double(float(std::cos(std::numbers::pi / 8)))};
    still.doc["nodes"][AnimatedGltf::kSquare]["scale"] = {1.5, 1.5, 1.5};
    still.doc["nodes"][AnimatedGltf::kSquare]["weights"] = {0.25};
    expectSamePose(posed, loadAt(still, dir, std::nullopt, "still.gltf"));

    // Something moved: the rest pose differs in every part.
    const Scene rest = loadAt(animated, dir, std::nullopt);
    EXPECT_NE(rest.camera.view, posed.camera.view);
    EXPECT_NE(rest.lights[0].direction, posed.lights[0].direction);
    EXPECT_NE(rest.objects[0].model, posed.objects[0].model);
    EXPECT_NE(rest.vertices[0].position, posed.vertices[0].position);
}

TEST(GltfAnimation, BeforeTheFirstKeyframeAndAfterTheLastTheEndsHold) {
    TempDir dir;
    AnimatedGltf animated;
    animated.addChannel(0, AnimatedGltf::kCamera, "translation", "LINEAR", {1.0f, 2.0f}, {0, 0, 4, 0, 0, 6});
    EXPECT_EQ(loadAt(animated, dir, 0.0).camera.position(), glm::vec3(0.0f, 0.0f, 4.0f));
    EXPECT_EQ(loadAt(animated, dir, 1.5).camera.position(), glm::vec3(0.0f, 0.0f, 5.0f));
    EXPECT_EQ(loadAt(animated, dir, 100.0).camera.position(), glm::vec3(0.0f, 0.0f, 6.0f));
}

// A parent moved by its animation carries its children: the square under a node translated
// (0, 1, 0) at the time drawn.
TEST(GltfAnimation, ChildrenFollowAnAnimatedParent) {
    TempDir dir;
    AnimatedGltf animated;
    animated.doc["nodes"].push_back({{"children", {AnimatedGltf::kSquare}}});
    animated.doc["scenes"][0]["nodes"] = {1, 2, 3};
    animated.addChannel(0, 3, "translation", "LINEAR", {0.0f, 1.0f}, {0, 0, 0, 0, 2, 0});
    const Scene posed = loadAt(animated, dir, 0.5);
    ASSERT_EQ(posed.objects.size(), 1u);
    EXPECT_EQ(glm::vec3(posed.objects[0].model[3]), glm::vec3(0.0f, 1.0f, 0.0f));
}

// Two animations driving one property: the first drives it, and one warning says so.
TEST(GltfAnimation, EveryAnimationPlaysAndTheFirstDrivesAContestedProperty) {
    TempDir dir;
    AnimatedGltf animated;
    animated.addChannel(0, AnimatedGltf::kCamera, "translation", "STEP", {0.0f}, {0, 0, 4});
    animated.addChannel(1, AnimatedGltf::kCamera, "translation", "STEP", {0.0f}, {0, 0, 9});
    animated.addChannel(1, AnimatedGltf::kSpot, "translation", "STEP", {0.0f}, {0, 1, 2});
    WarningCapture capture;
    const Scene posed = loadAt(animated, dir, 0.0);
    EXPECT_EQ(posed.camera.position(), glm::vec3(0.0f, 0.0f, 4.0f));
    EXPECT_EQ(posed.lights[0].position, glm::vec3(0.0f, 1.0f, 2.0f));  // the second animation plays too
    ASSERT_EQ(capture.warnings.size(), 1u);
    EXPECT_NE(capture.warnings[0].find("animation 1 channel 0 animates the translation of node 1, which an earlier "
                                       "animation drives"),
              std::string::npos)
        << capture.warnings[0];
}

TEST(GltfAnimation, ATimeWithoutAnimationsWarnsAndDrawsTheFileAsStored) {
    TempDir dir;
    AnimatedGltf still;
    WarningCapture capture;
    const Scene scene = loadAt(still, dir, 2.0);
    EXPECT_EQ(scene.camera.position(), glm::vec3(0.0f, 0.0f, 3.0f));
    ASSERT_EQ(capture.warnings.size(), 1u);
    EXPECT_NE(capture.warnings[0].find("--time: the scene has no animations"), std::string::npos);
}

// Each malformed animation: one line naming the file and what is wrong where.
TEST(GltfAnimation, MalformedAnimationsFailWithOneLineNamingThePart) {
    TempDir dir;
    const auto expectError = [&](const AnimatedGltf& file, const std::string& mention) {
        try {
            loadAt(file, dir, 0.5);
            ADD_FAILURE() << "no error; expected " << mention;
        } catch (const Error& e) {
            const std::string message = e.what();
            EXPECT_NE(message.find(mention), std::string::npos) << message;
            EXPECT_NE(message.find("a.gltf"), std::string::npos) << message;
            EXPECT_EQ(message.find('\n'), std::string::npos) << message;
        }
    };
    const auto withChannel = [](const std::string& path, const std::string& interpolation, std::vector<float> times,
                                std::vector<float> values, int node = AnimatedGltf::kCamera) {
        AnimatedGltf file;
        file.addChannel(0, node, path, interpolation, times, values);
        return file;
    };
    expectError(withChannel("translation", "LINEAR", {0.0f, 0.0f}, {0, 0, 1, 0, 0, 2}),
                "animation 0 channel 0 sampler 0 has keyframe times that are not strictly increasing");
    expectError(withChannel("translation", "LINEAR", {0.0f, 1.0f}, {0, 0, 1}),
                "has 3 output numbers where 2 LINEAR keyframes need 6");
    expectError(withChannel("translation", "CUBICSPLINE", {0.0f, 1.0f}, {0, 0, 1, 0, 0, 2}),
                "has 6 output numbers where 2 CUBICSPLINE keyframes need 18");
    expectError(withChannel("translation", "SMOOTH", {0.0f}, {0, 0, 1}), "has interpolation 'SMOOTH'");
    expectError(withChannel("weights", "LINEAR", {0.0f}, {1.0f}, AnimatedGltf::kCamera),
                "animates the weights of node 1, whose mesh has no morph targets");
    expectError(withChannel("rotation", "LINEAR", {0.0f}, {0, 0, 0, 0}), "has a zero rotation quaternion at keyframe 0");

    AnimatedGltf file = withChannel("translation", "LINEAR", {0.0f}, {0, 0, 1});
    file.doc["animations"][0]["channels"][0]["target"]["node"] = 7;
    expectError(file, "animation 0 channel 0 targets node 7, which does not exist");
    file = withChannel("translation", "LINEAR", {0.0f}, {0, 0, 1});
    file.doc["animations"][0]["channels"][0]["sampler"] = 3;
    expectError(file, "animation 0 channel 0 uses sampler 3, which does not exist");
    file = withChannel("translation", "LINEAR", {0.0f}, {0, 0, 1});
    file.doc["animations"][0]["channels"].push_back(file.doc["animations"][0]["channels"][0]);
    expectError(file, "animation 0 channel 1 animates the translation of node 1, which another channel of the animation");
    file = withChannel("translation", "LINEAR", {0.0f}, {0, 0, 1});
    file.doc["nodes"][AnimatedGltf::kCamera].erase("translation");
    file.doc["nodes"][AnimatedGltf::kCamera]["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 3, 1};
    expectError(file, "animates node 1, which has a matrix");
    file = withChannel("translation", "LINEAR", {0.0f}, {0, 0, 1});
    file.doc["accessors"][file.doc["animations"][0]["samplers"][0]["output"].get<size_t>()]["type"] = "VEC2";
    expectError(file, "output accessor");
}

}  // namespace
}  // namespace punctual
