// Per-object light lists: candidates (the conservative reach test), ranking under the 8-light cap,
// ascending order, and the default scene's numbers.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <numeric>

#include <glm/gtc/matrix_transform.hpp>

#include "light_test_scenes.h"
#include "lights/light_setup.h"
#include "lights/per_object_lights.h"
#include "scene/default_scene.h"
#include "scene/light_generator.h"
#include "shading.h"

namespace punctual {
namespace {

using unit_testing::pointLight;
constexpr uint32_t kCap = PUNCTUAL_MAX_LIGHTS_PER_OBJECT;

struct BoxSpec {
    glm::vec3 center;
    glm::vec3 size;
};

// A scene of axis-aligned boxes (one box mesh each, placed by a translation).
Scene boxScene(const std::vector<BoxSpec>& boxes) {
    Scene scene;
    scene.materials.push_back(Material{});
    for (const BoxSpec& box : boxes) {
        Object object;
        object.name = "box";
        object.mesh = appendBoxMesh(scene, "box", box.size, 0);
        object.model = glm::translate(glm::mat4(1.0f), box.center);
        scene.objects.push_back(object);
    }
    scene.computeBounds();
    return scene;
}

Bounds boxBounds(const glm::vec3& center, const glm::vec3& halfSize) {
    Bounds bounds;
    bounds.extend(center - halfSize);
    bounds.extend(center + halfSize);
    return bounds;
}

// The shared spot light, with its direction normalized.
Light spotLight(glm::vec3 position, glm::vec3 direction, float range, float outerDegrees, float innerDegrees,
                float intensity = 10.0f) {
    return unit_testing::spotLight(position, glm::normalize(direction), range, outerDegrees, innerDegrees, intensity);
}

// Packs the lights in the given order (callers list spots first, as setupFrameLights does).
FrameLights packByHand(const std::vector<Light>& lights) {
    FrameLights frame;
    for (uint32_t i = 0; i < lights.size(); ++i) {
        frame.packed.push_back(packPunctualLight(lights[i]));
        frame.sceneLightIndex.push_back(i);
        ++(lights[i].type == LightType::Spot ? frame.spotCount : frame.pointCount);
    }
    return frame;
}

std::vector<uint32_t> listOf(const PerObjectLightLists& lists, size_t object) {
    const auto first = lists.lights.begin() + static_cast<std::ptrdiff_t>(object * kCap);
    return {first, first + lists.counts[object]};
}

float squaredDistanceToBox(const glm::vec3& p, const Bounds& box) {
    const glm::vec3 offset = p - glm::clamp(p, box.min, box.max);
    return glm::dot(offset, offset);
}

// True when the shader lights some point of an n x n x n grid spanning the box (corners included).
bool gridPointLit(const gpu::GpuPunctualLight& light, const Bounds& box, int n) {
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            for (int k = 0; k < n; ++k) {
                const glm::vec3 t = glm::vec3(float(i), float(j), float(k)) / float(n - 1);
                if (gpu::punctualAttenuation(light, glm::mix(box.min, box.max, t)) > 0.0f) return true;
            }
    return false;
}

// ---- candidates and order ------------------------------------------------------------------------

TEST(PerObjectLights, ObjectReachedByThreeLightsGetsExactlyThoseAscending) {
    const Scene scene = boxScene({{{0, 0, 0}, {2, 2, 2}}, {{30, 0, 0}, {2, 2, 2}}});
    const std::vector<Light> lights = {
        spotLight({0, 4, 0}, {0, -1, 0}, 8.0f, 30, 20),   // 0: above box A, aimed at it
        spotLight({3, 0, 0}, {0, 0, 1}, 5.0f, 30, 20),    // 1: beside A, aimed away (+z)
        spotLight({36, 0, 0}, {-1, 0, 0}, 8.0f, 10, 5),   // 2: narrow spot aimed at box B
        pointLight({50, 0, 0}, 3.0f),                      // 3: far from both
        pointLight({2, 0, 0}, 3.0f),                       // 4: reaches A
        pointLight({0, 0, -2.5f}, 2.0f),                   // 5: reaches A (1.5 m from its face)
    };
    const FrameLights frame = packByHand(lights);
    const PerObjectLightLists lists = buildPerObjectLightLists(scene, frame);

    ASSERT_EQ(lists.counts.size(), 2u);
    ASSERT_EQ(lists.lights.size(), 2u * kCap);
    EXPECT_EQ(listOf(lists, 0), (std::vector<uint32_t>{0, 4, 5}));
    EXPECT_EQ(listOf(lists, 1), (std::vector<uint32_t>{2}));
    for (size_t object = 0; object < 2; ++object)
        for (uint32_t k = lists.counts[object]; k < kCap; ++k) EXPECT_EQ(lists.lights[object * kCap + k], kUnusedLightSlot);
    EXPECT_EQ(lists.objectsOverCap, 0u);
    EXPECT_EQ(lists.maxCandidates, 3u);

    // Light 1 is rejected by the cone test, not by a sphere: its range sphere and its cone's
    // bounding sphere both overlap box A.
    const Bounds& boxA = scene.objects[0].worldBounds;
    const BoundingSphere sphere = lightBoundingSphere(lights[1]);
    EXPECT_LT(squaredDistanceToBox(sphere.center, boxA), sphere.radius * sphere.radius);
    EXPECT_LT(squaredDistanceToBox(lights[1].position, boxA), lights[1].range * lights[1].range);
    EXPECT_FALSE(lightMayReachBox(frame.packed[1], boxA));
    EXPECT_EQ(estimatedContribution(frame.packed[1], boxA), 0.0f);
    // The far light misses both; the aimed spots are kept with a positive contribution.
    EXPECT_FALSE(lightMayReachBox(frame.packed[3], boxA));
    EXPECT_FALSE(lightMayReachBox(frame.packed[3], scene.objects[1].worldBounds));
    EXPECT_GT(estimatedContribution(frame.packed[0], boxA), 0.0f);
    EXPECT_GT(estimatedContribution(frame.packed[2], scene.objects[1].worldBounds), 0.0f);
}

TEST(PerObjectLights, SpotBehindOrBesideBoxIsRejectedAimedSpotKept) {
    const Bounds box = boxBounds({0, 0, 0}, {1, 1, 1});
    // Aimed straight away (+x, box behind it) with a 90 degree cone: a half-space light.
    EXPECT_FALSE(lightMayReachBox(packPunctualLight(spotLight({1.5f, 0, 0}, {1, 0, 0}, 10.0f, 90, 60)), box));
    // The same light aimed at the box, and at a corner it only just sees.
    EXPECT_TRUE(lightMayReachBox(packPunctualLight(spotLight({1.5f, 0, 0}, {-1, 0, 0}, 10.0f, 90, 60)), box));
    EXPECT_TRUE(lightMayReachBox(packPunctualLight(spotLight({1.5f, 0, 0}, {0, 0, 1}, 10.0f, 90, 60)), box));
    // Narrow spot passing 0.5 m beside the box.
    EXPECT_FALSE(lightMayReachBox(packPunctualLight(spotLight({-5, 0, 1.5f}, {1, 0, 0}, 10.0f, 3, 1)), box));
    EXPECT_TRUE(lightMayReachBox(packPunctualLight(spotLight({-5, 0, 0.5f}, {1, 0, 0}, 10.0f, 3, 1)), box));
    // A light inside the box always reaches it, whatever its aim.
    EXPECT_TRUE(lightMayReachBox(packPunctualLight(spotLight({0.5f, 0, 0}, {1, 0, 0}, 0.1f, 5, 1)), box));
    // An empty box is never reached.
    EXPECT_FALSE(lightMayReachBox(packPunctualLight(pointLight({0, 0, 0}, 5.0f)), Bounds{}));
}

TEST(PerObjectLights, FloorUnderTwentyLightsKeepsTheEightStrongest) {
    const Scene scene = boxScene({{{0, -0.1f, 0}, {40, 0.2f, 30}}});
    std::vector<Light> lights;
    for (int i = 0; i < 20; ++i) {
        const glm::vec3 position(-18.0f + 1.9f * float(i), 1.0f + 0.15f * float(i), float((i * 7) % 13) - 6.0f);
        Light light = i % 3 == 0 ? spotLight(position, {0.1f * float(i % 4), -1, 0}, 6.0f, 40, 25)
                                 : pointLight(position, 5.0f + 0.1f * float(i));
        light.intensity = 10.0f + 3.0f * float((i * 37) % 20);
        lights.push_back(light);
    }
    std::stable_partition(lights.begin(), lights.end(), [](const Light& l) { return l.type == LightType::Spot; });
    const FrameLights frame = packByHand(lights);
    const PerObjectLightLists lists = buildPerObjectLightLists(scene, frame);

    EXPECT_EQ(lists.counts[0], kCap);
    EXPECT_EQ(lists.objectsOverCap, 1u);
    EXPECT_EQ(lists.maxCandidates, 20u);

    const Bounds& floor = scene.objects[0].worldBounds;
    std::vector<uint32_t> ranked(frame.packed.size());
    std::iota(ranked.begin(), ranked.end(), 0u);
    std::vector<float> contribution;
    for (const gpu::GpuPunctualLight& light : frame.packed) contribution.push_back(estimatedContribution(light, floor));
    for (const float c : contribution) EXPECT_GT(c, 0.0f);
    std::stable_sort(ranked.begin(), ranked.end(), [&](uint32_t a, uint32_t b) { return contribution[a] > contribution[b]; });
    ranked.resize(kCap);
    std::sort(ranked.begin(), ranked.end());
    EXPECT_EQ(listOf(lists, 0), ranked);
}

TEST(PerObjectLights, TiesGoToTheLowerPackedIndex) {
    const Scene scene = boxScene({{{0, -0.1f, 0}, {40, 0.2f, 30}}});
    // Ten identical lights at the same spot: all tie, so the first eight are kept.
    const std::vector<Light> lights(10, pointLight({0, 2, 0}, 5.0f));
    const PerObjectLightLists lists = buildPerObjectLightLists(scene, packByHand(lights));
    EXPECT_EQ(listOf(lists, 0), (std::vector<uint32_t>{0, 1, 2, 3, 4, 5, 6, 7}));
}

TEST(PerObjectLights, NoObjectsOrNoLights) {
    const PerObjectLightLists none = buildPerObjectLightLists(Scene{}, packByHand({pointLight({0, 0, 0}, 1.0f)}));
    EXPECT_TRUE(none.lights.empty());
    EXPECT_TRUE(none.counts.empty());
    const PerObjectLightLists dark = buildPerObjectLightLists(boxScene({{{0, 0, 0}, {1, 1, 1}}}), FrameLights{});
    EXPECT_EQ(dark.counts, std::vector<uint32_t>{0u});
    EXPECT_EQ(dark.lights, std::vector<uint32_t>(kCap, kUnusedLightSlot));
    EXPECT_EQ(dark.maxCandidates, 0u);
}

// ---- the reach test is conservative --------------------------------------------------------------

// Random lights against random boxes: whenever the shader lights a grid point of the box, the
// light must be a candidate. Also counts how often the cone test rejects a spot whose bounding
// sphere overlaps the box, so the test cannot pass by accepting everything.
TEST(PerObjectReach, ConservativeForRandomLightsAndBoxes) {
    PortableRandom random(20240611u);
    int litCases = 0, rejected = 0, rejectedByCone = 0, acceptedUnlit = 0;
    constexpr int kCases = 4000;
    for (int c = 0; c < kCases; ++c) {
        const glm::vec3 position(random.uniform(-4, 4), random.uniform(-4, 4), random.uniform(-4, 4));
        const float range = random.uniform(0.5f, 6.0f);
        Light light = pointLight(position, range, random.uniform(1.0f, 100.0f));
        if (c % 4 != 0) {  // three in four are spots, some of them half-space (90 degree) ones
            const glm::vec3 direction(random.uniform(-1, 1), random.uniform(-1, 1), random.uniform(-1, 1));
            const float outer = c % 17 == 1 ? 90.0f : random.uniform(2.0f, 90.0f);
            light = spotLight(position, glm::length(direction) > 0.01f ? direction : glm::vec3(0, -1, 0), range, outer,
                              outer * random.uniform(0.0f, 0.95f), light.intensity);
        }
        const glm::vec3 center(random.uniform(-5, 5), random.uniform(-5, 5), random.uniform(-5, 5));
        const glm::vec3 half(random.uniform(0.02f, 2.5f), random.uniform(0.02f, 2.5f), random.uniform(0.02f, 2.5f));
        const Bounds box = boxBounds(center, half);
        const gpu::GpuPunctualLight packed = packPunctualLight(light);

        const bool mayReach = lightMayReachBox(packed, box);
        const float contribution = estimatedContribution(packed, box);
        EXPECT_GE(contribution, 0.0f);
        if (!mayReach) {
            EXPECT_EQ(contribution, 0.0f);
        }
        if (gridPointLit(packed, box, 9)) {
            ++litCases;
            EXPECT_TRUE(mayReach) << "case " << c << ": lit box rejected";
            EXPECT_GT(contribution, 0.0f) << "case " << c;
        } else if (mayReach) {
            ++acceptedUnlit;
        }
        if (!mayReach) {
            ++rejected;
            const BoundingSphere sphere = lightBoundingSphere(light);
            if (light.type == LightType::Spot && squaredDistanceToBox(sphere.center, box) < sphere.radius * sphere.radius)
                ++rejectedByCone;
        }
    }
    std::cout << "[ stats    ] " << kCases << " cases: " << litCases << " lit, " << rejected << " rejected ("
              << rejectedByCone << " by the cone test), " << acceptedUnlit << " accepted with no lit grid point\n";
    EXPECT_GT(litCases, kCases / 10);
    EXPECT_GT(rejected, kCases / 10);
    EXPECT_GT(rejectedByCone, kCases / 50);
}

// Tiny boxes around points just inside the lit region (near the cone's edge and near the range)
// are candidates: the slack errs on the side of keeping lights.
TEST(PerObjectReach, TinyBoxesJustInsideTheEdgesAreReached) {
    PortableRandom random(7u);
    int litPoints = 0;
    for (int c = 0; c < 2000; ++c) {
        const float outer = random.uniform(1.0f, 90.0f);
        const Light light = spotLight({random.uniform(-50, 50), random.uniform(-50, 50), random.uniform(-50, 50)},
                                      {random.uniform(-1, 1), random.uniform(-1, 1), 0.3f}, random.uniform(0.2f, 20.0f),
                                      outer, outer * 0.5f);
        const gpu::GpuPunctualLight packed = packPunctualLight(light);
        // A direction 0.999 of the way to the outer angle, at 0.999 of the range.
        const glm::vec3 axis = glm::vec3(packed.directionAngleScale);
        const glm::vec3 side = glm::normalize(glm::cross(axis, glm::vec3(0.3f, 0.5f, 0.8f)));
        const float angle = light.outerConeAngle * 0.999f;
        const glm::vec3 direction = axis * std::cos(angle) + side * std::sin(angle);
        const glm::vec3 point = light.position + direction * (light.range * 0.999f);
        const Bounds box = boxBounds(point, glm::vec3(1e-4f));
        if (gpu::punctualAttenuation(packed, point) > 0.0f) {
            ++litPoints;
            EXPECT_TRUE(lightMayReachBox(packed, box)) << "case " << c;
        }
    }
    EXPECT_GT(litPoints, 1900);  // the construction really lands inside the lit region
}

TEST(PerObjectReach, PackedBoundingSphereMatchesLightBoundingSphere) {
    for (const Light& light : {pointLight({1, 2, 3}, 4.0f), spotLight({1, 2, 3}, {0, -1, 0}, 5.0f, 30, 10),
                               spotLight({-1, 0, 2}, {1, 1, 0}, 7.0f, 70, 50), spotLight({0, 0, 0}, {0, 0, -1}, 3.0f, 90, 80)}) {
        const BoundingSphere expected = lightBoundingSphere(light);
        const BoundingSphere actual = packedLightBoundingSphere(packPunctualLight(light));
        EXPECT_NEAR(glm::distance(expected.center, actual.center), 0.0f, 1e-4f);
        EXPECT_NEAR(actual.radius, expected.radius, 1e-4f * expected.radius);
    }
}

// ---- ranking -------------------------------------------------------------------------------------

TEST(PerObjectContribution, PointLightKnownAnswer) {
    const Bounds box = boxBounds({0, 0, 0}, {1, 1, 1});
    const float intensity = 40.0f, range = 10.0f, distance = 2.5f;
    Light light = pointLight({0, 0, 1.0f + distance}, range, intensity);
    light.color = {1.0f, 0.5f, 0.25f};  // peak channel 1: peak radiant intensity = intensity
    const float expected = intensity * gpu::distanceAttenuation(distance * distance, 1.0f / (range * range));
    EXPECT_EQ(estimatedContribution(packPunctualLight(light), box), expected);
    EXPECT_GT(expected, 0.0f);
}

TEST(PerObjectContribution, SpotAimedAtTheBoxHasItsAxisFactor) {
    const Bounds box = boxBounds({0, 0, 0}, {1, 1, 1});
    const gpu::GpuPunctualLight packed = packPunctualLight(spotLight({0, 0, 3.5f}, {0, 0, -1}, 10.0f, 40, 20, 40.0f));
    const float angular = gpu::spotAttenuation(glm::vec3(0, 0, -1), glm::vec3(0, 0, 1), packed.directionAngleScale.w,
                                               packed.angleOffsetShadow.x);
    EXPECT_NEAR(angular, 1.0f, 1e-6f);
    EXPECT_EQ(estimatedContribution(packed, box), 40.0f * gpu::distanceAttenuation(6.25f, 0.01f) * angular);
}

TEST(PerObjectContribution, GrazingSpotGetsTheFloorFactor) {
    // A spot 1 m above a wide floor, shining horizontally: neither the floor point below it nor
    // the floor's centre is in its 30 degree cone, but the cone meets the floor from x = 1.73 m.
    const Bounds floor = boxBounds({0, -0.5f, 0}, {10, 0.5f, 10});
    const gpu::GpuPunctualLight packed = packPunctualLight(spotLight({0, 1, 0}, {1, 0, 0}, 20.0f, 30, 20, 40.0f));
    ASSERT_TRUE(lightMayReachBox(packed, floor));
    EXPECT_EQ(estimatedContribution(packed, floor), 40.0f * gpu::distanceAttenuation(1.0f, 1.0f / 400.0f) * 0.05f);
}

TEST(PerObjectContribution, LightsInsideTheBoxRankByIntensity) {
    const Bounds box = boxBounds({0, 0, 0}, {1, 1, 1});
    const float dim = estimatedContribution(packPunctualLight(pointLight({0.2f, 0, 0}, 5.0f, 5.0f)), box);
    const float bright = estimatedContribution(packPunctualLight(pointLight({-0.7f, 0.3f, 0}, 5.0f, 10.0f)), box);
    EXPECT_GT(dim, 0.0f);
    EXPECT_FLOAT_EQ(bright / dim, 2.0f);
}

// ---- the default scene ---------------------------------------------------------------------------

struct DefaultSceneLists {
    Scene scene = makeDefaultScene();
    FrameLights frame;
    PerObjectLightLists lists;
    DefaultSceneLists() {
        frame = setupFrameLights(scene, scene.camera.view, scene.camera.projection(default_scene::kDesignAspect));
        lists = buildPerObjectLightLists(scene, frame);
    }
};

const DefaultSceneLists& defaultSceneLists() {
    static const DefaultSceneLists lists;
    return lists;
}

TEST(PerObjectDefaultScene, ListsAreCappedAscendingAndUnique) {
    const DefaultSceneLists& d = defaultSceneLists();
    const PerObjectLightLists& lists = d.lists;
    ASSERT_EQ(lists.counts.size(), d.scene.objects.size());
    ASSERT_EQ(lists.lights.size(), d.scene.objects.size() * kCap);
    uint32_t overCap = 0;
    for (size_t object = 0; object < d.scene.objects.size(); ++object) {
        EXPECT_LE(lists.counts[object], kCap);
        const std::vector<uint32_t> list = listOf(lists, object);
        EXPECT_TRUE(std::adjacent_find(list.begin(), list.end(), std::greater_equal<uint32_t>()) == list.end())
            << "object " << object << " list not strictly ascending";
        for (const uint32_t light : list) EXPECT_LT(light, d.frame.packed.size());
        for (uint32_t k = lists.counts[object]; k < kCap; ++k) EXPECT_EQ(lists.lights[object * kCap + k], kUnusedLightSlot);
        // Candidates counted independently.
        uint32_t candidates = 0;
        for (const gpu::GpuPunctualLight& light : d.frame.packed)
            candidates += lightMayReachBox(light, d.scene.objects[object].worldBounds) ? 1u : 0u;
        EXPECT_EQ(lists.counts[object], std::min(candidates, kCap));
        overCap += candidates > kCap ? 1u : 0u;
    }
    EXPECT_EQ(lists.objectsOverCap, overCap);
    EXPECT_GE(lists.objectsOverCap, 1u);
    ASSERT_EQ(d.scene.objects[0].name, "floor");
    EXPECT_EQ(lists.counts[0], kCap);
    EXPECT_GT(lists.maxCandidates, kCap);
    EXPECT_LE(lists.maxCandidates, d.frame.packed.size());
    std::cout << "[ stats    ] default scene: " << d.scene.objects.size() << " objects, " << d.frame.packed.size()
              << " lights, " << lists.objectsOverCap << " over the cap, max candidates " << lists.maxCandidates << "\n";
}

TEST(PerObjectDefaultScene, Deterministic) {
    const DefaultSceneLists& d = defaultSceneLists();
    const PerObjectLightLists again = buildPerObjectLightLists(d.scene, d.frame);
    EXPECT_EQ(again.lights, d.lists.lights);
    EXPECT_EQ(again.counts, d.lists.counts);
    EXPECT_EQ(again.objectsOverCap, d.lists.objectsOverCap);
    EXPECT_EQ(again.maxCandidates, d.lists.maxCandidates);
}

// For an object under the cap, summing only its listed lights in list order gives the brute-force
// sum over all lights bit for bit (the others add exactly +0); over the cap the sum can only drop.
TEST(PerObjectDefaultScene, UncappedObjectsMatchBruteForceBitForBit) {
    const DefaultSceneLists& d = defaultSceneLists();
    int uncappedObjects = 0;
    for (size_t object = 0; object < d.scene.objects.size(); ++object) {
        const Bounds& box = d.scene.objects[object].worldBounds;
        uint32_t candidates = 0;
        for (const gpu::GpuPunctualLight& light : d.frame.packed) candidates += lightMayReachBox(light, box) ? 1u : 0u;
        const bool capped = candidates > kCap;
        uncappedObjects += capped ? 0 : 1;
        const std::vector<uint32_t> list = listOf(d.lists, object);
        constexpr int kGrid = 6;
        for (int i = 0; i < kGrid * kGrid * kGrid; ++i) {
            const glm::vec3 t(float(i % kGrid), float(i / kGrid % kGrid), float(i / (kGrid * kGrid)));
            const glm::vec3 p = glm::mix(box.min, box.max, t / float(kGrid - 1));
            glm::vec3 brute(0.0f), listed(0.0f);
            for (const gpu::GpuPunctualLight& light : d.frame.packed)
                brute += glm::vec3(light.radiantColor) * gpu::punctualAttenuation(light, p);
            for (const uint32_t l : list)
                listed += glm::vec3(d.frame.packed[l].radiantColor) * gpu::punctualAttenuation(d.frame.packed[l], p);
            if (capped) {
                EXPECT_TRUE(glm::all(glm::lessThanEqual(listed, brute)));
            } else {
                EXPECT_EQ(listed.x, brute.x);
                EXPECT_EQ(listed.y, brute.y);
                EXPECT_EQ(listed.z, brute.z);
            }
        }
    }
    EXPECT_GT(uncappedObjects, 0);
}

}  // namespace
}  // namespace punctual
