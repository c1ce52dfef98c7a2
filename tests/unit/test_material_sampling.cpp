// Known answers for what a material reads before shading: KHR_texture_transform and the alpha
// test (shaders/shared/materials.h), the mip chain (scene/texture_mips.h) and Vulkan's texel
// filtering as the reference does it (reference/texture_sampler.h), all computed by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "materials.h"
#include "reference/material_sampling.h"
#include "reference/texture_sampler.h"
#include "scene/texture_mips.h"

namespace punctual {
namespace {

using reference::sampleTexture;
using reference::textureLod;

constexpr float kHalfPi = 1.57079632679f;

// ---- KHR_texture_transform ------------------------------------------------------------------

TEST(TextureTransform, IdentityKeepsCoordinatesExactly) {
    const glm::vec3 u = gpu::textureTransformRowU(glm::vec2(0.0f), 0.0f, glm::vec2(1.0f));
    const glm::vec3 v = gpu::textureTransformRowV(glm::vec2(0.0f), 0.0f, glm::vec2(1.0f));
    const glm::vec2 uv(0.3125f, -7.75f);
    EXPECT_EQ(gpu::materialUv(glm::vec4(u, 0.0f), glm::vec4(v, 0.0f), uv, glm::vec2(9.0f)), uv);
}

TEST(TextureTransform, ScaleThenRotateThenOffset) {
    // The extension's example order T * R * S on uv = (1, 0) with scale (2, 3), rotation pi/2,
    // offset (0.5, 0.25): S gives (2, 0); R = [c s; -s c] = [0 1; -1 0] gives (0, -2); T adds the
    // offset: (0.5, -1.75).
    const glm::vec2 offset(0.5f, 0.25f), scale(2.0f, 3.0f);
    const glm::vec4 u(gpu::textureTransformRowU(offset, kHalfPi, scale), 0.0f);
    const glm::vec4 v(gpu::textureTransformRowV(offset, kHalfPi, scale), 0.0f);
    const glm::vec2 moved = gpu::materialUv(u, v, glm::vec2(1.0f, 0.0f), glm::vec2(0.0f));
    EXPECT_NEAR(moved.x, 0.5f, 1e-6f);
    EXPECT_NEAR(moved.y, -1.75f, 1e-6f);
    // And (0, 1): S gives (0, 3); R gives (3, 0); plus the offset: (3.5, 0.25).
    const glm::vec2 other = gpu::materialUv(u, v, glm::vec2(0.0f, 1.0f), glm::vec2(0.0f));
    EXPECT_NEAR(other.x, 3.5f, 1e-6f);
    EXPECT_NEAR(other.y, 0.25f, 1e-6f);
}

TEST(TextureTransform, RowUsWPicksTheCoordinateSet) {
    const glm::vec4 u(1.0f, 0.0f, 0.0f, 1.0f), v(0.0f, 1.0f, 0.0f, 0.0f);
    EXPECT_EQ(gpu::materialUv(u, v, glm::vec2(1.0f, 2.0f), glm::vec2(3.0f, 4.0f)), glm::vec2(3.0f, 4.0f));
    EXPECT_EQ(gpu::materialUv(glm::vec4(glm::vec3(u), 0.0f), v, glm::vec2(1.0f, 2.0f), glm::vec2(3.0f, 4.0f)),
              glm::vec2(1.0f, 2.0f));
}

TEST(AlphaMask, KeepsAlphaEqualToTheCutoff) {
    // glTF: "fully opaque if alpha >= alphaCutoff".
    EXPECT_TRUE(gpu::alphaMaskKeeps(0.5f, 0.5f));
    EXPECT_FALSE(gpu::alphaMaskKeeps(std::nextafter(0.5f, 0.0f), 0.5f));
    EXPECT_TRUE(gpu::alphaMaskKeeps(0.0f, 0.0f));  // cutoff 0 keeps everything
}

// ---- mip chains -----------------------------------------------------------------------------

TEST(Mipmaps, SizesFollowVulkansFloorRule) {
    EXPECT_EQ(fullMipCount(1, 1), 1u);
    EXPECT_EQ(fullMipCount(256, 256), 9u);
    EXPECT_EQ(fullMipCount(5, 3), 3u);  // 5x3, 2x1, 1x1
    EXPECT_EQ(mipSide(5, 1), 2u);
    EXPECT_EQ(mipSide(5, 2), 1u);
    EXPECT_EQ(mipSide(3, 7), 1u);
}

Texture solidTexture(uint32_t width, uint32_t height, glm::u8vec4 rgba) {
    Texture texture;
    texture.width = width;
    texture.height = height;
    texture.rgba.resize(size_t(width) * height * 4);
    for (size_t i = 0; i < texture.rgba.size(); ++i) texture.rgba[i] = rgba[int(i % 4)];
    return texture;
}

// Black and white texels in a checkerboard, opaque.
Texture checkerTexture(uint32_t side) {
    Texture texture;
    texture.width = side;
    texture.height = side;
    for (uint32_t y = 0; y < side; ++y)
        for (uint32_t x = 0; x < side; ++x) {
            const uint8_t c = (x + y) % 2 ? 255 : 0;
            texture.rgba.insert(texture.rgba.end(), {c, c, c, 255});
        }
    return texture;
}

TEST(Mipmaps, ChainAveragesInLinearLight) {
    Texture texture = checkerTexture(4);
    generateMipmaps(texture);
    ASSERT_EQ(texture.levelCount(), 3u);
    ASSERT_EQ(texture.mipLevels[0].width, 2u);
    ASSERT_EQ(texture.mipLevels[1].width, 1u);
    // Half black, half white averages to linear 0.5, which sRGB encodes as code 188
    // (1.055 * 0.5^(1/2.4) - 0.055 = 0.7354 -> 187.5, and the resampler rounds up). An average of
    // the codes (128) would be the classic gamma mistake.
    for (const TextureLevel& level : texture.mipLevels)
        for (size_t i = 0; i < level.rgba.size(); i += 4) {
            EXPECT_NEAR(int(level.rgba[i]), 188, 1);
            EXPECT_EQ(level.rgba[i + 3], 255);
        }
}

TEST(Mipmaps, RegeneratingReplacesTheChain) {
    Texture texture = solidTexture(8, 2, glm::u8vec4(10, 20, 30, 40));
    generateMipmaps(texture);
    generateMipmaps(texture);
    EXPECT_EQ(texture.levelCount(), 4u);  // 8x2, 4x1, 2x1, 1x1
    EXPECT_EQ(texture.mipLevels.back().width, 1u);
    EXPECT_EQ(texture.mipLevels.back().height, 1u);
}

// ---- Vulkan's texel filtering -----------------------------------------------------------------

TEST(TextureSampling, LodIsLog2OfTheLongerFootprint) {
    const Texture texture = solidTexture(64, 32, glm::u8vec4(0, 0, 0, 255));
    // dx spans 4 texels across u (4/64), dy spans 1 texel along v (1/32): rho = 4, lambda = 2.
    EXPECT_FLOAT_EQ(textureLod(texture, glm::vec2(4.0f / 64.0f, 0.0f), glm::vec2(0.0f, 1.0f / 32.0f)), 2.0f);
    EXPECT_EQ(textureLod(texture, glm::vec2(0.0f), glm::vec2(0.0f)), -std::numeric_limits<float>::infinity());
}

TEST(TextureSampling, MagnificationReadsLevelZeroAndMinificationTheChain) {
    Texture texture = checkerTexture(4);
    generateMipmaps(texture);
    TextureSampler sampler;
    sampler.magFilter = TextureFilter::Nearest;
    sampler.minFilter = TextureFilter::Nearest;
    sampler.mipFilter = TextureFilter::Nearest;
    // Texel (1, 0) is white; its centre is uv (0.375, 0.125).
    EXPECT_EQ(sampleTexture(texture, sampler, glm::vec2(0.375f, 0.125f), -1.0f).r, 1.0f);
    EXPECT_EQ(sampleTexture(texture, sampler, glm::vec2(0.125f, 0.125f), 0.0f).r, 0.0f);
    // lambda 0.4: d = ceil(0.4 + 0.5) - 1 = 0, still level 0; lambda 0.6: d = 1, the grey level.
    EXPECT_EQ(sampleTexture(texture, sampler, glm::vec2(0.375f, 0.125f), 0.4f).r, 1.0f);
    EXPECT_NEAR(sampleTexture(texture, sampler, glm::vec2(0.375f, 0.125f), 0.6f).r, 0.5f, 0.005f);
    // Beyond the last level lambda clamps to it.
    EXPECT_NEAR(sampleTexture(texture, sampler, glm::vec2(0.375f, 0.125f), 30.0f).r, 0.5f, 0.005f);
    // Without mipmaps (glTF minFilter NEAREST) every lambda reads level 0.
    sampler.mipmaps = false;
    EXPECT_EQ(sampleTexture(texture, sampler, glm::vec2(0.375f, 0.125f), 5.0f).r, 1.0f);
}

TEST(TextureSampling, TrilinearMixesTwoLevels) {
    // Level 0 opaque white, level 1 black (set by hand): lambda 1.25 mixes levels 1 and 2;
    // lambda 0.25 mixes level 0 (weight 0.75) and level 1 (0.25).
    Texture texture = solidTexture(4, 4, glm::u8vec4(255));
    generateMipmaps(texture);
    for (uint8_t& byte : texture.mipLevels[0].rgba) byte = 0;
    for (size_t i = 3; i < texture.mipLevels[0].rgba.size(); i += 4) texture.mipLevels[0].rgba[i] = 255;
    const TextureSampler trilinear;  // glTF's default: linear, mipmapped linear
    EXPECT_NEAR(sampleTexture(texture, trilinear, glm::vec2(0.5f), 0.25f).r, 0.75f, 1e-6f);
    EXPECT_NEAR(sampleTexture(texture, trilinear, glm::vec2(0.5f), 1.25f).r, 0.25f, 1e-6f);  // 0.75 black + 0.25 white
}

TEST(TextureSampling, WrapModesAddressAsVulkanSays) {
    // A 4x1 texture with codes 0, 85, 170, 255 in red; nearest filtering at texel x = -1 and 4.
    Texture texture;
    texture.width = 4;
    texture.height = 1;
    texture.rgba = {0, 0, 0, 255, 85, 0, 0, 255, 170, 0, 0, 255, 255, 0, 0, 255};
    TextureSampler sampler;
    sampler.magFilter = TextureFilter::Nearest;
    const auto red = [&](float u) { return sampleTexture(texture, sampler, glm::vec2(u, 0.5f), -1.0f).r; };
    const float c255 = 1.0f, c0 = 0.0f, c85 = reference::srgbToLinear(85);
    sampler.wrapU = TextureWrap::Repeat;
    EXPECT_EQ(red(-0.125f), c255);  // texel -1 -> 3
    EXPECT_EQ(red(1.125f), c0);     // texel 4 -> 0
    sampler.wrapU = TextureWrap::ClampToEdge;
    EXPECT_EQ(red(-0.125f), c0);
    EXPECT_EQ(red(1.125f), c255);
    sampler.wrapU = TextureWrap::MirroredRepeat;
    EXPECT_EQ(red(-0.125f), c0);    // texel -1 mirrors to 0
    EXPECT_EQ(red(1.125f), c255);   // texel 4 mirrors to 3
    EXPECT_EQ(red(1.375f), reference::srgbToLinear(170));  // texel 5 -> 2
    EXPECT_EQ(red(-0.375f), c85);   // texel -2 -> 1
}

TEST(TextureSampling, BilinearAgreesWithTheLevelZeroSampler) {
    Texture texture = checkerTexture(4);
    generateMipmaps(texture);
    for (const glm::vec2 uv : {glm::vec2(0.1f, 0.7f), glm::vec2(-1.3f, 2.2f), glm::vec2(0.5f, 0.5f)})
        EXPECT_EQ(sampleTexture(texture, TextureSampler{}, uv, -2.0f), reference::sampleBilinearRepeat(texture, uv));
}

TEST(MaterialSampling, AlphaIsTheFactorTimesTheTexture) {
    Scene scene;
    scene.textures.push_back(solidTexture(2, 2, glm::u8vec4(255, 255, 255, 128)));
    Material material;
    material.baseColorFactor = glm::vec4(1.0f, 1.0f, 1.0f, 0.5f);
    material.baseColorTexture.image = 0;
    // 0.5 x 128/255: alpha is linear, not sRGB-decoded.
    EXPECT_FLOAT_EQ(reference::baseColorAlpha(scene, material, glm::vec2(0.25f), glm::vec2(0.0f)), 0.5f * 128.0f / 255.0f);
    material.baseColorTexture.image = -1;
    EXPECT_FLOAT_EQ(reference::baseColorAlpha(scene, material, glm::vec2(0.25f), glm::vec2(0.0f)), 0.5f);
}

}  // namespace
}  // namespace punctual
