#pragma once
// Shared by the glTF loader tests (test_gltf_loader.cpp, test_gltf_malformed.cpp): a temporary
// directory per test and helpers that build and write glTF, binary and GLB files.
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "base64.h"

namespace punctual::unit_testing {

// glTF accessor component types.
constexpr int kFloat = 5126;
constexpr int kUnsignedShort = 5123;

// A fresh directory per test, named after the running test, removed afterwards.
class TempDir {
public:
    TempDir();
    ~TempDir();
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    const std::filesystem::path& path() const { return path_; }

private:
    std::filesystem::path path_;
};

void writeFile(const std::filesystem::path& path, const void* data, size_t size);
void writeFile(const std::filesystem::path& path, const std::string& text);
void writeFile(const std::filesystem::path& path, const std::vector<unsigned char>& bytes);

// Standard base64 with '=' padding, for data: URIs (tests/support/base64.h).
using testing::base64;

// A buffer view into buffer 0.
nlohmann::json bufferViewJson(size_t byteOffset, size_t byteLength);
// An accessor without a byteOffset (the glTF default, 0).
nlohmann::json accessorJson(int bufferView, int componentType, size_t count, const char* type);

// A GLB file holding `doc`, its buffer 0 being the BIN chunk `bin`, followed by `moreBuffers`
// (any "buffers" in `doc` are replaced).
std::vector<unsigned char> glbFile(const nlohmann::json& doc, const std::vector<unsigned char>& bin,
                                   const nlohmann::json& moreBuffers = nlohmann::json::array());

}  // namespace punctual::unit_testing
