// Heatmap rendering of per-pixel light counts: the viridis colour map, the frame area of the
// output, the legend, size checks and a PNG round trip.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/image.h"
#include "metrics/heatmap.h"
#include "metrics/text_overlay.h"

namespace punctual {
namespace {

namespace fs = std::filesystem;

// First and last entries of matplotlib's viridis table, times 255, rounded.
constexpr glm::u8vec3 kViridisFirst{68, 1, 84};
constexpr glm::u8vec3 kViridisLast{253, 231, 37};

glm::u8vec3 pixelAt(const ImageRgba8& image, uint32_t x, uint32_t y) {
    const uint8_t* pixel = image.at(x, y);
    return {pixel[0], pixel[1], pixel[2]};
}

float luminance(glm::u8vec3 color) {
    return 0.2126f * float(color.r) + 0.7152f * float(color.g) + 0.0722f * float(color.b);
}

// count = x + y: a diagonal gradient 0..(width + height - 2).
std::vector<uint32_t> diagonalGradient(uint32_t width, uint32_t height) {
    std::vector<uint32_t> counts(size_t{width} * height);
    for (uint32_t y = 0; y < height; ++y) {
        for (uint32_t x = 0; x < width; ++x) counts[size_t{y} * width + x] = x + y;
    }
    return counts;
}

void expectFrameMatchesColorMap(const ImageRgba8& image, const std::vector<uint32_t>& counts,
                                uint32_t width, uint32_t height, float scaleMax) {
    for (uint32_t y = 0; y < height; ++y) {
        for (uint32_t x = 0; x < width; ++x) {
            glm::u8vec3 expected = heatmapColor(float(counts[size_t{y} * width + x]), scaleMax);
            ASSERT_EQ(pixelAt(image, x, y), expected) << "pixel " << x << "," << y;
            ASSERT_EQ(image.at(x, y)[3], 255);
        }
    }
}

// ---- heatmapColor ----------------------------------------------------------------------------

TEST(HeatmapColor, ZeroIsFirstAnchor) {
    EXPECT_EQ(heatmapColor(0.0f, 10.0f), kViridisFirst);
    EXPECT_EQ(heatmapColor(0.0f, 1.0f), kViridisFirst);
}

TEST(HeatmapColor, MaxIsLastAnchor) {
    EXPECT_EQ(heatmapColor(10.0f, 10.0f), kViridisLast);
    EXPECT_EQ(heatmapColor(7.0f, 7.0f), kViridisLast);
    EXPECT_EQ(heatmapColor(1.0f, 1.0f), kViridisLast);
}

TEST(HeatmapColor, LuminanceIncreasesAlongTheScale) {
    constexpr int kSteps = 64;
    float previous = -1.0f;
    for (int step = 0; step < kSteps; ++step) {
        float value = float(step) / float(kSteps - 1);
        float current = luminance(heatmapColor(value, 1.0f));
        EXPECT_GT(current, previous) << "step " << step;
        previous = current;
    }
}

TEST(HeatmapColor, ClampsOutsideTheScale) {
    EXPECT_EQ(heatmapColor(11.0f, 10.0f), kViridisLast);
    EXPECT_EQ(heatmapColor(1e9f, 10.0f), kViridisLast);
    EXPECT_EQ(heatmapColor(-3.0f, 10.0f), kViridisFirst);
    EXPECT_EQ(heatmapColor(5.0f, 0.0f), kViridisFirst);
    EXPECT_EQ(heatmapColor(std::numeric_limits<float>::quiet_NaN(), 10.0f), kViridisFirst);
}

// ---- renderHeatmap: frame area ---------------------------------------------------------------

TEST(Heatmap, FramePixelsMatchColorMapOneToOne) {
    constexpr uint32_t kWidth = 32, kHeight = 16;
    std::vector<uint32_t> counts = diagonalGradient(kWidth, kHeight);
    ImageRgba8 image = renderHeatmap(counts, {}, kWidth, kHeight, {});
    ASSERT_GE(image.width, kWidth);
    ASSERT_GT(image.height, kHeight);  // the legend is below the frame
    ASSERT_EQ(image.pixels.size(), size_t{image.width} * image.height * 4);
    // Auto scale: the largest count, 31 + 15.
    expectFrameMatchesColorMap(image, counts, kWidth, kHeight, 46.0f);
    EXPECT_EQ(pixelAt(image, 0, 0), kViridisFirst);
    EXPECT_EQ(pixelAt(image, kWidth - 1, kHeight - 1), kViridisLast);
}

TEST(Heatmap, ExplicitMaxValueSetsScaleAndClamps) {
    constexpr uint32_t kWidth = 32, kHeight = 16;
    std::vector<uint32_t> counts = diagonalGradient(kWidth, kHeight);
    HeatmapOptions options;
    options.maxValue = 20;
    ImageRgba8 image = renderHeatmap(counts, {}, kWidth, kHeight, options);
    expectFrameMatchesColorMap(image, counts, kWidth, kHeight, 20.0f);
    EXPECT_EQ(pixelAt(image, 20, 0), kViridisLast);
    EXPECT_EQ(pixelAt(image, kWidth - 1, kHeight - 1), kViridisLast);  // 46 clamps to the top
}

TEST(Heatmap, BackgroundPixelsGetBackgroundColor) {
    constexpr uint32_t kWidth = 8, kHeight = 4;
    std::vector<uint32_t> counts(kWidth * kHeight, 3);
    std::vector<uint8_t> background(kWidth * kHeight, 0);
    background[0] = 1;
    background[kWidth * kHeight - 1] = 1;
    counts[0] = 100;  // a background count must not stretch the auto scale

    ImageRgba8 marked = renderHeatmap(counts, background, kWidth, kHeight, {});
    EXPECT_EQ(pixelAt(marked, 0, 0), kHeatmapBackgroundColor);
    EXPECT_EQ(pixelAt(marked, kWidth - 1, kHeight - 1), kHeatmapBackgroundColor);
    EXPECT_EQ(pixelAt(marked, 1, 0), kViridisLast);  // 3 is the top of the geometry's scale

    HeatmapOptions unmarked;
    unmarked.markBackground = false;
    ImageRgba8 plain = renderHeatmap(counts, background, kWidth, kHeight, unmarked);
    EXPECT_EQ(pixelAt(plain, 0, 0), kViridisLast);
    EXPECT_EQ(pixelAt(plain, 1, 0), heatmapColor(3.0f, 100.0f));
}

// ---- renderHeatmap: legend -------------------------------------------------------------------

TEST(Heatmap, LegendHasBarAndText) {
    constexpr uint32_t kWidth = 320, kHeight = 180;
    HeatmapOptions options;
    options.title = "lights tested per pixel (tiled 16x16)";
    ImageRgba8 image = renderHeatmap(diagonalGradient(kWidth, kHeight), {}, kWidth, kHeight, options);

    size_t dark = 0, text = 0, barBottom = 0, barTop = 0;
    for (uint32_t y = kHeight; y < image.height; ++y) {
        for (uint32_t x = 0; x < image.width; ++x) {
            glm::u8vec3 color = pixelAt(image, x, y);
            if (luminance(color) < 40.0f) ++dark;
            if (color.r > 200 && color.r == color.g && color.g == color.b) ++text;
            if (color == kViridisFirst) ++barBottom;
            if (color == kViridisLast) ++barTop;
        }
    }
    EXPECT_GT(dark, 0u);
    EXPECT_GT(text, 100u);  // title, tick labels and stats make many light pixels
    EXPECT_GT(barBottom, 0u);
    EXPECT_GT(barTop, 0u);
}

TEST(Heatmap, LongTitleWidensOutput) {
    HeatmapOptions options;
    options.title = std::string(120, 'W');
    ImageRgba8 image = renderHeatmap({1, 2, 3, 4}, {}, 2, 2, options);
    EXPECT_GE(image.width, textWidth(options.title, 1));
}

TEST(Heatmap, TinyFramesWork) {
    for (auto [width, height] : {std::pair<uint32_t, uint32_t>{1, 1}, {1, 7}, {7, 1}, {64, 36}}) {
        std::vector<uint32_t> counts = diagonalGradient(width, height);
        ImageRgba8 image = renderHeatmap(counts, {}, width, height, {});
        ASSERT_GE(image.width, 100u) << width << "x" << height;  // legend keeps a minimum width
        ASSERT_GT(image.height, height);
        expectFrameMatchesColorMap(image, counts, width, height,
                                   float(std::max(width + height - 2, 1u)));
        // Right of a narrow frame is padding in the panel colour.
        EXPECT_EQ(pixelAt(image, width, 0), kHeatmapPanelColor);
    }
}

TEST(Heatmap, AllZeroAndAllBackgroundFramesWork) {
    ImageRgba8 zeros = renderHeatmap(std::vector<uint32_t>(12, 0), {}, 4, 3, {});
    EXPECT_EQ(pixelAt(zeros, 3, 2), kViridisFirst);
    ImageRgba8 empty = renderHeatmap(std::vector<uint32_t>(12, 5), std::vector<uint8_t>(12, 1), 4, 3, {});
    EXPECT_EQ(pixelAt(empty, 3, 2), kHeatmapBackgroundColor);
}

TEST(Heatmap, MismatchedSizesThrow) {
    auto expectHeatmapError = [](auto&& call) {
        try {
            call();
            ADD_FAILURE() << "no punctual::Error thrown";
        } catch (const Error& error) {
            EXPECT_EQ(error.subject(), "heatmap");
        }
    };
    expectHeatmapError([] { renderHeatmap(std::vector<uint32_t>(5), {}, 2, 2, {}); });
    expectHeatmapError([] { renderHeatmap(std::vector<uint32_t>(4), std::vector<uint8_t>(3), 2, 2, {}); });
    expectHeatmapError([] { renderHeatmap({}, {}, 0, 0, {}); });
    expectHeatmapError([] { renderHeatmap({}, {}, 3, 0, {}); });
}

// ---- PNG round trip --------------------------------------------------------------------------

TEST(Heatmap, PngRoundTripIsLossless) {
    fs::path dir = fs::temp_directory_path() / ("punctual-heatmap-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    constexpr uint32_t kWidth = 96, kHeight = 54;
    HeatmapOptions options;
    options.title = "round trip";
    ImageRgba8 written = renderHeatmap(diagonalGradient(kWidth, kHeight), {}, kWidth, kHeight, options);
    std::string path = (dir / "gradient.png").string();
    writePng(path, written);
    ImageRgba8 read = readPng(path);
    fs::remove_all(dir);
    EXPECT_EQ(read.width, written.width);
    EXPECT_EQ(read.height, written.height);
    EXPECT_TRUE(read.pixels == written.pixels);
}

// ---- text overlay ----------------------------------------------------------------------------

TEST(HeatmapText, WidthScalesAndTextClipsAtEdges) {
    EXPECT_GT(textWidth("12", 1), 0u);
    EXPECT_EQ(textWidth("12", 2), 2 * textWidth("12", 1));
    EXPECT_EQ(textWidth("", 1), 0u);

    ImageRgba8 image;
    image.width = 10;
    image.height = 6;
    image.pixels.assign(10 * 6 * 4, 0);
    // Hanging off every edge, and bytes the font has no glyph for: nothing may be written
    // outside the image (ASan/valgrind would notice) and something must land inside.
    drawText(image, -7, -3, "8\x01\xff\n8", 3, {255, 255, 255});
    drawText(image, 8, 4, "888", 2, {255, 255, 255});
    size_t lit = 0;
    for (size_t i = 0; i < image.pixels.size(); i += 4) lit += image.pixels[i] == 255;
    EXPECT_GT(lit, 0u);
}

}  // namespace
}  // namespace punctual
