#pragma once
// Plain bytes as 64-bit words, eight to a word (the last one zero-padded), after their count, so
// that "ab" + "c" and "a" + "bc" differ: how the object cache's keys (vk/object_cache.cpp) and the
// shadow cache's signatures (lights/shadow_view_signature.cpp) take in raw memory.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>

namespace punctual {

template <typename AddWord>
void addBytesAsWords(const void* data, size_t size, AddWord&& add) {
    add(uint64_t(size));
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (size_t offset = 0; offset < size; offset += 8) {
        uint64_t word = 0;
        std::memcpy(&word, bytes + offset, std::min<size_t>(8, size - offset));
        add(word);
    }
}

}  // namespace punctual
