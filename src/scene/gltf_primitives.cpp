// glTF mesh primitives -> punctual vertices and indices. Every accessor is bounds-checked against
// its buffer view and buffer before a byte is read: a malformed file must give an Error, never
// an out-of-bounds read.
#include <cmath>
#include <cstring>
#include <limits>

#include "core/error.h"
#include "scene/gltf_detail.h"

namespace punctual::gltf_detail {
namespace {

// Elements of one accessor after validation: element i starts at first + i * stride, and all
// `count` elements lie inside the buffer.
struct AccessorSpan {
    const unsigned char* first = nullptr;
    size_t stride = 0;
    size_t count = 0;
    int componentType = 0;
    int type = 0;
    bool normalized = false;

    const unsigned char* element(size_t i) const { return first + i * stride; }
};

size_t componentBytes(int componentType) {
    switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
        case TINYGLTF_COMPONENT_TYPE_SHORT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
        default: return 0;  // INT and DOUBLE are not valid glTF 2.0 accessor types
    }
}

size_t componentsPerElement(int type) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR: return 1;
        case TINYGLTF_TYPE_VEC2: return 2;
        case TINYGLTF_TYPE_VEC3: return 3;
        case TINYGLTF_TYPE_VEC4:
        case TINYGLTF_TYPE_MAT2: return 4;
        case TINYGLTF_TYPE_MAT3: return 9;
        case TINYGLTF_TYPE_MAT4: return 16;
        default: return 0;
    }
}

// a + b and a * b on sizes that come straight from the file, where wrap-around would hide an
// out-of-bounds read.
bool checkedAdd(size_t a, size_t b, size_t& sum) { return !__builtin_add_overflow(a, b, &sum); }
bool checkedMultiply(size_t a, size_t b, size_t& product) { return !__builtin_mul_overflow(a, b, &product); }

float readFloat(const unsigned char* bytes) {
    float value;
    std::memcpy(&value, bytes, sizeof value);
    return value;
}

template <typename T>
T readUnsigned(const unsigned char* bytes) {
    T value;
    std::memcpy(&value, bytes, sizeof value);
    return value;
}

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
bool finite(const glm::vec2& v) { return std::isfinite(v.x) && std::isfinite(v.y); }

// Unit normal of triangle (a, b, c) wound counter-clockwise, or +Y for a degenerate triangle.
// Computed in double so thin but valid triangles keep their true normal.
glm::vec3 faceNormal(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
    const glm::dvec3 edge1 = glm::dvec3(b) - glm::dvec3(a);
    const glm::dvec3 edge2 = glm::dvec3(c) - glm::dvec3(a);
    const glm::dvec3 normal = glm::cross(edge1, edge2);
    const double length = glm::length(normal);
    // Degenerate: zero area, or the edges are parallel to within rounding.
    if (!(length > 1e-12 * glm::length(edge1) * glm::length(edge2)) || !std::isfinite(length))
        return glm::vec3(0.0f, 1.0f, 0.0f);
    return glm::vec3(normal / length);
}

class PrimitiveReader {
public:
    PrimitiveReader(const tinygltf::Model& model, const std::string& label, const std::string& path)
        : model_(model), label_(label), path_(path) {}

    [[noreturn]] void fail(const std::string& problem) const { throw Error(path_, label_ + ": " + problem); }

    AccessorSpan span(int accessorIndex, const std::string& semantic) const {
        if (accessorIndex < 0 || size_t(accessorIndex) >= model_.accessors.size())
            fail(semantic + " refers to accessor " + std::to_string(accessorIndex) + ", which does not exist");
        const tinygltf::Accessor& accessor = model_.accessors[size_t(accessorIndex)];
        const std::string who = semantic + " accessor " + std::to_string(accessorIndex);
        if (accessor.sparse.isSparse) fail(who + " is sparse, which is not supported");
        if (accessor.bufferView < 0) fail(who + " has no buffer view");
        if (size_t(accessor.bufferView) >= model_.bufferViews.size())
            fail(who + " refers to buffer view " + std::to_string(accessor.bufferView) + ", which does not exist");
        const tinygltf::BufferView& view = model_.bufferViews[size_t(accessor.bufferView)];
        const std::string viewName = "buffer view " + std::to_string(accessor.bufferView);
        if (view.buffer < 0 || size_t(view.buffer) >= model_.buffers.size())
            fail(viewName + " refers to buffer " + std::to_string(view.buffer) + ", which does not exist");
        const tinygltf::Buffer& buffer = model_.buffers[size_t(view.buffer)];
        size_t viewEnd = 0;
        if (!checkedAdd(view.byteOffset, view.byteLength, viewEnd) || viewEnd > buffer.data.size())
            fail(viewName + " reads past the end of buffer " + std::to_string(view.buffer));

        const size_t componentSize = componentBytes(accessor.componentType);
        const size_t components = componentsPerElement(accessor.type);
        if (componentSize == 0 || components == 0) fail(who + " has an unsupported componentType or type");
        const size_t elementSize = componentSize * components;
        const size_t stride = view.byteStride != 0 ? view.byteStride : elementSize;
        if (stride < elementSize)
            fail(viewName + " has byteStride " + std::to_string(stride) + ", smaller than one element of " + who);

        AccessorSpan result;
        result.stride = stride;
        result.count = accessor.count;
        result.componentType = accessor.componentType;
        result.type = accessor.type;
        result.normalized = accessor.normalized;
        if (accessor.count == 0) return result;
        // The last element must end inside the view:
        // byteOffset + stride * (count - 1) + elementSize <= view.byteLength.
        size_t end = 0;
        if (!checkedMultiply(stride, accessor.count - 1, end) || !checkedAdd(end, accessor.byteOffset, end) ||
            !checkedAdd(end, elementSize, end) || end > view.byteLength)
            fail(who + " reads past the end of " + viewName);
        result.first = buffer.data.data() + view.byteOffset + accessor.byteOffset;
        return result;
    }

    std::vector<glm::vec3> readVec3(int accessorIndex, const std::string& semantic, const char* what) const {
        const AccessorSpan s = span(accessorIndex, semantic);
        if (s.type != TINYGLTF_TYPE_VEC3 || s.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
            fail(semantic + " accessor " + std::to_string(accessorIndex) + " is not VEC3 of FLOAT");
        std::vector<glm::vec3> values(s.count);
        for (size_t i = 0; i < s.count; ++i) {
            const unsigned char* e = s.element(i);
            values[i] = glm::vec3(readFloat(e), readFloat(e + 4), readFloat(e + 8));
            if (!finite(values[i])) fail(std::string(what) + " " + std::to_string(i) + " is not finite (NaN or inf)");
        }
        return values;
    }

    std::vector<glm::vec2> readTexcoords(int accessorIndex, const std::string& semantic) const {
        const AccessorSpan s = span(accessorIndex, semantic);
        const bool isFloat = s.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT;
        const bool isUnorm8 = s.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && s.normalized;
        const bool isUnorm16 = s.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT && s.normalized;
        if (s.type != TINYGLTF_TYPE_VEC2 || !(isFloat || isUnorm8 || isUnorm16))
            fail(semantic + " accessor " + std::to_string(accessorIndex) +
                 " is not VEC2 of FLOAT or normalized UNSIGNED_BYTE/UNSIGNED_SHORT");
        std::vector<glm::vec2> values(s.count);
        for (size_t i = 0; i < s.count; ++i) {
            const unsigned char* e = s.element(i);
            if (isFloat) {
                values[i] = glm::vec2(readFloat(e), readFloat(e + 4));
            } else if (isUnorm8) {
                values[i] = glm::vec2(float(e[0]), float(e[1])) / 255.0f;
            } else {
                values[i] = glm::vec2(float(readUnsigned<uint16_t>(e)), float(readUnsigned<uint16_t>(e + 2))) / 65535.0f;
            }
            if (!finite(values[i]))
                fail("texture coordinate " + std::to_string(i) + " is not finite (NaN or inf)");
        }
        return values;
    }

    std::vector<uint32_t> readIndices(int accessorIndex) const {
        const AccessorSpan s = span(accessorIndex, "indices");
        if (s.type != TINYGLTF_TYPE_SCALAR ||
            (s.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
             s.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
             s.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT))
            fail("indices accessor " + std::to_string(accessorIndex) +
                 " is not SCALAR of UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT");
        std::vector<uint32_t> values(s.count);
        for (size_t i = 0; i < s.count; ++i) {
            const unsigned char* e = s.element(i);
            switch (s.componentType) {
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: values[i] = e[0]; break;
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: values[i] = readUnsigned<uint16_t>(e); break;
                default: values[i] = readUnsigned<uint32_t>(e); break;
            }
        }
        return values;
    }

private:
    const tinygltf::Model& model_;
    const std::string& label_;
    const std::string& path_;
};

int attribute(const tinygltf::Primitive& primitive, const char* semantic) {
    const auto it = primitive.attributes.find(semantic);
    return it == primitive.attributes.end() ? -1 : it->second;
}

// Loaded normals made unit length. A zero normal carries no direction; such a vertex gets the
// (area-weighted) average of the face normals of its triangles, which is its face normal when it
// belongs to one triangle.
void repairNormals(std::vector<glm::vec3>& normals, const std::vector<glm::vec3>& positions,
                   const std::vector<uint32_t>& triangleIndices) {
    std::vector<bool> needsFaceNormal(normals.size(), false);
    bool anyZero = false;
    for (size_t i = 0; i < normals.size(); ++i) {
        const float length = glm::length(normals[i]);
        if (length > 1e-20f) {
            normals[i] /= length;
        } else {
            needsFaceNormal[i] = true;
            anyZero = true;
        }
    }
    if (!anyZero) return;
    std::vector<glm::dvec3> accumulated(normals.size(), glm::dvec3(0.0));
    for (size_t t = 0; t + 2 < triangleIndices.size(); t += 3) {
        const uint32_t a = triangleIndices[t], b = triangleIndices[t + 1], c = triangleIndices[t + 2];
        if (!needsFaceNormal[a] && !needsFaceNormal[b] && !needsFaceNormal[c]) continue;
        const glm::dvec3 pa(positions[a]);
        const glm::dvec3 areaWeighted = glm::cross(glm::dvec3(positions[b]) - pa, glm::dvec3(positions[c]) - pa);
        for (uint32_t v : {a, b, c})
            if (needsFaceNormal[v]) accumulated[v] += areaWeighted;
    }
    for (size_t i = 0; i < normals.size(); ++i) {
        if (!needsFaceNormal[i]) continue;
        const double length = glm::length(accumulated[i]);
        normals[i] = length > 0.0 && std::isfinite(length) ? glm::vec3(accumulated[i] / length)
                                                           : glm::vec3(0.0f, 1.0f, 0.0f);
    }
}

}  // namespace

std::optional<Mesh> appendPrimitive(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                                    const std::string& label, const std::string& path,
                                    std::vector<Vertex>& vertices, std::vector<uint32_t>& indices) {
    const PrimitiveReader reader(model, label, path);
    const int positionAccessor = attribute(primitive, "POSITION");
    if (positionAccessor < 0) reader.fail("has no POSITION attribute");
    const std::vector<glm::vec3> positions = reader.readVec3(positionAccessor, "POSITION", "position");
    const size_t vertexCount = positions.size();

    std::vector<glm::vec3> normals;
    if (const int accessor = attribute(primitive, "NORMAL"); accessor >= 0) {
        normals = reader.readVec3(accessor, "NORMAL", "normal");
        if (normals.size() != vertexCount)
            reader.fail("NORMAL has " + std::to_string(normals.size()) + " elements but POSITION has " +
                        std::to_string(vertexCount));
    }
    std::vector<glm::vec2> texcoordSets[2];
    for (size_t set = 0; set < 2; ++set) {
        const std::string semantic = set == 0 ? "TEXCOORD_0" : "TEXCOORD_1";
        const int accessor = attribute(primitive, semantic.c_str());
        if (accessor < 0) continue;
        texcoordSets[set] = reader.readTexcoords(accessor, semantic);
        if (texcoordSets[set].size() != vertexCount)
            reader.fail(semantic + " has " + std::to_string(texcoordSets[set].size()) + " elements but POSITION has " +
                        std::to_string(vertexCount));
    }

    std::vector<uint32_t> triangleIndices;
    if (primitive.indices >= 0) {
        triangleIndices = reader.readIndices(primitive.indices);
        for (size_t i = 0; i < triangleIndices.size(); ++i)
            if (triangleIndices[i] >= vertexCount)
                reader.fail("index " + std::to_string(i) + " is " + std::to_string(triangleIndices[i]) +
                            ", out of range for " + std::to_string(vertexCount) + " vertices");
        if (triangleIndices.size() % 3 != 0)
            reader.fail(std::to_string(triangleIndices.size()) + " indices are not a whole number of triangles");
    } else {
        if (vertexCount % 3 != 0)
            reader.fail(std::to_string(vertexCount) + " vertices (no indices) are not a whole number of triangles");
        if (vertexCount > std::numeric_limits<uint32_t>::max()) reader.fail("has more than 2^32 vertices");
        triangleIndices.reserve(vertexCount);
        for (size_t v = 0; v < vertexCount; ++v) triangleIndices.push_back(uint32_t(v));
    }
    if (triangleIndices.empty()) return std::nullopt;

    // Without NORMAL the glTF spec asks for flat shading: every triangle gets its own three
    // vertices carrying the face normal.
    const bool flat = normals.empty();
    const size_t outputVertices = flat ? triangleIndices.size() : vertexCount;
    constexpr size_t kMaxCount = std::numeric_limits<uint32_t>::max();
    if (outputVertices > kMaxCount - vertices.size() || triangleIndices.size() > kMaxCount - indices.size())
        reader.fail("the scene has more than 2^32 vertices or indices");

    Mesh mesh;
    mesh.firstIndex = uint32_t(indices.size());
    mesh.indexCount = uint32_t(triangleIndices.size());
    mesh.vertexOffset = uint32_t(vertices.size());
    mesh.vertexCount = uint32_t(outputVertices);
    const auto uvOf = [&](size_t set, size_t v) {
        return texcoordSets[set].empty() ? glm::vec2(0.0f) : texcoordSets[set][v];
    };

    vertices.reserve(vertices.size() + outputVertices);
    indices.reserve(indices.size() + triangleIndices.size());
    if (flat) {
        for (size_t t = 0; t < triangleIndices.size(); t += 3) {
            const uint32_t a = triangleIndices[t], b = triangleIndices[t + 1], c = triangleIndices[t + 2];
            const glm::vec3 normal = faceNormal(positions[a], positions[b], positions[c]);
            for (uint32_t v : {a, b, c}) {
                indices.push_back(uint32_t(vertices.size()) - mesh.vertexOffset);
                vertices.push_back(Vertex{positions[v], normal, uvOf(0, v), uvOf(1, v)});
                mesh.localBounds.extend(positions[v]);
            }
        }
    } else {
        repairNormals(normals, positions, triangleIndices);
        for (size_t v = 0; v < vertexCount; ++v) {
            vertices.push_back(Vertex{positions[v], normals[v], uvOf(0, v), uvOf(1, v)});
            mesh.localBounds.extend(positions[v]);
        }
        indices.insert(indices.end(), triangleIndices.begin(), triangleIndices.end());
    }
    return mesh;
}

}  // namespace punctual::gltf_detail
