#include "metrics/heatmap.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include <glm/glm.hpp>

#include "core/error.h"
#include "metrics/text_overlay.h"

namespace punctual {
namespace {

// Viridis (van der Walt & Smith, matplotlib 2.0 default colour map): perceptually uniform,
// monotone in lightness, readable with the common colour-vision deficiencies and in greyscale.
// These are 18 evenly spaced entries (indices 0, 15, 30, ..., 255) of the published 256-entry
// table `_viridis_data` in matplotlib/_cm_listed.py (checked against matplotlib 3.6.3), each
// channel multiplied by 255 and rounded. Interpolating linearly between them stays within one
// or two 8-bit steps of the full table.
constexpr std::array<glm::u8vec3, 18> kViridisAnchors{{
    {68, 1, 84},     // 0/255
    {72, 23, 105},   // 15/255
    {71, 42, 122},   // 30/255
    {67, 61, 132},   // 45/255
    {61, 78, 138},   // 60/255
    {53, 94, 141},   // 75/255
    {46, 109, 142},  // 90/255
    {41, 123, 142},  // 105/255
    {35, 137, 142},  // 120/255
    {31, 151, 139},  // 135/255
    {33, 165, 133},  // 150/255
    {46, 179, 124},  // 165/255
    {70, 192, 111},  // 180/255
    {101, 203, 94},  // 195/255
    {137, 213, 72},  // 210/255
    {176, 221, 47},  // 225/255
    {216, 226, 25},  // 240/255
    {253, 231, 37},  // 255/255
}};

constexpr glm::u8vec3 kTextColor{235, 235, 235};

// Legend geometry in stb_easy_font units (one unit = `scale` pixels).
constexpr uint32_t kMarginUnits = 6;
constexpr uint32_t kBarHeightUnits = 10;
constexpr uint32_t kTickLengthUnits = 3;
constexpr uint32_t kGapUnits = 2;
// Narrow frames still get a legend this wide, so a few ticks and the stats line fit.
constexpr uint32_t kMinLegendWidthUnits = 200;
// Frames at least this wide get text at twice the font size; smaller ones would be dwarfed.
constexpr uint32_t kDoubleScaleFrameWidth = 480;
// Aim for about this many intervals between ticks; fewer when the bar is too short.
constexpr uint32_t kTargetTickIntervals = 5;

struct CountStats {
    uint64_t pixelCount = 0;  // non-background pixels
    double mean = 0.0;
    uint32_t max = 0;
};

bool isBackground(const std::vector<uint8_t>& background, size_t index) {
    return !background.empty() && background[index] != 0;
}

CountStats geometryStats(const std::vector<uint32_t>& counts, const std::vector<uint8_t>& background) {
    CountStats stats;
    uint64_t sum = 0;
    for (size_t i = 0; i < counts.size(); ++i) {
        if (isBackground(background, i)) continue;
        ++stats.pixelCount;
        sum += counts[i];
        stats.max = std::max(stats.max, counts[i]);
    }
    if (stats.pixelCount > 0) stats.mean = static_cast<double>(sum) / static_cast<double>(stats.pixelCount);
    return stats;
}

// The auto scale covers the pixels that are actually drawn in colour: with markBackground, a
// high count in the (grey) background must not squash the colours of the geometry.
uint32_t autoScaleMax(const std::vector<uint32_t>& counts, const std::vector<uint8_t>& background,
                      bool markBackground) {
    uint32_t largest = 0;
    for (size_t i = 0; i < counts.size(); ++i) {
        if (markBackground && isBackground(background, i)) continue;
        largest = std::max(largest, counts[i]);
    }
    return std::max(largest, 1u);
}

// "Nice" step (1, 2 or 5 times a power of ten) giving at most `intervals` steps up to maxValue.
uint64_t niceTickStep(uint32_t maxValue, uint32_t intervals) {
    uint64_t minimumStep = (uint64_t{maxValue} + intervals - 1) / intervals;
    for (uint64_t power = 1;; power *= 10) {
        for (uint64_t multiplier : {1u, 2u, 5u}) {
            if (multiplier * power >= minimumStep) return multiplier * power;
        }
    }
}

struct Tick {
    uint32_t value;
    int64_t x;  // pixel column of the tick mark
    std::string label;
};

// Integer ticks: 0, multiples of a nice step, and the scale maximum; a multiple too close to the
// maximum for its label to fit is dropped.
std::vector<Tick> integerTicks(uint32_t scaleMax, bool clamped, int64_t barLeft, int64_t barWidth,
                               uint32_t labelSlotWidth) {
    auto columnOf = [&](uint64_t value) {
        double fraction = static_cast<double>(value) / static_cast<double>(scaleMax);
        return barLeft + std::llround(fraction * static_cast<double>(barWidth - 1));
    };
    uint32_t fittingIntervals = static_cast<uint32_t>(
        std::max<int64_t>(1, barWidth / std::max<int64_t>(1, labelSlotWidth)));
    uint32_t intervals = std::min(kTargetTickIntervals, fittingIntervals);
    uint64_t step = niceTickStep(scaleMax, intervals);

    std::vector<Tick> ticks;
    int64_t maxColumn = columnOf(scaleMax);
    for (uint64_t value = 0; value < scaleMax; value += step) {
        int64_t column = columnOf(value);
        if (value > 0 && maxColumn - column < labelSlotWidth) break;
        ticks.push_back({static_cast<uint32_t>(value), column, std::to_string(value)});
    }
    ticks.push_back({scaleMax, maxColumn, std::to_string(scaleMax) + (clamped ? "+" : "")});
    return ticks;
}

std::string statsLine(const CountStats& stats, uint32_t scaleMax) {
    if (stats.pixelCount == 0) return "mean -  max -  (no geometry)";
    char buffer[96];
    std::snprintf(buffer, sizeof(buffer), "mean %.2f  max %u", stats.mean, stats.max);
    std::string line = buffer;
    if (stats.max > scaleMax) line += "  (colour clamps at " + std::to_string(scaleMax) + ")";
    return line;
}

}  // namespace

glm::u8vec3 heatmapColor(float value, float maxValue) {
    float position = maxValue > 0.0f ? value / maxValue : 0.0f;
    if (!(position > 0.0f)) position = 0.0f;  // also catches NaN
    position = std::min(position, 1.0f);

    constexpr size_t kLastSegment = kViridisAnchors.size() - 2;
    float scaled = position * static_cast<float>(kViridisAnchors.size() - 1);
    size_t segment = std::min(static_cast<size_t>(scaled), kLastSegment);
    float fraction = scaled - static_cast<float>(segment);
    // Anchors are integers, so fraction 0 and 1 reproduce the end anchors exactly.
    glm::vec3 low(kViridisAnchors[segment]);
    glm::vec3 high(kViridisAnchors[segment + 1]);
    glm::vec3 mixed = low + (high - low) * fraction;
    return glm::u8vec3(glm::round(mixed));
}

ImageRgba8 renderHeatmap(const std::vector<uint32_t>& counts, const std::vector<uint8_t>& background,
                         uint32_t width, uint32_t height, const HeatmapOptions& options) {
    size_t pixelCount = size_t{width} * height;
    if (width == 0 || height == 0) {
        throw Error("heatmap", "frame is empty (" + std::to_string(width) + "x" + std::to_string(height) + ")");
    }
    if (counts.size() != pixelCount) {
        throw Error("heatmap", std::to_string(counts.size()) + " counts for a " + std::to_string(width) +
                                   "x" + std::to_string(height) + " frame (expected " +
                                   std::to_string(pixelCount) + ")");
    }
    if (!background.empty() && background.size() != pixelCount) {
        throw Error("heatmap", std::to_string(background.size()) + " background flags for a " +
                                   std::to_string(width) + "x" + std::to_string(height) +
                                   " frame (expected 0 or " + std::to_string(pixelCount) + ")");
    }

    const uint32_t scaleMax =
        options.maxValue > 0 ? options.maxValue : autoScaleMax(counts, background, options.markBackground);
    const CountStats stats = geometryStats(counts, background);
    const std::string statsText = options.statsText.empty() ? statsLine(stats, scaleMax) : options.statsText;
    const bool clamped = stats.max > scaleMax;

    const uint32_t scale = width >= kDoubleScaleFrameWidth ? 2 : 1;
    const uint32_t margin = kMarginUnits * scale;
    const uint32_t lineHeight = textLineHeight(scale);
    const uint32_t widestLabel = textWidth(std::to_string(scaleMax) + "+", scale);
    const uint32_t outputWidth = std::max({width, kMinLegendWidthUnits * scale,
                                           textWidth(options.title, scale) + 2 * margin,
                                           textWidth(statsText, scale) + 2 * margin});
    // Legend rows, top to bottom: title, colour bar, tick marks + labels, stats line.
    const uint32_t titleTop = height + margin;
    const uint32_t barTop = titleTop + (options.title.empty() ? 0 : lineHeight + kGapUnits * scale);
    const uint32_t barHeight = kBarHeightUnits * scale;
    const uint32_t labelsTop = barTop + barHeight + (kTickLengthUnits + kGapUnits) * scale;
    const uint32_t statsTop = labelsTop + lineHeight;
    const uint32_t outputHeight = statsTop + lineHeight + margin;

    ImageRgba8 image;
    image.width = outputWidth;
    image.height = outputHeight;
    image.pixels.resize(size_t{outputWidth} * outputHeight * 4);
    fillRect(image, 0, 0, outputWidth, outputHeight, kHeatmapPanelColor);

    for (uint32_t y = 0; y < height; ++y) {
        for (uint32_t x = 0; x < width; ++x) {
            size_t index = size_t{y} * width + x;
            glm::u8vec3 color = options.markBackground && isBackground(background, index)
                                    ? kHeatmapBackgroundColor
                                    : heatmapColor(static_cast<float>(counts[index]), static_cast<float>(scaleMax));
            uint8_t* pixel = image.at(x, y);
            pixel[0] = color.r;
            pixel[1] = color.g;
            pixel[2] = color.b;
        }
    }

    drawText(image, margin, titleTop, options.title, scale, kTextColor);

    // The bar is inset by half the widest label so the end labels can be centred on their ticks.
    const int64_t barLeft = margin + widestLabel / 2;
    const int64_t barWidth = std::max<int64_t>(1, int64_t{outputWidth} - 2 * barLeft);
    for (int64_t column = 0; column < barWidth; ++column) {
        float value = barWidth > 1 ? static_cast<float>(column) / static_cast<float>(barWidth - 1) : 1.0f;
        fillRect(image, barLeft + column, barTop, 1, barHeight, heatmapColor(value, 1.0f));
    }
    const uint32_t labelSlot = widestLabel + 2 * margin;
    std::vector<Tick> ticks;
    if (options.ticks.empty()) {
        ticks = integerTicks(scaleMax, clamped, barLeft, barWidth, labelSlot);
    } else {
        for (const auto& [value, label] : options.ticks) {
            const double fraction = std::min(1.0, double(value) / double(scaleMax));
            ticks.push_back({value, barLeft + std::llround(fraction * double(barWidth - 1)), label});
        }
    }
    for (const Tick& tick : ticks) {
        fillRect(image, tick.x, barTop + barHeight, scale, kTickLengthUnits * scale, kTextColor);
        int64_t labelWidth = textWidth(tick.label, scale);
        int64_t labelLeft = std::clamp<int64_t>(tick.x - labelWidth / 2, 0,
                                                std::max<int64_t>(0, int64_t{outputWidth} - labelWidth));
        drawText(image, labelLeft, labelsTop, tick.label, scale, kTextColor);
    }

    drawText(image, margin, statsTop, statsText, scale, kTextColor);
    return image;
}

}  // namespace punctual
