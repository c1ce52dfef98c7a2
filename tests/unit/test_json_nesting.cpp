// Known answers for the JSON nesting bound checked before tinygltf sees a document.
#include <gtest/gtest.h>

#include <string>

#include "scene/json_nesting.h"

namespace punctual {
namespace {

std::string problem(const std::string& text, size_t depth) {
    return jsonNestingProblem(reinterpret_cast<const unsigned char*>(text.data()), text.size(), depth);
}

TEST(JsonNesting, CountsArraysAndObjectsButNotBracketsInStrings) {
    EXPECT_EQ(problem("{\"a\": [[1]]}", 3), "");
    EXPECT_EQ(problem("{\"a\": [[[1]]]}", 3), "JSON nests more than 3 levels deep (at byte 8); punctual reads at most 3");
    // Siblings do not add up: depth is how many are open at once.
    EXPECT_EQ(problem("[[],[],[],[],[]]", 2), "");
    // Brackets inside strings, escaped quotes and escaped backslashes do not open anything.
    EXPECT_EQ(problem("{\"a\": \"[[[[{{{{\"}", 1), "");
    EXPECT_EQ(problem("{\"a\": \"\\\"[[[[\"}", 1), "");
    EXPECT_EQ(problem("{\"a\": \"\\\\\", \"b\": [[1]]}", 2), "JSON nests more than 2 levels deep (at byte 18); punctual reads at most 2");
    // Unbalanced closers do not hide later openers (the parser reports the syntax error).
    EXPECT_EQ(problem("]]]]][[[", 2), "JSON nests more than 2 levels deep (at byte 7); punctual reads at most 2");
    EXPECT_EQ(problem("", 0), "");
}

TEST(JsonNesting, TheDefaultBoundCoversWhatGltfItselfNests) {
    EXPECT_EQ(kMaxJsonNesting, 128u);
    const std::string deep = std::string(128, '[') + std::string(128, ']');
    EXPECT_EQ(problem(deep, kMaxJsonNesting), "");
    EXPECT_NE(problem("[" + deep + "]", kMaxJsonNesting), "");
}

}  // namespace
}  // namespace punctual
