// EXT_meshopt_compression: buffer views compressed with meshoptimizer's codecs (Debian's
// libmeshoptimizer). The extension works below accessors: a compressed view names where its
// compressed bytes are (buffer, byteOffset, byteLength), how they decode (mode, filter, count,
// byteStride), and keeps the view's own buffer/byteOffset/byteLength as the place the decoded
// bytes belong, often in a "fallback" buffer that holds no data at all. We decode every such
// view into a buffer of its own before any accessor is read, so accessors need not know.
//
// meshoptimizer checks its input for truncation and corruption (a negative return code) but
// asserts its layout preconditions (vertex size, index size, filter stride), and Debian builds
// it with assertions on: every precondition is checked here first, from the extension's rules.
#include <algorithm>
#include <cstring>
#include <limits>

#include <meshoptimizer.h>

#include "core/error.h"
#include "scene/gltf_detail.h"

namespace punctual::gltf_detail {
namespace {

constexpr const char* kExtension = "EXT_meshopt_compression";

// The codecs cannot expand data more than 64 times (the attribute codec spends at least 2 bits
// of header on every 16 bytes; the index codecs at least a byte a triangle or an index). Views
// that claim more are refused before anything is allocated for them, so a small hostile file
// cannot make us allocate what a declared byteLength asks for. 256 leaves a wide margin.
constexpr size_t kMaxExpansion = 256;

const nlohmann::json* member(const nlohmann::json& object, const char* key) {
    const auto it = object.find(key);
    return it == object.end() ? nullptr : &*it;
}

// The extension object of a glTF element (buffer view, buffer), or nullptr.
const nlohmann::json* extensionOf(const nlohmann::json& element) {
    if (!element.is_object()) return nullptr;
    const nlohmann::json* extensions = member(element, "extensions");
    if (!extensions || !extensions->is_object()) return nullptr;
    return member(*extensions, kExtension);
}

const nlohmann::json* arrayOf(const nlohmann::json& gltf, const char* key) {
    const nlohmann::json* array = member(gltf, key);
    return array && array->is_array() ? array : nullptr;
}

bool isFallback(const nlohmann::json& buffer) {
    const nlohmann::json* extension = extensionOf(buffer);
    if (!extension || !extension->is_object()) return false;
    const nlohmann::json* fallback = member(*extension, "fallback");
    return fallback && fallback->is_boolean() && fallback->get<bool>();
}

std::string problemWithLayout(const MeshoptStream& stream) {
    using Mode = MeshoptStream::Mode;
    using Filter = MeshoptStream::Filter;
    const size_t stride = stream.byteStride;
    if (stream.mode == Mode::Attributes && (stride == 0 || stride % 4 != 0 || stride > 256))
        return "ATTRIBUTES needs a byteStride divisible by 4 and at most 256, not " + std::to_string(stride);
    if (stream.mode != Mode::Attributes) {
        if (stride != 2 && stride != 4) return "indices need a byteStride of 2 or 4, not " + std::to_string(stride);
        if (stream.filter != Filter::None) return "indices cannot have a filter";
    }
    if (stream.mode == Mode::Triangles && stream.count % 3 != 0)
        return "TRIANGLES needs a count divisible by 3, not " + std::to_string(stream.count);
    if (stream.filter == Filter::Octahedral && stride != 4 && stride != 8)
        return "OCTAHEDRAL needs a byteStride of 4 or 8, not " + std::to_string(stride);
    if (stream.filter == Filter::Quaternion && stride != 8)
        return "QUATERNION needs a byteStride of 8, not " + std::to_string(stride);
    if (stream.filter == Filter::Exponential && stride % 4 != 0)
        return "EXPONENTIAL needs a byteStride divisible by 4, not " + std::to_string(stride);
    return "";
}

[[noreturn]] void viewError(const std::string& path, size_t view, const std::string& problem) {
    throw Error(path, "buffer view " + std::to_string(view) + ": " + kExtension + ": " + problem);
}

}  // namespace

std::string decodeMeshoptStream(const MeshoptStream& stream, const unsigned char* data, size_t size,
                                std::vector<unsigned char>& out) {
    using Mode = MeshoptStream::Mode;
    if (const std::string problem = problemWithLayout(stream); !problem.empty()) return problem;
    size_t bytes = 0;
    if (__builtin_mul_overflow(stream.count, stream.byteStride, &bytes)) return "count * byteStride overflows";
    if (bytes / kMaxExpansion > size)
        return std::to_string(bytes) + " decoded bytes are more than " + std::to_string(size) + " compressed ones could hold";
    out.assign(bytes, 0);
    if (bytes == 0) return "";
    int result = 0;
    switch (stream.mode) {
        case Mode::Attributes:
            result = meshopt_decodeVertexBuffer(out.data(), stream.count, stream.byteStride, data, size);
            break;
        case Mode::Triangles:
            result = meshopt_decodeIndexBuffer(out.data(), stream.count, stream.byteStride, data, size);
            break;
        case Mode::Indices:
            result = meshopt_decodeIndexSequence(out.data(), stream.count, stream.byteStride, data, size);
            break;
    }
    // -1: an unsupported version in the header (not meshopt data), -2: data truncated or corrupt.
    if (result == -1) return "the data is not a stream meshoptimizer " + std::to_string(MESHOPTIMIZER_VERSION / 100) +
                             "." + std::to_string(MESHOPTIMIZER_VERSION % 100) + " can decode (unknown header)";
    if (result != 0) return "the compressed data is truncated or corrupt (meshoptimizer error " + std::to_string(result) + ")";
    switch (stream.filter) {
        case MeshoptStream::Filter::None: break;
        case MeshoptStream::Filter::Octahedral: meshopt_decodeFilterOct(out.data(), stream.count, stream.byteStride); break;
        case MeshoptStream::Filter::Quaternion: meshopt_decodeFilterQuat(out.data(), stream.count, stream.byteStride); break;
        case MeshoptStream::Filter::Exponential: meshopt_decodeFilterExp(out.data(), stream.count, stream.byteStride); break;
    }
    return "";
}

void addMeshoptPlaceholders(const nlohmann::json& gltf, std::optional<nlohmann::json>& patched, bool binary,
                            const std::string& path) {
    const nlohmann::json* buffers = arrayOf(gltf, "buffers");
    const nlohmann::json* views = arrayOf(gltf, "bufferViews");
    if (!buffers || !views) return;

    // Buffers that compressed views decode into, and whether any other view uses them.
    std::set<size_t> targets;
    std::vector<bool> compressed(views->size(), false);
    for (size_t i = 0; i < views->size(); ++i) {
        const nlohmann::json& view = (*views)[i];
        if (!extensionOf(view)) continue;
        compressed[i] = true;
        const nlohmann::json* buffer = member(view, "buffer");
        if (buffer && buffer->is_number_unsigned()) targets.insert(buffer->get<size_t>());
    }
    if (const nlohmann::json* images = arrayOf(gltf, "images")) {
        for (size_t i = 0; i < images->size(); ++i) {
            const nlohmann::json& image = (*images)[i];
            const nlohmann::json* view = image.is_object() ? member(image, "bufferView") : nullptr;
            if (view && view->is_number_unsigned() && view->get<size_t>() < compressed.size() && compressed[view->get<size_t>()])
                throw Error(path, "image " + std::to_string(i) + " is stored in buffer view " +
                                      std::to_string(view->get<size_t>()) + ", which " + kExtension +
                                      " compresses: punctual decodes compressed views for geometry only");
        }
    }

    for (size_t i = 0; i < buffers->size(); ++i) {
        const nlohmann::json& buffer = (*buffers)[i];
        if (!buffer.is_object()) continue;
        const bool hasUri = buffer.contains("uri");
        const bool glbChunk = binary && i == 0 && !hasUri;
        // Tagged fallbacks are skipped even with a URI (the extension allows it: their data is
        // what we decode anyway); untagged ones only when they have no data to read.
        const bool placeholder = isFallback(buffer) || (!hasUri && !glbChunk && targets.count(i));
        if (!placeholder || glbChunk) continue;
        if (!patched) patched = gltf;
        nlohmann::json replacement = {{"byteLength", 1}, {"uri", "data:application/octet-stream;base64,AA=="}};
        if (buffer.contains("name")) replacement["name"] = buffer["name"];
        (*patched)["buffers"][i] = replacement;
    }
}

void decodeMeshoptViews(tinygltf::Model& model, const nlohmann::json& gltf, const std::string& path) {
    const nlohmann::json* views = arrayOf(gltf, "bufferViews");
    if (!views) return;
    // A budget for all views together, as for one (kMaxExpansion): many views naming the same
    // compressed bytes must not decode to more than the file could hold.
    size_t budget = 0;
    for (const tinygltf::Buffer& buffer : model.buffers) budget += buffer.data.size();
    constexpr size_t kMaxSize = std::numeric_limits<size_t>::max();
    budget = budget > kMaxSize / kMaxExpansion ? kMaxSize : budget * kMaxExpansion;

    const size_t originalBuffers = model.buffers.size();
    for (size_t i = 0; i < views->size() && i < model.bufferViews.size(); ++i) {
        const nlohmann::json* extension = extensionOf((*views)[i]);
        if (!extension) continue;
        if (!extension->is_object()) viewError(path, i, "is not a JSON object");
        const auto unsignedMember = [&](const char* key, bool required) -> size_t {
            const nlohmann::json* value = member(*extension, key);
            if (!value && required) viewError(path, i, std::string("has no '") + key + "'");
            if (!value) return 0;
            if (!value->is_number_unsigned()) viewError(path, i, std::string("'") + key + "' is not a non-negative integer");
            return value->get<size_t>();
        };
        // `fallback` nullptr: the member is required.
        const auto stringMember = [&](const char* key, const char* fallback) -> std::string {
            const nlohmann::json* value = member(*extension, key);
            if (!value && !fallback) viewError(path, i, std::string("has no '") + key + "'");
            if (!value) return fallback;
            if (!value->is_string()) viewError(path, i, std::string("'") + key + "' is not a string");
            return value->get<std::string>();
        };

        const size_t bufferIndex = unsignedMember("buffer", true);
        const size_t byteOffset = unsignedMember("byteOffset", false);
        const size_t byteLength = unsignedMember("byteLength", true);
        MeshoptStream stream;
        stream.byteStride = unsignedMember("byteStride", true);
        stream.count = unsignedMember("count", true);
        const std::string mode = stringMember("mode", nullptr);
        if (mode == "ATTRIBUTES") stream.mode = MeshoptStream::Mode::Attributes;
        else if (mode == "TRIANGLES") stream.mode = MeshoptStream::Mode::Triangles;
        else if (mode == "INDICES") stream.mode = MeshoptStream::Mode::Indices;
        else viewError(path, i, "unknown mode '" + mode + "' (expected ATTRIBUTES, TRIANGLES or INDICES)");
        const std::string filter = stringMember("filter", "NONE");
        if (filter == "NONE") stream.filter = MeshoptStream::Filter::None;
        else if (filter == "OCTAHEDRAL") stream.filter = MeshoptStream::Filter::Octahedral;
        else if (filter == "QUATERNION") stream.filter = MeshoptStream::Filter::Quaternion;
        else if (filter == "EXPONENTIAL") stream.filter = MeshoptStream::Filter::Exponential;
        else viewError(path, i, "unknown filter '" + filter + "' (expected NONE, OCTAHEDRAL, QUATERNION or EXPONENTIAL)");

        // Decoded buffers are appended after the file's own; compressed data comes from those.
        if (bufferIndex >= originalBuffers)
            viewError(path, i, "refers to buffer " + std::to_string(bufferIndex) + ", which does not exist");
        const std::vector<unsigned char>& source = model.buffers[bufferIndex].data;
        if (byteOffset > source.size() || byteLength > source.size() - byteOffset)
            viewError(path, i, "its compressed bytes lie outside buffer " + std::to_string(bufferIndex));
        tinygltf::BufferView& view = model.bufferViews[i];
        if (view.byteStride != 0 && view.byteStride != stream.byteStride)
            viewError(path, i, "byteStride " + std::to_string(stream.byteStride) + " differs from the view's " +
                 std::to_string(view.byteStride));
        size_t decodedBytes = 0;
        if (__builtin_mul_overflow(stream.count, stream.byteStride, &decodedBytes) || decodedBytes != view.byteLength)
            viewError(path, i, "count * byteStride is not the view's byteLength " + std::to_string(view.byteLength));
        if (decodedBytes > budget) viewError(path, i, "decodes to more than the file's compressed data could hold");
        budget -= decodedBytes;

        tinygltf::Buffer decoded;
        decoded.name = "decoded buffer view " + std::to_string(i);
        if (const std::string problem =
                decodeMeshoptStream(stream, source.data() + byteOffset, byteLength, decoded.data);
            !problem.empty())
            viewError(path, i, problem);
        model.buffers.push_back(std::move(decoded));
        view.buffer = int(model.buffers.size() - 1);
        view.byteOffset = 0;
    }
}

}  // namespace punctual::gltf_detail
