#pragma once
// Standard base64 (RFC 4648, with '=' padding), for the data: URIs of the glTF files the tests
// write (unit and GPU tests alike).
#include <span>
#include <string>
#include <vector>

namespace punctual::testing {

std::string base64(std::span<const unsigned char> bytes);
inline std::string base64(const std::vector<unsigned char>& bytes) { return base64(std::span<const unsigned char>(bytes)); }
inline std::string base64(const std::string& bytes) {
    return base64(std::span<const unsigned char>(reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size()));
}

}  // namespace punctual::testing
