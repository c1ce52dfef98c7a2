// KHR_draco_mesh_compression: a primitive's attributes and indices decoded with Draco (Debian's
// libdraco). The extension names a buffer view holding the Draco data and maps attribute
// semantics to Draco attribute ids; the primitive's accessors still describe the decoded data
// (count, type, component type) but have no buffer view. Draco's output is checked as strictly
// as a plain accessor, since a Draco stream is file data like any other: a truncated or
// corrupted stream must end in one Error line, never in a read past Draco's buffers.
#include <cstring>
#include <exception>
#include <limits>
#include <optional>

#include <draco/compression/decode.h>
#include <draco/core/decoder_buffer.h>
#include <draco/mesh/mesh.h>

#include "scene/gltf_detail.h"

namespace punctual::gltf_detail {
namespace {

constexpr const char* kExtension = "KHR_draco_mesh_compression";

// The glTF component type of Draco's type, or -1 for types an accessor cannot describe.
int componentTypeOf(draco::DataType type) {
    switch (type) {
        case draco::DT_INT8: return TINYGLTF_COMPONENT_TYPE_BYTE;
        case draco::DT_UINT8: return TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
        case draco::DT_INT16: return TINYGLTF_COMPONENT_TYPE_SHORT;
        case draco::DT_UINT16: return TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
        case draco::DT_UINT32: return TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
        case draco::DT_FLOAT32: return TINYGLTF_COMPONENT_TYPE_FLOAT;
        default: return -1;
    }
}

// Calls visit(meshIndex, primitiveIndex, primitive JSON) for each primitive of `gltf` that has
// the extension.
template <typename Visit>
void forEachDracoPrimitive(const nlohmann::json& gltf, Visit visit) {
    const auto meshes = gltf.find("meshes");
    if (meshes == gltf.end() || !meshes->is_array()) return;
    for (size_t m = 0; m < meshes->size(); ++m) {
        const nlohmann::json& mesh = (*meshes)[m];
        if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
        for (size_t p = 0; p < mesh["primitives"].size(); ++p) {
            const nlohmann::json& primitive = mesh["primitives"][p];
            if (!primitive.is_object() || !primitive.contains("extensions") || !primitive["extensions"].is_object() ||
                !primitive["extensions"].contains(kExtension))
                continue;
            visit(m, p, primitive);
        }
    }
}

// Draco's messages are short phrases; keep whatever it says on the one line of our error.
std::string oneLine(std::string text) {
    for (char& c : text)
        if (c == '\n' || c == '\r') c = ' ';
    return text.empty() ? "no reason given" : text;
}

}  // namespace

void hideDracoIndices(const nlohmann::json& gltf, std::optional<nlohmann::json>& patched) {
    forEachDracoPrimitive(gltf, [&](size_t m, size_t p, const nlohmann::json& primitive) {
        if (!primitive.contains("indices")) return;
        if (!patched) patched = gltf;
        (*patched)["meshes"][m]["primitives"][p].erase("indices");
    });
}

void restoreDracoIndices(tinygltf::Model& model, const nlohmann::json& gltf) {
    forEachDracoPrimitive(gltf, [&](size_t m, size_t p, const nlohmann::json& primitive) {
        const auto indices = primitive.find("indices");
        if (indices == primitive.end() || m >= model.meshes.size() || p >= model.meshes[m].primitives.size()) return;
        // Whatever the file says, even nonsense: the accessor reads check it like any other.
        model.meshes[m].primitives[p].indices =
            indices->is_number_integer() && indices->get<int64_t>() >= 0 && indices->get<int64_t>() <= std::numeric_limits<int>::max()
                ? int(indices->get<int64_t>())
                : std::numeric_limits<int>::max();
    });
}

struct DracoPrimitive::Decoded {
    std::unique_ptr<draco::Mesh> mesh;
    std::map<std::string, uint32_t> attributeIds;  // semantic -> Draco unique id
};

DracoPrimitive::DracoPrimitive(const tinygltf::Model& model, const tinygltf::Value& extension,
                               const AccessorReader& reader)
    : decoded_(std::make_unique<Decoded>()), reader_(reader) {
    const std::string who = kExtension;
    if (!extension.IsObject()) reader.fail(who + " is not a JSON object");
    if (!extension.Has("bufferView") || !extension.Get("bufferView").IsInt())
        reader.fail(who + " has no integer 'bufferView'");
    const int viewIndex = extension.Get("bufferView").GetNumberAsInt();
    if (viewIndex < 0 || size_t(viewIndex) >= model.bufferViews.size())
        reader.fail(who + " refers to buffer view " + std::to_string(viewIndex) + ", which does not exist");
    if (!extension.Has("attributes") || !extension.Get("attributes").IsObject())
        reader.fail(who + " has no 'attributes' object");
    const tinygltf::Value& attributes = extension.Get("attributes");
    for (const std::string& semantic : attributes.Keys()) {
        const tinygltf::Value& id = attributes.Get(semantic);
        if (!id.IsInt() || id.GetNumberAsInt() < 0)
            reader.fail(who + ": attribute " + semantic + " has no Draco attribute id (a non-negative integer)");
        decoded_->attributeIds[semantic] = uint32_t(id.GetNumberAsInt());
    }

    // The compressed bytes: the whole buffer view, which must lie inside its buffer.
    const tinygltf::BufferView& view = model.bufferViews[size_t(viewIndex)];
    const std::string viewName = "buffer view " + std::to_string(viewIndex);
    if (view.buffer < 0 || size_t(view.buffer) >= model.buffers.size())
        reader.fail(who + ": " + viewName + " refers to buffer " + std::to_string(view.buffer) + ", which does not exist");
    const std::vector<unsigned char>& data = model.buffers[size_t(view.buffer)].data;
    if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset)
        reader.fail(who + ": " + viewName + " reads past the end of buffer " + std::to_string(view.buffer));

    draco::DecoderBuffer buffer;
    buffer.Init(reinterpret_cast<const char*>(data.data() + view.byteOffset), view.byteLength);
    draco::Decoder decoder;
    // Draco reports bad data through its status, but sizes read from corrupt data can still make
    // it allocate more than there is: that is the file's fault too.
    std::optional<draco::StatusOr<std::unique_ptr<draco::Mesh>>> result;
    try {
        result.emplace(decoder.DecodeMeshFromBuffer(&buffer));
    } catch (const std::exception& e) {
        reader.fail(who + ": the Draco data in " + viewName + " does not decode (" + oneLine(e.what()) + ")");
    }
    if (!result->ok())
        reader.fail(who + ": the Draco data in " + viewName + " does not decode (" +
                    oneLine(result->status().error_msg_string()) + ")");
    decoded_->mesh = std::move(*result).value();
    if (!decoded_->mesh) reader.fail(who + ": the Draco data in " + viewName + " decodes to nothing");
}

DracoPrimitive::~DracoPrimitive() = default;

bool DracoPrimitive::has(const std::string& semantic) const { return decoded_->attributeIds.count(semantic) != 0; }

size_t DracoPrimitive::vertexCount() const { return decoded_->mesh->num_points(); }

namespace {

// The decoded values of one attribute, element by element, component by component, as floats
// converted like the accessor's own data would be. Checks everything the accessor and the
// Draco attribute say about each other, and that every value lies inside Draco's buffer.
std::vector<float> attributeValues(const draco::Mesh& mesh, uint32_t dracoId, const std::string& semantic,
                                   int accessorIndex, AttributeKind kind, const AccessorReader& reader) {
    const std::string who = std::string(kExtension) + ": " + semantic;
    reader.checkAttributeFormat(accessorIndex, semantic, kind);
    const tinygltf::Accessor& accessor = reader.accessor(accessorIndex, semantic);
    const draco::PointAttribute* attribute = mesh.GetAttributeByUniqueId(dracoId);
    if (!attribute) reader.fail(who + " maps to Draco attribute " + std::to_string(dracoId) + ", which the data lacks");

    const size_t components = kind == AttributeKind::Texcoord ? 2 : 3;
    const size_t points = mesh.num_points();
    if (accessor.count != points)
        reader.fail(who + ": accessor " + std::to_string(accessorIndex) + " has count " +
                    std::to_string(accessor.count) + " but the Draco data has " + std::to_string(points) + " vertices");
    if (attribute->num_components() != components)
        reader.fail(who + ": Draco attribute " + std::to_string(dracoId) + " has " +
                    std::to_string(attribute->num_components()) + " components, not " + std::to_string(components));
    const int componentType = componentTypeOf(attribute->data_type());
    if (componentType != accessor.componentType)
        reader.fail(who + ": Draco attribute " + std::to_string(dracoId) + " holds " +
                    (componentType < 0 ? "a type glTF accessors cannot describe" : componentTypeName(componentType)) +
                    " but accessor " + std::to_string(accessorIndex) + " says " +
                    componentTypeName(accessor.componentType));

    const draco::DataBuffer* buffer = attribute->buffer();
    const size_t componentSize = componentBytes(componentType);
    const int64_t stride = attribute->byte_stride();
    const int64_t offset = attribute->byte_offset();
    const size_t values = attribute->size();
    // Value v occupies [offset + v * stride, + components * componentSize) of Draco's buffer.
    const bool layoutFits = buffer != nullptr && stride >= int64_t(components * componentSize) && offset >= 0 &&
                            (values == 0 || uint64_t(offset) + uint64_t(stride) * (values - 1) +
                                                    components * componentSize <= buffer->data_size());
    if (!layoutFits) reader.fail(who + ": Draco attribute " + std::to_string(dracoId) + " has an inconsistent layout");
    if (!attribute->is_mapping_identity() && attribute->indices_map_size() < points)
        reader.fail(who + ": Draco attribute " + std::to_string(dracoId) + " does not map every vertex");

    std::vector<float> result(points * components);
    for (size_t p = 0; p < points; ++p) {
        const draco::AttributeValueIndex index = attribute->mapped_index(draco::PointIndex(uint32_t(p)));
        if (index.value() >= values)
            reader.fail(who + ": vertex " + std::to_string(p) + " refers to a Draco value that does not exist");
        const unsigned char* value = buffer->data() + offset + stride * int64_t(index.value());
        for (size_t c = 0; c < components; ++c)
            result[p * components + c] = componentAsFloat(value + c * componentSize, componentType, accessor.normalized);
    }
    return result;
}

}  // namespace

std::vector<glm::vec3> DracoPrimitive::readVec3(const std::string& semantic, int accessorIndex, AttributeKind kind) const {
    const std::vector<float> values =
        attributeValues(*decoded_->mesh, decoded_->attributeIds.at(semantic), semantic, accessorIndex, kind, reader_);
    std::vector<glm::vec3> result(values.size() / 3);
    for (size_t i = 0; i < result.size(); ++i) result[i] = glm::vec3(values[3 * i], values[3 * i + 1], values[3 * i + 2]);
    checkFinite(reader_, kind, result);
    return result;
}

std::vector<glm::vec2> DracoPrimitive::readTexcoords(const std::string& semantic, int accessorIndex) const {
    const std::vector<float> values = attributeValues(*decoded_->mesh, decoded_->attributeIds.at(semantic), semantic,
                                                      accessorIndex, AttributeKind::Texcoord, reader_);
    std::vector<glm::vec2> result(values.size() / 2);
    for (size_t i = 0; i < result.size(); ++i) result[i] = glm::vec2(values[2 * i], values[2 * i + 1]);
    checkFinite(reader_, AttributeKind::Texcoord, result);
    return result;
}

std::vector<uint32_t> DracoPrimitive::indices(int accessorIndex) const {
    const draco::Mesh& mesh = *decoded_->mesh;
    const size_t faces = mesh.num_faces();
    if (accessorIndex >= 0) {
        reader_.checkIndexFormat(accessorIndex);
        const size_t count = reader_.accessor(accessorIndex, "indices").count;
        if (count != faces * 3)
            reader_.fail(std::string(kExtension) + ": indices accessor " + std::to_string(accessorIndex) +
                         " has count " + std::to_string(count) + " but the Draco data has " + std::to_string(faces) +
                         " triangles (" + std::to_string(faces * 3) + " indices)");
    }
    std::vector<uint32_t> result;
    result.reserve(faces * 3);
    for (uint32_t f = 0; f < faces; ++f)
        for (const draco::PointIndex& point : mesh.face(draco::FaceIndex(f))) result.push_back(point.value());
    // Range-checked against the vertex count with the plain indices, in one place.
    return result;
}

}  // namespace punctual::gltf_detail
