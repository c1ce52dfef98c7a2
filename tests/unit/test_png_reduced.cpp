// PNGs decoded row by row at a reduced size (scene/png_reduced.h) and the decoder's choice of
// path by the header's dimensions (scene/image_decoding.h): known answers on tiny images, and a
// file that declares more texels than punctual decodes whole.
#include <gtest/gtest.h>

#include <png.h>
#include <webp/encode.h>

#include <cmath>
#include <string>
#include <vector>

#include "scene/image_decoding.h"
#include "scene/png_reduced.h"

namespace punctual {
namespace {

// A PNG of width x height RGBA8 texels from `texel(x, y)`, written with libpng (interlaced when
// asked: Adam7, which the row-by-row decoder refuses).
template <typename Texel>
std::vector<unsigned char> pngFile(uint32_t width, uint32_t height, Texel texel, bool interlaced = false) {
    std::vector<unsigned char> file;
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png_create_info_struct(png);
    png_set_write_fn(
        png, &file,
        [](png_structp p, png_bytep data, size_t length) {
            auto* out = static_cast<std::vector<unsigned char>*>(png_get_io_ptr(p));
            out->insert(out->end(), data, data + length);
        },
        nullptr);
    png_set_IHDR(png, info, width, height, 8, PNG_COLOR_TYPE_RGB_ALPHA,
                 interlaced ? PNG_INTERLACE_ADAM7 : PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
                 PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    std::vector<unsigned char> image(size_t(width) * height * 4);
    std::vector<png_bytep> rows(height);
    for (uint32_t y = 0; y < height; ++y) {
        for (uint32_t x = 0; x < width; ++x) {
            const std::array<unsigned char, 4> value = texel(x, y);
            std::copy(value.begin(), value.end(), image.begin() + std::ptrdiff_t((size_t(y) * width + x) * 4));
        }
        rows[y] = image.data() + size_t(y) * width * 4;
    }
    png_write_image(png, rows.data());
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    return file;
}

TEST(PngReduced, TheReductionIsTheLargestPowerOfTwoThatKeepsTheWantedSize) {
    EXPECT_EQ(reductionFactor({16384, 16384}, {256, 256}), 64u);
    EXPECT_EQ(reductionFactor({20000, 20000}, {256, 256}), 64u);  // 20000 / 64 = 313 >= 256; / 128 = 157
    EXPECT_EQ(reductionFactor({300, 100}, {64, 21}), 4u);         // 75 x 25; by 8, 38 < 64
    EXPECT_EQ(reductionFactor({300, 100}, {300, 100}), 1u);
    EXPECT_EQ(reductionFactor({5, 3}, {3, 2}), 2u);                // by 2: 3 x 2 (sides round up), exactly enough
    EXPECT_EQ(reductionFactor({5, 3}, {4, 2}), 1u);
}

TEST(PngReduced, BlocksAverageInLinearLightWeightedByAlpha) {
    // A black and white checker: every 2 x 2 block is half white, 0.5 in linear light, which sRGB
    // encodes as 1.055 * 0.5^(1/2.4) - 0.055 = 0.7354, byte 188 (not 128: averaging the bytes).
    const auto checker = [](uint32_t x, uint32_t y) {
        const unsigned char v = (x + y) % 2 ? 255 : 0;
        return std::array<unsigned char, 4>{v, v, v, 255};
    };
    const std::vector<unsigned char> file = pngFile(6, 4, checker);
    ReducedImage image;
    std::string failure;
    ASSERT_TRUE(decodePngReduced(file.data(), file.size(), {3, 2}, image, failure)) << failure;
    EXPECT_EQ(image.original.width, 6u);
    EXPECT_EQ(image.size.width, 3u);
    EXPECT_EQ(image.size.height, 2u);
    ASSERT_EQ(image.rgba.size(), 3u * 2u * 4u);
    for (size_t i = 0; i < image.rgba.size(); i += 4) {
        EXPECT_EQ(image.rgba[i], 188) << i;
        EXPECT_EQ(image.rgba[i + 3], 255) << i;
    }
    // One opaque red texel among three transparent green ones: the colour is red (transparent
    // texels lend no colour), the alpha a quarter, 64.
    const auto lonely = [](uint32_t x, uint32_t y) {
        return x == 0 && y == 0 ? std::array<unsigned char, 4>{255, 0, 0, 255} : std::array<unsigned char, 4>{0, 255, 0, 0};
    };
    const std::vector<unsigned char> red = pngFile(2, 2, lonely);
    ASSERT_TRUE(decodePngReduced(red.data(), red.size(), {1, 1}, image, failure)) << failure;
    EXPECT_EQ(std::vector<uint8_t>(image.rgba.begin(), image.rgba.end()), (std::vector<uint8_t>{255, 0, 0, 64}));
}

TEST(PngReduced, EdgeBlocksAverageOnlyTheTexelsTheyHave) {
    // 5 x 3 by 2: the right column and bottom row of blocks are one texel wide or tall. Column 4
    // is white, the rest black: the right blocks are all white, the others black.
    const auto column = [](uint32_t x, uint32_t) {
        const unsigned char v = x == 4 ? 255 : 0;
        return std::array<unsigned char, 4>{v, v, v, 255};
    };
    const std::vector<unsigned char> file = pngFile(5, 3, column);
    ReducedImage image;
    std::string failure;
    ASSERT_TRUE(decodePngReduced(file.data(), file.size(), {3, 2}, image, failure)) << failure;
    ASSERT_EQ(image.size.width, 3u);
    ASSERT_EQ(image.size.height, 2u);
    for (uint32_t y = 0; y < 2; ++y)
        for (uint32_t x = 0; x < 3; ++x) EXPECT_EQ(image.rgba[(y * 3 + x) * 4], x == 2 ? 255 : 0) << x << "," << y;
}

TEST(PngReduced, InterlacedAndCorruptFilesFailWithAReason) {
    const auto grey = [](uint32_t, uint32_t) { return std::array<unsigned char, 4>{90, 90, 90, 255}; };
    std::vector<unsigned char> file = pngFile(8, 8, grey, true);
    ReducedImage image;
    std::string failure;
    EXPECT_FALSE(decodePngReduced(file.data(), file.size(), {2, 2}, image, failure));
    EXPECT_EQ(failure, "an interlaced PNG this large cannot be decoded row by row");
    file = pngFile(8, 8, grey);
    file.resize(file.size() / 2);  // cut short
    EXPECT_FALSE(decodePngReduced(file.data(), file.size(), {2, 2}, image, failure));
    EXPECT_FALSE(failure.empty());
    EXPECT_TRUE(image.rgba.empty());
}

TEST(ImageDecoding, AnImageTooLargeToDecodeWholeIsDecodedReducedOrRefusedByItsHeader) {
    // 4200 x 4100 RGBA8 is 66 MiB, just over what is decoded whole: the PNG goes row by row.
    const auto flat = [](uint32_t, uint32_t) { return std::array<unsigned char, 4>{200, 100, 50, 255}; };
    const std::vector<unsigned char> big = pngFile(4200, 4100, flat);
    FittedImage image;
    std::string failure;
    ASSERT_TRUE(decodeFittedRgba8(big.data(), big.size(), 256, image, failure)) << failure;
    EXPECT_EQ(image.original.width, 4200u);
    EXPECT_EQ(image.size.width, 256u);
    EXPECT_EQ(image.size.height, 250u);  // 4100 x 256 / 4200 = 249.9
    ASSERT_EQ(image.rgba.size(), size_t(256) * 250 * 4);
    for (size_t i = 0; i < image.rgba.size(); i += 4) {
        ASSERT_EQ(image.rgba[i], 200) << i;  // a flat colour stays exactly flat
        ASSERT_EQ(image.rgba[i + 1], 100) << i;
        ASSERT_EQ(image.rgba[i + 2], 50) << i;
        ASSERT_EQ(image.rgba[i + 3], 255) << i;
    }
    // The same as a WebP: libwebp scales while decoding, straight to the fitted size.
    {
        const std::vector<uint8_t> rgba = [] {
            std::vector<uint8_t> pixels(size_t(4200) * 4100 * 4);
            for (size_t i = 0; i < pixels.size(); i += 4) {
                pixels[i] = 200;
                pixels[i + 1] = 100;
                pixels[i + 2] = 50;
                pixels[i + 3] = 255;
            }
            return pixels;
        }();
        uint8_t* encoded = nullptr;
        const size_t size = WebPEncodeLosslessRGBA(rgba.data(), 4200, 4100, 4200 * 4, &encoded);
        ASSERT_GT(size, 0u);
        const std::vector<unsigned char> webp(encoded, encoded + size);
        WebPFree(encoded);
        ASSERT_TRUE(decodeFittedRgba8(webp.data(), webp.size(), 256, image, failure)) << failure;
        EXPECT_EQ(image.original.width, 4200u);
        EXPECT_EQ(image.size.width, 256u);
        EXPECT_EQ(image.size.height, 250u);
        ASSERT_EQ(image.rgba.size(), size_t(256) * 250 * 4);
        EXPECT_EQ(std::vector<uint8_t>(image.rgba.begin(), image.rgba.begin() + 4), (std::vector<uint8_t>{200, 100, 50, 255}));
    }
    // A TGA header declaring 16384 x 16384 (1 GiB): no reduced decoder, refused before decoding.
    std::vector<unsigned char> tga(18 + 16, 0);
    tga[2] = 2;  // uncompressed true colour
    tga[12] = 0x00;
    tga[13] = 0x40;  // width 16384
    tga[14] = 0x00;
    tga[15] = 0x40;  // height 16384
    tga[16] = 32;
    EXPECT_FALSE(decodeFittedRgba8(tga.data(), tga.size(), 256, image, failure));
    EXPECT_EQ(failure, "a 16384x16384 image needs 1024 MiB to decode, more than the 64 MiB punctual decodes whole; "
                       "only PNG and WebP are decoded at a reduced size");
}

}  // namespace
}  // namespace punctual
