// The same box written as a triangle list and in every other way the loader reads triangles
// (tests/support/gltf_geometry_variants.h): each file must load the list's triangles, in world
// space, within the encoding's quantization step (exactly for the lossless ones). Plus the
// pieces on their own: the glTF rules for normalized integers, meshopt's streams and filters,
// strips without indices, and files mixing points and lines with triangles.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>

#include <gtest/gtest.h>
#include <meshoptimizer.h>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "gltf_geometry_variants.h"
#include "gltf_test_files.h"
#include "scene/gltf_detail.h"
#include "scene/gltf_loader.h"
#include "warning_capture.h"

namespace punctual {
namespace {

using nlohmann::json;
using testing::GeometryEncoding;
using testing::WarningCapture;
using unit_testing::TempDir;

// A box with no two equal sides and corners off every quantization grid, so the quantized
// encodings really round.
testing::QuadGeometry irregularBox() { return testing::boxGeometry({-0.7f, -0.2f, -0.45f}, {0.55f, 0.9f, 0.3f}); }

struct WorldVertex {
    glm::vec3 position;
    glm::vec3 normal;
    glm::vec2 uv;
};
using Triangle = std::array<WorldVertex, 3>;

// Every drawn triangle in world space, objects in order, vertices in the order they are drawn.
std::vector<Triangle> worldTriangles(const Scene& scene) {
    std::vector<Triangle> triangles;
    for (const Object& object : scene.objects) {
        const Mesh& mesh = scene.meshes[object.mesh];
        const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(object.model)));
        for (uint32_t i = 0; i + 2 < mesh.indexCount; i += 3) {
            Triangle t;
            for (uint32_t k = 0; k < 3; ++k) {
                const Vertex& v = scene.vertices[mesh.vertexOffset + scene.indices[mesh.firstIndex + i + k]];
                t[k] = {glm::vec3(object.model * glm::vec4(v.position, 1.0f)), glm::normalize(normalMatrix * v.normal),
                        v.uv};
            }
            triangles.push_back(t);
        }
    }
    return triangles;
}

float maxDifference(const glm::vec3& a, const glm::vec3& b) {
    return std::max({std::abs(a.x - b.x), std::abs(a.y - b.y), std::abs(a.z - b.z)});
}
float maxDifference(const glm::vec2& a, const glm::vec2& b) { return std::max(std::abs(a.x - b.x), std::abs(a.y - b.y)); }

// Whether `a` is `b` started at its vertex `rotation` (the same triangle, the same winding).
bool sameTriangle(const Triangle& a, const Triangle& b, size_t rotation, const testing::EncodingTolerance& tolerance) {
    for (size_t k = 0; k < 3; ++k) {
        const WorldVertex& x = a[k];
        const WorldVertex& y = b[(k + rotation) % 3];
        if (maxDifference(x.position, y.position) > tolerance.position || maxDifference(x.normal, y.normal) > tolerance.normal ||
            maxDifference(x.uv, y.uv) > tolerance.uv)
            return false;
    }
    return true;
}

std::string paramName(const ::testing::TestParamInfo<GeometryEncoding>& info) {
    std::string name = testing::encodingName(info.param);
    for (char& c : name)
        if (c == '-') c = '_';
    return name;
}

class GltfGeometryEncodings : public ::testing::TestWithParam<GeometryEncoding> {};

TEST_P(GltfGeometryEncodings, LoadTheTrianglesOfTheList) {
    TempDir dir;
    const testing::QuadGeometry box = irregularBox();
    const Scene reference = loadGltf(testing::writeGeometryScene(dir.path().string(), box, GeometryEncoding::List));
    const Scene loaded = loadGltf(testing::writeGeometryScene(dir.path().string(), box, GetParam()));
    const std::vector<Triangle> expected = worldTriangles(reference);
    const std::vector<Triangle> actual = worldTriangles(loaded);
    ASSERT_EQ(expected.size(), 12u);
    ASSERT_EQ(actual.size(), expected.size());
    const testing::EncodingTolerance tolerance = testing::encodingTolerance(GetParam(), box);

    // Draco may reorder vertices and triangles, and start a triangle at another corner;
    // meshopt's TRIANGLES codec keeps the order but may also start a triangle elsewhere (it
    // rotates triangles to compress them better). Every other encoding keeps the list exactly.
    const bool reorders = GetParam() == GeometryEncoding::Draco || GetParam() == GeometryEncoding::DracoQuantized;
    const bool rotates = reorders || GetParam() == GeometryEncoding::Meshopt;
    std::vector<bool> used(actual.size(), false);
    for (size_t i = 0; i < expected.size(); ++i) {
        bool found = false;
        for (size_t j = 0; j < actual.size() && !found; ++j) {
            if (used[j] || (!reorders && j != i)) continue;
            for (size_t rotation = 0; rotation < (rotates ? 3u : 1u) && !found; ++rotation)
                found = sameTriangle(actual[j], expected[i], rotation, tolerance);
            if (found) used[j] = true;
        }
        EXPECT_TRUE(found) << "triangle " << i << " of the list (first corner " << expected[i][0].position.x << ", "
                           << expected[i][0].position.y << ", " << expected[i][0].position.z << ")";
    }
}

INSTANTIATE_TEST_SUITE_P(Encodings, GltfGeometryEncodings, ::testing::ValuesIn(testing::allGeometryEncodings()), paramName);

TEST(GltfEncodedGeometry, LosslessEncodingsGiveTheListsVerticesBitForBit) {
    TempDir dir;
    const testing::QuadGeometry box = irregularBox();
    const Scene reference = loadGltf(testing::writeGeometryScene(dir.path().string(), box, GeometryEncoding::List));
    for (GeometryEncoding encoding : {GeometryEncoding::Strip, GeometryEncoding::Meshopt}) {
        const Scene loaded = loadGltf(testing::writeGeometryScene(dir.path().string(), box, encoding));
        ASSERT_EQ(loaded.vertices.size(), reference.vertices.size()) << testing::encodingName(encoding);
        EXPECT_EQ(std::memcmp(loaded.vertices.data(), reference.vertices.data(), sizeof(Vertex) * reference.vertices.size()), 0)
            << testing::encodingName(encoding);
        ASSERT_EQ(loaded.indices.size(), reference.indices.size()) << testing::encodingName(encoding);
        // The same triangles in the same order; meshopt may start each at another corner.
        for (size_t t = 0; t < reference.indices.size(); t += 3) {
            const uint32_t* a = &loaded.indices[t];
            const uint32_t* b = &reference.indices[t];
            const bool same = (a[0] == b[0] && a[1] == b[1] && a[2] == b[2]) ||
                              (encoding == GeometryEncoding::Meshopt &&
                               ((a[0] == b[1] && a[1] == b[2] && a[2] == b[0]) || (a[0] == b[2] && a[1] == b[0] && a[2] == b[1])));
            EXPECT_TRUE(same) << testing::encodingName(encoding) << " triangle " << t / 3;
        }
    }
}

TEST(GltfEncodedGeometry, MeshoptInGlbWithAFallbackBufferWithoutData) {
    TempDir dir;
    const std::string gltfPath = testing::writeGeometryScene(dir.path().string(), irregularBox(), GeometryEncoding::Meshopt);
    std::ifstream gltfFile(gltfPath);
    json doc = json::parse(gltfFile);
    std::ifstream binFile(dir.path() / "meshopt.bin", std::ios::binary);
    const std::vector<unsigned char> bin((std::istreambuf_iterator<char>(binFile)), std::istreambuf_iterator<char>());
    // Buffer 0 becomes the BIN chunk; buffer 1 stays the fallback, with neither URI nor data.
    const json fallback = doc["buffers"][1];
    ASSERT_FALSE(fallback.contains("uri"));
    const std::string glbPath = (dir.path() / "meshopt.glb").string();
    unit_testing::writeFile(glbPath, unit_testing::glbFile(doc, bin, json::array({fallback})));
    const Scene fromGlb = loadGltf(glbPath);
    const Scene fromGltf = loadGltf(gltfPath);
    EXPECT_EQ(fromGlb.triangleCount(), 12u);
    ASSERT_EQ(fromGlb.vertices.size(), fromGltf.vertices.size());
    EXPECT_EQ(std::memcmp(fromGlb.vertices.data(), fromGltf.vertices.data(), sizeof(Vertex) * fromGltf.vertices.size()), 0);
}

// --- the pieces on their own ------------------------------------------------------------------

TEST(GltfQuantization, NormalizedIntegersFollowTheSpecsFormulas) {
    using gltf_detail::componentAsFloat;
    const auto value = [](auto stored, int componentType, bool normalized) {
        unsigned char bytes[sizeof stored];
        std::memcpy(bytes, &stored, sizeof stored);
        return componentAsFloat(bytes, componentType, normalized);
    };
    // BYTE: max(c / 127, -1): both -128 and -127 are -1.
    EXPECT_EQ(value(int8_t(127), 5120, true), 1.0f);
    EXPECT_EQ(value(int8_t(-127), 5120, true), -1.0f);
    EXPECT_EQ(value(int8_t(-128), 5120, true), -1.0f);
    EXPECT_FLOAT_EQ(value(int8_t(64), 5120, true), 64.0f / 127.0f);
    EXPECT_EQ(value(uint8_t(255), 5121, true), 1.0f);
    EXPECT_FLOAT_EQ(value(uint8_t(51), 5121, true), 0.2f);
    EXPECT_EQ(value(int16_t(-32768), 5122, true), -1.0f);
    EXPECT_EQ(value(int16_t(32767), 5122, true), 1.0f);
    EXPECT_FLOAT_EQ(value(int16_t(-16384), 5122, true), -16384.0f / 32767.0f);
    EXPECT_EQ(value(uint16_t(65535), 5123, true), 1.0f);
    // Not normalized: the integer itself.
    EXPECT_EQ(value(int8_t(-128), 5120, false), -128.0f);
    EXPECT_EQ(value(uint8_t(200), 5121, false), 200.0f);
    EXPECT_EQ(value(int16_t(-300), 5122, false), -300.0f);
    EXPECT_EQ(value(uint16_t(65535), 5123, false), 65535.0f);
    EXPECT_EQ(value(1.5f, 5126, false), 1.5f);
}

TEST(GltfQuantization, IntegerPositionsNeedTheExtension) {
    TempDir dir;
    const std::string path =
        testing::writeGeometryScene(dir.path().string(), irregularBox(), GeometryEncoding::QuantizedShortNormalized);
    std::ifstream in(path);
    json doc = json::parse(in);
    in.close();
    doc.erase("extensionsRequired");
    doc["extensionsUsed"] = {"KHR_lights_punctual"};
    unit_testing::writeFile(path, doc.dump());
    try {
        loadGltf(path);
        FAIL() << "loaded SHORT positions without KHR_mesh_quantization";
    } catch (const Error& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("POSITION accessor 0 is normalized SHORT, which needs KHR_mesh_quantization"),
                  std::string::npos)
            << message;
    }
}

// Encodes `data` as meshopt would for EXT_meshopt_compression's ATTRIBUTES mode and decodes it
// back through the loader's decoder with `filter`.
std::vector<unsigned char> roundTrip(const std::vector<unsigned char>& data, size_t count, size_t stride,
                                     gltf_detail::MeshoptStream::Filter filter) {
    std::vector<unsigned char> encoded(meshopt_encodeVertexBufferBound(count, stride));
    encoded.resize(meshopt_encodeVertexBuffer(encoded.data(), encoded.size(), data.data(), count, stride));
    gltf_detail::MeshoptStream stream;
    stream.count = count;
    stream.byteStride = stride;
    stream.filter = filter;
    std::vector<unsigned char> decoded;
    EXPECT_EQ(gltf_detail::decodeMeshoptStream(stream, encoded.data(), encoded.size(), decoded), "");
    return decoded;
}

TEST(GltfMeshopt, EveryFilterDecodesWhatMeshoptsEncoderMade) {
    using Filter = gltf_detail::MeshoptStream::Filter;
    const size_t count = 40;
    // Unit vectors, unit quaternions and plain floats, each encoded by meshopt's own filters;
    // decoding must give what meshopt's decode filters give from the same bytes.
    std::vector<float> vectors, quaternions, floats;
    for (size_t i = 0; i < count; ++i) {
        const float a = 0.37f * float(i), b = 0.11f * float(i) + 0.3f;
        const glm::vec3 v = glm::normalize(glm::vec3(std::cos(a), std::sin(a) * std::cos(b), std::sin(b) - 0.2f));
        vectors.insert(vectors.end(), {v.x, v.y, v.z, 0.0f});
        const glm::vec4 q = glm::normalize(glm::vec4(std::cos(b), std::sin(a), 0.5f, std::sin(a + b)));
        quaternions.insert(quaternions.end(), {q.x, q.y, q.z, q.w});
        floats.insert(floats.end(), {float(i) * 0.731f - 9.0f, std::ldexp(1.0f, int(i % 20) - 10), -0.001f * float(i)});
    }
    struct Case {
        Filter filter;
        size_t stride;
        std::vector<unsigned char> encoded;
    };
    std::vector<Case> cases;
    for (size_t stride : {4u, 8u}) {
        std::vector<unsigned char> oct(count * stride);
        meshopt_encodeFilterOct(oct.data(), count, stride, stride == 4 ? 8 : 16, vectors.data());
        cases.push_back({Filter::Octahedral, stride, oct});
    }
    std::vector<unsigned char> quat(count * 8);
    meshopt_encodeFilterQuat(quat.data(), count, 8, 12, quaternions.data());
    cases.push_back({Filter::Quaternion, 8, quat});
    std::vector<unsigned char> exp(count * 12);
    meshopt_encodeFilterExp(exp.data(), count, 12, 15, floats.data());
    cases.push_back({Filter::Exponential, 12, exp});
    for (const Case& c : cases) {
        std::vector<unsigned char> expected = c.encoded;
        if (c.filter == Filter::Octahedral) meshopt_decodeFilterOct(expected.data(), count, c.stride);
        if (c.filter == Filter::Quaternion) meshopt_decodeFilterQuat(expected.data(), count, c.stride);
        if (c.filter == Filter::Exponential) meshopt_decodeFilterExp(expected.data(), count, c.stride);
        EXPECT_EQ(roundTrip(c.encoded, count, c.stride, c.filter), expected) << "filter " << int(c.filter);
    }
    // And the filter really gives back the data, within its precision: 15 bits of mantissa
    // below an exponent the three components of an element share.
    const std::vector<unsigned char> decodedExp = roundTrip(exp, count, 12, Filter::Exponential);
    for (size_t i = 0; i < floats.size(); ++i) {
        float value;
        std::memcpy(&value, decodedExp.data() + 4 * i, 4);
        const size_t first = i / 3 * 3;
        const float largest = std::max({std::abs(floats[first]), std::abs(floats[first + 1]), std::abs(floats[first + 2])});
        EXPECT_NEAR(value, floats[i], largest * std::ldexp(1.0f, -13)) << i;
    }
}

TEST(GltfMeshopt, IndexModesDecodeTheIndices) {
    const std::vector<uint32_t> triangles = {0, 1, 2, 2, 1, 3, 3, 4, 2, 5, 6, 7, 7, 6, 0};
    for (size_t stride : {2u, 4u}) {
        for (auto mode : {gltf_detail::MeshoptStream::Mode::Triangles, gltf_detail::MeshoptStream::Mode::Indices}) {
            const bool asTriangles = mode == gltf_detail::MeshoptStream::Mode::Triangles;
            std::vector<unsigned char> encoded(asTriangles ? meshopt_encodeIndexBufferBound(triangles.size(), 8)
                                                           : meshopt_encodeIndexSequenceBound(triangles.size(), 8));
            encoded.resize(asTriangles
                               ? meshopt_encodeIndexBuffer(encoded.data(), encoded.size(), triangles.data(), triangles.size())
                               : meshopt_encodeIndexSequence(encoded.data(), encoded.size(), triangles.data(),
                                                             triangles.size()));
            gltf_detail::MeshoptStream stream;
            stream.mode = mode;
            stream.count = triangles.size();
            stream.byteStride = stride;
            std::vector<unsigned char> decoded;
            ASSERT_EQ(gltf_detail::decodeMeshoptStream(stream, encoded.data(), encoded.size(), decoded), "");
            ASSERT_EQ(decoded.size(), triangles.size() * stride);
            std::vector<uint32_t> values(triangles.size());
            for (size_t i = 0; i < triangles.size(); ++i)
                std::memcpy(&values[i], decoded.data() + i * stride, stride);  // little-endian
            // TRIANGLES may start a triangle at another corner, keeping its winding.
            for (size_t t = 0; t < triangles.size(); t += 3) {
                bool same = false;
                for (size_t r = 0; r < (asTriangles ? 3u : 1u); ++r)
                    same = same || (values[t] == triangles[t + r] && values[t + 1] == triangles[t + (r + 1) % 3] &&
                                    values[t + 2] == triangles[t + (r + 2) % 3]);
                EXPECT_TRUE(same) << "stride " << stride << (asTriangles ? " TRIANGLES" : " INDICES") << " triangle " << t / 3;
            }
        }
    }
}

TEST(GltfMeshopt, LayoutsTheExtensionForbidsAreRefusedBeforeDecoding) {
    using Mode = gltf_detail::MeshoptStream::Mode;
    using Filter = gltf_detail::MeshoptStream::Filter;
    const unsigned char data[64] = {0xa0};
    const auto problem = [&](Mode mode, Filter filter, size_t count, size_t stride) {
        gltf_detail::MeshoptStream stream{mode, filter, count, stride};
        std::vector<unsigned char> out;
        return gltf_detail::decodeMeshoptStream(stream, data, sizeof data, out);
    };
    // Each of these would trip an assertion inside meshoptimizer (or decode nonsense).
    EXPECT_NE(problem(Mode::Attributes, Filter::None, 4, 6), "");
    EXPECT_NE(problem(Mode::Attributes, Filter::None, 4, 260), "");
    EXPECT_NE(problem(Mode::Triangles, Filter::None, 4, 2), "");
    EXPECT_NE(problem(Mode::Indices, Filter::None, 4, 3), "");
    EXPECT_NE(problem(Mode::Indices, Filter::Exponential, 4, 4), "");
    EXPECT_NE(problem(Mode::Attributes, Filter::Octahedral, 4, 12), "");
    EXPECT_NE(problem(Mode::Attributes, Filter::Quaternion, 4, 4), "");
    // A size no 64 compressed bytes can decode to is refused without allocating it.
    EXPECT_NE(problem(Mode::Attributes, Filter::None, size_t(1) << 40, 4).find("could hold"), std::string::npos);
}

// --- topologies and skipped primitives ------------------------------------------------------

// A glTF file with one mesh of the given primitives over one 4-vertex POSITION accessor (a unit
// quad in z = 0, corners counter-clockwise) and, when `indices` is not empty, an index accessor.
std::string writeQuadPrimitives(const TempDir& dir, const std::string& name, const json& primitives,
                                const std::vector<uint16_t>& indices = {}) {
    const float positions[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    std::vector<unsigned char> bin(sizeof positions + indices.size() * 2);
    std::memcpy(bin.data(), positions, sizeof positions);
    if (!indices.empty()) std::memcpy(bin.data() + sizeof positions, indices.data(), indices.size() * 2);
    json doc = {{"asset", {{"version", "2.0"}}},
                {"scenes", {{{"nodes", {0}}}}},
                {"nodes", {{{"mesh", 0}}}},
                {"meshes", {{{"name", name}, {"primitives", primitives}}}},
                {"accessors", {unit_testing::accessorJson(0, unit_testing::kFloat, 4, "VEC3")}},
                {"bufferViews", {unit_testing::bufferViewJson(0, sizeof positions)}},
                {"buffers", {{{"uri", name + ".bin"}, {"byteLength", bin.size()}}}}};
    if (!indices.empty()) {
        doc["bufferViews"].push_back(unit_testing::bufferViewJson(sizeof positions, indices.size() * 2));
        doc["accessors"].push_back(unit_testing::accessorJson(1, unit_testing::kUnsignedShort, indices.size(), "SCALAR"));
    }
    unit_testing::writeFile(dir.path() / (name + ".bin"), bin);
    unit_testing::writeFile(dir.path() / (name + ".gltf"), doc.dump());
    return (dir.path() / (name + ".gltf")).string();
}

TEST(GltfTopology, StripAndFanWithoutIndicesUseTheVerticesInOrder) {
    TempDir dir;
    // Strip 0 1 3 2 needs indices; without them the strip is 0 1 2 3: (0 1 2), (1 3 2).
    const Scene strip = loadGltf(writeQuadPrimitives(dir, "strip", {{{"attributes", {{"POSITION", 0}}}, {"mode", 5}}}));
    ASSERT_EQ(strip.triangleCount(), 2u);
    // Without normals every triangle gets its own vertices, in triangle order.
    const glm::vec3 corners[4] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    const uint32_t stripOrder[6] = {0, 1, 2, 1, 3, 2};
    for (size_t i = 0; i < 6; ++i) EXPECT_EQ(strip.vertices[strip.indices[i]].position, corners[stripOrder[i]]) << i;
    const Scene fan = loadGltf(writeQuadPrimitives(dir, "fan", {{{"attributes", {{"POSITION", 0}}}, {"mode", 6}}}));
    ASSERT_EQ(fan.triangleCount(), 2u);
    const uint32_t fanOrder[6] = {1, 2, 0, 2, 3, 0};
    for (size_t i = 0; i < 6; ++i) EXPECT_EQ(fan.vertices[fan.indices[i]].position, corners[fanOrder[i]]) << i;
    // Both wind counter-clockwise seen from +Z, like the quad: the face normals say so.
    for (const Vertex& v : fan.vertices) EXPECT_EQ(v.normal, glm::vec3(0, 0, 1));
    EXPECT_EQ(strip.vertices[0].normal, glm::vec3(0, 0, 1));
}

TEST(GltfTopology, StripOfOnlyDegenerateTrianglesDrawsNothing) {
    TempDir dir;
    const json primitives = {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}, {"mode", 5}}};
    try {
        loadGltf(writeQuadPrimitives(dir, "flat", primitives, {0, 0, 1, 1}));
        FAIL() << "a strip of degenerate triangles loaded";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("no triangle meshes to draw"), std::string::npos) << e.what();
    }
}

TEST(GltfTopology, PointsAndLinesBesideTrianglesAreSkippedWithOneWarning) {
    TempDir dir;
    const json primitives = {{{"attributes", {{"POSITION", 0}}}, {"mode", 0}},
                             {{"attributes", {{"POSITION", 0}}}, {"indices", 1}, {"mode", 4}},
                             {{"attributes", {{"POSITION", 0}}}, {"mode", 3}},
                             {{"attributes", {{"POSITION", 0}}}, {"mode", 0}}};
    WarningCapture capture;
    const std::string path = writeQuadPrimitives(dir, "mixed", primitives, {0, 1, 2, 0, 2, 3});
    const Scene scene = loadGltf(path);
    EXPECT_EQ(scene.objects.size(), 1u);
    EXPECT_EQ(scene.triangleCount(), 2u);
    ASSERT_EQ(capture.warnings.size(), 1u);
    const std::string& warning = capture.warnings[0];
    EXPECT_NE(warning.find(path), std::string::npos) << warning;
    EXPECT_NE(warning.find("3 primitive(s)"), std::string::npos) << warning;
    EXPECT_NE(warning.find("POINTS, LINE_STRIP"), std::string::npos) << warning;
    EXPECT_EQ(warning.find('\n'), std::string::npos) << warning;
}

TEST(GltfTopology, PointsOnlyFileNamesWhatItSkipped) {
    TempDir dir;
    const std::string path = writeQuadPrimitives(dir, "points", {{{"attributes", {{"POSITION", 0}}}, {"mode", 0}}});
    WarningCapture capture;
    try {
        loadGltf(path);
        FAIL() << "a file of points loaded";
    } catch (const Error& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find(path), std::string::npos) << message;
        EXPECT_NE(message.find("no triangle meshes to draw, only 1 primitive(s) that are not triangles (POINTS)"),
                  std::string::npos)
            << message;
    }
    EXPECT_TRUE(capture.warnings.empty());  // the error says it all
}

}  // namespace
}  // namespace punctual
