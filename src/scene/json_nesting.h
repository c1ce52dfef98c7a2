#pragma once
// A bound on how deeply a JSON text nests, checked before any JSON library sees it.
//
// nlohmann::json parses with an explicit stack, but tinygltf converts the parsed document into its
// own values by recursion, one call frame (a few hundred bytes, several kilobytes under
// AddressSanitizer) per level: 15,000 nested arrays in a 64 KB file overflow an 8 MiB stack and
// kill the process with SIGSEGV, which no try/catch can turn into a message. This scan is
// iterative, so it bounds the depth of any input in O(length) time and O(1) memory.
#include <cstddef>
#include <string>

namespace punctual {

// glTF itself nests 7 levels (root, materials, material, pbrMetallicRoughness, baseColorTexture,
// extensions, one extension's object); KHR_texture_transform and friends add 2 or 3. The rest of
// the budget is for application `extras`. 128 levels is 18x what the spec's own objects need,
// and at ~4 KiB a level (the sanitizer build's frames) stays under 1 MiB of stack.
constexpr size_t kMaxJsonNesting = 128;

// Empty when no array or object in `text` (bytes [0, length)) nests deeper than `maxDepth`;
// otherwise the problem as one phrase, naming the byte offset where the limit is passed. Brackets
// inside strings (with their escapes) do not count. The text need not be valid JSON: syntax is
// the parser's business, this only guarantees the parser's recursion a bound.
std::string jsonNestingProblem(const unsigned char* text, size_t length, size_t maxDepth = kMaxJsonNesting);

}  // namespace punctual
