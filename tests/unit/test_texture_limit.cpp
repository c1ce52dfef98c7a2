// How large a base-colour texture may stay (the frame's rule), and the downscaling: sizes,
// linear-light filtering, alpha weighting, determinism.
#include <gtest/gtest.h>

#include "scene/texture_limit.h"

namespace punctual {
namespace {

TEST(TextureLimit, FrameLimitIsThePowerOfTwoAboveTheLongerSide) {
    EXPECT_EQ(textureLimitForFrame(160, 120).maxSide, 256u);
    EXPECT_EQ(textureLimitForFrame(1280, 720).maxSide, 2048u);
    EXPECT_EQ(textureLimitForFrame(1024, 1024).maxSide, 2048u);  // strictly above: 1x to 2x headroom
    EXPECT_EQ(textureLimitForFrame(1, 1).maxSide, 2u);
    EXPECT_EQ(textureLimitForFrame(90, 3000).maxSide, 4096u);
    EXPECT_EQ(textureLimitForFrame(160, 120).reason, "enough for a 160x120 frame");
}

TEST(TextureLimit, FittedSizesKeepTheAspectRatio) {
    const auto expectSize = [](TextureSize size, uint32_t width, uint32_t height) {
        EXPECT_EQ(size.width, width);
        EXPECT_EQ(size.height, height);
    };
    expectSize(fittedTextureSize(16384, 16384, 256), 256, 256);
    expectSize(fittedTextureSize(300, 100, 64), 64, 21);
    expectSize(fittedTextureSize(100, 300, 64), 21, 64);
    expectSize(fittedTextureSize(16385, 2, 256), 256, 1);  // never 0
    expectSize(fittedTextureSize(200, 100, 200), 200, 100);  // fits: unchanged
    expectSize(fittedTextureSize(5000, 4000, 0), 5000, 4000);  // no limit
}

TEST(TextureLimit, DownscalingAveragesInLinearLightAndWeightsByAlpha) {
    // Black and white average to linear 0.5, which sRGB encodes as 188 (not 128).
    const uint8_t blackWhite[8] = {0, 0, 0, 255, 255, 255, 255, 255};
    const std::vector<uint8_t> grey = resizedRgba8Srgb(blackWhite, {2, 1}, {1, 1});
    ASSERT_EQ(grey.size(), 4u);
    EXPECT_NEAR(grey[0], 188, 1);
    EXPECT_EQ(grey[3], 255);
    // A transparent red texel next to an opaque blue one: half-transparent blue, no red fringe.
    const uint8_t redBlue[8] = {255, 0, 0, 0, 0, 0, 255, 255};
    const std::vector<uint8_t> blue = resizedRgba8Srgb(redBlue, {2, 1}, {1, 1});
    EXPECT_LE(blue[0], 1);
    EXPECT_GE(blue[2], 254);
    EXPECT_NEAR(blue[3], 128, 1);
}

TEST(TextureLimit, FittedTextureIsDeterministicAndFlatColoursStayFlat) {
    Texture texture;
    texture.name = "t";
    texture.width = 999;
    texture.height = 333;
    texture.rgba.resize(size_t(999) * 333 * 4);
    for (size_t i = 0; i < texture.rgba.size(); ++i) texture.rgba[i] = uint8_t((i * 7919) % 251);
    const Texture a = fittedTexture(texture, 100);
    const Texture b = fittedTexture(texture, 100);
    EXPECT_EQ(a.width, 100u);
    EXPECT_EQ(a.height, 33u);
    EXPECT_EQ(a.rgba, b.rgba);
    EXPECT_EQ(a.name, "t");
    EXPECT_EQ(fittedTexture(texture, 1000).rgba, texture.rgba);  // fits: a plain copy

    texture.rgba.assign(texture.rgba.size(), 77);
    EXPECT_EQ(fittedTexture(texture, 64).rgba, std::vector<uint8_t>(size_t(64) * 21 * 4, 77));
}

TEST(TextureLimit, WarningNamesTheTextureAndBothSizes) {
    EXPECT_EQ(downscaleWarning("base colour image 0 'big.png'", {16384, 8192}, {256, 128}, "enough for a 160x120 frame"),
              "base colour image 0 'big.png' is 16384x8192 texels; downscaled to 256x128 (enough for a 160x120 frame)");
}

}  // namespace
}  // namespace punctual
