// Reading a glTF file before tinygltf sees it, and the glue around tinygltf: error and warning
// text, image decoding.
#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>
#include <tuple>

#include <sys/stat.h>

#include "scene/image_decoding.h"

#include "core/error.h"
#include "core/log.h"
#include "scene/gltf_detail.h"
#include "scene/input_file.h"
#include "scene/json_nesting.h"

namespace punctual::gltf_detail {
namespace {

constexpr uint32_t kGlbMagic = 0x46546C67;      // "glTF"
constexpr uint32_t kGlbJsonChunk = 0x4E4F534A;  // "JSON"
constexpr size_t kGlbHeaderBytes = 12;
constexpr size_t kGlbChunkHeaderBytes = 8;

uint32_t readLittleEndian32(const unsigned char* bytes) {
    return uint32_t(bytes[0]) | (uint32_t(bytes[1]) << 8) | (uint32_t(bytes[2]) << 16) |
           (uint32_t(bytes[3]) << 24);
}

bool hasGlbExtension(const std::string& path) {
    std::string extension = std::filesystem::path(path).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return extension == ".glb";
}

// Where the JSON text is inside a GLB; throws for the truncations and corruptions a user can
// hit (a partial download, a file cut short), with the sizes involved.
std::pair<size_t, size_t> glbJsonChunk(const std::vector<unsigned char>& bytes, const std::string& path) {
    const size_t minimum = kGlbHeaderBytes + kGlbChunkHeaderBytes;
    if (bytes.size() < minimum)
        throw Error(path, "truncated GLB file: " + std::to_string(bytes.size()) + " bytes, less than the " +
                              std::to_string(minimum) + "-byte header");
    if (readLittleEndian32(bytes.data()) != kGlbMagic) throw Error(path, "not a GLB file (no \"glTF\" magic)");
    const uint32_t version = readLittleEndian32(bytes.data() + 4);
    if (version != 2) throw Error(path, "GLB version " + std::to_string(version) + " is not supported (need 2)");
    const uint32_t declaredLength = readLittleEndian32(bytes.data() + 8);
    if (declaredLength > bytes.size())
        throw Error(path, "truncated GLB file: the header says " + std::to_string(declaredLength) +
                              " bytes but the file has " + std::to_string(bytes.size()));
    const uint32_t jsonLength = readLittleEndian32(bytes.data() + kGlbHeaderBytes);
    const uint32_t jsonType = readLittleEndian32(bytes.data() + kGlbHeaderBytes + 4);
    if (jsonType != kGlbJsonChunk) throw Error(path, "invalid GLB file: the first chunk is not JSON");
    if (uint64_t(minimum) + jsonLength > declaredLength)
        throw Error(path, "truncated GLB file: the JSON chunk runs past the end of the file");
    return {minimum, jsonLength};
}

// "[json.exception.parse_error.101] parse error at line 3, ..." -> "parse error at line 3, ..."
std::string withoutNlohmannPrefix(const std::string& message) {
    if (!message.empty() && message.front() == '[') {
        const size_t end = message.find("] ");
        if (end != std::string::npos) return message.substr(end + 2);
    }
    return message;
}

std::vector<std::string> splitLines(const std::string& text) {
    std::vector<std::string> result;
    std::istringstream stream(text);
    std::string line;
    while (std::getline(stream, line)) {
        const size_t first = line.find_first_not_of(" \t\r");
        if (first == std::string::npos) continue;
        const size_t last = line.find_last_not_of(" \t\r");
        result.push_back(line.substr(first, last - first + 1));
    }
    return result;
}

bool startsWith(const std::string& text, const std::string& prefix) {
    return text.compare(0, prefix.size(), prefix) == 0;
}

unsigned char hexValue(unsigned char c) {
    if (c >= '0' && c <= '9') return static_cast<unsigned char>(c - '0');
    if (c >= 'a' && c <= 'f') return static_cast<unsigned char>(c - 'a' + 10);
    if (c >= 'A' && c <= 'F') return static_cast<unsigned char>(c - 'A' + 10);
    return 0;
}

// How many bytes formatProblem needs: the GLB header, or enough of a .gltf to pass a UTF-8 byte
// order mark and some whitespace before its '{'.
constexpr size_t kHeadBytes = 4096;

// Why the file starting with `head` (at most kHeadBytes of it) cannot be glTF, or empty. A GLB
// starts with its magic; JSON text (RFC 8259) with optional whitespace, here after an optional
// UTF-8 byte order mark (which tinygltf skips), then the '{' of the top-level object. A GLB's
// length is checked by glbJsonChunk once the file is read.
std::string formatProblem(const std::vector<unsigned char>& head, bool glbExtension) {
    if (head.size() >= 4 && readLittleEndian32(head.data()) == kGlbMagic) return "";
    if (glbExtension) return "";  // glbJsonChunk names what is wrong with the header
    size_t i = head.size() >= 3 && head[0] == 0xEF && head[1] == 0xBB && head[2] == 0xBF ? 3 : 0;
    while (i < head.size() && (head[i] == ' ' || head[i] == '\t' || head[i] == '\n' || head[i] == '\r')) ++i;
    if (i == head.size()) {
        return head.size() < kHeadBytes ? "not glTF: the file is empty or only whitespace"
                                        : "not glTF: the first " + std::to_string(kHeadBytes) + " bytes are whitespace";
    }
    if (head[i] == '{') return "";
    char found[8];
    std::snprintf(found, sizeof found, "0x%02X", head[i]);
    return "not glTF: JSON text must start with '{' but byte " + std::to_string(i) + " is " + found +
           " (and the file has no GLB magic)";
}

}  // namespace

std::string decodedUri(const std::string& uri) {
    std::string out;
    for (size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '+') {
            out.push_back(' ');
        } else if (uri[i] == '%' && i + 2 < uri.size()) {
            const auto high = hexValue(static_cast<unsigned char>(uri[i + 1]));
            const auto low = hexValue(static_cast<unsigned char>(uri[i + 2]));
            out.push_back(static_cast<char>((high << 4) | low));
            i += 2;
        } else {
            out.push_back(uri[i]);
        }
    }
    return out;
}

namespace {

// Index of the buffer whose URI is `file` (as tinygltf reports it: decoded, possibly with the
// base directory in front), or -1.
int bufferWithUri(const nlohmann::json& gltf, const std::string& file) {
    const auto buffers = gltf.find("buffers");
    if (buffers == gltf.end() || !buffers->is_array()) return -1;
    for (size_t i = 0; i < buffers->size(); ++i) {
        const nlohmann::json& buffer = (*buffers)[i];
        if (!buffer.is_object() || !buffer.contains("uri") || !buffer["uri"].is_string()) continue;
        const std::string uri = decodedUri(buffer["uri"].get<std::string>());
        if (uri.empty()) continue;
        const bool suffix = file.size() >= uri.size() && file.compare(file.size() - uri.size(), uri.size(), uri) == 0;
        if (file == uri || suffix) return static_cast<int>(i);
    }
    return -1;
}

// "buffer 2: 'name.bin'" for a file that is some buffer's URI, else "'file'" as tinygltf gave it
// (with the base directory in front).
std::string describeFile(const nlohmann::json& gltf, const std::string& file) {
    const int index = bufferWithUri(gltf, file);
    if (index < 0) return "'" + file + "'";
    return "buffer " + std::to_string(index) + ": '" + gltf["buffers"][size_t(index)]["uri"].get<std::string>() + "'";
}

// Non-negative integer member `key` of `object`, or nullopt when absent or of another type.
std::optional<uint64_t> unsignedMember(const nlohmann::json& object, const char* key) {
    const auto it = object.find(key);
    if (it == object.end() || !it->is_number_integer() || it->get<int64_t>() < 0) return std::nullopt;
    return it->get<uint64_t>();
}

const nlohmann::json* arrayElement(const nlohmann::json& gltf, const char* array, uint64_t index) {
    const auto it = gltf.find(array);
    if (it == gltf.end() || !it->is_array() || index >= it->size() || !(*it)[index].is_object()) return nullptr;
    return &(*it)[index];
}

void checkImageBufferViews(const nlohmann::json& gltf, const std::string& path) {
    const auto images = gltf.find("images");
    if (images == gltf.end() || !images->is_array()) return;
    for (size_t i = 0; i < images->size(); ++i) {
        const nlohmann::json& image = (*images)[i];
        if (!image.is_object()) continue;
        const std::optional<uint64_t> viewIndex = unsignedMember(image, "bufferView");
        if (!viewIndex) continue;  // no buffer view, or a malformed one tinygltf reports itself
        const std::string who = "image " + std::to_string(i) + ": buffer view " + std::to_string(*viewIndex);
        const nlohmann::json* view = arrayElement(gltf, "bufferViews", *viewIndex);
        if (!view) throw Error(path, who + " does not exist");
        const std::optional<uint64_t> bufferIndex = unsignedMember(*view, "buffer");
        const nlohmann::json* buffer = bufferIndex ? arrayElement(gltf, "buffers", *bufferIndex) : nullptr;
        if (!buffer) throw Error(path, who + " refers to a buffer that does not exist");
        const uint64_t offset = unsignedMember(*view, "byteOffset").value_or(0);
        const uint64_t length = unsignedMember(*view, "byteLength").value_or(0);
        const uint64_t bufferLength = unsignedMember(*buffer, "byteLength").value_or(0);
        // tinygltf checks that a buffer's data has exactly its byteLength, so this bounds the read.
        if (length == 0 || offset > bufferLength || length > bufferLength - offset)
            throw Error(path, who + " lies outside buffer " + std::to_string(*bufferIndex));
    }
}

// How many bytes base64 text of `length` characters, `padding` of them '=', decodes to.
uint64_t base64DecodedBytes(uint64_t length, uint64_t padding) { return length / 4 * 3 - std::min<uint64_t>(padding, 2); }

// A buffer's data URI must hold exactly byteLength bytes. tinygltf would report a mismatch as
// "Failed to decode 'data:...'" with the whole base64 text and not the lengths; this names both.
void checkBufferDataUris(const nlohmann::json& gltf, const std::string& path) {
    const auto buffers = gltf.find("buffers");
    if (buffers == gltf.end() || !buffers->is_array()) return;
    for (size_t i = 0; i < buffers->size(); ++i) {
        const nlohmann::json& buffer = (*buffers)[i];
        if (!buffer.is_object() || !buffer.contains("uri") || !buffer["uri"].is_string()) continue;
        const std::string& uri = buffer["uri"].get_ref<const std::string&>();
        if (!startsWith(uri, "data:")) continue;
        const std::string who = "buffer " + std::to_string(i);
        const size_t comma = uri.find(',');
        if (comma == std::string::npos || uri.rfind(";base64", comma) == std::string::npos)
            throw Error(path, who + ": its data URI is not base64 (data:<type>;base64,<data>)");
        const uint64_t length = uri.size() - comma - 1;
        if (length % 4 != 0)
            throw Error(path, who + ": its data URI's base64 text has " + std::to_string(length) +
                                  " characters, not a multiple of 4");
        const uint64_t padding = uint64_t(uri.size() - 1 - std::min(uri.find_last_not_of('='), uri.size() - 1));
        const uint64_t decoded = length == 0 ? 0 : base64DecodedBytes(length, padding);
        const std::optional<uint64_t> byteLength = unsignedMember(buffer, "byteLength");
        if (byteLength && decoded != *byteLength)
            throw Error(path, who + ": its data URI holds " + std::to_string(decoded) + " bytes but its byteLength is " +
                                  std::to_string(*byteLength));
    }
}

// "2.0" -> {2, 0}; nullopt unless the text is <major>.<minor> in decimal digits (the spec's
// pattern ^[0-9]+\.[0-9]+$).
std::optional<std::pair<unsigned long, unsigned long>> versionNumbers(const std::string& text) {
    const size_t dot = text.find('.');
    const auto digits = [](const std::string& part) {
        return !part.empty() && part.size() < 10 && std::all_of(part.begin(), part.end(), [](unsigned char c) { return std::isdigit(c); });
    };
    if (dot == std::string::npos || !digits(text.substr(0, dot)) || !digits(text.substr(dot + 1))) return std::nullopt;
    return std::make_pair(std::stoul(text.substr(0, dot)), std::stoul(text.substr(dot + 1)));
}

// punctual reads glTF 2.x: a file for another major version (or one whose minVersion is newer
// than 2.0, the version this loader implements) means something else by the same names.
void checkAssetVersion(const nlohmann::json& gltf, const std::string& path) {
    const auto asset = gltf.find("asset");
    if (asset == gltf.end() || !asset->is_object() || !asset->contains("version") || !(*asset)["version"].is_string())
        throw Error(path, "asset.version is missing (glTF requires it; punctual reads version 2.0)");
    const std::string version = (*asset)["version"].get<std::string>();
    const auto numbers = versionNumbers(version);
    if (!numbers) throw Error(path, "asset.version '" + version.substr(0, 40) + "' is not <major>.<minor>");
    if (numbers->first != 2) throw Error(path, "glTF version " + version + " is not supported (punctual reads 2.x)");
    if (asset->contains("minVersion") && (*asset)["minVersion"].is_string()) {
        const std::string minimum = (*asset)["minVersion"].get<std::string>();
        const auto minNumbers = versionNumbers(minimum);
        if (!minNumbers || *minNumbers > std::make_pair(2ul, 0ul))
            throw Error(path, "asset.minVersion '" + minimum.substr(0, 40) + "' needs a newer loader (punctual reads 2.0)");
    }
}

// glTF: "When a node is targeted for animation, only TRS properties may be present; matrix will
// not be present", and a node has either a matrix or TRS. tinygltf keeps both and the loader
// would silently take the matrix.
void checkNodeTransforms(const nlohmann::json& gltf, const std::string& path) {
    const auto nodes = gltf.find("nodes");
    if (nodes == gltf.end() || !nodes->is_array()) return;
    for (size_t i = 0; i < nodes->size(); ++i) {
        const nlohmann::json& node = (*nodes)[i];
        if (!node.is_object() || !node.contains("matrix")) continue;
        for (const char* key : {"translation", "rotation", "scale"})
            if (node.contains(key))
                throw Error(path, "node " + std::to_string(i) + " has both a matrix and a " + key +
                                      " (glTF allows one or the other)");
    }
}

void checkLightPropertyTypes(const nlohmann::json& gltf, const std::string& path) {
    const auto extensions = gltf.find("extensions");
    if (extensions == gltf.end() || !extensions->is_object()) return;
    const auto punctual = extensions->find("KHR_lights_punctual");
    if (punctual == extensions->end() || !punctual->is_object()) return;
    const auto lights = punctual->find("lights");
    if (lights == punctual->end()) return;
    if (!lights->is_array()) throw Error(path, "KHR_lights_punctual: 'lights' is not an array");
    for (size_t i = 0; i < lights->size(); ++i) {
        const nlohmann::json& light = (*lights)[i];
        std::string who = "light " + std::to_string(i);
        if (!light.is_object()) throw Error(path, who + " is not a JSON object");
        if (light.contains("name") && light["name"].is_string()) who += " '" + light["name"].get<std::string>() + "'";
        for (const char* key : {"intensity", "range"})
            if (light.contains(key) && !light[key].is_number())
                throw Error(path, who + ": '" + key + "' is not a number");
        // tinygltf reads an absent range as 0, and we read 0 as "absent: infinite". The spec
        // requires range > 0 when it is given, so a 0 written in the file is an error here,
        // where absent and 0 can still be told apart. (JSON has no NaN; a number too large for
        // a float is an infinite range, see convertLights.)
        if (light.contains("range") && !(light["range"].get<double>() > 0.0)) {
            std::ostringstream value;
            value << light["range"].get<double>();
            throw Error(path, who + " has an invalid range " + value.str() +
                                  " (KHR_lights_punctual requires range > 0; leave it out for an infinite range)");
        }
        if (light.contains("color")) {
            const nlohmann::json& color = light["color"];
            if (!color.is_array() || color.size() != 3 ||
                !std::all_of(color.begin(), color.end(), [](const nlohmann::json& c) { return c.is_number(); }))
                throw Error(path, who + ": 'color' is not an array of 3 numbers");
        }
        // tinygltf 2.7 rejects a spot light without a "spot" object with a message that does
        // not say which light.
        if (light.contains("type") && light["type"] == "spot" && !light.contains("spot"))
            throw Error(path, who + " is a spot light without a 'spot' object");
        if (light.contains("spot")) {
            const nlohmann::json& spot = light["spot"];
            if (!spot.is_object()) throw Error(path, who + ": 'spot' is not an object");
            for (const char* key : {"innerConeAngle", "outerConeAngle"})
                if (spot.contains(key) && !spot[key].is_number())
                    throw Error(path, who + ": '" + key + "' is not a number");
        }
    }
}

}  // namespace

SourceFile readSource(const std::string& path) {
    namespace fs = std::filesystem;
    SourceFile source;
    // tinygltf takes the size as an unsigned int. The first bytes say whether the file can be
    // glTF at all before the rest is read: a 3 GB file of zeros is refused at byte 0, unread.
    constexpr uint64_t kMaxSourceBytes = std::numeric_limits<uint32_t>::max();
    std::string problem = readRegularFileHead(path, kMaxSourceBytes, kHeadBytes, source.bytes);
    if (problem.empty()) {
        if (std::string format = formatProblem(source.bytes, hasGlbExtension(path)); !format.empty()) throw Error(path, format);
        problem = readRegularFile(path, kMaxSourceBytes, source.bytes);
    }
    if (!problem.empty()) throw Error(path, "cannot be read (" + problem + ")");
    source.baseDir = fs::path(path).parent_path().string();

    const bool magic = source.bytes.size() >= 4 && readLittleEndian32(source.bytes.data()) == kGlbMagic;
    source.binary = magic || hasGlbExtension(path);
    source.jsonOffset = 0;
    source.jsonLength = source.bytes.size();
    if (source.binary) std::tie(source.jsonOffset, source.jsonLength) = glbJsonChunk(source.bytes, path);

    const auto jsonBegin = source.bytes.begin() + static_cast<std::ptrdiff_t>(source.jsonOffset);
    if (std::string nesting = jsonNestingProblem(source.bytes.data() + source.jsonOffset, source.jsonLength); !nesting.empty())
        throw Error(path, "cannot parse JSON: " + nesting);
    try {
        source.json = nlohmann::json::parse(jsonBegin, jsonBegin + static_cast<std::ptrdiff_t>(source.jsonLength));
    } catch (const nlohmann::json::exception& e) {
        throw Error(path, "cannot parse JSON: " + withoutNlohmannPrefix(e.what()));
    }
    if (!source.json.is_object()) throw Error(path, "cannot parse JSON: the top level is not an object");
    return source;
}

std::vector<unsigned char> withJson(const SourceFile& source, const nlohmann::json& json) {
    std::string text = json.dump();
    if (!source.binary) return std::vector<unsigned char>(text.begin(), text.end());
    // GLB chunks are 4-byte aligned; JSON is padded with spaces.
    while (text.size() % 4 != 0) text += ' ';
    // The chunks after the JSON one, up to the length the header declares (readSource checked
    // that the JSON chunk ends within it).
    const size_t rest = source.jsonOffset + source.jsonLength;
    const size_t declaredEnd = readLittleEndian32(source.bytes.data() + 8);
    std::vector<unsigned char> glb(source.bytes.begin(), source.bytes.begin() + kGlbHeaderBytes);
    const auto appendU32 = [&glb](size_t value) {
        for (int shift = 0; shift < 32; shift += 8) glb.push_back(static_cast<unsigned char>(value >> shift));
    };
    appendU32(text.size());
    appendU32(kGlbJsonChunk);
    glb.insert(glb.end(), text.begin(), text.end());
    glb.insert(glb.end(), source.bytes.begin() + static_cast<std::ptrdiff_t>(rest),
               source.bytes.begin() + static_cast<std::ptrdiff_t>(declaredEnd));
    const size_t length = glb.size();
    for (int i = 0; i < 4; ++i) glb[8 + size_t(i)] = static_cast<unsigned char>(length >> (8 * i));
    return glb;
}

namespace {

// tinygltf::FsCallbacks, all through readRegularFile. `user` is the UriFiles.
bool uriFileExists(const std::string& path, void* user) {
    const auto& files = *static_cast<const UriFiles*>(user);
    // tinygltf looks for a URI next to the scene, then in the current folder. A relative URI
    // is relative to the scene's file (the glTF spec), so never fall back to another file
    // that happens to have the name.
    const std::string prefix = files.baseDir.empty() || files.baseDir.back() == '/' ? files.baseDir : files.baseDir + "/";
    if (!startsWith(path, prefix)) return false;
    // Anything that exists "exists": uriReadWholeFile then says what is wrong with it, which
    // "not found" would hide.
    struct stat info {};
    return ::lstat(path.c_str(), &info) == 0;
}

std::string uriExpandFilePath(const std::string& path, void* /*user*/) { return path; }

bool uriReadWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
    auto& files = *static_cast<UriFiles*>(user);
    // A buffer's file holds exactly its byteLength (tinygltf checks after reading): a larger one
    // is refused by its size, unread.
    std::string problem;
    uint64_t maxBytes = files.maxBytes;
    if (const auto buffer = files.bufferBytes.find(path); buffer != files.bufferBytes.end()) {
        maxBytes = buffer->second;
        struct stat info {};
        if (::stat(path.c_str(), &info) == 0 && S_ISREG(info.st_mode) && uint64_t(info.st_size) > maxBytes)
            problem = std::to_string(info.st_size) + " bytes, more than the buffer's byteLength " + std::to_string(maxBytes);
    }
    if (problem.empty()) problem = readRegularFile(path, maxBytes, *out);
    if (problem.empty()) return true;
    files.problems[path] = problem;
    if (err) *err += problem;
    return false;
}

bool uriWriteWholeFile(std::string* err, const std::string& /*path*/, const std::vector<unsigned char>& /*contents*/,
                       void* /*user*/) {
    if (err) *err += "punctual never writes glTF files";
    return false;
}

// tinygltf's JoinPath: the path it asks the callbacks for.
std::string joinedPath(const std::string& baseDir, const std::string& file) {
    if (baseDir.empty()) return file;
    return baseDir.back() == '/' ? baseDir + file : baseDir + "/" + file;
}

}  // namespace

UriFiles::UriFiles(const nlohmann::json& gltf, std::string sceneBaseDir) : baseDir(std::move(sceneBaseDir)) {
    // Images reach stb as an int-sized array; a buffer may be as large as its byteLength says
    // (tinygltf then checks the file has exactly that size). Anything larger is refused by its
    // size before it is read.
    maxBytes = uint64_t(std::numeric_limits<int>::max());
    const auto buffers = gltf.find("buffers");
    if (buffers != gltf.end() && buffers->is_array())
        for (const nlohmann::json& buffer : *buffers)
            if (buffer.is_object()) {
                const uint64_t length = unsignedMember(buffer, "byteLength").value_or(0);
                maxBytes = std::max(maxBytes, length);
                if (buffer.contains("uri") && buffer["uri"].is_string()) {
                    const std::string uri = buffer["uri"].get<std::string>();
                    if (!startsWith(uri, "data:")) bufferBytes[joinedPath(baseDir, decodedUri(uri))] = length;
                }
            }
}

tinygltf::FsCallbacks UriFiles::callbacks() {
    return tinygltf::FsCallbacks{&uriFileExists, &uriExpandFilePath, &uriReadWholeFile, &uriWriteWholeFile, this};
}

std::string UriFiles::problemWith(const std::string& uri) const {
    const auto found = problems.find(joinedPath(baseDir, decodedUri(uri)));
    return found == problems.end() ? "" : found->second;
}

void preflight(const nlohmann::json& gltf, const std::string& path) {
    checkImageBufferViews(gltf, path);
    checkAssetVersion(gltf, path);
    checkNodeTransforms(gltf, path);
    checkBufferDataUris(gltf, path);
    checkLightPropertyTypes(gltf, path);
}

std::set<int> colourImages(const nlohmann::json& gltf) {
    std::set<int> images;
    const auto addTexture = [&](const nlohmann::json& owner, const char* member) {
        const auto info = owner.find(member);
        if (info == owner.end() || !info->is_object()) return;
        const std::optional<uint64_t> textureIndex = unsignedMember(*info, "index");
        const nlohmann::json* texture = textureIndex ? arrayElement(gltf, "textures", *textureIndex) : nullptr;
        if (!texture) return;
        std::vector<std::optional<uint64_t>> sources = {unsignedMember(*texture, "source")};
        // EXT_texture_webp names its own image; the plain source stays as the fallback.
        const auto extensions = texture->find("extensions");
        if (extensions != texture->end() && extensions->is_object()) {
            const auto webp = extensions->find("EXT_texture_webp");
            if (webp != extensions->end() && webp->is_object()) sources.push_back(unsignedMember(*webp, "source"));
        }
        for (const std::optional<uint64_t>& source : sources)
            if (source && *source <= uint64_t(std::numeric_limits<int>::max())) images.insert(static_cast<int>(*source));
    };
    const auto materials = gltf.find("materials");
    if (materials == gltf.end() || !materials->is_array()) return images;
    for (const nlohmann::json& material : *materials) {
        if (!material.is_object()) continue;
        addTexture(material, "emissiveTexture");
        const auto pbr = material.find("pbrMetallicRoughness");
        if (pbr != material.end() && pbr->is_object()) addTexture(*pbr, "baseColorTexture");
    }
    return images;
}

bool decodeImage(tinygltf::Image* image, int imageIndex, std::string* /*err*/, std::string* /*warn*/,
                 int /*requestedWidth*/, int /*requestedHeight*/, const unsigned char* bytes, int size,
                 void* userData) {
    auto& decoding = *static_cast<ImageDecoding*>(userData);
    // Other images (normal, occlusion, ... maps) are not rendered: skip the decoding cost.
    if (!decoding.wanted.count(imageIndex)) return true;
    if (bytes == nullptr || size <= 0) {
        decoding.failures[imageIndex] = "no image data";
        return true;
    }
    // Fitted while decoding (scene/image_decoding.h): a texture too large for the frame never
    // exists twice at full size, and one too large to decode whole is decoded reduced.
    std::string failure;
    FittedImage decoded;
    if (!decodeFittedRgba8(bytes, size_t(size), decoding.limit.maxSide, decoded, failure)) {
        decoding.failures[imageIndex] = failure;
        return true;
    }
    const TextureSize from = decoded.original;
    const TextureSize to = decoded.size;
    if (to.width != from.width || to.height != from.height) {
        std::string what = "image " + std::to_string(imageIndex);
        if (!image->uri.empty()) what += " '" + image->uri + "'";
        else if (!image->name.empty()) what += " '" + image->name + "'";
        log::warn(decoding.source + ": " + downscaleWarning(what, from, to, decoding.limit.reason));
    }
    image->image = std::move(decoded.rgba);
    image->width = int(to.width);
    image->height = int(to.height);
    image->component = 4;
    image->bits = 8;
    image->pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
    return true;
}

namespace {

// tinygltf quotes a data URI whole in its messages ("Failed to decode 'data:...'"): keep its
// head, say how long the rest was.
std::string withShortDataUris(std::string line) {
    constexpr size_t kKept = 40;
    for (size_t at = line.find("data:"); at != std::string::npos; at = line.find("data:", at + kKept)) {
        const size_t end = std::min(line.find_first_of("' \"", at), line.size());
        if (end - at <= kKept + 16) continue;
        line.replace(at + kKept, end - at - kKept, "... (" + std::to_string(end - at) + " characters)");
    }
    return line;
}

}  // namespace

std::string describeLoadError(const std::string& tinygltfError, const nlohmann::json& gltf) {
    std::vector<std::string> lines = splitLines(tinygltfError);
    for (std::string& line : lines) line = withShortDataUris(std::move(line));
    for (const std::string& line : lines) {
        // Messages from tinygltf's LoadExternalFile; for buffers they are errors.
        if (startsWith(line, "File not found : ")) {
            const std::string file = line.substr(std::strlen("File not found : "));
            return describeFile(gltf, file) + " cannot be read (no such file)";
        }
        if (startsWith(line, "File read error : ")) {
            // "File read error : dir/a.bin : <problem>": our ReadWholeFile's problems never
            // contain " : ", so the last one ends the path.
            const std::string rest = line.substr(std::strlen("File read error : "));
            const size_t separator = rest.rfind(" : ");
            if (separator == std::string::npos) return describeFile(gltf, rest) + " cannot be read";
            return describeFile(gltf, rest.substr(0, separator)) + " cannot be read (" + rest.substr(separator + 3) + ")";
        }
        if (startsWith(line, "File is empty : ")) {
            const std::string file = line.substr(std::strlen("File is empty : "));
            return describeFile(gltf, file) + " is empty";
        }
        if (startsWith(line, "File size mismatch : ")) {
            // "File size mismatch : dir/a.bin, requestedBytes 96, but got 48"
            const std::string rest = line.substr(std::strlen("File size mismatch : "));
            const std::string file = rest.substr(0, rest.find(", requestedBytes"));
            const size_t requested = rest.find("requestedBytes ");
            const size_t got = rest.find("but got ");
            if (requested == std::string::npos || got == std::string::npos) break;
            const std::string wanted = rest.substr(requested + 15, rest.find(',', requested) - (requested + 15));
            return describeFile(gltf, file) + " has " + rest.substr(got + 8) + " bytes but the buffer's byteLength is " +
                   wanted;
        }
    }
    std::string joined;
    for (const std::string& line : lines) joined += (joined.empty() ? "" : "; ") + line;
    if (joined.empty()) joined = "tinygltf failed without saying why";
    constexpr size_t kMaxLength = 300;
    if (joined.size() > kMaxLength) joined = joined.substr(0, kMaxLength) + "...";
    return "invalid glTF: " + joined;
}

std::vector<std::string> relevantWarnings(const std::string& tinygltfWarnings) {
    std::vector<std::string> result;
    for (const std::string& line : splitLines(tinygltfWarnings)) {
        // tinygltf reads buffers with no warning sink, so these come from images only.
        const bool aboutImage = startsWith(line, "File not found : ") || startsWith(line, "File read error : ") ||
                                startsWith(line, "File is empty : ") || line.find("for image[") != std::string::npos;
        if (aboutImage) continue;
        if (std::find(result.begin(), result.end(), line) == result.end()) result.push_back(line);
    }
    return result;
}

}  // namespace punctual::gltf_detail
