#include "gltf_test_files.h"

#include <unistd.h>

#include <cstdint>
#include <fstream>

#include <gtest/gtest.h>

namespace punctual::unit_testing {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

void appendU32(std::vector<unsigned char>& out, uint32_t value) {
    for (int shift = 0; shift < 32; shift += 8) out.push_back(static_cast<unsigned char>(value >> shift));
}

}  // namespace

TempDir::TempDir() {
    const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() /
            ("punctual-gltf-" + std::to_string(::getpid()) + "-" + test->test_suite_name() + "-" + test->name());
    fs::remove_all(path_);
    fs::create_directories(path_);
}

TempDir::~TempDir() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
}

void writeFile(const fs::path& path, const void* data, size_t size) {
    std::ofstream out(path, std::ios::binary);
    out.write(static_cast<const char*>(data), static_cast<std::streamsize>(size));
}
void writeFile(const fs::path& path, const std::string& text) { writeFile(path, text.data(), text.size()); }
void writeFile(const fs::path& path, const std::vector<unsigned char>& bytes) {
    writeFile(path, bytes.data(), bytes.size());
}

json bufferViewJson(size_t byteOffset, size_t byteLength) {
    return {{"buffer", 0}, {"byteOffset", byteOffset}, {"byteLength", byteLength}};
}

json accessorJson(int bufferView, int componentType, size_t count, const char* type) {
    return {{"bufferView", bufferView}, {"componentType", componentType}, {"count", count}, {"type", type}};
}

std::vector<unsigned char> glbFile(const json& doc, const std::vector<unsigned char>& bin, const json& moreBuffers) {
    json out = doc;
    out["buffers"] = json::array({json{{"byteLength", bin.size()}}});
    for (const json& buffer : moreBuffers) out["buffers"].push_back(buffer);
    std::string text = out.dump();
    while (text.size() % 4 != 0) text += ' ';
    std::vector<unsigned char> payload = bin;
    while (payload.size() % 4 != 0) payload.push_back(0);
    std::vector<unsigned char> glb;
    appendU32(glb, 0x46546C67);  // "glTF"
    appendU32(glb, 2);
    appendU32(glb, uint32_t(12 + 8 + text.size() + 8 + payload.size()));
    appendU32(glb, uint32_t(text.size()));
    appendU32(glb, 0x4E4F534A);  // "JSON"
    glb.insert(glb.end(), text.begin(), text.end());
    appendU32(glb, uint32_t(payload.size()));
    appendU32(glb, 0x004E4942);  // "BIN\0"
    glb.insert(glb.end(), payload.begin(), payload.end());
    return glb;
}

}  // namespace punctual::unit_testing
