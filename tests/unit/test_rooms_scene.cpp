// The procedural rooms scene (--scene rooms): the triangle count lands near its target, objects
// and triangles grow together, the same target gives the same scene bit for bit, memory grows
// linearly with the triangles, the foliage is alpha-masked and mipmapped, and the lamps stand in
// view, clear of the furniture. Plus the meshes it is built of: unitCircle's known values and
// lathes whose triangles face outwards.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "scene/procedural_meshes.h"
#include "scene/rooms_scene.h"
#include "scene_test_support.h"

namespace punctual {
namespace {

// The scene's own memory: vertices, indices, meshes, objects, textures (every level).
size_t sceneBytes(const Scene& scene) {
    size_t bytes = scene.vertices.size() * sizeof(Vertex) + scene.indices.size() * sizeof(uint32_t) +
                   scene.meshes.size() * sizeof(Mesh) + scene.objects.size() * sizeof(Object);
    for (const Texture& texture : scene.textures) {
        bytes += texture.rgba.size();
        for (const TextureLevel& level : texture.mipLevels) bytes += level.rgba.size();
    }
    return bytes;
}

// The triangles the camera would draw with no culling: every object's mesh.
uint64_t drawnTriangles(const Scene& scene) {
    uint64_t triangles = 0;
    for (const Object& object : scene.objects) triangles += scene.meshes[object.mesh].indexCount / 3;
    return triangles;
}

TEST(RoomsScene, UnitCircleKnownValues) {
    // Quarter turns are exact: the quadrant is found in integers and x = 0 there.
    EXPECT_EQ(unitCircle(0, 4), glm::vec2(1.0f, 0.0f));
    EXPECT_EQ(unitCircle(1, 4), glm::vec2(0.0f, 1.0f));
    EXPECT_EQ(unitCircle(2, 4), glm::vec2(-1.0f, 0.0f));
    EXPECT_EQ(unitCircle(3, 4), glm::vec2(0.0f, -1.0f));
    EXPECT_EQ(unitCircle(5, 4), unitCircle(1, 4));  // k wraps
    // 45 degrees: (sqrt(2)/2, sqrt(2)/2); 30 degrees: (sqrt(3)/2, 1/2); 210 degrees: (-sqrt(3)/2, -1/2).
    EXPECT_NEAR(unitCircle(1, 8).x, 0.70710678f, 2e-7f);
    EXPECT_NEAR(unitCircle(1, 8).y, 0.70710678f, 2e-7f);
    EXPECT_NEAR(unitCircle(1, 12).x, 0.86602540f, 2e-7f);
    EXPECT_NEAR(unitCircle(1, 12).y, 0.5f, 2e-7f);
    EXPECT_NEAR(unitCircle(7, 12).x, -0.86602540f, 2e-7f);
    EXPECT_NEAR(unitCircle(7, 12).y, -0.5f, 2e-7f);
    for (uint32_t k = 0; k < 97; ++k) EXPECT_NEAR(glm::length(unitCircle(k, 97)), 1.0f, 3e-7f) << k;
}

TEST(RoomsScene, LatheTrianglesFaceOutwards) {
    const glm::vec2 profile[] = {{0.3f, 0.0f}, {0.4f, 0.5f}, {0.2f, 1.0f}};
    MeshBuilder lathe;
    lathe.addLathe(profile, 16);
    EXPECT_EQ(lathe.triangleCount(), latheTriangles(3, 16));  // 2 x 16 x 2 sides + 2 x 14 caps = 92
    EXPECT_EQ(latheTriangles(3, 16), 92u);
    Scene scene;
    lathe.appendTo(scene, "lathe", 0);
    size_t outward = 0;
    for (size_t i = 0; i < scene.indices.size(); i += 3) {
        const glm::vec3 a = scene.vertices[scene.indices[i]].position;
        const glm::vec3 b = scene.vertices[scene.indices[i + 1]].position;
        const glm::vec3 c = scene.vertices[scene.indices[i + 2]].position;
        const glm::vec3 normal = glm::cross(b - a, c - a);
        const glm::vec3 centre = (a + b + c) / 3.0f;
        // Outwards: away from the axis on the sides, down at the bottom cap, up at the top one.
        const glm::vec3 away = std::abs(normal.x) + std::abs(normal.z) > std::abs(normal.y)
                                   ? glm::vec3(centre.x, 0.0f, centre.z)
                                   : glm::vec3(0.0f, centre.y - 0.5f, 0.0f);
        if (glm::dot(normal, away) > 0.0f) ++outward;
    }
    EXPECT_EQ(outward, scene.indices.size() / 3);
}

TEST(RoomsScene, TriangleCountWithinTwoPercentOfTheTarget) {
    for (const uint64_t target : {10'000ull, 100'000ull, 1'000'000ull}) {
        const rooms_scene::Layout layout = rooms_scene::layoutFor(target);
        const Scene scene = makeRoomsScene(target);
        EXPECT_EQ(scene.triangleCount(), layout.triangles) << target;
        EXPECT_EQ(drawnTriangles(scene), layout.triangles) << target;  // every object a mesh of its own
        EXPECT_NEAR(double(scene.triangleCount()), double(target), 0.02 * double(target)) << target;
    }
    // The largest, by its layout only (building it takes a few seconds and half a gigabyte).
    const rooms_scene::Layout largest = rooms_scene::layoutFor(10'000'000);
    EXPECT_NEAR(double(largest.triangles), 1e7, 2e5);
}

TEST(RoomsScene, ObjectsAndTessellationGrowWithTheTriangles) {
    const Scene small = makeRoomsScene(10'000);
    EXPECT_GE(small.objects.size(), 10u);
    EXPECT_LE(small.objects.size(), 30u);
    const Scene large = makeRoomsScene(1'000'000);
    EXPECT_GE(large.objects.size(), 500u);
    EXPECT_LE(large.objects.size(), 2'000u);
    // 10^7: rooms x (9 pieces + crates) + the grid's closing walls, by the layout.
    const rooms_scene::Layout largest = rooms_scene::layoutFor(10'000'000);
    const uint64_t objects = uint64_t(largest.rooms) * (9 + largest.cratesPerRoom);
    EXPECT_GE(objects, 5'000u);
    EXPECT_LE(objects, 15'000u);
    EXPECT_GT(largest.segments, rooms_scene::layoutFor(10'000).segments);
    EXPECT_GE(rooms_scene::layoutFor(10'000).segments, 24u);  // round enough at the smallest
}

TEST(RoomsScene, SameTargetSameSceneBitForBit) {
    EXPECT_EQ(testing::firstSceneDifference(makeRoomsScene(100'000), makeRoomsScene(100'000)), "");
    EXPECT_NE(testing::firstSceneDifference(makeRoomsScene(100'000), makeRoomsScene(110'000)), "");
}

TEST(RoomsScene, MemoryGrowsLinearlyWithTheTriangles) {
    // About 0.55 vertices (40 bytes) and 3 indices (4 bytes) a triangle: ~34 bytes; 64 bounds it
    // at every size, and ten times the triangles take between 8 and 12 times the memory.
    const Scene tenThousand = makeRoomsScene(10'000);
    const Scene hundredThousand = makeRoomsScene(100'000);
    const Scene million = makeRoomsScene(1'000'000);
    for (const Scene* scene : {&tenThousand, &hundredThousand, &million}) {
        EXPECT_LE(double(sceneBytes(*scene)) / double(scene->triangleCount()), 64.0) << scene->triangleCount();
    }
    const double ratio = double(sceneBytes(million)) / double(sceneBytes(hundredThousand));
    EXPECT_GT(ratio, 8.0);
    EXPECT_LT(ratio, 12.0);
}

TEST(RoomsScene, FoliageIsAlphaMaskedDoubleSidedAndMipmapped) {
    const Scene scene = makeRoomsScene(100'000);
    const rooms_scene::Layout layout = rooms_scene::layoutFor(100'000);
    size_t foliage = 0;
    for (const Object& object : scene.objects) {
        const Material& material = scene.materials[scene.meshes[object.mesh].material];
        if (material.alphaMode != AlphaMode::Mask) continue;
        ++foliage;
        EXPECT_TRUE(material.doubleSided);
        ASSERT_TRUE(material.baseColorTexture.present());
        const Texture& texture = scene.textures[size_t(material.baseColorTexture.image)];
        EXPECT_EQ(texture.levelCount(), 8u);  // 128 x 128 down to 1 x 1
        // Leaves and gaps both: the mask cuts something out, and keeps something.
        size_t opaque = 0;
        for (size_t i = 3; i < texture.rgba.size(); i += 4) opaque += texture.rgba[i] >= 128;
        EXPECT_GT(opaque, texture.rgba.size() / 4 / 10);
        EXPECT_LT(opaque, texture.rgba.size() / 4 * 9 / 10);
    }
    EXPECT_EQ(foliage, layout.rooms);  // one planter a room
}

TEST(RoomsScene, LampsInViewAndClearOfTheFurniture) {
    const Scene scene = makeRoomsScene(1'000'000);
    const glm::mat4 viewProjection = scene.camera.projection(16.0f / 9.0f) * scene.camera.view;
    int spots = 0, points = 0, suns = 0;
    for (const Light& light : scene.lights) {
        if (light.type == LightType::Directional) {
            ++suns;
            continue;
        }
        (light.type == LightType::Spot ? spots : points)++;
        const glm::vec4 clip = viewProjection * glm::vec4(light.position, 1.0f);
        EXPECT_GT(clip.w, 0.0f) << light.name;
        EXPECT_LE(std::abs(clip.x), clip.w) << light.name;
        EXPECT_LE(std::abs(clip.y), clip.w) << light.name;
        for (const Object& object : scene.objects) {
            if (object.name == std::string("floor")) continue;
            EXPECT_GT(testing::distanceToObjectBox(scene, object, light.position), 0.05f) << light.name << " in " << object.name;
        }
    }
    EXPECT_EQ(spots, 64);
    EXPECT_EQ(points, 32);
    EXPECT_EQ(suns, 1);
}

TEST(RoomsScene, TargetsOutsideTheRangeFailNamingTheOption) {
    for (const uint64_t target : {0ull, 9'999ull, 10'000'001ull}) {
        try {
            rooms_scene::layoutFor(target);
            ADD_FAILURE() << target;
        } catch (const Error& error) {
            EXPECT_EQ(error.subject(), "--scene-triangles");
        }
    }
}

}  // namespace
}  // namespace punctual
