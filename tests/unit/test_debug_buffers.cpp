// The forward shader's debug buffers decoded by the layouts gpu_types.h declares: buffers written
// here word by word as the shader writes them, then decoded (metrics/debug_buffers.h).
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "gpu_types.h"
#include "metrics/debug_buffers.h"

namespace punctual {
namespace {

void putWord(std::vector<uint8_t>& bytes, size_t word, uint32_t value) {
    std::memcpy(bytes.data() + word * 4, &value, 4);
}

uint32_t floatBits(float value) {
    uint32_t bits = 0;
    std::memcpy(&bits, &value, 4);
    return bits;
}

TEST(DebugBuffers, LightStatisticsDecodeEachBlockAndWord) {
    // A 2 x 1 frame: pixel 0 covered, pixel 1 background (all zero, as cleared).
    const uint32_t width = 2, height = 1, pixels = 2;
    // Three list cells of two mask words each (up to 64 lights).
    const uint32_t listCells = 3, gridWords = 2;
    std::vector<uint8_t> bytes(lightStatsBytes(width, height, listCells, gridWords), 0);
    EXPECT_EQ(bytes.size(), (2u * 3u * 4u + 3u * 2u) * 4u);  // 2 pixels, 3 blocks of 4 words; 3 cells of 2 words
    const auto word = [&](uint32_t block, uint32_t pixel, uint32_t w) { return gpu::lightStatsWord(block, pixels, pixel, w); };
    putWord(bytes, word(PUNCTUAL_LIGHT_STATS_OPAQUE, 0, PUNCTUAL_LIGHT_STATS_WORK), gpu::packPixelWork(3, 27));
    putWord(bytes, word(PUNCTUAL_LIGHT_STATS_OPAQUE, 0, PUNCTUAL_LIGHT_STATS_REACHING), 5u | PUNCTUAL_LIGHT_STATS_COVERED);
    putWord(bytes, word(PUNCTUAL_LIGHT_STATS_OPAQUE, 0, PUNCTUAL_LIGHT_STATS_LUMINANCE), floatBits(0.25f));
    putWord(bytes, word(PUNCTUAL_LIGHT_STATS_OPAQUE, 0, PUNCTUAL_LIGHT_STATS_BRUTE_LUMINANCE), floatBits(0.5f));
    putWord(bytes, word(PUNCTUAL_LIGHT_STATS_TRANSPARENT, 1, PUNCTUAL_LIGHT_STATS_TESTED), 40);
    putWord(bytes, word(PUNCTUAL_LIGHT_STATS_TRANSPARENT, 1, PUNCTUAL_LIGHT_STATS_REACHING), 9);
    putWord(bytes, word(PUNCTUAL_LIGHT_STATS_TRANSPARENT, 1, PUNCTUAL_LIGHT_STATS_FRAGMENTS), 2);
    putWord(bytes, word(PUNCTUAL_LIGHT_STATS_TRANSPARENT, 1, PUNCTUAL_LIGHT_STATS_MISSING), 1);
    putWord(bytes, word(PUNCTUAL_LIGHT_STATS_LIST, 0, PUNCTUAL_LIGHT_STATS_LIST_CELL), 2);
    putWord(bytes, word(PUNCTUAL_LIGHT_STATS_LIST, 0, PUNCTUAL_LIGHT_STATS_LIST_TESTED), 12);
    // Cell 2 reached by lights 0, 1 and 40 (word 1, bit 8); cell 0 by light 63.
    putWord(bytes, gpu::lightStatsCellWord(pixels, gridWords, 2, 0), 0x3u);
    putWord(bytes, gpu::lightStatsCellWord(pixels, gridWords, 2, 1), 0x100u);
    putWord(bytes, gpu::lightStatsCellWord(pixels, gridWords, 0, 1), 0x80000000u);

    const LightStatsImage stats = decodeLightStats(bytes, width, height, listCells, gridWords);
    ASSERT_EQ(stats.tested.size(), 2u);
    EXPECT_EQ(stats.covered, (std::vector<uint8_t>{1, 0}));
    EXPECT_EQ(stats.tested, (std::vector<uint32_t>{12, 0}));
    EXPECT_EQ(stats.shadowLookups, (std::vector<uint32_t>{3, 0}));
    EXPECT_EQ(stats.shadowTaps, (std::vector<uint32_t>{27, 0}));
    EXPECT_EQ(stats.affecting, (std::vector<uint32_t>{5, 0}));  // the covered bit is not a light
    EXPECT_EQ(stats.methodLuminance[0], 0.25f);
    EXPECT_EQ(stats.bruteLuminance[0], 0.5f);
    EXPECT_EQ(stats.transparentTested, (std::vector<uint32_t>{0, 40}));
    EXPECT_EQ(stats.transparentAffecting, (std::vector<uint32_t>{0, 9}));
    EXPECT_EQ(stats.transparentFragments, (std::vector<uint32_t>{0, 2}));
    EXPECT_EQ(stats.transparentMissingLight, (std::vector<uint32_t>{0, 1}));
    EXPECT_EQ(stats.listCells, (std::vector<uint32_t>{2, 0}));
    EXPECT_EQ(stats.cellReachingLights, (std::vector<uint32_t>{1, 0, 3}));
}

TEST(DebugBuffers, ShadowFactorsDecodeSurfacesSlotsAndTheSun) {
    // A 2 x 1 frame with two shadowed lights and a cascaded sun: pixel 0 covered, pixel 1 not.
    const uint32_t width = 2, height = 1, pixels = 2;
    std::vector<uint8_t> bytes(shadowFactorBytes(width, height), 0);
    const float position[3] = {1.0f, 2.0f, 3.0f};
    const float normal[3] = {0.0f, 1.0f, 0.0f};
    std::memcpy(bytes.data(), position, sizeof position);  // surface words 0-2
    putWord(bytes, 3, 1);                                   // covered
    std::memcpy(bytes.data() + 4 * 4, normal, sizeof normal);  // words 4-6
    putWord(bytes, 7, 3);                                   // the sun's cascade 2, plus one
    uint8_t* factors = bytes.data() + size_t(pixels) * PUNCTUAL_SHADOW_DEBUG_SURFACE_WORDS * 4;
    factors[0] = 10;    // slot 0
    factors[1] = 254;   // slot 1: lit
    factors[PUNCTUAL_SUN_SHADOW_SLOT] = 127;

    const ShadowFactorImage image = decodeShadowFactors(bytes, width, height, 2, true);
    EXPECT_EQ(image.slots, 2u);
    EXPECT_EQ(image.positions[0], glm::vec3(1.0f, 2.0f, 3.0f));
    EXPECT_EQ(image.normals[0], glm::vec3(0.0f, 1.0f, 0.0f));
    EXPECT_EQ(image.covered, (std::vector<uint8_t>{1, 0}));
    EXPECT_EQ(image.factors, (std::vector<uint8_t>{10, 254, 255, 255}));  // uncovered: not reached
    EXPECT_EQ(image.sunFactors, (std::vector<uint8_t>{127, 255}));
    EXPECT_EQ(image.sunCascades, (std::vector<uint8_t>{3, 0}));
    // Without cascades the sun's vectors stay empty.
    EXPECT_TRUE(decodeShadowFactors(bytes, width, height, 2, false).sunFactors.empty());
}

}  // namespace
}  // namespace punctual
