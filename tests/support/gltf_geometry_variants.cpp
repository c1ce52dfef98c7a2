#include "gltf_geometry_variants.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <stdexcept>

#include <draco/compression/encode.h>
#include <draco/mesh/mesh.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtx/quaternion.hpp>
#include <meshoptimizer.h>
#include <nlohmann/json.hpp>

namespace punctual::testing {
namespace {

using nlohmann::json;

constexpr int kByte = 5120;
constexpr int kUnsignedByte = 5121;
constexpr int kShort = 5122;
constexpr int kUnsignedShort = 5123;
constexpr int kUnsignedInt = 5125;
constexpr int kFloat = 5126;

constexpr int kDracoPositionBits = 14;
constexpr int kDracoNormalBits = 10;
constexpr int kDracoUvBits = 12;
constexpr int kMeshoptExpBits = 16;
constexpr int kMeshoptOctBits = 8;

// The two triangles of quad q, in the order and winding the strip and the fans produce them.
std::vector<uint32_t> listIndices(size_t quads) {
    std::vector<uint32_t> indices;
    for (uint32_t b = 0; b < 4 * quads; b += 4) indices.insert(indices.end(), {b, b + 1, b + 3, b + 1, b + 2, b + 3});
    return indices;
}

// Each quad as b, b+1, b+3, b+2 (triangles (b, b+1, b+3) and, odd, (b+1, b+2, b+3)); between
// quads the last index and the next first one are repeated, giving four degenerate triangles
// and an even start for the next quad.
std::vector<uint32_t> stripIndices(size_t quads) {
    std::vector<uint32_t> indices;
    for (uint32_t b = 0; b < 4 * quads; b += 4) {
        if (b > 0) indices.insert(indices.end(), {b - 2, b});
        indices.insert(indices.end(), {b, b + 1, b + 3, b + 2});
    }
    return indices;
}

// A fan around corner 3 gives (b, b+1, b+3) and (b+1, b+2, b+3), as the list.
std::vector<uint32_t> fanIndices(uint32_t quad) {
    const uint32_t b = 4 * quad;
    return {b + 3, b, b + 1, b + 2};
}

struct Bounds3 {
    glm::vec3 min{1e30f};
    glm::vec3 max{-1e30f};
    glm::vec3 center() const { return (min + max) * 0.5f; }
    float maxExtent() const { return std::max({max.x - min.x, max.y - min.y, max.z - min.z}); }
};

Bounds3 boundsOf(const std::vector<glm::vec3>& points) {
    Bounds3 b;
    for (const glm::vec3& p : points) {
        b.min = glm::min(b.min, p);
        b.max = glm::max(b.max, p);
    }
    return b;
}

// A glTF document under construction, with its binary buffer 0 and (for meshopt) a fallback
// buffer 1 that only makes room for decoded views.
class Document {
public:
    json doc;
    std::vector<unsigned char> bin;
    size_t fallbackBytes = 0;

    Document() {
        doc = {{"asset", {{"version", "2.0"}}}, {"accessors", json::array()}, {"bufferViews", json::array()}};
    }

    void require(const std::string& extension) {
        for (const char* list : {"extensionsUsed", "extensionsRequired"}) {
            json& names = doc[list];
            if (std::find(names.begin(), names.end(), extension) == names.end()) names.push_back(extension);
        }
    }

    size_t append(const void* data, size_t size) {
        while (bin.size() % 4 != 0) bin.push_back(0);
        const size_t offset = bin.size();
        const auto* bytes = static_cast<const unsigned char*>(data);
        bin.insert(bin.end(), bytes, bytes + size);
        return offset;
    }

    int view(const std::vector<unsigned char>& bytes, size_t stride) {
        json v = {{"buffer", 0}, {"byteOffset", append(bytes.data(), bytes.size())}, {"byteLength", bytes.size()}};
        if (stride != 0) v["byteStride"] = stride;
        return push("bufferViews", v);
    }

    // A view whose data is the meshopt stream `compressed`, decoding to count * stride bytes of
    // the fallback buffer.
    int compressedView(const std::vector<unsigned char>& compressed, size_t count, size_t stride, const char* mode,
                       const char* filter, bool attributeStride) {
        require("EXT_meshopt_compression");
        const size_t decoded = count * stride;
        json v = {{"buffer", 1}, {"byteOffset", fallbackBytes}, {"byteLength", decoded}};
        if (attributeStride) v["byteStride"] = stride;
        fallbackBytes += (decoded + 3) / 4 * 4;
        v["extensions"]["EXT_meshopt_compression"] = {
            {"buffer", 0},        {"byteOffset", append(compressed.data(), compressed.size())},
            {"byteLength", compressed.size()}, {"byteStride", stride},
            {"count", count},     {"mode", mode}};
        if (std::string(filter) != "NONE") v["extensions"]["EXT_meshopt_compression"]["filter"] = filter;
        return push("bufferViews", v);
    }

    int accessor(int view, int componentType, size_t count, const char* type, bool normalized = false) {
        json a = {{"componentType", componentType}, {"count", count}, {"type", type}};
        if (view >= 0) a["bufferView"] = view;
        if (normalized) a["normalized"] = true;
        return push("accessors", a);
    }

    int push(const char* array, const json& value) {
        doc[array].push_back(value);
        return int(doc[array].size()) - 1;
    }
};

// `values` (components per element) as integers of type T, each element padded to `stride`.
template <typename T>
std::vector<unsigned char> packed(const std::vector<float>& values, size_t components, size_t stride) {
    const size_t count = values.size() / components;
    std::vector<unsigned char> bytes(count * stride, 0);
    for (size_t i = 0; i < count; ++i)
        for (size_t c = 0; c < components; ++c) {
            const T value = static_cast<T>(values[i * components + c]);
            std::memcpy(bytes.data() + i * stride + c * sizeof(T), &value, sizeof(T));
        }
    return bytes;
}

std::vector<float> flatten(const std::vector<glm::vec3>& v) {
    std::vector<float> out;
    for (const glm::vec3& x : v) out.insert(out.end(), {x.x, x.y, x.z});
    return out;
}
std::vector<float> flatten(const std::vector<glm::vec2>& v) {
    std::vector<float> out;
    for (const glm::vec2& x : v) out.insert(out.end(), {x.x, x.y});
    return out;
}

std::vector<unsigned char> bytesOf(const std::vector<float>& values) {
    std::vector<unsigned char> bytes(values.size() * sizeof(float));
    std::memcpy(bytes.data(), values.data(), bytes.size());
    return bytes;
}

template <typename T>
std::vector<unsigned char> indexBytes(const std::vector<uint32_t>& indices) {
    std::vector<unsigned char> bytes(indices.size() * sizeof(T));
    for (size_t i = 0; i < indices.size(); ++i) {
        const T value = static_cast<T>(indices[i]);
        std::memcpy(bytes.data() + i * sizeof(T), &value, sizeof(T));
    }
    return bytes;
}

// round(v * scale) for each value: the spec's float-to-int rule for normalized data.
std::vector<float> rounded(std::vector<float> values, float scale) {
    for (float& v : values) v = std::round(v * scale);
    return values;
}

// Stored integer positions and the node transform that maps them back to world space
// (world = translation + scale * loaded value).
struct QuantizedPositions {
    std::vector<float> values;
    glm::vec3 translation{0.0f};
    float scale = 1.0f;
};

QuantizedPositions quantizePositions(const std::vector<glm::vec3>& positions, GeometryEncoding encoding) {
    const Bounds3 b = boundsOf(positions);
    QuantizedPositions q;
    float divisor = 1.0f;  // loaded value = stored integer / divisor
    switch (encoding) {
        case GeometryEncoding::QuantizedByte:  // BYTE: -127..127 about the centre
            q.translation = b.center();
            q.scale = b.maxExtent() * 0.5f / 127.0f;
            break;
        case GeometryEncoding::QuantizedUnsignedByteNormalized:  // 0..1 from the minimum
            q.translation = b.min;
            q.scale = b.maxExtent();
            divisor = 255.0f;
            break;
        case GeometryEncoding::QuantizedShortNormalized:  // -1..1 about the centre
            q.translation = b.center();
            q.scale = b.maxExtent() * 0.5f;
            divisor = 32767.0f;
            break;
        default:  // UNSIGNED_SHORT: 0..65535 from the minimum
            q.translation = b.min;
            q.scale = b.maxExtent() / 65535.0f;
            break;
    }
    for (const glm::vec3& p : positions)
        for (int c = 0; c < 3; ++c) q.values.push_back(std::round((p[c] - q.translation[c]) / q.scale * divisor));
    return q;
}

std::vector<unsigned char> dracoData(const QuadGeometry& g, const std::vector<uint32_t>& triangles, bool quantized,
                                     uint32_t ids[3]) {
    draco::Mesh mesh;
    const size_t points = g.positions.size();
    mesh.set_num_points(uint32_t(points));
    const auto add = [&](draco::GeometryAttribute::Type type, int components, const std::vector<float>& values) {
        draco::GeometryAttribute attribute;
        attribute.Init(type, nullptr, uint8_t(components), draco::DT_FLOAT32, false,
                       int64_t(sizeof(float)) * components, 0);
        const int id = mesh.AddAttribute(attribute, true, uint32_t(points));
        for (size_t i = 0; i < points; ++i)
            mesh.attribute(id)->SetAttributeValue(draco::AttributeValueIndex(uint32_t(i)),
                                                  values.data() + i * size_t(components));
        return mesh.attribute(id)->unique_id();
    };
    ids[0] = add(draco::GeometryAttribute::POSITION, 3, flatten(g.positions));
    ids[1] = add(draco::GeometryAttribute::NORMAL, 3, flatten(g.normals));
    ids[2] = add(draco::GeometryAttribute::TEX_COORD, 2, flatten(g.uvs));
    for (size_t t = 0; t < triangles.size(); t += 3)
        mesh.AddFace({draco::PointIndex(triangles[t]), draco::PointIndex(triangles[t + 1]),
                      draco::PointIndex(triangles[t + 2])});
    draco::Encoder encoder;
    if (quantized) {
        encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, kDracoPositionBits);
        encoder.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, kDracoNormalBits);
        encoder.SetAttributeQuantization(draco::GeometryAttribute::TEX_COORD, kDracoUvBits);
        encoder.SetEncodingMethod(draco::MESH_EDGEBREAKER_ENCODING);
    } else {
        encoder.SetEncodingMethod(draco::MESH_SEQUENTIAL_ENCODING);
    }
    draco::EncoderBuffer buffer;
    const draco::Status status = encoder.EncodeMeshToBuffer(mesh, &buffer);
    if (!status.ok()) throw std::runtime_error("draco encoding failed: " + status.error_msg_string());
    return std::vector<unsigned char>(buffer.data(), buffer.data() + buffer.size());
}

std::vector<unsigned char> meshoptVertices(const std::vector<unsigned char>& data, size_t count, size_t stride) {
    std::vector<unsigned char> out(meshopt_encodeVertexBufferBound(count, stride));
    out.resize(meshopt_encodeVertexBuffer(out.data(), out.size(), data.data(), count, stride));
    return out;
}

// The camera, the lights and the material every scene shares; `meshNode` is the geometry's node.
void addSceneAround(Document& d, const json& meshNode) {
    const glm::vec3 target(0.125f, 0.25f, -0.125f);
    const glm::vec3 eye(2.2f, 1.8f, 2.6f);
    const glm::quat cameraRotation = glm::quat_cast(glm::inverse(glm::lookAt(eye, target, glm::vec3(0, 1, 0))));
    const glm::quat sunRotation = glm::rotation(glm::vec3(0, 0, -1), glm::normalize(glm::vec3(-0.4f, -1.0f, -0.6f)));
    const auto rotationJson = [](const glm::quat& q) { return json::array({q.x, q.y, q.z, q.w}); };
    d.doc["scene"] = 0;
    d.doc["scenes"] = {{{"nodes", {0, 1, 2, 3}}}};
    d.doc["nodes"] = json::array(
        {meshNode,
         {{"camera", 0}, {"translation", {eye.x, eye.y, eye.z}}, {"rotation", rotationJson(cameraRotation)}},
         {{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}, {"rotation", rotationJson(sunRotation)}},
         {{"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}, {"translation", {1.4, 2.0, 0.9}}}});
    d.doc["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.7}, {"znear", 0.1}, {"zfar", 20}}}}};
    d.doc["extensionsUsed"].push_back("KHR_lights_punctual");
    d.doc["extensions"]["KHR_lights_punctual"]["lights"] = {
        {{"type", "directional"}, {"intensity", 1.5}},
        {{"type", "point"}, {"intensity", 6.0}, {"range", 8.0}, {"color", {1.0, 0.9, 0.8}}}};
    d.doc["materials"] = {{{"pbrMetallicRoughness",
                            {{"baseColorFactor", {0.8, 0.6, 0.4, 1.0}}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.6}}}}};
}

}  // namespace

QuadGeometry boxGeometry(const glm::vec3& min, const glm::vec3& max, const glm::vec2& uvMin, const glm::vec2& uvMax) {
    // Per face: the normal and two in-plane axes u, v with u x v = normal, so the corners
    // (-u-v, +u-v, +u+v, -u+v) run counter-clockwise seen from outside.
    struct Face {
        glm::vec3 n, u, v;
    };
    const Face faces[6] = {{{1, 0, 0}, {0, 0, -1}, {0, 1, 0}}, {{-1, 0, 0}, {0, 0, 1}, {0, 1, 0}},
                           {{0, 1, 0}, {1, 0, 0}, {0, 0, -1}}, {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}},
                           {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}},  {{0, 0, -1}, {-1, 0, 0}, {0, 1, 0}}};
    const float signs[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    QuadGeometry g;
    for (const Face& face : faces)
        for (const auto& [su, sv] : signs) {
            const glm::vec3 direction = face.n + su * face.u + sv * face.v;
            // Each coordinate picked from min or max, never computed, so it is exact.
            g.positions.emplace_back(direction.x > 0 ? max.x : min.x, direction.y > 0 ? max.y : min.y,
                                     direction.z > 0 ? max.z : min.z);
            g.normals.push_back(face.n);
            g.uvs.emplace_back(su < 0 ? uvMin.x : uvMax.x, sv < 0 ? uvMin.y : uvMax.y);
        }
    return g;
}

QuadGeometry exactCubeGeometry() { return boxGeometry({-0.5f, -0.375f, -0.75f}, {0.75f, 0.875f, 0.5f}); }

const std::vector<GeometryEncoding>& allGeometryEncodings() {
    static const std::vector<GeometryEncoding> all = {
        GeometryEncoding::List,
        GeometryEncoding::Strip,
        GeometryEncoding::Fan,
        GeometryEncoding::QuantizedByte,
        GeometryEncoding::QuantizedUnsignedByteNormalized,
        GeometryEncoding::QuantizedShortNormalized,
        GeometryEncoding::QuantizedUnsignedShort,
        GeometryEncoding::Draco,
        GeometryEncoding::DracoQuantized,
        GeometryEncoding::Meshopt,
        GeometryEncoding::MeshoptFiltered,
    };
    return all;
}

std::string encodingName(GeometryEncoding encoding) {
    switch (encoding) {
        case GeometryEncoding::List: return "list";
        case GeometryEncoding::Strip: return "strip";
        case GeometryEncoding::Fan: return "fan";
        case GeometryEncoding::QuantizedByte: return "quantized-byte";
        case GeometryEncoding::QuantizedUnsignedByteNormalized: return "quantized-unsigned-byte-normalized";
        case GeometryEncoding::QuantizedShortNormalized: return "quantized-short-normalized";
        case GeometryEncoding::QuantizedUnsignedShort: return "quantized-unsigned-short";
        case GeometryEncoding::Draco: return "draco";
        case GeometryEncoding::DracoQuantized: return "draco-quantized";
        case GeometryEncoding::Meshopt: return "meshopt";
        case GeometryEncoding::MeshoptFiltered: return "meshopt-filtered";
    }
    return "unknown";
}

EncodingTolerance encodingTolerance(GeometryEncoding encoding, const QuadGeometry& geometry) {
    const Bounds3 b = boundsOf(geometry.positions);
    const float extent = b.maxExtent();
    const float largest = std::max(glm::length(b.min), glm::length(b.max));
    // Float rounding of the dequantization and of the node transform.
    const float rounding = 4e-6f * std::max(1.0f, largest);
    EncodingTolerance t;
    switch (encoding) {
        case GeometryEncoding::List:
        case GeometryEncoding::Strip:
        case GeometryEncoding::Fan:
        case GeometryEncoding::Draco:
        case GeometryEncoding::Meshopt: return t;
        case GeometryEncoding::QuantizedByte:
            t.position = extent * 0.5f / 127.0f * 0.5f;
            t.normal = 0.5f / 127.0f;
            break;
        case GeometryEncoding::QuantizedUnsignedByteNormalized:
            t.position = extent / 255.0f * 0.5f;
            t.normal = 0.5f / 32767.0f;
            t.uv = 0.5f / 127.0f;
            break;
        case GeometryEncoding::QuantizedShortNormalized:
            t.position = extent * 0.5f / 32767.0f * 0.5f;
            t.normal = 0.5f / 127.0f;
            break;
        case GeometryEncoding::QuantizedUnsignedShort:
            t.position = extent / 65535.0f * 0.5f;
            t.normal = 0.5f / 32767.0f;
            t.uv = 0.5f / 65535.0f;
            break;
        case GeometryEncoding::DracoQuantized:
            t.position = extent / float((1 << kDracoPositionBits) - 1) * 0.5f;
            t.normal = 4.0f / float(1 << kDracoNormalBits);
            t.uv = 1.0f / float((1 << kDracoUvBits) - 1) * 0.5f;
            break;
        case GeometryEncoding::MeshoptFiltered:
            t.position = largest * std::ldexp(1.0f, -kMeshoptExpBits + 1);
            t.normal = 2.0f / float((1 << (kMeshoptOctBits - 1)) - 1);
            t.uv = 0.5f / 65535.0f;
            break;
    }
    t.position += rounding;
    t.normal += 1e-6f;
    t.uv += 1e-6f;
    return t;
}

std::string writeGeometryScene(const std::string& folder, const QuadGeometry& g, GeometryEncoding encoding) {
    const std::string name = encodingName(encoding);
    const size_t vertices = g.positions.size();
    const std::vector<uint32_t> list = listIndices(g.quadCount());
    Document d;
    json node = {{"mesh", 0}};
    json attributes;
    std::vector<json> primitives;
    const auto plainFloats = [&] {
        attributes = {{"POSITION", d.accessor(d.view(bytesOf(flatten(g.positions)), 12), kFloat, vertices, "VEC3")},
                      {"NORMAL", d.accessor(d.view(bytesOf(flatten(g.normals)), 12), kFloat, vertices, "VEC3")},
                      {"TEXCOORD_0", d.accessor(d.view(bytesOf(flatten(g.uvs)), 8), kFloat, vertices, "VEC2")}};
    };
    const auto indexed = [&](const std::vector<uint32_t>& indices, int mode) {
        const int accessor = d.accessor(d.view(indexBytes<uint16_t>(indices), 0), kUnsignedShort, indices.size(), "SCALAR");
        return json{{"attributes", attributes}, {"indices", accessor}, {"mode", mode}, {"material", 0}};
    };

    switch (encoding) {
        case GeometryEncoding::List:
            plainFloats();
            primitives.push_back(indexed(list, 4));
            break;
        case GeometryEncoding::Strip:
            plainFloats();
            primitives.push_back(indexed(stripIndices(g.quadCount()), 5));
            break;
        case GeometryEncoding::Fan:
            plainFloats();
            for (uint32_t q = 0; q < g.quadCount(); ++q) primitives.push_back(indexed(fanIndices(q), 6));
            break;
        case GeometryEncoding::QuantizedByte:
        case GeometryEncoding::QuantizedUnsignedByteNormalized:
        case GeometryEncoding::QuantizedShortNormalized:
        case GeometryEncoding::QuantizedUnsignedShort: {
            d.require("KHR_mesh_quantization");
            const QuantizedPositions q = quantizePositions(g.positions, encoding);
            node["translation"] = {q.translation.x, q.translation.y, q.translation.z};
            node["scale"] = {q.scale, q.scale, q.scale};
            const std::vector<float> normals = flatten(g.normals);
            const std::vector<float> uvs = flatten(g.uvs);
            int position = 0, normal = 0, uv = 0;
            // Each element starts on a 4-byte boundary, as the extension requires.
            if (encoding == GeometryEncoding::QuantizedByte) {
                position = d.accessor(d.view(packed<int8_t>(q.values, 3, 4), 4), kByte, vertices, "VEC3");
                normal = d.accessor(d.view(packed<int8_t>(rounded(normals, 127), 3, 4), 4), kByte, vertices, "VEC3", true);
                uv = d.accessor(d.view(packed<uint8_t>(rounded(uvs, 1), 2, 4), 4), kUnsignedByte, vertices, "VEC2");
            } else if (encoding == GeometryEncoding::QuantizedUnsignedByteNormalized) {
                position = d.accessor(d.view(packed<uint8_t>(q.values, 3, 4), 4), kUnsignedByte, vertices, "VEC3", true);
                normal = d.accessor(d.view(packed<int16_t>(rounded(normals, 32767), 3, 8), 8), kShort, vertices, "VEC3", true);
                uv = d.accessor(d.view(packed<int8_t>(rounded(uvs, 127), 2, 4), 4), kByte, vertices, "VEC2", true);
            } else if (encoding == GeometryEncoding::QuantizedShortNormalized) {
                position = d.accessor(d.view(packed<int16_t>(q.values, 3, 8), 8), kShort, vertices, "VEC3", true);
                normal = d.accessor(d.view(packed<int8_t>(rounded(normals, 127), 3, 4), 4), kByte, vertices, "VEC3", true);
                uv = d.accessor(d.view(packed<int16_t>(rounded(uvs, 1), 2, 4), 4), kShort, vertices, "VEC2");
            } else {
                position = d.accessor(d.view(packed<uint16_t>(q.values, 3, 8), 8), kUnsignedShort, vertices, "VEC3");
                normal = d.accessor(d.view(packed<int16_t>(rounded(normals, 32767), 3, 8), 8), kShort, vertices, "VEC3", true);
                uv = d.accessor(d.view(packed<uint16_t>(rounded(uvs, 65535), 2, 4), 4), kUnsignedShort, vertices, "VEC2",
                                true);
            }
            attributes = {{"POSITION", position}, {"NORMAL", normal}, {"TEXCOORD_0", uv}};
            primitives.push_back(indexed(list, 4));
            break;
        }
        case GeometryEncoding::Draco:
        case GeometryEncoding::DracoQuantized: {
            d.require("KHR_draco_mesh_compression");
            uint32_t ids[3];
            const std::vector<unsigned char> data = dracoData(g, list, encoding == GeometryEncoding::DracoQuantized, ids);
            const int view = d.view(data, 0);
            attributes = {{"POSITION", d.accessor(-1, kFloat, vertices, "VEC3")},
                          {"NORMAL", d.accessor(-1, kFloat, vertices, "VEC3")},
                          {"TEXCOORD_0", d.accessor(-1, kFloat, vertices, "VEC2")}};
            const int indices = d.accessor(-1, kUnsignedShort, list.size(), "SCALAR");
            primitives.push_back(
                {{"attributes", attributes},
                 {"indices", indices},
                 {"material", 0},
                 {"extensions",
                  {{"KHR_draco_mesh_compression",
                    {{"bufferView", view},
                     {"attributes", {{"POSITION", ids[0]}, {"NORMAL", ids[1]}, {"TEXCOORD_0", ids[2]}}}}}}}});
            break;
        }
        case GeometryEncoding::Meshopt: {
            const auto attribute = [&](const std::vector<float>& values, size_t components, const char* type) {
                const size_t stride = components * sizeof(float);
                const int view = d.compressedView(meshoptVertices(bytesOf(values), vertices, stride), vertices, stride,
                                                  "ATTRIBUTES", "NONE", true);
                return d.accessor(view, kFloat, vertices, type);
            };
            attributes = {{"POSITION", attribute(flatten(g.positions), 3, "VEC3")},
                          {"NORMAL", attribute(flatten(g.normals), 3, "VEC3")},
                          {"TEXCOORD_0", attribute(flatten(g.uvs), 2, "VEC2")}};
            std::vector<unsigned char> encoded(meshopt_encodeIndexBufferBound(list.size(), vertices));
            encoded.resize(meshopt_encodeIndexBuffer(encoded.data(), encoded.size(), list.data(), list.size()));
            const int view = d.compressedView(encoded, list.size(), 2, "TRIANGLES", "NONE", false);
            primitives.push_back({{"attributes", attributes},
                                  {"indices", d.accessor(view, kUnsignedShort, list.size(), "SCALAR")},
                                  {"material", 0}});
            break;
        }
        case GeometryEncoding::MeshoptFiltered: {
            d.require("KHR_mesh_quantization");  // the BYTE normals
            std::vector<unsigned char> filtered(vertices * 12);
            meshopt_encodeFilterExp(filtered.data(), vertices, 12, kMeshoptExpBits, flatten(g.positions).data());
            const int position = d.accessor(
                d.compressedView(meshoptVertices(filtered, vertices, 12), vertices, 12, "ATTRIBUTES", "EXPONENTIAL", true),
                kFloat, vertices, "VEC3");
            std::vector<float> normals4;  // x, y, z, w: the filter's input
            for (const glm::vec3& n : g.normals) normals4.insert(normals4.end(), {n.x, n.y, n.z, 0.0f});
            filtered.assign(vertices * 4, 0);
            meshopt_encodeFilterOct(filtered.data(), vertices, 4, kMeshoptOctBits, normals4.data());
            const int normal = d.accessor(
                d.compressedView(meshoptVertices(filtered, vertices, 4), vertices, 4, "ATTRIBUTES", "OCTAHEDRAL", true),
                kByte, vertices, "VEC3", true);
            const std::vector<unsigned char> uvBytes = packed<uint16_t>(rounded(flatten(g.uvs), 65535), 2, 4);
            const int uv = d.accessor(
                d.compressedView(meshoptVertices(uvBytes, vertices, 4), vertices, 4, "ATTRIBUTES", "NONE", true),
                kUnsignedShort, vertices, "VEC2", true);
            std::vector<unsigned char> encoded(meshopt_encodeIndexSequenceBound(list.size(), vertices));
            encoded.resize(meshopt_encodeIndexSequence(encoded.data(), encoded.size(), list.data(), list.size()));
            const int indices =
                d.accessor(d.compressedView(encoded, list.size(), 4, "INDICES", "NONE", false), kUnsignedInt, list.size(),
                           "SCALAR");
            attributes = {{"POSITION", position}, {"NORMAL", normal}, {"TEXCOORD_0", uv}};
            primitives.push_back({{"attributes", attributes}, {"indices", indices}, {"material", 0}});
            break;
        }
    }

    d.doc["meshes"] = {{{"name", name}, {"primitives", primitives}}};
    addSceneAround(d, node);
    d.doc["buffers"] = {{{"uri", name + ".bin"}, {"byteLength", d.bin.size()}}};
    if (d.fallbackBytes > 0)
        d.doc["buffers"].push_back(
            {{"byteLength", d.fallbackBytes}, {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}});
    std::ofstream(folder + "/" + name + ".bin", std::ios::binary)
        .write(reinterpret_cast<const char*>(d.bin.data()), std::streamsize(d.bin.size()));
    const std::string path = folder + "/" + name + ".gltf";
    std::ofstream(path) << d.doc.dump(1);
    return path;
}

}  // namespace punctual::testing
