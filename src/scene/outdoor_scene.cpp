#include "scene/outdoor_scene.h"

#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/box_layout.h"
#include "scene/scene_path.h"
#include "scene/light_generator.h"
#include "shading.h"

namespace punctual {

namespace {

// ---- geometry --------------------------------------------------------------------------------

enum MaterialId : uint32_t { kGround, kWood, kConcrete, kBrick, kSteel, kBluePlastic, kBark, kFoliage, kFacade };

void addMaterials(Scene& scene) {
    // Order matches MaterialId. Albedos stay below ~0.8 as real materials do; the ground is dark
    // (dry earth and asphalt, ~0.35), so the sun does not wash out the large areas it fills.
    scene.materials = {
        plainMaterial("ground", {0.36f, 0.34f, 0.30f}, 0.0f, 0.90f),
        plainMaterial("wood", {0.45f, 0.30f, 0.18f}, 0.0f, 0.80f),
        plainMaterial("concrete", {0.62f, 0.60f, 0.56f}, 0.0f, 0.75f),
        plainMaterial("brick", {0.55f, 0.25f, 0.18f}, 0.0f, 0.85f),
        plainMaterial("painted steel", {0.55f, 0.56f, 0.58f}, 1.0f, 0.45f),
        plainMaterial("blue plastic", {0.10f, 0.25f, 0.65f}, 0.0f, 0.30f),
        plainMaterial("bark", {0.30f, 0.22f, 0.15f}, 0.0f, 0.95f),
        plainMaterial("foliage", {0.16f, 0.34f, 0.12f}, 0.0f, 0.85f),
        plainMaterial("facade", {0.58f, 0.55f, 0.50f}, 0.0f, 0.65f),
    };
}

// Street lamps stand in two rows along the street, every kLampSpacing metres from kFirstLampZ;
// bollards stand along the left kerb between them. Lights and poles share these numbers.
constexpr int kLampsPerSide = 8;
constexpr float kLeftLampX = -8.0f;
constexpr float kRightLampX = 9.0f;
constexpr float kFirstLampZ = -7.0f;
constexpr float kLampSpacing = 8.0f;
constexpr float kLampPostHeight = 5.6f;
constexpr float kLampArm = 1.1f;  // the lamp head hangs this far out over the street
constexpr float kLampHeadY = 5.4f;
constexpr int kBollards = 16;
constexpr float kBollardX = -3.2f;
constexpr float kFirstBollardZ = -3.0f;
constexpr float kBollardSpacing = 3.5f;
constexpr float kBollardHeight = 0.8f;
constexpr float kBollardLightAbove = 0.25f;  // the lantern floats above the bollard's top

float lampZ(int i) { return kFirstLampZ - kLampSpacing * static_cast<float>(i); }
float bollardZ(int i) { return kFirstBollardZ - kBollardSpacing * static_cast<float>(i); }

// Near to far, so a cascade split shows in which part of the list its casters are:
//  - a post-and-rail fence right of the eye, its top rail 0.9 m from it, running 30 m ahead;
//  - crates, stacked crates and pillars 2-20 m away, some turned;
//  - lamp posts and bollards along the street to 63 m;
//  - a row of trees (box trunk, box canopy) on the left to 135 m, a row of low walls on the
//    right to 133 m, both at a slant;
//  - five buildings 150-320 m away, the tallest 90 m.
std::vector<BoxSpec> outdoorLayout() {
    using outdoor_scene::kGroundFarZ;
    using outdoor_scene::kGroundHalfWidth;
    using outdoor_scene::kGroundNearZ;
    std::vector<BoxSpec> boxes = {
        {"ground", {-kGroundHalfWidth, -0.2f, kGroundFarZ}, {kGroundHalfWidth, 0.0f, kGroundNearZ}, kGround},
        {"fence top rail", {0.55f, 0.92f, -30.0f}, {0.61f, 1.0f, 1.5f}, kWood},
        {"fence middle rail", {0.55f, 0.45f, -30.0f}, {0.61f, 0.52f, 1.5f}, kWood},
    };
    for (int i = 0; i < 13; ++i) {
        const float z = 1.2f - 2.5f * static_cast<float>(i);
        boxes.push_back(standing("fence post", 0.58f, z, {0.08f, 1.05f, 0.08f}, kWood));
    }

    const std::vector<BoxSpec> near = {
        standing("crate", -1.3f, -2.4f, {0.7f, 0.7f, 0.7f}, kWood),
        standing("crate", -2.6f, -5.0f, {1.2f, 1.2f, 1.2f}, kBluePlastic, {4.0f, 3.0f}),         // 37 deg
        standing("stacked crate", -2.6f, -5.0f, {0.6f, 0.6f, 0.6f}, kWood, {5.0f, -2.0f}, 1.2f),  // -22 deg, on top
        standing("crate", 2.0f, -7.5f, {1.0f, 0.8f, 1.4f}, kWood, {3.0f, 1.0f}),                  // 18 deg
        standing("crate", -4.5f, -11.0f, {1.5f, 1.5f, 1.5f}, kConcrete),
        standing("crate", 2.8f, -14.0f, {1.2f, 1.0f, 2.0f}, kBluePlastic, {2.0f, -1.0f}),         // -27 deg
        standing("crate", -1.8f, -18.0f, {2.0f, 1.0f, 1.0f}, kWood, {7.0f, 4.0f}),                // 30 deg
        standing("pillar", -6.5f, -7.0f, {0.6f, 5.0f, 0.6f}, kConcrete),
        standing("pillar", 4.5f, -10.0f, {0.8f, 6.0f, 0.8f}, kBrick),
        standing("pillar", -8.5f, -16.0f, {0.8f, 4.5f, 0.8f}, kConcrete, {3.0f, 2.0f}),           // 34 deg
        standing("pillar", 6.0f, -19.0f, {0.7f, 7.0f, 0.7f}, kConcrete),
    };
    boxes.insert(boxes.end(), near.begin(), near.end());

    for (int i = 0; i < kLampsPerSide; ++i) {
        boxes.push_back(standing("lamp post", kLeftLampX, lampZ(i), {0.16f, kLampPostHeight, 0.16f}, kSteel));
        boxes.push_back(standing("lamp post", kRightLampX, lampZ(i), {0.16f, kLampPostHeight, 0.16f}, kSteel));
        // The arms reach over the lamp heads, so they are above the spots and out of their cones.
        boxes.push_back(standing("lamp arm", kLeftLampX + 0.5f * kLampArm, lampZ(i), {kLampArm + 0.2f, 0.08f, 0.1f},
                                 kSteel, {1.0f, 0.0f}, kLampHeadY + 0.1f));
        boxes.push_back(standing("lamp arm", kRightLampX - 0.5f * kLampArm, lampZ(i), {kLampArm + 0.2f, 0.08f, 0.1f},
                                 kSteel, {1.0f, 0.0f}, kLampHeadY + 0.1f));
    }
    for (int i = 0; i < kBollards; ++i)
        boxes.push_back(standing("bollard", kBollardX, bollardZ(i), {0.2f, kBollardHeight, 0.2f}, kConcrete));

    // Trees every 11 m, alternately 0.8 m either side of x = -14 and turned, so the canopies'
    // shadows do not line up into one straight band.
    for (int i = 0; i < 12; ++i) {
        const float x = i % 2 == 0 ? -14.8f : -13.2f;
        const float z = -14.0f - 11.0f * static_cast<float>(i);
        const glm::vec2 facing = i % 2 == 0 ? glm::vec2(1.0f, 0.0f) : glm::vec2(4.0f, 3.0f);
        boxes.push_back(standing("tree trunk", x, z, {0.5f, 3.5f, 0.5f}, kBark, facing));
        boxes.push_back(standing("tree canopy", x, z, {3.4f, 3.2f, 3.4f}, kFoliage, facing, 3.0f));
    }
    // Low walls every 18 m on the right, turned 22 degrees off the street.
    for (int i = 0; i < 7; ++i)
        boxes.push_back(standing("wall", 14.0f, -25.0f - 18.0f * static_cast<float>(i), {7.0f, 2.2f, 0.4f}, kBrick,
                                 {5.0f, 2.0f}));

    const std::vector<BoxSpec> far = {
        standing("building", 85.0f, -150.0f, {25.0f, 20.0f, 25.0f}, kConcrete),
        standing("building", -45.0f, -185.0f, {30.0f, 28.0f, 40.0f}, kFacade, {6.0f, 1.0f}),  // 9 deg
        standing("building", 40.0f, -220.0f, {40.0f, 45.0f, 30.0f}, kBrick, {4.0f, -1.0f}),   // -14 deg
        standing("building", -100.0f, -260.0f, {40.0f, 35.0f, 30.0f}, kBrick, {3.0f, 1.0f}),  // 18 deg
        standing("tower", -5.0f, -300.0f, {35.0f, 90.0f, 35.0f}, kFacade, {5.0f, 2.0f}),      // 22 deg
    };
    boxes.insert(boxes.end(), far.begin(), far.end());
    return boxes;
}

// ---- camera ----------------------------------------------------------------------------------

// At eye height (1.7 m) on the pavement, looking down the street 9.6 degrees below the horizon
// (atan(1.7 / 10)) and 4.6 degrees to the left of -z: the fence runs up the lower right of the
// frame, the horizon lies 9.6 degrees above the centre of the 60 degree field of view, and the
// buildings rise above it. The far plane is just beyond the farthest corner of the ground.
// (Built with lookAt from points, no trigonometry, so it is the same everywhere.)
void addCamera(Scene& scene) {
    Camera& camera = scene.camera;
    camera.name = "outdoor";
    const glm::vec3 eye(0.0f, 1.7f, 0.0f);
    const glm::vec3 target(-0.8f, 0.0f, -10.0f);
    camera.view = glm::lookAtRH(eye, target, glm::vec3(0.0f, 1.0f, 0.0f));
    camera.yfov = 1.04719755f;  // 60 degrees
    camera.znear = 0.1f;        // the fence's top rail is 0.9 m from the eye
    camera.zfar = farthestViewDepth(scene.bounds, camera.view) + 1.0f;
    scene.cameraFromFile = true;
}

// ---- lights ----------------------------------------------------------------------------------

constexpr float kDegree = 0.0174532925f;

// The sun: 36 degrees above the horizon (asin(0.8 / |(1, 0.8, 0.45)|)), behind the camera and to
// its right, so shadows fall away from the eye and to the left, long and across the street, and
// no shadow edge follows a box's axis. 2.5 lux (not the real 100,000: nothing here is exposed for
// daylight, and the lamps would vanish) lights the ground with 1.5 lux, which shows as mid-grey
// (sRGB 0.53) at exposure 1, leaving headroom for the lamps' pools.
void addSun(Scene& scene) {
    Light sun;
    sun.name = "sun";
    sun.type = LightType::Directional;
    sun.direction = glm::normalize(glm::vec3(-1.0f, -0.8f, -0.45f));
    sun.color = glm::vec3(1.0f, 0.95f, 0.86f);  // a late-afternoon white; the largest channel is 1
    sun.intensity = 2.5f;
    sun.castsShadow = true;
    scene.lights.push_back(sun);
}

// One spot per lamp head, shining down and 14 degrees out over the street (and a little ahead,
// so no cone is symmetric about an axis), outer cone 50 degrees: each lights a pool about 13 m
// across. Range twice the distance to the ground along the axis; 2-4 lux there.
void addStreetLamps(Scene& scene, PortableRandom& random) {
    for (int i = 0; i < 2 * kLampsPerSide; ++i) {
        const bool left = i % 2 == 0;
        const float poleX = left ? kLeftLampX : kRightLampX;
        Light light;
        light.name = "street lamp " + std::to_string(i);
        light.type = LightType::Spot;
        light.position = glm::vec3(poleX + (left ? kLampArm : -kLampArm), kLampHeadY, lampZ(i / 2));
        light.direction = glm::normalize(glm::vec3(left ? 0.25f : -0.25f, -1.0f, -0.12f));
        light.color = randomLightColor(random);
        light.outerConeAngle = 50.0f * kDegree;
        light.innerConeAngle = 30.0f * kDegree;
        const float axisDistance = kLampHeadY / -light.direction.y;
        light.range = 2.0f * axisDistance;
        light.intensity = intensityForIlluminance(random.uniform(2.0f, 4.0f), axisDistance, light.range);
        light.castsShadow = true;
        scene.lights.push_back(light);
    }
}

// A lantern above each bollard, range 6 m, 1.5-3 lux on the ground 1.5 m from the bollard.
void addBollardLights(Scene& scene, PortableRandom& random) {
    const float height = kBollardHeight + kBollardLightAbove;
    for (int i = 0; i < kBollards; ++i) {
        Light light;
        light.name = "bollard " + std::to_string(i);
        light.type = LightType::Point;
        light.position = glm::vec3(kBollardX, height, bollardZ(i));
        light.direction = glm::vec3(0.0f, -1.0f, 0.0f);
        light.color = randomLightColor(random);
        light.range = 6.0f;
        const float distance = glm::length(glm::vec2(1.5f, height));
        light.intensity = intensityForIlluminance(random.uniform(1.5f, 3.0f), distance, light.range);
        light.castsShadow = true;
        scene.lights.push_back(light);
    }
}

}  // namespace

// ---- the drive (issue 34) --------------------------------------------------------------------

// Down the street at 6 m/s (21.6 km/h) for 10 s, at eye height between the fence (0.55 m to the
// right, to z = -30) and the crates on the left, the view fixed on a point 10 m ahead, so the
// sun's cascades slide along the ground with the camera and the lamps and bollards pass by.
void poseOutdoorScene(Scene& scene, double time, const PathMotion& motion) {
    using outdoor_scene::kDriveSeconds;
    ScenePath path;
    path.eye = linearTrack({0.0f, kDriveSeconds}, {{0.0f, 1.7f, 0.0f}, {0.0f, 1.7f, -60.0f}});
    path.target = linearTrack({0.0f, kDriveSeconds}, {{-0.8f, 0.0f, -10.0f}, {-0.8f, 0.0f, -70.0f}});
    path.seconds = double(kDriveSeconds);
    addSwayingLights(path, uint32_t(scene.lights.size()), motion.lights.value_or(0.0));
    addLiftedProps(path, scene, motion.casters);
    applyScenePath(scene, path, time);
}

Scene makeOutdoorScene() {
    Scene scene;
    scene.source = outdoor_scene::kSource;
    addMaterials(scene);
    addBoxes(scene, outdoorLayout());
    scene.computeBounds();
    addCamera(scene);
    addSun(scene);
    PortableRandom random(0x6F7574646F6F72ull);  // "outdoor": any fixed value works
    addStreetLamps(scene, random);
    addBollardLights(scene, random);
    return scene;
}

}  // namespace punctual
