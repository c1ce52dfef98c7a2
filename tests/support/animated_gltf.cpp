#include "animated_gltf.h"

#include "base64.h"

#include <cstring>
#include <fstream>

namespace punctual::testing {
namespace {

using nlohmann::json;

constexpr int kFloatComponents = 5126;
constexpr int kUnsignedShortComponents = 5123;

const char* typeName(size_t components) {
    switch (components) {
        case 1: return "SCALAR";
        case 3: return "VEC3";
        case 4: return "VEC4";
        default: return "?";
    }
}

}  // namespace

AnimatedGltf::AnimatedGltf() {
    doc = {{"asset", {{"version", "2.0"}}},
           {"scene", 0},
           {"scenes", {{{"nodes", {0, 1, 2}}}}},
           {"extensionsUsed", {"KHR_lights_punctual"}},
           {"extensions", {{"KHR_lights_punctual", {{"lights", {{{"type", "spot"}, {"intensity", 40.0}, {"range", 10.0},
                                                                 {"spot", {{"outerConeAngle", 0.6}}}}}}}}}},
           {"nodes", {{{"mesh", 0}, {"name", "square"}},
                      {{"camera", 0}, {"translation", {0.0, 0.0, 3.0}}},
                      {{"translation", {0.0, 0.0, 2.0}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}}}},
           {"cameras", {{{"type", "perspective"}, {"perspective", {{"yfov", 0.9}, {"znear", 0.1}, {"zfar", 20.0}}}}}},
           {"materials", {{{"pbrMetallicRoughness", {{"metallicFactor", 0.0}}}, {"doubleSided", true}}}},
           {"accessors", json::array()},
           {"bufferViews", json::array()}};
    const int positions = addAccessor({-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0}, 3);
    const int normals = addAccessor({0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, 3);
    const int deltas = addAccessor({0, 0, 2, 0, 0, 2, 0, 0, 2, 0, 0, 2}, 3);
    doc["accessors"][size_t(positions)]["min"] = {-1.0, -1.0, 0.0};
    doc["accessors"][size_t(positions)]["max"] = {1.0, 1.0, 0.0};
    const uint16_t indices[6] = {0, 1, 2, 0, 2, 3};
    const size_t offset = bin.size();
    bin.resize(offset + sizeof indices);
    std::memcpy(bin.data() + offset, indices, sizeof indices);
    doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", sizeof indices}});
    doc["accessors"].push_back({{"bufferView", doc["bufferViews"].size() - 1}, {"componentType", kUnsignedShortComponents},
                                {"count", 6}, {"type", "SCALAR"}});
    const size_t indexAccessor = doc["accessors"].size() - 1;
    doc["meshes"] = {{{"primitives", {{{"attributes", {{"POSITION", positions}, {"NORMAL", normals}}},
                                       {"indices", indexAccessor}, {"material", 0},
                                       {"targets", {{{"POSITION", deltas}}}}}}}}};
}

int AnimatedGltf::addAccessor(const std::vector<float>& values, size_t components) {
    while (bin.size() % 4 != 0) bin.push_back(0);
    const size_t offset = bin.size();
    bin.resize(offset + values.size() * sizeof(float));
    std::memcpy(bin.data() + offset, values.data(), values.size() * sizeof(float));
    doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", values.size() * sizeof(float)}});
    json accessor = {{"bufferView", doc["bufferViews"].size() - 1}, {"componentType", kFloatComponents},
                     {"count", values.size() / components}, {"type", typeName(components)}};
    if (components == 1 && !values.empty()) {  // animation inputs need their bounds
        accessor["min"] = {values.front()};
        accessor["max"] = {values.back()};
    }
    doc["accessors"].push_back(accessor);
    return int(doc["accessors"].size() - 1);
}

void AnimatedGltf::addChannel(size_t animation, int node, const std::string& path, const std::string& interpolation,
                              const std::vector<float>& times, const std::vector<float>& values) {
    if (!doc.contains("animations")) doc["animations"] = json::array();
    while (doc["animations"].size() <= animation) doc["animations"].push_back({{"channels", json::array()}, {"samplers", json::array()}});
    json& a = doc["animations"][animation];
    const size_t components = path == "weights" ? 1 : path == "rotation" ? 4 : 3;
    const int input = addAccessor(times, 1);
    const int output = addAccessor(values, components);
    a["samplers"].push_back({{"input", input}, {"output", output}, {"interpolation", interpolation}});
    a["channels"].push_back({{"sampler", a["samplers"].size() - 1}, {"target", {{"node", node}, {"path", path}}}});
}

std::string AnimatedGltf::text() const {
    json out = doc;
    out["buffers"] = {{{"byteLength", bin.size()}, {"uri", "data:application/octet-stream;base64," + base64(bin)}}};
    return out.dump();
}

std::string AnimatedGltf::write(const std::string& path) const {
    std::ofstream(path) << text();
    return path;
}

}  // namespace punctual::testing
