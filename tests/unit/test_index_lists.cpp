// Known answers for the index lists' layout (culling.h, "Index lists") and their reading back as
// masks (metrics/index_lists.h), worked out by hand.
#include <gtest/gtest.h>

#include <vector>

#include "core/check.h"
#include "culling.h"
#include "metrics/index_lists.h"

namespace punctual {
namespace {

TEST(IndexLists, AListIsItsCountAndItsEntriesTwoAWord) {
    // n lights and the count: n + 1 entries of 16 bits, rounded up to whole words.
    EXPECT_EQ(gpu::lightListWords(1), 1u);  // count, light
    EXPECT_EQ(gpu::lightListWords(2), 2u);  // count, light | light, (empty)
    EXPECT_EQ(gpu::lightListWords(3), 2u);
    EXPECT_EQ(gpu::lightListWords(80), 41u);
    // Entry e: the low half of word e / 2 when e is even, the high half when odd.
    const uint32_t word = gpu::lightListPair(3, 700);
    EXPECT_EQ(word, 3u | (700u << 16));
    EXPECT_EQ(gpu::lightListEntry(word, 0), 3u);
    EXPECT_EQ(gpu::lightListEntry(word, 1), 700u);
    EXPECT_EQ(gpu::lightListEntry(word, 2), 3u);
    EXPECT_EQ(gpu::lightListEntry(0xFFFF0000u | 16383u, 4), 16383u);
}

TEST(IndexLists, ReadBackAsTheMasksTheyStandFor) {
    // Three cells of 2 words (64 lights): cell 0 holds 1, 33 and 40 (three lights: words
    // {3, 1}, {33, 40}), cell 1 none, cell 2 the light 63 alone ({1, 63}). The lists start at
    // words 2 and 0 of the array: a list's place in it is the atomics', not the cells' order.
    const std::vector<uint32_t> headers = {2u, PUNCTUAL_LIGHT_LIST_NONE, 0u};
    const std::vector<uint32_t> words = {gpu::lightListPair(1, 63), 0xDEADBEEFu, gpu::lightListPair(3, 1),
                                         gpu::lightListPair(33, 40)};
    const std::vector<uint32_t> masks = masksFromIndexLists(headers, words, 2, 64);
    EXPECT_EQ(masks, (std::vector<uint32_t>{1u << 1, (1u << 1) | (1u << 8), 0u, 0u, 0u, 1u << 31}));
    // An even count: its last light alone in its word's low half.
    const std::vector<uint32_t> two = {gpu::lightListPair(2, 5), 9u};
    EXPECT_EQ(masksFromIndexLists(std::vector<uint32_t>{0u}, two, 1, 10), (std::vector<uint32_t>{(1u << 5) | (1u << 9)}));
}

TEST(IndexLists, AMalformedListIsAnInternalErrorNamingItsCell) {
    const std::vector<uint32_t> fits = {gpu::lightListPair(1, 4)};
    auto problem = [](const std::vector<uint32_t>& headers, const std::vector<uint32_t>& words, uint32_t lights) {
        try {
            masksFromIndexLists(headers, words, 1, lights);
        } catch (const InternalError& error) {
            return std::string(error.what());
        }
        return std::string("(no error)");
    };
    EXPECT_EQ(problem({0u}, fits, 8), "(no error)");
    EXPECT_NE(problem({PUNCTUAL_LIGHT_LIST_NONE, PUNCTUAL_LIGHT_LIST_OVERFLOW}, fits, 8).find("cell 1 did not fit"),
              std::string::npos);
    EXPECT_NE(problem({1u}, fits, 8).find("cell 0 starts past"), std::string::npos);
    // Two lights claimed, one word present.
    EXPECT_NE(problem({0u}, {gpu::lightListPair(2, 4)}, 8).find("runs past"), std::string::npos);
    // A light past the frame's, and lights out of order.
    EXPECT_NE(problem({0u}, fits, 4).find("out of range or out of order"), std::string::npos);
    EXPECT_NE(problem({0u}, {gpu::lightListPair(2, 5), 3u}, 8).find("out of order"), std::string::npos);
}

}  // namespace
}  // namespace punctual
