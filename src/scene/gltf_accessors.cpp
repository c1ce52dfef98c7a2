// glTF accessors -> arrays of numbers. Every accessor is bounds-checked against its buffer view
// and buffer before a byte is read: a malformed file must give an Error, never an out-of-bounds
// read. Integer attribute data (KHR_mesh_quantization) is turned into floats here, by the rules
// the glTF spec gives, so nothing after this knows how a value was stored.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <utility>

#include "core/error.h"
#include "scene/gltf_detail.h"

namespace punctual::gltf_detail {
namespace {

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

template <typename T>
T readRaw(const unsigned char* bytes) {
    T value;
    std::memcpy(&value, bytes, sizeof value);
    return value;
}

bool isInteger8Or16(int componentType) {
    return componentType == TINYGLTF_COMPONENT_TYPE_BYTE || componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
           componentType == TINYGLTF_COMPONENT_TYPE_SHORT || componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
}

bool isSigned8Or16(int componentType) {
    return componentType == TINYGLTF_COMPONENT_TYPE_BYTE || componentType == TINYGLTF_COMPONENT_TYPE_SHORT;
}

// "" when an attribute of `kind` may be stored as componentType/normalized, else why not.
std::string formatProblem(AttributeKind kind, int componentType, bool normalized, bool quantization) {
    if (componentType == TINYGLTF_COMPONENT_TYPE_FLOAT) return "";
    const std::string stored = (normalized ? "normalized " : "") + componentTypeName(componentType);
    // glTF 2.0 itself allows only these integer forms (for texture coordinates).
    const bool core = kind == AttributeKind::Texcoord && normalized &&
                      (componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                       componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
    if (core) return "";
    // KHR_mesh_quantization's table: positions and texture coordinates in any 8- or 16-bit
    // integer, normalized or not; normals only as normalized signed ones.
    const bool quantized = kind == AttributeKind::Normal ? normalized && isSigned8Or16(componentType)
                                                         : isInteger8Or16(componentType);
    if (!quantized) return "is " + stored + ", which no glTF extension allows for it";
    if (!quantization) return "is " + stored + ", which needs KHR_mesh_quantization (not in the file's extensionsUsed)";
    return "";
}

}  // namespace

std::string componentTypeName(int componentType) {
    switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_BYTE: return "BYTE";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return "UNSIGNED_BYTE";
        case TINYGLTF_COMPONENT_TYPE_SHORT: return "SHORT";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return "UNSIGNED_SHORT";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return "UNSIGNED_INT";
        case TINYGLTF_COMPONENT_TYPE_FLOAT: return "FLOAT";
        default: return "componentType " + std::to_string(componentType);
    }
}

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

float componentAsFloat(const unsigned char* bytes, int componentType, bool normalized) {
    // The divisions are done in float, as the spec's formulas are usually implemented (and as
    // GPUs convert normalized vertex formats), so 1 maps to exactly 1 and -127 to exactly -1.
    switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT: return readRaw<float>(bytes);
        case TINYGLTF_COMPONENT_TYPE_BYTE: {
            const float c = float(readRaw<int8_t>(bytes));
            return normalized ? std::max(c / 127.0f, -1.0f) : c;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
            const float c = float(bytes[0]);
            return normalized ? c / 255.0f : c;
        }
        case TINYGLTF_COMPONENT_TYPE_SHORT: {
            const float c = float(readRaw<int16_t>(bytes));
            return normalized ? std::max(c / 32767.0f, -1.0f) : c;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            const float c = float(readRaw<uint16_t>(bytes));
            return normalized ? c / 65535.0f : c;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return float(readRaw<uint32_t>(bytes));
        default: return 0.0f;
    }
}

bool allowsMeshQuantization(const tinygltf::Model& model) {
    const auto lists = [](const std::vector<std::string>& names) {
        return std::find(names.begin(), names.end(), "KHR_mesh_quantization") != names.end();
    };
    return lists(model.extensionsUsed) || lists(model.extensionsRequired);
}

const char* attributeNoun(AttributeKind kind) {
    switch (kind) {
        case AttributeKind::Position: return "position";
        case AttributeKind::Normal: return "normal";
        case AttributeKind::Texcoord: return "texture coordinate";
    }
    return "value";
}

void checkFinite(const AccessorReader& reader, AttributeKind kind, const std::vector<glm::vec3>& values) {
    for (size_t i = 0; i < values.size(); ++i)
        if (!std::isfinite(values[i].x) || !std::isfinite(values[i].y) || !std::isfinite(values[i].z))
            reader.fail(std::string(attributeNoun(kind)) + " " + std::to_string(i) + " is not finite (NaN or inf)");
}

void checkFinite(const AccessorReader& reader, AttributeKind kind, const std::vector<glm::vec2>& values) {
    for (size_t i = 0; i < values.size(); ++i)
        if (!std::isfinite(values[i].x) || !std::isfinite(values[i].y))
            reader.fail(std::string(attributeNoun(kind)) + " " + std::to_string(i) + " is not finite (NaN or inf)");
}

// Elements of one accessor after validation: element i starts at first + i * stride, and all
// `count` elements lie inside the buffer.
struct AccessorReader::Span {
    const unsigned char* first = nullptr;
    size_t stride = 0;
    size_t count = 0;
    int componentType = 0;
    bool normalized = false;

    const unsigned char* element(size_t i) const { return first + i * stride; }
    float component(size_t i, size_t c) const {
        return componentAsFloat(element(i) + c * componentBytes(componentType), componentType, normalized);
    }
};

AccessorReader::AccessorReader(const tinygltf::Model& model, std::string label, std::string path)
    : model_(model), label_(std::move(label)), path_(std::move(path)), quantization_(allowsMeshQuantization(model)) {}

void AccessorReader::fail(const std::string& problem) const { throw Error(path_, label_ + ": " + problem); }

const tinygltf::Accessor& AccessorReader::accessor(int index, const std::string& semantic) const {
    if (index < 0 || size_t(index) >= model_.accessors.size())
        fail(semantic + " refers to accessor " + std::to_string(index) + ", which does not exist");
    return model_.accessors[size_t(index)];
}

void AccessorReader::checkAttributeFormat(int index, const std::string& semantic, AttributeKind kind) const {
    const tinygltf::Accessor& a = accessor(index, semantic);
    const int wantedType = kind == AttributeKind::Texcoord ? TINYGLTF_TYPE_VEC2 : TINYGLTF_TYPE_VEC3;
    const std::string who = semantic + " accessor " + std::to_string(index);
    if (a.type != wantedType) fail(who + " is not " + (wantedType == TINYGLTF_TYPE_VEC2 ? "VEC2" : "VEC3"));
    if (const std::string problem = formatProblem(kind, a.componentType, a.normalized, quantization_); !problem.empty())
        fail(who + " " + problem);
}

void AccessorReader::checkIndexFormat(int index) const {
    const tinygltf::Accessor& a = accessor(index, "indices");
    if (a.type != TINYGLTF_TYPE_SCALAR ||
        (a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
         a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
         a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT))
        fail("indices accessor " + std::to_string(index) +
             " is not SCALAR of UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT");
}

AccessorReader::Span AccessorReader::span(int index, const std::string& semantic) const {
    const tinygltf::Accessor& a = accessor(index, semantic);
    const std::string who = semantic + " accessor " + std::to_string(index);
    if (a.sparse.isSparse) fail(who + " is sparse, which is not supported");
    if (a.bufferView < 0) fail(who + " has no buffer view");
    if (size_t(a.bufferView) >= model_.bufferViews.size())
        fail(who + " refers to buffer view " + std::to_string(a.bufferView) + ", which does not exist");
    const tinygltf::BufferView& view = model_.bufferViews[size_t(a.bufferView)];
    const std::string viewName = "buffer view " + std::to_string(a.bufferView);
    if (view.buffer < 0 || size_t(view.buffer) >= model_.buffers.size())
        fail(viewName + " refers to buffer " + std::to_string(view.buffer) + ", which does not exist");
    const tinygltf::Buffer& buffer = model_.buffers[size_t(view.buffer)];
    size_t viewEnd = 0;
    if (!checkedAdd(view.byteOffset, view.byteLength, viewEnd) || viewEnd > buffer.data.size())
        fail(viewName + " reads past the end of buffer " + std::to_string(view.buffer));

    const size_t componentSize = componentBytes(a.componentType);
    const size_t components = componentsPerElement(a.type);
    if (componentSize == 0 || components == 0) fail(who + " has an unsupported componentType or type");
    const size_t elementSize = componentSize * components;
    const size_t stride = view.byteStride != 0 ? view.byteStride : elementSize;
    if (stride < elementSize)
        fail(viewName + " has byteStride " + std::to_string(stride) + ", smaller than one element of " + who);

    Span result;
    result.stride = stride;
    result.count = a.count;
    result.componentType = a.componentType;
    result.normalized = a.normalized;
    if (a.count == 0) return result;
    // The last element must end inside the view:
    // byteOffset + stride * (count - 1) + elementSize <= view.byteLength.
    size_t end = 0;
    if (!checkedMultiply(stride, a.count - 1, end) || !checkedAdd(end, a.byteOffset, end) ||
        !checkedAdd(end, elementSize, end) || end > view.byteLength)
        fail(who + " reads past the end of " + viewName);
    result.first = buffer.data.data() + view.byteOffset + a.byteOffset;
    return result;
}

std::vector<glm::vec3> AccessorReader::readVec3(int index, const std::string& semantic, AttributeKind kind) const {
    checkAttributeFormat(index, semantic, kind);
    const Span s = span(index, semantic);
    std::vector<glm::vec3> values(s.count);
    for (size_t i = 0; i < s.count; ++i) values[i] = glm::vec3(s.component(i, 0), s.component(i, 1), s.component(i, 2));
    checkFinite(*this, kind, values);
    return values;
}

std::vector<glm::vec2> AccessorReader::readTexcoords(int index, const std::string& semantic) const {
    checkAttributeFormat(index, semantic, AttributeKind::Texcoord);
    const Span s = span(index, semantic);
    std::vector<glm::vec2> values(s.count);
    for (size_t i = 0; i < s.count; ++i) values[i] = glm::vec2(s.component(i, 0), s.component(i, 1));
    checkFinite(*this, AttributeKind::Texcoord, values);
    return values;
}

std::vector<float> AccessorReader::readFloats(int index, const std::string& semantic, int type,
                                             bool normalizedIntegers) const {
    const tinygltf::Accessor& a = accessor(index, semantic);
    const std::string who = semantic + " accessor " + std::to_string(index);
    const size_t components = componentsPerElement(type);
    if (a.type != type) {
        fail(who + " is not " + (type == TINYGLTF_TYPE_SCALAR ? "SCALAR" : "VEC" + std::to_string(components)));
    }
    const bool integer = a.componentType == TINYGLTF_COMPONENT_TYPE_BYTE ||
                         a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                         a.componentType == TINYGLTF_COMPONENT_TYPE_SHORT ||
                         a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
    if (a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT && !(normalizedIntegers && integer && a.normalized)) {
        fail(who + " has component type " + componentTypeName(a.componentType) + " where FLOAT" +
             (normalizedIntegers ? " or a normalized integer" : "") + " is needed");
    }
    const Span s = span(index, semantic);
    std::vector<float> values(s.count * components);
    for (size_t i = 0; i < s.count; ++i) {
        for (size_t c = 0; c < components; ++c) values[i * components + c] = s.component(i, c);
    }
    return values;
}

std::vector<uint32_t> AccessorReader::readIndices(int index) const {
    checkIndexFormat(index);
    const Span s = span(index, "indices");
    std::vector<uint32_t> values(s.count);
    for (size_t i = 0; i < s.count; ++i) {
        const unsigned char* e = s.element(i);
        switch (s.componentType) {
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: values[i] = e[0]; break;
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: values[i] = readRaw<uint16_t>(e); break;
            default: values[i] = readRaw<uint32_t>(e); break;
        }
    }
    return values;
}

}  // namespace punctual::gltf_detail
