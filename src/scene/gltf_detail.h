#pragma once
// Internals of the glTF loader, shared by gltf_loader.cpp (scene graph, materials, cameras,
// lights), gltf_source.cpp (file reading, checks tinygltf does not make, image decoding) and
// gltf_primitives.cpp (validated accessor reads, triangle meshes).
#include <cstdint>
#include <map>
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
};

// Reads the file and parses its JSON. Throws Error for a missing or unreadable file, a
// truncated GLB and JSON syntax errors, so those get a clearer message than tinygltf gives.
SourceFile readSource(const std::string& path);

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

// --- gltf_primitives.cpp ---------------------------------------------------------------------

// Appends one TRIANGLES primitive to `vertices`/`indices` (indices relative to the returned
// Mesh::vertexOffset) and returns its Mesh with `material` left for the caller, or nullopt when
// the primitive has no triangles. `label` names the primitive in errors, e.g.
// "mesh 'box' primitive 0". Validates every accessor before reading it; throws Error(path, ...).
std::optional<Mesh> appendPrimitive(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                                    const std::string& label, const std::string& path,
                                    std::vector<Vertex>& vertices, std::vector<uint32_t>& indices);

}  // namespace punctual::gltf_detail
