// Fuzz target: the glTF loader on JSON documents built from the input's bytes, structure first.
//
// fuzz_gltf mutates bytes, so most of its inputs die in the JSON parser, and it never reached the
// 15,000-level nesting that crashed tinygltf (issue 30). Here the bytes are a program of edits to
// a valid document (a textured quad under a camera, a spot, a point and the sun): each edit picks
// a place in the document (a member of one of its objects, at any depth) and puts there one of the
// values that break parsers: arrays and objects nested up to 20,000 deep, numbers at and past the
// limits of double and float (written as text, so 1e400 and 2^64 reach the parser as such), long
// strings, escapes, and values of the wrong type. The document is then loaded as fuzz_gltf loads
// its files, and the same contract holds: a scene or a punctual::Error, nothing else.
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/log.h"
#include "fuzz_target.h"
#include "lights/light_setup.h"
#include "lights/shadow_setup.h"
#include "scene/gltf_loader.h"

namespace {

using nlohmann::json;

std::string gFolder;
std::string gInputPath;

// The input read as a stream of choices; past its end every choice is 0.
class Choices {
public:
    Choices(const uint8_t* data, size_t size) : data_(data), size_(size) {}
    uint32_t next(uint32_t count) {
        uint32_t value = 0;
        for (int i = 0; i < 2; ++i) value = (value << 8) | (offset_ < size_ ? data_[offset_++] : 0u);
        return count == 0 ? 0 : value % count;
    }
    bool done() const { return offset_ >= size_; }

private:
    const uint8_t* data_;
    size_t size_;
    size_t offset_ = 0;
};

// A valid glTF: a quad with a textured material, a camera and three lights.
json baseDocument() {
    // 4 positions, 4 normals, 4 UVs, 6 uint16 indices: 48 + 48 + 32 + 12 bytes of zeros and ones.
    return json::parse(R"({
      "asset": {"version": "2.0"},
      "extensionsUsed": ["KHR_lights_punctual", "KHR_texture_transform"],
      "extensions": {"KHR_lights_punctual": {"lights": [
        {"type": "spot", "intensity": 50, "range": 20, "spot": {"innerConeAngle": 0.2, "outerConeAngle": 0.6}},
        {"type": "point", "intensity": 20, "color": [1, 0.5, 0.2]},
        {"type": "directional", "intensity": 2}]}},
      "scene": 0, "scenes": [{"nodes": [0, 1, 2, 3, 4]}],
      "nodes": [{"mesh": 0, "scale": [4, 1, 4]},
                {"camera": 0, "translation": [0, 3, 0], "rotation": [-0.70710678, 0, 0, 0.70710678]},
                {"translation": [0, 2, 0], "rotation": [-0.70710678, 0, 0, 0.70710678],
                 "extensions": {"KHR_lights_punctual": {"light": 0}}},
                {"translation": [1, 1, 0], "extensions": {"KHR_lights_punctual": {"light": 1}}},
                {"rotation": [-0.5, 0, 0, 0.8660254], "extensions": {"KHR_lights_punctual": {"light": 2}}}],
      "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1, "zfar": 50}}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3,
                                  "material": 0}]}],
      "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.8, 1], "metallicFactor": 0,
                     "baseColorTexture": {"index": 0, "extensions": {"KHR_texture_transform": {"scale": [2, 2]}}}},
                     "alphaMode": "MASK", "alphaCutoff": 0.5, "extras": {"note": "fuzz"}}],
      "textures": [{"source": 0, "sampler": 0}], "samplers": [{"wrapS": 33071}],
      "images": [{"uri": "data:image/png;base64,iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAADUlEQVR42mP8z8DwHwAFBQIAX8jx0gAAAABJRU5ErkJggg=="}],
      "buffers": [{"byteLength": 140, "uri": "data:application/octet-stream;base64,AACAvwAAAAAAAIC/AACAPwAAAAAAAIC/AACAPwAAAAAAAIA/AACAvwAAAAAAAIA/AAAAAAAAgD8AAAAAAAAAAAAAgD8AAAAAAAAAAAAAgD8AAAAAAAAAAAAAgD8AAAAAAAAAAAAAAAAAAIA/AAAAAAAAgD8AAIA/AAAAAAAAgD8AAAIAAQAAAAMAAgA="}],
      "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 48},
                      {"buffer": 0, "byteOffset": 96, "byteLength": 32}, {"buffer": 0, "byteOffset": 128, "byteLength": 12}],
      "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-1, 0, -1], "max": [1, 0, 1]},
                    {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
                    {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"},
                    {"bufferView": 3, "componentType": 5123, "count": 6, "type": "SCALAR"}]
    })");
}

// Numbers as the parser sees them: past double's range, at float's edges, integers past 2^64.
const char* const kNumbers[] = {"1e400", "-1e400", "1e308", "1.7976931348623157e308", "4.9e-324", "1e-400",
                                "3.4028235e38", "3.5e38", "1.17549435e-38", "18446744073709551616",
                                "-9223372036854775809", "9007199254740993", "-0", "0.0", "1", "-1", "2147483648",
                                "4294967296", "1e37", "1e-8", "1e-12", "0.5", "65535", "65536"};

// Raw JSON text for one value: a nesting, a number, a string or a value of some type.
std::string rawValue(Choices& choices) {
    switch (choices.next(6)) {
        case 0: {  // nested arrays or objects, up to 20,000 deep (past the 128 limit, and far past it)
            const uint32_t depth = choices.next(4) == 0 ? 20000 : choices.next(300);
            const bool objects = choices.next(2) == 1;
            std::string open, close;
            for (uint32_t i = 0; i < depth; ++i) {
                open += objects ? "{\"a\":" : "[";
                close += objects ? "}" : "]";
            }
            return open + (objects ? "null" : "0") + close;
        }
        case 1: return kNumbers[choices.next(sizeof kNumbers / sizeof *kNumbers)];
        case 2: {  // a long string, perhaps with escapes that decode to odd bytes
            const uint32_t length = choices.next(4) == 0 ? 1u << 20 : choices.next(4096);
            const char* unit = choices.next(3) == 0 ? "\\u0000" : choices.next(2) ? "\\\"" : "x";
            std::string text = "\"";
            for (uint32_t i = 0; i < length; ++i) text += unit;
            return text + "\"";
        }
        case 3: return choices.next(2) ? "[]" : "{}";
        case 4: return choices.next(3) == 0 ? "null" : choices.next(2) ? "true" : "false";
        default: return "[" + std::string(kNumbers[choices.next(sizeof kNumbers / sizeof *kNumbers)]) + ", 1, 2]";
    }
}

// The place of one edit: a member name in some object reached by walking down from the root.
json* pickObject(json& root, Choices& choices) {
    json* at = &root;
    for (uint32_t steps = choices.next(6); steps > 0; --steps) {
        if (at->is_object() && !at->empty()) {
            auto it = at->begin();
            std::advance(it, choices.next(uint32_t(at->size())));
            if (!it->is_structured()) break;
            at = &*it;
        } else if (at->is_array() && !at->empty()) {
            json& element = (*at)[choices.next(uint32_t(at->size()))];
            if (!element.is_structured()) break;
            at = &element;
        } else {
            break;
        }
    }
    return at->is_object() ? at : &root;
}

// The document text: the base with up to 8 edits. Each edit stores a placeholder string, replaced
// by its raw text after dumping (nlohmann cannot hold 1e400 or 20,000 levels to dump them).
std::string buildDocument(Choices& choices) {
    json doc = baseDocument();
    std::vector<std::string> raws;
    for (uint32_t edits = 1 + choices.next(8); edits > 0 && !choices.done(); --edits) {
        json* object = pickObject(doc, choices);
        std::string key;
        if (!object->empty() && choices.next(4) != 0) {
            auto it = object->begin();
            std::advance(it, choices.next(uint32_t(object->size())));
            key = it.key();
        } else {
            key = choices.next(2) ? "extras" : "weights";
        }
        (*object)[key] = "@@raw" + std::to_string(raws.size()) + "@@";
        raws.push_back(rawValue(choices));
    }
    std::string text = doc.dump();
    for (size_t i = raws.size(); i-- > 0;) {
        const std::string placeholder = "\"@@raw" + std::to_string(i) + "@@\"";
        const size_t at = text.find(placeholder);
        if (at != std::string::npos) text.replace(at, placeholder.size(), raws[i]);
    }
    return text;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int* /*argc*/, char*** /*argv*/) {
    gFolder = punctual::fuzzing::makeInputFolder("gltf-json");
    gInputPath = gFolder + "/input.gltf";
    punctual::log::setSink([](const std::string&, const std::string&) {});
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    Choices choices(data, size);
    const std::string text = buildDocument(choices);
    std::FILE* file = std::fopen(gInputPath.c_str(), "wb");
    if (file == nullptr || std::fwrite(text.data(), 1, text.size(), file) != text.size() || std::fclose(file) != 0) {
        std::perror("fuzz_gltf_json: cannot write the input file");
        std::abort();
    }
    try {
        const punctual::Scene scene = punctual::loadGltf(gInputPath);
        const glm::mat4 projection = scene.camera.projection(16.0f / 9.0f);
        punctual::FrameLights lights = punctual::setupFrameLights(scene, scene.camera.view, projection);
        (void)punctual::planShadows(scene, lights, scene.camera.position(), punctual::ShadowSettings{});
    } catch (const punctual::Error&) {
        // A clean, named error: what bad input must give.
    }
    return 0;
}
