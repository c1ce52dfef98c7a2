// The Embree reference as a ruler: its conventions (Ng orientation, errors), visibility against
// an analytic shadow, agreement with the GPU image where the two must agree, and determinism.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include <glm/gtc/matrix_transform.hpp>
#include <tbb/task_arena.h>

#include "core/error.h"
#include "culling_test_scenes.h"
#include "gpu_test_support.h"
#include "lights/light_setup.h"
#include "reference/reference_renderer.h"
#include "reference/texture_sampler.h"
#include "render/renderer.h"
#include "scene/default_scene.h"
#include "scene/gltf_loader.h"
#include "scene/study_scenes.h"

namespace punctual {
namespace {

using reference::ReferenceRenderer;
using reference::ReferenceSettings;
using reference::SurfaceHit;

Material greyMaterial() {
    Material material;
    material.name = "grey";
    material.baseColorFactor = glm::vec4(0.7f, 0.7f, 0.7f, 1.0f);
    material.metallic = 0.0f;
    material.roughness = 0.5f;
    return material;
}

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
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    rtcIntersect1(embree.handle(), &context, &query);
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

// ---- the reference against the GPU ------------------------------------------------------------

struct Agreement {
    size_t pixels = 0;
    size_t within = 0;                // every channel within the tolerance
    size_t offSilhouette = 0;         // differing pixels not on a silhouette or crease
    double withinFraction() const { return double(within) / double(pixels); }
};

// A pixel is on a silhouette when its 3x3 neighbourhood in the GPU depth buffer holds background
// or a view-distance jump above 3%, or when the reference's neighbouring hits cross an object
// boundary or a crease (geometric normals apart by more than ~8 degrees). There, a pixel centre
// can lie on the edge itself, and the rasteriser's tie-breaking and Embree's may pick different
// sides; anywhere else the two must agree.
Agreement compare(const ImageRgba8& gpu, const std::vector<float>& depth, const glm::mat4& projection,
                  const ImageRgba8& ref, const std::vector<SurfaceHit>& hits, const std::string& name, int tolerance = 2) {
    const int width = int(gpu.width), height = int(gpu.height);
    // View distance from depth (culling.h): a / (depth + b) with a = P[3][2], b = P[2][2].
    auto viewDistance = [&](size_t i) { return projection[3][2] / (depth[i] + projection[2][2]); };
    auto onSilhouette = [&](int x, int y) {
        const size_t centre = size_t(y) * size_t(width) + size_t(x);
        for (int dy = -1; dy <= 1; ++dy) {
            for (int dx = -1; dx <= 1; ++dx) {
                const int nx = std::clamp(x + dx, 0, width - 1), ny = std::clamp(y + dy, 0, height - 1);
                const size_t i = size_t(ny) * size_t(width) + size_t(nx);
                if (depth[i] >= 1.0f || depth[centre] >= 1.0f || !hits[i].hit || !hits[centre].hit) return true;
                if (std::abs(viewDistance(i) - viewDistance(centre)) > 0.03f * viewDistance(centre)) return true;
                if (hits[i].object != hits[centre].object) return true;
                if (glm::dot(hits[i].geometricNormal, hits[centre].geometricNormal) < 0.99f) return true;
            }
        }
        return false;
    };
    Agreement result;
    ImageRgba8 diff = gpu;
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const uint8_t* g = gpu.at(uint32_t(x), uint32_t(y));
            const uint8_t* r = ref.at(uint32_t(x), uint32_t(y));
            int worst = 0;
            for (int c = 0; c < 4; ++c) worst = std::max(worst, std::abs(int(g[c]) - int(r[c])));
            ++result.pixels;
            uint8_t* d = diff.at(uint32_t(x), uint32_t(y));
            const uint8_t shade = uint8_t(std::min(255, worst * 32));
            d[0] = d[1] = d[2] = shade;  // grey: the difference x 32
            if (worst <= tolerance) {
                ++result.within;
            } else if (onSilhouette(x, y)) {
                d[0] = 0, d[1] = 0, d[2] = 255;  // blue: differs on a silhouette (allowed)
            } else {
                ++result.offSilhouette;
                d[0] = 255, d[1] = 0, d[2] = 0;  // red: differs where it must not
            }
        }
    }
    testing::saveTestImage(name + "-gpu", gpu);
    testing::saveTestImage(name + "-reference", ref);
    testing::saveTestImage(name + "-diff", diff);
    return result;
}

struct GpuFrame {
    ImageRgba8 image;
    std::vector<float> depth;
    glm::mat4 projection;
};

GpuFrame renderGpu(vk::Context& context, const Scene& scene, uint32_t width, uint32_t height) {
    render::RenderSettings settings = testing::renderSettings(width, height);
    settings.method = render::LightListMethod::Brute;
    settings.shadows.enabled = false;  // compared with the unshadowed reference
    render::Renderer renderer(context, scene, settings);
    GpuFrame frame{renderer.render(1, 0).image, {}, renderer.projection()};
    frame.depth = renderer.readDepth();
    return frame;
}

ReferenceSettings unshadowed(uint32_t width, uint32_t height, float exposure = 1.0f) {
    ReferenceSettings settings;
    settings.width = width;
    settings.height = height;
    settings.exposure = exposure;
    settings.shadows = false;  // the GPU draws no shadows yet
    return settings;
}

void expectAgreement(const Agreement& agreement, const std::string& what) {
    EXPECT_GE(agreement.withinFraction(), 0.999) << what << ": " << agreement.pixels - agreement.within << " of "
                                                 << agreement.pixels << " pixels differ by more than 2/255";
    EXPECT_EQ(agreement.offSilhouette, 0u) << what << ": differing pixels away from silhouettes";
}

TEST(ReferenceImage, MatchesGpuBruteForceOnTheDefaultScene) {
    auto context = testing::makeValidatedContext();
    const Scene scene = makeDefaultScene();
    for (const auto& [width, height] : {std::pair<uint32_t, uint32_t>{320, 180}, {237, 161}}) {
        const std::string size = std::to_string(width) + "x" + std::to_string(height);
        const GpuFrame gpu = renderGpu(*context, scene, width, height);
        const ReferenceRenderer reference(scene, unshadowed(width, height));
        std::vector<SurfaceHit> hits;
        const ImageRgba8 image = reference.render(nullptr, &hits);
        EXPECT_GT(testing::fractionBrighterThan(image, 20), 0.6) << "a black frame would prove nothing";
        expectAgreement(compare(gpu.image, gpu.depth, gpu.projection, image, hits, "reference-default-" + size), size);

        // The check can fail: 10% more exposure in the reference breaks it.
        const ReferenceRenderer wrong(scene, unshadowed(width, height, 1.1f));
        const Agreement bad = compare(gpu.image, gpu.depth, gpu.projection, wrong.render(), hits, "reference-wrong-" + size);
        EXPECT_LT(bad.withinFraction(), 0.999) << size;
        EXPECT_GT(bad.offSilhouette, 0u) << size;
    }
    testing::expectNoValidationMessages(*context);
}

// A room seen from inside (every wall is a back face, its normal must turn to the viewer on
// both paths), with a mirrored box (negative determinant: its world winding is reversed) and a
// rotated, non-uniformly scaled one (the inverse-transpose normal matrix matters).
TEST(ReferenceImage, MatchesGpuOnBackFacesAndMirroredObjects) {
    Scene scene;
    scene.source = "room";
    scene.materials.push_back(greyMaterial());
    Material metal = greyMaterial();
    metal.baseColorFactor = glm::vec4(0.9f, 0.6f, 0.3f, 1.0f);
    metal.metallic = 1.0f;
    metal.roughness = 0.35f;
    scene.materials.push_back(metal);
    study::addBox(scene, glm::vec3(0.0f, 3.0f, 0.0f), glm::vec3(12.0f, 6.0f, 12.0f));
    Object mirrored;
    mirrored.mesh = appendBoxMesh(scene, "mirrored", glm::vec3(1.5f, 1.0f, 2.0f), 1);
    mirrored.model = glm::scale(glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(-2.0f, 1.0f, -1.0f)), 0.6f,
                                            glm::vec3(0.0f, 1.0f, 0.0f)),
                                glm::vec3(-1.0f, 1.0f, 1.0f));
    scene.objects.push_back(mirrored);
    Object squashed = mirrored;
    squashed.mesh = appendBoxMesh(scene, "squashed", glm::vec3(1.0f), 0);
    squashed.model = glm::scale(glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(2.0f, 1.2f, -2.0f)), 0.8f,
                                            glm::normalize(glm::vec3(1.0f, 1.0f, 0.0f))),
                                glm::vec3(2.5f, 0.7f, 1.2f));
    scene.objects.push_back(squashed);
    scene.lights.push_back(study::pointLight(glm::vec3(1.0f, 4.5f, 2.0f), 14.0f, 60.0f));
    scene.lights.push_back(testing::withColor(
        study::spotLight(glm::vec3(-3.0f, 5.0f, 3.0f), glm::vec3(0.3f, -1.0f, -0.6f), 14.0f, 120.0f, 0.3f, 0.6f),
        glm::vec3(0.4f, 0.7f, 1.0f)));
    scene.camera.view = glm::lookAtRH(glm::vec3(0.5f, 2.5f, 5.5f), glm::vec3(0.0f, 1.5f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f));
    scene.camera.zfar = 40.0f;
    scene.computeBounds();

    auto context = testing::makeValidatedContext();
    const GpuFrame gpu = renderGpu(*context, scene, 240, 160);
    const ReferenceRenderer reference(scene, unshadowed(240, 160));
    std::vector<SurfaceHit> hits;
    const ImageRgba8 image = reference.render(nullptr, &hits);
    size_t backFaces = 0;
    for (const SurfaceHit& hit : hits) backFaces += hit.backFace;
    EXPECT_GT(backFaces, hits.size() / 2) << "the room's inside must fill most of the frame";
    EXPECT_GT(testing::meanLuma(image), 0.1);
    expectAgreement(compare(gpu.image, gpu.depth, gpu.projection, image, hits, "reference-room"), "room");
    testing::expectNoValidationMessages(*context);
}

// A 2 x 2 m quad in the XZ plane with a 4 x 4 texture repeated twice across it (UVs 0..2:
// REPEAT wrapping and bilinear filtering across the wrap are both visible), a tinted base-colour
// factor, a sun from the side, and a camera looking down at it at an angle.
std::string writeTexturedQuad(const testing::TempFolder& folder) {
    ImageRgba8 texture;
    texture.width = 4;
    texture.height = 4;
    for (uint32_t i = 0; i < 16; ++i) {
        texture.pixels.insert(texture.pixels.end(), {uint8_t(80 + 55 * (i % 4)), uint8_t(240 - 40 * (i / 4)),
                                                     uint8_t(i % 2 ? 230 : 90), 255});
    }
    const std::string gltf = R"({
  "asset": {"version": "2.0"},
  "extensionsUsed": ["KHR_lights_punctual"],
  "extensions": {"KHR_lights_punctual": {"lights": [{"type": "directional", "intensity": 2.5}]}},
  "scene": 0,
  "scenes": [{"nodes": [0, 1, 2]}],
  "nodes": [
    {"mesh": 0},
    {"camera": 0, "translation": [0.4, 1.6, 1.9], "rotation": [-0.3826834, 0, 0, 0.9238795]},
    {"extensions": {"KHR_lights_punctual": {"light": 0}}, "rotation": [-0.5, 0.3, 0.1, 0.8062258]}
  ],
  "cameras": [{"type": "perspective", "perspective": {"yfov": 0.9, "znear": 0.1, "zfar": 10}}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3, "material": 0}]}],
  "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "baseColorFactor": [1, 0.9, 0.8, 1],
                 "metallicFactor": 0, "roughnessFactor": 0.6}}],
  "textures": [{"source": 0}],
  "images": [{"uri": "data:image/png;base64,)" + testing::base64(encodePng(texture)) + R"("}],)" +
                             testing::quadGltfBuffers({0, 2, 2, 2, 2, 0, 0, 0}) + "\n}";
    const std::string path = folder.file("quad.gltf");
    std::ofstream(path) << gltf;
    return path;
}

TEST(ReferenceImage, MatchesGpuOnATexturedGltfQuadUnderTheSun) {
    testing::TempFolder folder;
    const Scene scene = loadGltf(writeTexturedQuad(folder));
    ASSERT_EQ(scene.textures.size(), 1u);
    auto context = testing::makeValidatedContext();
    const GpuFrame gpu = renderGpu(*context, scene, 200, 150);
    const ReferenceRenderer reference(scene, unshadowed(200, 150));
    ASSERT_EQ(reference.lights().directionalCount, 1u);
    std::vector<SurfaceHit> hits;
    const ImageRgba8 image = reference.render(nullptr, &hits);
    EXPECT_GT(testing::fractionBrighterThan(image, 40), 0.3) << "the quad must fill much of the frame, lit";
    expectAgreement(compare(gpu.image, gpu.depth, gpu.projection, image, hits, "reference-textured-quad"), "quad");
    testing::expectNoValidationMessages(*context);
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
