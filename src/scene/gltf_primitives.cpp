// glTF mesh primitives -> punctual vertices and indices. The attributes are first gathered into
// arrays that no longer say where they came from (plain accessors, meshopt-decoded views, Draco
// data), then turned into a triangle list and vertices the same way for all of them.
#include <cmath>
#include <limits>

#include "scene/gltf_detail.h"
#include "scene/triangle_topology.h"

namespace punctual::gltf_detail {
namespace {

constexpr const char* kDraco = "KHR_draco_mesh_compression";

int attribute(const tinygltf::Primitive& primitive, const std::string& semantic) {
    const auto it = primitive.attributes.find(semantic);
    return it == primitive.attributes.end() ? -1 : it->second;
}

// A primitive's vertex data, one element per vertex in every non-empty array.
struct PrimitiveArrays {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;                           // empty: the file has none
    std::map<std::string, std::vector<glm::vec2>> texcoords;  // by semantic, e.g. "TEXCOORD_0"
    std::optional<std::vector<uint32_t>> indices;             // nullopt: not indexed
};

// Reads a primitive's attributes from wherever the file keeps them: the Draco data for those
// its extension maps, the accessors for the rest.
class AttributeSource {
public:
    AttributeSource(const tinygltf::Model& model, const tinygltf::Primitive& primitive, const AccessorReader& reader)
        : primitive_(primitive), reader_(reader) {
        if (const auto extension = primitive.extensions.find(kDraco); extension != primitive.extensions.end()) {
            // The extension only defines triangle data; anything else is a broken file, not
            // a topology to guess at.
            if (primitive.mode != TINYGLTF_MODE_TRIANGLES && primitive.mode != TINYGLTF_MODE_TRIANGLE_STRIP)
                reader.fail(std::string(kDraco) + " needs mode TRIANGLES or TRIANGLE_STRIP, not mode " +
                            std::to_string(primitive.mode));
            draco_ = std::make_unique<DracoPrimitive>(model, extension->second, reader);
        }
    }

    // nullopt when the primitive has no such attribute.
    std::optional<std::vector<glm::vec3>> vec3(const std::string& semantic, AttributeKind kind) const {
        const int accessor = attribute(primitive_, semantic);
        if (draco_ && draco_->has(semantic)) {
            if (accessor < 0)
                reader_.fail(std::string(kDraco) + " maps " + semantic + ", which the primitive's attributes lack");
            return draco_->readVec3(semantic, accessor, kind);
        }
        if (accessor < 0) return std::nullopt;
        return reader_.readVec3(accessor, semantic, kind);
    }

    // A texture coordinate set by its semantic ("TEXCOORD_0", "TEXCOORD_1", ...).
    std::optional<std::vector<glm::vec2>> texcoords(const std::string& semantic) const {
        const int accessor = attribute(primitive_, semantic);
        if (draco_ && draco_->has(semantic)) {
            if (accessor < 0)
                reader_.fail(std::string(kDraco) + " maps " + semantic + ", which the primitive's attributes lack");
            return draco_->readTexcoords(semantic, accessor);
        }
        if (accessor < 0) return std::nullopt;
        return reader_.readTexcoords(accessor, semantic);
    }

    std::optional<std::vector<uint32_t>> indices() const {
        // Draco data always has faces: they are the indices, whether or not an accessor says so.
        if (draco_) return draco_->indices(primitive_.indices);
        if (primitive_.indices < 0) return std::nullopt;
        return reader_.readIndices(primitive_.indices);
    }

private:
    const tinygltf::Primitive& primitive_;
    const AccessorReader& reader_;
    std::unique_ptr<DracoPrimitive> draco_;
};

// The texture coordinate sets the renderer uses.
const char* const kTexcoordSets[] = {"TEXCOORD_0", "TEXCOORD_1"};

PrimitiveArrays gatherArrays(const AttributeSource& source, const AccessorReader& reader) {
    PrimitiveArrays arrays;
    std::optional<std::vector<glm::vec3>> positions = source.vec3("POSITION", AttributeKind::Position);
    if (!positions) reader.fail("has no POSITION attribute");
    arrays.positions = std::move(*positions);
    const size_t vertexCount = arrays.positions.size();
    const auto checkCount = [&](const std::string& semantic, size_t count) {
        if (count != vertexCount)
            reader.fail(semantic + " has " + std::to_string(count) + " elements but POSITION has " +
                        std::to_string(vertexCount));
    };
    if (std::optional<std::vector<glm::vec3>> normals = source.vec3("NORMAL", AttributeKind::Normal)) {
        checkCount("NORMAL", normals->size());
        arrays.normals = std::move(*normals);
    }
    for (const char* semantic : kTexcoordSets) {
        if (std::optional<std::vector<glm::vec2>> texcoords = source.texcoords(semantic)) {
            checkCount(semantic, texcoords->size());
            arrays.texcoords[semantic] = std::move(*texcoords);
        }
    }
    arrays.indices = source.indices();
    return arrays;
}

// Adds each morph target's POSITION and NORMAL deltas times its weight (glTF 2.0, 3.7.2.2:
// p = p0 + sum w_i d_i). A weight of 0 (the default) adds nothing and reads nothing. An accessor
// without a buffer view holds zeros (and is skipped likewise); a sparse one is not read: the
// target is counted in `unmorphed` for the loader's warning.
void applyMorphTargets(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                       const std::vector<double>& weights, const AccessorReader& reader, PrimitiveArrays& arrays,
                       size_t& unmorphed) {
    for (size_t t = 0; t < primitive.targets.size() && t < weights.size(); ++t) {
        const float weight = float(weights[t]);
        if (weight == 0.0f || !std::isfinite(weight)) continue;
        for (const auto& [semantic, accessor] : primitive.targets[t]) {
            std::vector<glm::vec3>* values = semantic == "POSITION" ? &arrays.positions
                                             : semantic == "NORMAL" && !arrays.normals.empty() ? &arrays.normals
                                                                                               : nullptr;
            if (!values || accessor < 0 || size_t(accessor) >= model.accessors.size()) continue;
            const tinygltf::Accessor& a = model.accessors[size_t(accessor)];
            if (a.sparse.isSparse) {
                ++unmorphed;
                continue;
            }
            if (a.bufferView < 0) continue;  // all zeros
            const std::string what = "morph target " + std::to_string(t) + " " + semantic;
            const std::vector<glm::vec3> deltas =
                reader.readVec3(accessor, what, semantic == "POSITION" ? AttributeKind::Position : AttributeKind::Normal);
            if (deltas.size() != values->size())
                reader.fail(what + " has " + std::to_string(deltas.size()) + " elements but POSITION has " +
                            std::to_string(values->size()));
            for (size_t v = 0; v < deltas.size(); ++v) (*values)[v] += weight * deltas[v];
        }
    }
}

// The primitive's triangles as a list of vertex indices, whatever its topology.
std::vector<uint32_t> triangleList(int mode, const PrimitiveArrays& arrays, const AccessorReader& reader) {
    const size_t vertexCount = arrays.positions.size();
    std::vector<uint32_t> topology;
    if (arrays.indices) {
        topology = *arrays.indices;
        for (size_t i = 0; i < topology.size(); ++i)
            if (topology[i] >= vertexCount)
                reader.fail("index " + std::to_string(i) + " is " + std::to_string(topology[i]) + ", out of range for " +
                            std::to_string(vertexCount) + " vertices");
    } else {
        if (vertexCount > std::numeric_limits<uint32_t>::max()) reader.fail("has more than 2^32 vertices");
        topology.reserve(vertexCount);
        for (size_t v = 0; v < vertexCount; ++v) topology.push_back(uint32_t(v));
    }
    switch (mode) {
        case TINYGLTF_MODE_TRIANGLE_STRIP: return triangleListFromStrip(topology);
        case TINYGLTF_MODE_TRIANGLE_FAN: return triangleListFromFan(topology);
        default:
            if (topology.size() % 3 != 0)
                reader.fail(std::to_string(topology.size()) +
                            (arrays.indices ? " indices are not a whole number of triangles"
                                            : " vertices (no indices) are not a whole number of triangles"));
            return topology;
    }
}

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

bool drawsTriangles(int mode) {
    return mode == TINYGLTF_MODE_TRIANGLES || mode == TINYGLTF_MODE_TRIANGLE_STRIP || mode == TINYGLTF_MODE_TRIANGLE_FAN;
}

std::optional<Mesh> appendPrimitive(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                                    const std::string& label, const std::string& path,
                                    const std::vector<double>& morphWeights, size_t& unmorphedTargets,
                                    std::vector<Vertex>& vertices, std::vector<uint32_t>& indices) {
    const AccessorReader reader(model, label, path);
    PrimitiveArrays arrays = gatherArrays(AttributeSource(model, primitive, reader), reader);
    applyMorphTargets(model, primitive, morphWeights, reader, arrays, unmorphedTargets);
    const std::vector<uint32_t> triangleIndices = triangleList(primitive.mode, arrays, reader);
    if (triangleIndices.empty()) return std::nullopt;

    const std::vector<glm::vec3>& positions = arrays.positions;
    const size_t vertexCount = positions.size();
    const auto uvs = arrays.texcoords.find("TEXCOORD_0");
    const auto uvs1 = arrays.texcoords.find("TEXCOORD_1");
    const auto uvOf = [&](size_t v) { return uvs == arrays.texcoords.end() ? glm::vec2(0.0f) : uvs->second[v]; };
    const auto uv1Of = [&](size_t v) { return uvs1 == arrays.texcoords.end() ? glm::vec2(0.0f) : uvs1->second[v]; };

    // Without NORMAL the glTF spec asks for flat shading: every triangle gets its own three
    // vertices carrying the face normal.
    const bool flat = arrays.normals.empty();
    const size_t outputVertices = flat ? triangleIndices.size() : vertexCount;
    constexpr size_t kMaxCount = std::numeric_limits<uint32_t>::max();
    if (outputVertices > kMaxCount - vertices.size() || triangleIndices.size() > kMaxCount - indices.size())
        reader.fail("the scene has more than 2^32 vertices or indices");

    Mesh mesh;
    mesh.firstIndex = uint32_t(indices.size());
    mesh.indexCount = uint32_t(triangleIndices.size());
    mesh.vertexOffset = uint32_t(vertices.size());
    mesh.vertexCount = uint32_t(outputVertices);

    vertices.reserve(vertices.size() + outputVertices);
    indices.reserve(indices.size() + triangleIndices.size());
    if (flat) {
        for (size_t t = 0; t < triangleIndices.size(); t += 3) {
            const uint32_t a = triangleIndices[t], b = triangleIndices[t + 1], c = triangleIndices[t + 2];
            const glm::vec3 normal = faceNormal(positions[a], positions[b], positions[c]);
            for (uint32_t v : {a, b, c}) {
                indices.push_back(uint32_t(vertices.size()) - mesh.vertexOffset);
                vertices.push_back(Vertex{positions[v], normal, uvOf(v), uv1Of(v)});
                mesh.localBounds.extend(positions[v]);
            }
        }
    } else {
        repairNormals(arrays.normals, positions, triangleIndices);
        for (size_t v = 0; v < vertexCount; ++v) {
            vertices.push_back(Vertex{positions[v], arrays.normals[v], uvOf(v), uv1Of(v)});
            mesh.localBounds.extend(positions[v]);
        }
        indices.insert(indices.end(), triangleIndices.begin(), triangleIndices.end());
    }
    return mesh;
}

}  // namespace punctual::gltf_detail
