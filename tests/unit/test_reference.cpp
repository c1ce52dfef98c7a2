// The Embree reference on its own (no GPU): its conventions (Ng orientation, errors), visibility
// against an analytic shadow, texture sampling, and determinism. Its agreement with the GPU image
// is tested in tests/gpu/test_reference.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <tbb/task_arena.h>

#include "core/error.h"
#include "image_test_support.h"
#include "lights/light_setup.h"
#include "reference/reference_renderer.h"
#include "reference/texture_sampler.h"
#include "reference_test_support.h"
#include "scene/default_scene.h"
#include "scene/study_scenes.h"

namespace punctual {
namespace {

using reference::ReferenceRenderer;
using reference::ReferenceSettings;
using testing::greyMaterial;
using testing::unshadowed;

// Appends one object made of `vertices` and `triangles` (indices relative to the mesh).
void addMesh(Scene& scene, const std::vector<Vertex>& vertices, const std::vector<uint32_t>& triangles,
             const glm::mat4& model = glm::mat4(1.0f)) {
    Mesh mesh;
    mesh.name = "mesh";
    mesh.firstIndex = uint32_t(scene.indices.size());
    mesh.indexCount = uint32_t(triangles.size());
    mesh.vertexOffset = uint32_t(scene.vertices.size());
    mesh.vertexCount = uint32_t(vertices.size());
    for (const Vertex& v : vertices) mesh.localBounds.extend(v.position);
    scene.vertices.insert(scene.vertices.end(), vertices.begin(), vertices.end());
    scene.indices.insert(scene.indices.end(), triangles.begin(), triangles.end());
    scene.meshes.push_back(mesh);
    Object object;
    object.name = "mesh";
    object.mesh = uint32_t(scene.meshes.size() - 1);
    object.model = model;
    scene.objects.push_back(object);
}

// A UV sphere: `rings` bands of latitude, `segments` of longitude, outward counter-clockwise
// triangles. Returns the largest angle any triangle edge subtends at the centre, which bounds
// how far inside the true sphere the polygon can reach (see SphereShadowMatchesTheTangentCone).
double addUvSphere(Scene& scene, glm::vec3 center, float radius, int rings, int segments) {
    std::vector<Vertex> vertices;
    std::vector<uint32_t> triangles;
    for (int r = 0; r <= rings; ++r) {
        const double polar = M_PI * r / rings;
        for (int s = 0; s <= segments; ++s) {
            const double azimuth = 2.0 * M_PI * s / segments;
            const glm::vec3 n(float(std::sin(polar) * std::cos(azimuth)), float(std::cos(polar)),
                              float(std::sin(polar) * std::sin(azimuth)));
            vertices.push_back({center + radius * n, n, glm::vec2(0.0f)});
        }
    }
    const uint32_t stride = uint32_t(segments + 1);
    for (uint32_t r = 0; r < uint32_t(rings); ++r) {
        for (uint32_t s = 0; s < uint32_t(segments); ++s) {
            const uint32_t a = r * stride + s, b = a + stride;
            triangles.insert(triangles.end(), {a, a + 1, b, a + 1, b + 1, b});
        }
    }
    double maxEdgeAngle = 0.0;
    for (size_t t = 0; t < triangles.size(); t += 3) {
        for (int e = 0; e < 3; ++e) {
            const glm::dvec3 p = glm::dvec3(vertices[triangles[t + size_t(e)]].position - center);
            const glm::dvec3 q = glm::dvec3(vertices[triangles[t + size_t((e + 1) % 3)]].position - center);
            maxEdgeAngle = std::max(maxEdgeAngle, std::acos(std::clamp(glm::dot(glm::normalize(p), glm::normalize(q)), -1.0, 1.0)));
        }
    }
    addMesh(scene, vertices, triangles);
    return maxEdgeAngle;
}

// A 40 x 40 m floor whose top is the plane y = 0, optionally with a sphere above it.
Scene floorScene() {
    Scene scene;
    scene.source = "test floor";
    scene.materials.push_back(greyMaterial());
    study::addBox(scene, glm::vec3(0.0f, -0.05f, 0.0f), glm::vec3(40.0f, 0.1f, 40.0f));
    scene.camera.view = glm::lookAtRH(glm::vec3(0.0f, 8.0f, 12.0f), glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f));
    scene.camera.zfar = 60.0f;
    scene.computeBounds();
    return scene;
}

TEST(ReferenceEmbree, GeometricNormalIsCounterClockwiseFront) {
    // One triangle counter-clockwise when seen from +z, a second object behind it.
    Scene scene;
    scene.materials.push_back(greyMaterial());
    const glm::vec3 n(0.0f, 0.0f, 1.0f);
    addMesh(scene, {{{0, 0, 0}, n, {}}, {{1, 0, 0}, n, {}}, {{0, 1, 0}, n, {}}}, {0, 1, 2});
    addMesh(scene, {{{0, 0, -1}, n, {}}, {{1, 0, -1}, n, {}}, {{0, 1, -1}, n, {}}}, {0, 1, 2});
    const reference::EmbreeScene embree(scene);
    EXPECT_EQ(embree.geometryCount(), 2u);
    RTCRayHit query{};
    query.ray.org_x = 0.2f;
    query.ray.org_y = 0.2f;
    query.ray.org_z = 1.0f;
    query.ray.dir_z = -1.0f;
    query.ray.tfar = 10.0f;
    query.ray.mask = 0xFFFFFFFFu;
    query.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    // Every ray carries a RayContext: the filter functions of single-sided geometry read it.
    reference::RayContext context = reference::makeRayContext(reference::RayKind::Primary);
    rtcIntersect1(embree.handle(), &context.embree, &query);
    ASSERT_EQ(query.hit.geomID, 0u);  // geomID == object index
    const glm::vec3 ng = reference::EmbreeScene::geometricNormal(query.hit);
    EXPECT_GT(ng.z, 0.0f) << "Ng must point to the side the vertices are seen counter-clockwise from";
    EXPECT_NEAR(glm::length(glm::cross(ng, n)), 0.0f, 1e-6f);
}

TEST(ReferenceEmbree, DeviceErrorsBecomePunctualErrors) {
    const Scene scene = floorScene();
    const reference::EmbreeScene embree(scene);
    EXPECT_NO_THROW(embree.throwIfError("nothing"));
    // Attaching a geometry under an ID that object 0 already holds is an error Embree reports
    // through the device's callback.
    RTCGeometry extra = rtcNewGeometry(embree.device(), RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcAttachGeometryByID(embree.handle(), extra, 0);
    rtcReleaseGeometry(extra);
    try {
        embree.throwIfError("attaching twice");
        FAIL() << "no error reported";
    } catch (const Error& error) {
        EXPECT_EQ(error.subject(), "embree");
        EXPECT_NE(error.problem().find("attaching twice"), std::string::npos) << error.what();
    }
    EXPECT_NO_THROW(embree.throwIfError("after the report"));  // reported once
}

TEST(ReferenceVisibility, SphereShadowMatchesTheTangentCone) {
    // A sphere of radius a centred h above the floor, a point light H above the floor on the
    // same vertical. The light's cone tangent to the sphere has half-angle asin(a / (H - h)), so
    // the shadow on the floor is the disk of radius R(a) = H tan(asin(a / (H - h))).
    const double a = 1.0, h = 2.0, H = 6.0;
    auto shadowRadius = [&](double radius) { return H * std::tan(std::asin(radius / (H - h))); };
    Scene scene = floorScene();
    const double maxEdgeAngle = addUvSphere(scene, glm::vec3(0.0f, float(h), 0.0f), float(a), 64, 128);
    scene.computeBounds();
    // The polygon is inscribed: every point p of a triangle with vertices v_i on the sphere has
    // |p| >= dot(p, v0/a) >= a cos(largest edge angle). So its shadow lies between the shadows of
    // the spheres of radius aInner and a; 0.9 R(a) must be inside the inner one to be a fair test.
    const double aInner = a * std::cos(maxEdgeAngle);
    const double R = shadowRadius(a);
    ASSERT_LT(0.9 * R, shadowRadius(aInner));

    const reference::EmbreeScene embree(scene);
    const gpu::GpuPunctualLight light = packPunctualLight(study::pointLight(glm::vec3(0.0f, float(H), 0.0f), 30.0f, 50.0f));
    const glm::vec3 up(0.0f, 1.0f, 0.0f);
    EXPECT_EQ(reference::visibility(embree, glm::vec3(0.0f), up, light), 0.0f);
    for (int k = 0; k < 12; ++k) {
        const double angle = 2.0 * M_PI * (k + 0.3) / 12.0;
        const glm::vec3 direction(float(std::cos(angle)), 0.0f, float(std::sin(angle)));
        EXPECT_EQ(reference::visibility(embree, float(0.9 * R) * direction, up, light), 0.0f) << "angle " << angle;
        EXPECT_EQ(reference::visibility(embree, float(1.1 * R) * direction, up, light), 1.0f) << "angle " << angle;
    }

    // Without the occluder the same points are lit.
    const reference::EmbreeScene empty(floorScene());
    EXPECT_EQ(reference::visibility(empty, glm::vec3(0.0f), up, light), 1.0f);
    EXPECT_EQ(reference::visibility(empty, glm::vec3(float(0.9 * R), 0.0f, 0.0f), up, light), 1.0f);

    // A sun straight above casts the sphere's own silhouette: a disk of radius a.
    gpu::GpuDirectionalLight sun{};
    sun.directionToLight = glm::vec4(0.0f, 1.0f, 0.0f, 1.0f);
    EXPECT_EQ(reference::visibility(embree, glm::vec3(float(0.9 * aInner), 0.0f, 0.0f), up, sun), 0.0f);
    EXPECT_EQ(reference::visibility(embree, glm::vec3(0.0f, 0.0f, float(1.1 * a)), up, sun), 1.0f);
}

TEST(ReferenceImage, TextureSamplingIsVulkanBilinearRepeatInLinearSpace) {
    Texture texture;
    texture.width = 2;
    texture.height = 1;
    texture.rgba = {255, 0, 0, 255, 0, 0, 255, 0};
    // Texel centres: u = 0.25 and 0.75. Halfway between them: an even mix of the *linear*
    // values; at u = 0 the REPEAT wrap mixes the last and first texels evenly too.
    const glm::vec4 middle = reference::sampleBilinearRepeat(texture, glm::vec2(0.5f, 0.5f));
    EXPECT_FLOAT_EQ(middle.r, 0.5f);
    EXPECT_FLOAT_EQ(middle.b, 0.5f);
    EXPECT_FLOAT_EQ(middle.a, 0.5f);
    const glm::vec4 wrap = reference::sampleBilinearRepeat(texture, glm::vec2(-1.0f, 0.5f));
    EXPECT_FLOAT_EQ(wrap.r, 0.5f);
    EXPECT_FLOAT_EQ(reference::sampleBilinearRepeat(texture, glm::vec2(1.25f, 0.0f)).r, 1.0f);
    EXPECT_NEAR(reference::srgbToLinear(128), 0.2158605f, 1e-6f);
}

TEST(ReferenceImage, ShadowsOnlyDarkenAndRepeatBitForBit) {
    const Scene scene = makeDefaultScene();
    ReferenceSettings settings = unshadowed(320, 180);
    const ImageRgba8 lit = reference::renderReference(scene, settings);
    settings.shadows = true;
    reference::ReferenceStats stats;
    const ImageRgba8 shadowed = reference::renderReference(scene, settings, &stats);
    EXPECT_GT(stats.shadowRays, stats.primaryRays) << "about five lights reach each visible pixel";
    EXPECT_EQ(stats.primaryRays, 320u * 180u);

    // Every light term is >= 0 and shadows only remove terms, so no channel can get brighter;
    // somewhere a light must be blocked.
    size_t darker = 0;
    for (size_t i = 0; i < lit.pixels.size(); ++i) {
        ASSERT_LE(shadowed.pixels[i], lit.pixels[i]) << "pixel " << i / 4;
        darker += shadowed.pixels[i] < lit.pixels[i];
    }
    EXPECT_GT(darker, lit.pixels.size() / 100);
    EXPECT_LT(testing::meanLuma(shadowed), testing::meanLuma(lit) - 0.005);
    testing::saveTestImage("reference-default-shadows", shadowed);

    // The same bits on a second run and with one thread (no scheduling effects).
    EXPECT_TRUE(reference::renderReference(scene, settings).pixels == shadowed.pixels);
    ImageRgba8 singleThreaded;
    tbb::task_arena(1).execute([&] { singleThreaded = reference::renderReference(scene, settings); });
    EXPECT_TRUE(singleThreaded.pixels == shadowed.pixels);
}

TEST(ReferenceImage, BadSettingsNameTheOption) {
    const Scene scene = makeDefaultScene();
    ReferenceSettings settings = unshadowed(0, 10);
    try {
        ReferenceRenderer renderer(scene, settings);
        FAIL() << "accepted a zero width";
    } catch (const Error& error) {
        EXPECT_EQ(error.subject(), "--size");
    }
    settings = unshadowed(10, 10, -1.0f);
    EXPECT_THROW(ReferenceRenderer(scene, settings), Error);
}

}  // namespace
}  // namespace punctual
