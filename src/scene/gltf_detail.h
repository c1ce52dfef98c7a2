#pragma once
// Internals of the glTF loader, shared by gltf_loader.cpp (scene graph, materials, cameras,
// lights), gltf_source.cpp (file reading, checks tinygltf does not make, image decoding),
// gltf_accessors.cpp (validated accessor reads), gltf_primitives.cpp (triangle meshes),
// gltf_draco.cpp (KHR_draco_mesh_compression) and gltf_meshopt.cpp (EXT_meshopt_compression).
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "scene/scene.h"
#include "scene/texture_limit.h"

namespace punctual::gltf_detail {

// --- gltf_source.cpp -------------------------------------------------------------------------

struct SourceFile {
    std::vector<unsigned char> bytes;  // the whole file
    bool binary = false;               // GLB container
    std::string baseDir;               // where relative URIs are resolved
    nlohmann::json json;               // the glTF JSON (of the GLB's JSON chunk), parsed by us
    size_t jsonOffset = 0;             // where that JSON text lies in `bytes`
    size_t jsonLength = 0;
};

// Reads the file and parses its JSON. Throws Error for a missing or unreadable file, a
// truncated GLB and JSON syntax errors, so those get a clearer message than tinygltf gives.
SourceFile readSource(const std::string& path);

// The file's bytes with its JSON replaced by `json`: the text of a .gltf, or a GLB whose JSON
// chunk is `json` and whose other chunks are the file's own.
std::vector<unsigned char> withJson(const SourceFile& source, const nlohmann::json& json);

// A URI decoded exactly as tinygltf 2.7 decodes it before looking for the file: %XX escapes
// (a non-hex digit counts as 0) and '+' as a space.
std::string decodedUri(const std::string& uri);

// Every file a URI names (buffers and images, in .gltf and .glb files alike) is read through
// tinygltf's file callbacks, which this routes to readRegularFile (scene/input_file.h): only
// regular files under the scene's folder, never anything larger than maxBytes. Must outlive the
// load; pass callbacks() to TinyGLTF::SetFsCallbacks.
struct UriFiles {
    UriFiles(const nlohmann::json& gltf, std::string sceneBaseDir);
    tinygltf::FsCallbacks callbacks();
    // Why the file `uri` (as written in the glTF) could not be read; empty if it was not refused.
    std::string problemWith(const std::string& uri) const;

    std::string baseDir;
    uint64_t maxBytes = 0;
    std::map<std::string, std::string> problems;  // path tinygltf asked for -> readRegularFile's problem
    std::map<std::string, uint64_t> bufferBytes;   // a buffer file's path -> its byteLength (its read's limit)
};

// Checks tinygltf 2.7 does not make before it acts on the data: an image stored in a buffer
// view is read from that view without a bounds check, and light properties of the wrong JSON
// type are silently replaced by their defaults. Throws Error.
void preflight(const nlohmann::json& gltf, const std::string& path);

// Image indices referenced (through a texture, and its EXT_texture_webp) as some material's
// baseColorTexture or emissiveTexture: the only images we decode.
std::set<int> colourImages(const nlohmann::json& gltf);

// User data of decodeImage: which images to decode, how large they may stay, and why decoding
// failed for the others.
struct ImageDecoding {
    std::set<int> wanted;
    TextureLimit limit;                   // larger images are downscaled when decoded
    std::string source;                   // the scene file, for the downscaling warning
    std::map<int, std::string> failures;  // image index -> stb's failure reason
};

// tinygltf::LoadImageDataFunction. Decodes wanted images to RGBA8 with stb, downscaled under
// ImageDecoding::limit (one warning each). Never fails the load: an undecodable image is
// recorded in ImageDecoding::failures and left empty, so its materials fall back to their
// baseColorFactor.
bool decodeImage(tinygltf::Image* image, int imageIndex, std::string* err, std::string* warn,
                 int requestedWidth, int requestedHeight, const unsigned char* bytes, int size,
                 void* userData);

// tinygltf's multi-line error text as one short line; known messages are reworded to name the
// buffer they are about.
std::string describeLoadError(const std::string& tinygltfError, const nlohmann::json& gltf);

// tinygltf's warning text split into distinct lines, minus the lines about images that could
// not be read: loadGltf issues its own single warning for each of those it actually uses.
std::vector<std::string> relevantWarnings(const std::string& tinygltfWarnings);

// --- gltf_materials.cpp ----------------------------------------------------------------------

// Converts glTF materials one by one, appending the textures they use to `textures` (each image
// once, with its mip chain). Throws Error(path, ...) for invalid values; warns and falls back to
// the factor for images that cannot be used.
class MaterialConverter {
public:
    MaterialConverter(const tinygltf::Model& model, const std::string& path, const ImageDecoding& decoding,
                      const UriFiles& files, std::vector<Texture>& textures);
    Material convert(size_t materialIndex);

private:
    [[noreturn]] void fail(const std::string& problem) const;
    TextureRef textureRef(int textureIndex, int texCoord, const tinygltf::ExtensionMap& extensions,
                          const std::string& who, const char* slot);
    TextureSampler sampler(int samplerIndex, const std::string& who) const;
    bool imageDecoded(int imageIndex) const;
    std::string describeImage(int imageIndex) const;
    int textureOfImage(int imageIndex, const std::string& who, const char* slot);

    const tinygltf::Model& model_;
    const std::string& path_;
    const ImageDecoding& decoding_;
    const UriFiles& files_;
    std::vector<Texture>& textures_;
    std::map<int, int> textureOfImage_;  // image index -> index into textures_, or -1
};

// --- gltf_accessors.cpp ----------------------------------------------------------------------

// The vertex attributes punctual reads. Each allows the component types glTF 2.0 gives it,
// widened by KHR_mesh_quantization's table when the file uses that extension.
enum class AttributeKind { Position, Normal, Texcoord };

// The spec's name of a component type, e.g. "UNSIGNED_SHORT".
std::string componentTypeName(int componentType);

// Bytes of one component; 0 for the types accessors may not use (INT, DOUBLE, junk).
size_t componentBytes(int componentType);

// One component at `bytes` (any alignment) as a float: FLOAT as stored, normalized integers by
// the glTF rule (signed: max(c / 127, -1) or max(c / 32767, -1); unsigned: c / 255 or c / 65535),
// other integers as their value.
float componentAsFloat(const unsigned char* bytes, int componentType, bool normalized);

// Whether attributes may use KHR_mesh_quantization's component types: the file lists the
// extension in extensionsUsed or extensionsRequired.
bool allowsMeshQuantization(const tinygltf::Model& model);

// Validated reads of one primitive's accessors: every accessor is checked against its buffer
// view and buffer before a byte is read, and every problem throws Error(path, label + ": ...")
// (label e.g. "mesh 'box' primitive 0"), so a malformed file can never cause an out-of-bounds
// read. The Draco decoder uses it too, for the accessors that describe its decoded data.
class AccessorReader {
public:
    AccessorReader(const tinygltf::Model& model, std::string label, std::string path);

    [[noreturn]] void fail(const std::string& problem) const;

    // The accessor `index` that `semantic` ("POSITION", "indices", ...) refers to.
    const tinygltf::Accessor& accessor(int index, const std::string& semantic) const;
    // Fails unless accessor `index` has the element type and a component type `kind` allows.
    void checkAttributeFormat(int index, const std::string& semantic, AttributeKind kind) const;
    // Fails unless accessor `index` is SCALAR of UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT.
    void checkIndexFormat(int index) const;

    std::vector<glm::vec3> readVec3(int index, const std::string& semantic, AttributeKind kind) const;
    std::vector<glm::vec2> readTexcoords(int index, const std::string& semantic) const;
    std::vector<uint32_t> readIndices(int index) const;
    // Accessor `index` as floats, `type` (TINYGLTF_TYPE_SCALAR, _VEC3, _VEC4) numbers an element,
    // flattened: FLOAT, or where `normalizedIntegers` also the normalized BYTE, UNSIGNED_BYTE,
    // SHORT and UNSIGNED_SHORT that animation outputs of rotations and weights may use.
    std::vector<float> readFloats(int index, const std::string& semantic, int type, bool normalizedIntegers) const;

private:
    struct Span;
    Span span(int index, const std::string& semantic) const;

    const tinygltf::Model& model_;
    std::string label_;
    std::string path_;
    bool quantization_;
};

// What a value of `kind` is called in messages: "position", "normal", "texture coordinate".
const char* attributeNoun(AttributeKind kind);

// Fails through `reader` when a value of `kind` is NaN or infinite, naming the element.
void checkFinite(const AccessorReader& reader, AttributeKind kind, const std::vector<glm::vec3>& values);
void checkFinite(const AccessorReader& reader, AttributeKind kind, const std::vector<glm::vec2>& values);

// --- gltf_draco.cpp --------------------------------------------------------------------------

// A primitive's KHR_draco_mesh_compression data, decoded once. The reads give what the plain
// accessors would (same element order, same dequantization of integer data), so the primitive
// code does not care where an attribute came from. Every problem, Draco's own included, fails
// through the AccessorReader: one line naming the file and the primitive.
class DracoPrimitive {
public:
    // `extension` is the primitive's KHR_draco_mesh_compression object.
    DracoPrimitive(const tinygltf::Model& model, const tinygltf::Value& extension, const AccessorReader& reader);
    ~DracoPrimitive();
    DracoPrimitive(const DracoPrimitive&) = delete;
    DracoPrimitive& operator=(const DracoPrimitive&) = delete;

    // Whether the extension's `attributes` map `semantic` into the Draco data.
    bool has(const std::string& semantic) const;
    // `accessorIndex` is the primitive's accessor for `semantic`: its count, type and component
    // type must describe the decoded attribute (the extension says they match).
    std::vector<glm::vec3> readVec3(const std::string& semantic, int accessorIndex, AttributeKind kind) const;
    std::vector<glm::vec2> readTexcoords(const std::string& semantic, int accessorIndex) const;
    // The decoded faces as one index list (three a face), checked against the primitive's
    // indices accessor when it has one (`accessorIndex` >= 0).
    std::vector<uint32_t> indices(int accessorIndex) const;
    size_t vertexCount() const;

private:
    struct Decoded;
    std::unique_ptr<Decoded> decoded_;
    const AccessorReader& reader_;
};

// tinygltf 2.7, built without Draco, refuses a primitive whose indices accessor has no buffer
// view, which is what the extension asks of a Draco primitive's accessors. The JSON tinygltf
// reads leaves those primitives' "indices" out (`patched`, as for addMeshoptPlaceholders), and
// restoreDracoIndices puts them back into the model tinygltf loaded.
void hideDracoIndices(const nlohmann::json& gltf, std::optional<nlohmann::json>& patched);
void restoreDracoIndices(tinygltf::Model& model, const nlohmann::json& gltf);

// --- gltf_meshopt.cpp ------------------------------------------------------------------------

// One EXT_meshopt_compression stream: `count` elements of `byteStride` bytes once decoded.
struct MeshoptStream {
    enum class Mode { Attributes, Triangles, Indices };
    enum class Filter { None, Octahedral, Quaternion, Exponential };
    Mode mode = Mode::Attributes;
    Filter filter = Filter::None;
    size_t count = 0;
    size_t byteStride = 0;
};

// Decodes `size` compressed bytes into `out` (count * byteStride bytes). Returns "" on success,
// else the problem (a layout the extension forbids, or data meshoptimizer rejects).
std::string decodeMeshoptStream(const MeshoptStream& stream, const unsigned char* data, size_t size,
                                std::vector<unsigned char>& out);

// Buffers that hold nothing but room for decoded data (the extension's fallback buffers:
// tagged "fallback", or without a URI and not the GLB's BIN chunk, under a compressed view)
// become one-byte data URIs in the JSON tinygltf reads, which accepts those where it refuses a
// buffer without data. `patched` is that JSON, a copy of `gltf` (the file's) made on the first
// change by whichever function needs one. Throws Error for an image stored in a compressed view (tinygltf would
// read the image from the placeholder).
void addMeshoptPlaceholders(const nlohmann::json& gltf, std::optional<nlohmann::json>& patched, bool binary,
                            const std::string& path);

// Decodes every buffer view that has EXT_meshopt_compression (in `gltf`, the file's JSON) into
// a buffer of its own appended to model.buffers, and points the view there, so accessors read
// decoded data like any other. Throws Error naming the view for malformed extension JSON, a
// compressed range outside its buffer and data that does not decode.
void decodeMeshoptViews(tinygltf::Model& model, const nlohmann::json& gltf, const std::string& path);

// --- gltf_primitives.cpp ---------------------------------------------------------------------

// Whether appendPrimitive draws primitives of `mode`: TRIANGLES, TRIANGLE_STRIP, TRIANGLE_FAN.
bool drawsTriangles(int mode);

// Appends one triangle primitive (strips and fans become lists) to `vertices`/`indices`
// (indices relative to the returned Mesh::vertexOffset) and returns its Mesh with `material`
// left for the caller, or nullopt when the primitive has no triangles. `label` names the
// primitive in errors, e.g. "mesh 'box' primitive 0". Reads plain accessors, decoded meshopt
// views and KHR_draco_mesh_compression data alike; throws Error(path, ...). Morph targets are
// applied at `morphWeights` (the node's weights, else the mesh's: glTF's default pose), POSITION
// and NORMAL; a target whose accessor is sparse is skipped, counted in `unmorphedTargets`.
std::optional<Mesh> appendPrimitive(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                                    const std::string& label, const std::string& path,
                                    const std::vector<double>& morphWeights, size_t& unmorphedTargets,
                                    std::vector<Vertex>& vertices, std::vector<uint32_t>& indices);

}  // namespace punctual::gltf_detail
